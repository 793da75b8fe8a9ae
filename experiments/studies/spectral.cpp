// The spectral study: each scheme's spectral limit (core/spectral.hpp) beside two runs of the bar
// at a tiny amplitude under the spectral policy, at 0.95 and at 1.05 times the limit. The limit
// is confirmed when the first stays bounded and the second grows.
#include <algorithm>
#include <cmath>
#include <map>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "csv.hpp"
#include "report_util.hpp"
#include "study.hpp"

namespace mpmstab {

namespace {

using ojson = nlohmann::ordered_json;

// A run is bounded when it ends stable with an error over time of at most kBound A: a bounded
// run's error, its phase error included, is at most 2 A, and a growing mode passes 3 A.
constexpr double kBound = 3.0;

bool bounded(const ojson& r) {
  return outcome(r) == "stable" && has_number(r, "max_error_over_time") &&
         r["max_error_over_time"].get<double>() <= kBound * r["A"].get<double>();
}

// "bounded (error 0.41 A)", "grew (error 2.3e+02 A)", "* nonpositive_F at step 96 (...)".
std::string run_text(const ojson& r) {
  if (outcome(r) == "unstable") return verdict(r);
  if (!has_number(r, "max_error_over_time")) return "–";
  const double ratio_to_A = r["max_error_over_time"].get<double>() / r["A"].get<double>();
  return std::string(bounded(r) ? "bounded" : "grew") + " (error " + sci(ratio_to_A) + " A)";
}

// One scheme: its two runs, by the policy's safety factor.
struct Scheme {
  std::string name;  // method_label
  int ppc = 0;
  std::optional<double> limit;
  const ojson* below = nullptr;  // s < 1
  const ojson* above = nullptr;  // s > 1
  bool confirmed() const { return below && above && bounded(*below) && !bounded(*above); }
};

std::vector<Scheme> schemes_of(const std::vector<ojson>& rows) {
  std::vector<Scheme> out;
  for (const auto& r : rows) {
    const std::string name = method_label(r);
    const int ppc = r["ppc"].get<int>();
    auto it = std::find_if(out.begin(), out.end(),
                           [&](const Scheme& s) { return s.name == name && s.ppc == ppc; });
    if (it == out.end()) {
      out.push_back({name, ppc, std::nullopt, nullptr, nullptr});
      it = out.end() - 1;
    }
    if (has_number(r, "courant_spectral")) it->limit = r["courant_spectral"].get<double>();
    const double s = has_number(r, "safety") ? r["safety"].get<double>() : 1.0;
    (s < 1 ? it->below : it->above) = &r;
  }
  return out;
}

// The update order of a scheme's name ("gimp/xpic(2)/usf" -> "usf"; no suffix: usl).
std::string update_of(const std::string& name) {
  for (const char* u : {"usf", "musl"}) {
    const std::string suffix = std::string("/") + u;
    if (name.size() > suffix.size() &&
        name.compare(name.size() - suffix.size(), suffix.size(), suffix) == 0) {
      return u;
    }
  }
  return "usl";
}

std::string reading(const std::vector<Scheme>& schemes) {
  std::ostringstream md;
  int confirmed = 0;
  std::vector<std::string> not_confirmed;
  std::map<std::string, std::pair<double, double>> range;  // update order -> limits at ppc 2
  for (const auto& s : schemes) {
    if (s.confirmed()) {
      ++confirmed;
    } else {
      not_confirmed.push_back(s.name + (s.ppc != 2 ? " (ppc " + std::to_string(s.ppc) + ")" : ""));
    }
    if (s.limit && s.ppc == 2) {
      auto [it, fresh] = range.emplace(update_of(s.name), std::pair{*s.limit, *s.limit});
      if (!fresh) {
        it->second.first = std::min(it->second.first, *s.limit);
        it->second.second = std::max(it->second.second, *s.limit);
      }
    }
  }
  md << "**Reading** (computed from the rows). The limit is confirmed (the run at 0.95 times it "
        "stays bounded, the run at 1.05 times it grows) for "
     << confirmed << " of " << schemes.size() << " schemes";
  if (not_confirmed.empty()) {
    md << ". ";
  } else {
    md << "; not for ";
    for (std::size_t i = 0; i < not_confirmed.size(); ++i)
      md << (i ? ", " : "") << "`" << not_confirmed[i] << "`";
    md << " (their rows show which run disagrees). ";
  }
  md << "Limits at 2 particles per cell, in c dt / h, by update order:";
  std::string sep = " ";
  for (const char* u : {"usl", "usf", "musl"}) {
    const auto it = range.find(u);
    if (it == range.end()) continue;
    md << sep << u << " " << fixed(it->second.first, 3) << " to " << fixed(it->second.second, 3);
    sep = "; ";
  }
  md << ".\n\n";
  return md.str();
}

std::string spectral_markdown(const std::vector<ojson>& rows) {
  const std::vector<Scheme> schemes = schemes_of(rows);
  const ojson& first = rows.front();
  std::ostringstream md;
  md << "Each scheme's spectral limit: the largest c dt / h at which its one-step map, "
        "linearised about rest with the particles frozen at the bar's uniform layout, amplifies "
        "nothing (docs/design.md, \"The spectral limit\"). Beside it, two runs of the bar under "
        "the spectral policy at s = 0.95 and s = 1.05 times the limit, at A = "
     << shortest(first["A"].get<double>()) << ", E = " << shortest(first["E"].get<double>())
     << " and T = " << shortest(first["T"].get<double>())
     << " (c T / L = " << shortest(std::sqrt(first["E"].get<double>()) * first["T"].get<double>())
     << " crossings of the bar), " << first["cells"].get<int>()
     << " cells. A run is *bounded* when it ends stable with an error over time of at most 3 A "
        "(a bounded run's error, its phase error included, is at most 2 A); a run that grows "
        "passes 3 A or fails.\n\n"
     << reading(schemes)
     << "| scheme | particles per cell | spectral limit (c dt / h) | run at 0.95 x | run at 1.05 "
        "x | confirmed |\n|---|---|---|---|---|---|\n";
  for (const auto& s : schemes) {
    md << "| " << s.name << " | " << s.ppc << " | "
       << (s.limit ? fixed(*s.limit, 4) : std::string("none up to 8")) << " | "
       << (s.below ? run_text(*s.below) : "–") << " | " << (s.above ? run_text(*s.above) : "–")
       << " | " << (s.confirmed() ? "yes" : "**no**") << " |\n";
  }
  return md.str();
}

std::string spectral_index(const Spec& spec, const std::vector<ojson>& rows) {
  const std::vector<Scheme> schemes = schemes_of(rows);
  const auto confirmed =
      std::count_if(schemes.begin(), schemes.end(), [](const Scheme& s) { return s.confirmed(); });
  std::ostringstream md;
  md << "**What it shows.** The spectral limit of " << schemes.size()
     << " schemes (basis x transfer x update order, and particles per cell), each checked by "
        "two runs at a tiny amplitude just below and just above it: confirmed for "
     << confirmed << " of " << schemes.size() << ": [" << spec.name << ".md](" << spec.name
     << ".md).\n\n";
  return md.str();
}

const StudyRegistration kSpectral{{
    .name = "spectral",
    .summary = "each scheme's spectral limit, checked by runs just below and above it",
    .report =
        [](const ReportContext& c) { return StudyReport{.markdown = spectral_markdown(c.rows)}; },
    .index = spectral_index,
}};

}  // namespace

}  // namespace mpmstab
