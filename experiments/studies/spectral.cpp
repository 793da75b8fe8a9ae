// The spectral study: each scheme's spectral limit (core/spectral.hpp) beside two runs of the bar
// at a tiny amplitude under the spectral policy, at 0.95 and at 1.05 times the limit. The limit
// is confirmed when the first stays bounded and the second grows.
#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <map>
#include <optional>
#include <sstream>
#include <string>
#include <tuple>
#include <vector>

#include "csv.hpp"
#include "paper_table1.hpp"
#include "report_util.hpp"
#include "study.hpp"

namespace mpmstab {

namespace {

using ojson = nlohmann::ordered_json;

// A bounded run's error, its phase error included, is at most 2 A; a growing mode passes 3 A.
constexpr double kBound = 3.0;

// A run is bounded when it reached T and its error over time stayed within kBound A, as the
// spectral_edge search counts it; a bounded run may still be meaningless (error >= A), which
// its text says.
bool bounded(const ojson& r) {
  return survived(r) && has_number(r, "max_error_over_time") &&
         r["max_error_over_time"].get<double>() <= kBound * r["A"].get<double>();
}

// "bounded (error 0.41 A)", "bounded (error 1.2 A, meaningless)", "grew (error 2.3e+02 A)",
// "* nonpositive_F at step 96 (...)".
std::string run_text(const ojson& r) {
  if (outcome(r) == "unstable") return verdict(r);
  if (!has_number(r, "max_error_over_time")) return "–";
  const double ratio_to_A = r["max_error_over_time"].get<double>() / r["A"].get<double>();
  return std::string(bounded(r) ? "bounded" : "grew") + " (error " + sci(ratio_to_A) + " A" +
         (bounded(r) && outcome(r) == "meaningless" ? ", meaningless" : "") + ")";
}

// A row's layout parameter (0, the uniform layout, where the row has none).
double layout_of(const ojson& r, const char* key) {
  return has_number(r, key) ? r[key].get<double>() : 0.0;
}

// One scheme: its two runs, by the policy's safety factor.
struct Scheme {
  std::string name;              // scheme_label
  const ojson* below = nullptr;  // s < 1
  const ojson* above = nullptr;  // s > 1
  const ojson& row() const { return below ? *below : *above; }
  std::optional<double> limit() const {
    return has_number(row(), "courant_spectral")
               ? std::optional(row()["courant_spectral"].get<double>())
               : std::nullopt;
  }
  int ppc() const { return row()["ppc"].get<int>(); }
  bool uniform_two() const {  // 2 particles per cell, uniform layout
    return ppc() == 2 && layout_of(row(), "shift") == 0 && layout_of(row(), "jitter") == 0;
  }
  bool confirmed() const { return below && above && bounded(*below) && !bounded(*above); }
  // The eq. (108) bound of the run below the limit (its minimum over the run), in c dt / h.
  std::optional<double> eq108() const {
    if (!below || !has_number(*below, "dt_stable_min")) return std::nullopt;
    return (*below)["dt_stable_min"].get<double>() / (*below)["dt_cfl"].get<double>();
  }
};

std::vector<Scheme> schemes_of(const std::vector<ojson>& rows) {
  std::vector<Scheme> out;
  for (const auto& r : rows) {
    const std::string name = scheme_label(r);
    auto it = std::find_if(out.begin(), out.end(), [&](const Scheme& s) { return s.name == name; });
    if (it == out.end()) it = out.insert(out.end(), Scheme{name});
    const double s = has_number(r, "safety") ? r["safety"].get<double>() : 1.0;
    (s < 1 ? it->below : it->above) = &r;
  }
  return out;
}

// The measured edges of the spectral_edge experiment at a tiny amplitude, by scheme label, in
// c dt / h (empty when it has not been run).
std::map<std::string, double> measured_edges(const StudyInputs& inputs) {
  std::map<std::string, double> out;
  const auto it = inputs.find("spectral_edge");
  if (it == inputs.end() || !it->second.present()) return out;
  for (const auto& r : it->second.doc.at("cases")) {
    if (r["A"].get<double>() >= 1e-5 || !has_number(r, "dt_edge")) continue;
    out[scheme_label(r)] = r["dt_edge"].get<double>() / r["dt_cfl"].get<double>();
  }
  return out;
}

// The update order of a scheme's name ("gimp/xpic(2)/usf" -> "usf"; no suffix: usl).
std::string update_of(const std::string& name) {
  for (const char* u : {"/usf", "/musl"}) {
    if (name.find(u) != std::string::npos) return u + 1;
  }
  return "usl";
}

std::string reading(const std::vector<Scheme>& schemes,
                    const std::map<std::string, double>& edges) {
  std::ostringstream md;
  int confirmed = 0;
  std::vector<std::string> not_confirmed;
  std::map<std::string, std::pair<double, double>> range;  // update order -> limits at ppc 2
  double eq_lo = 1e300, eq_hi = 0, edge_lo = 1e300, edge_hi = 0;
  for (const auto& s : schemes) {
    if (s.confirmed()) {
      ++confirmed;
    } else {
      not_confirmed.push_back(s.name);
    }
    const auto limit = s.limit();
    if (limit && s.uniform_two()) {
      auto [it, fresh] = range.emplace(update_of(s.name), std::pair{*limit, *limit});
      if (!fresh) {
        it->second.first = std::min(it->second.first, *limit);
        it->second.second = std::max(it->second.second, *limit);
      }
    }
    if (const auto e = s.eq108(); e && limit) {
      eq_lo = std::min(eq_lo, *e / *limit);
      eq_hi = std::max(eq_hi, *e / *limit);
    }
    if (const auto e = edges.find(s.name); e != edges.end() && limit) {
      edge_lo = std::min(edge_lo, e->second / *limit);
      edge_hi = std::max(edge_hi, e->second / *limit);
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
  md << "Limits at 2 particles per cell and the uniform layout, in c dt / h, by update order:";
  std::string sep = " ";
  for (const char* u : {"usl", "usf", "musl"}) {
    const auto it = range.find(u);
    if (it == range.end()) continue;
    md << sep << u << " " << fixed(it->second.first, 3) << " to " << fixed(it->second.second, 3);
    sep = "; ";
  }
  md << " (the CFL number is 1).";
  if (edge_hi > 0) {
    md << " The measured edges lie at " << fixed(edge_lo, 4) << " to " << fixed(edge_hi, 4)
       << " times the limit.";
  }
  if (eq_hi > 0) {
    md << " Eq. (108) at the same state lies at " << fixed(eq_lo, 3) << " to " << fixed(eq_hi, 3)
       << " times the limit.";
  }
  md << "\n\n";
  return md.str();
}

// The paper's grid for Table 1 (experiments/table1.json): h = 1 / kPaperCells.
constexpr int kPaperCells = 100;

// The paper's dt stable column of Table 1 in c dt / h, per method, A and E: the median of its
// rows (each dt), with the count of rows read and of the rows whose value is unreadable.
std::string paper_table(const std::filesystem::path& reference,
                        const std::vector<Scheme>& schemes) {
  if (reference.empty() || !std::filesystem::exists(reference)) return "";
  const CsvTable t = read_csv(reference);
  std::map<std::tuple<std::string, double, double>, std::vector<double>> values;
  std::vector<double> Es;
  std::vector<std::pair<std::string, double>> keys;  // method, A, in order
  for (const auto& r : t.rows) {
    const double A = std::stod(r.at("A")), E = std::stod(r.at("E"));
    if (std::find(Es.begin(), Es.end(), E) == Es.end()) Es.push_back(E);
    std::string method = r.at("method");
    std::transform(method.begin(), method.end(), method.begin(),
                   [](unsigned char ch) { return char(std::tolower(ch)); });
    if (std::find(keys.begin(), keys.end(), std::pair{method, A}) == keys.end())
      keys.emplace_back(method, A);
    // Table 1's own reading of a cell: '*' and unreadable text ('4.?e-6') are no number.
    const PaperValue dt_stable = paper_value(r.at("dt_stable"));
    if (dt_stable.kind != PaperValue::number || !(dt_stable.value > 0)) continue;
    values[{method, A, E}].push_back(dt_stable.value * std::sqrt(E) * kPaperCells);
  }
  std::sort(Es.begin(), Es.end());
  auto limit_of = [&](const std::string& method) -> std::string {
    for (const auto& s : schemes)
      if (s.name == method && s.limit()) return fixed(*s.limit(), 3);
    return "–";
  };
  auto eq108_of = [&](const std::string& method) -> std::string {
    for (const auto& s : schemes)
      if (s.name == method && s.eq108()) return fixed(*s.eq108(), 3);
    return "–";
  };
  std::ostringstream md;
  md << "## The paper's dt stable column\n\nTable 1's \"dt stable\" (eq. (108) of the paper's "
        "runs, at its amplitudes and E, on "
     << kPaperCells
     << " cells), converted to c dt / h: the median over the dts of each cell's block. The "
        "paper's bound changes with the state (A and E); the spectral limit and our eq. (108) at "
        "the tiny amplitude do not.\n\n| method | A | ";
  for (double E : Es)
    md << "E = " << shortest(E) << " | ";
  md << "spectral limit | our eq. (108) at A = 1e-6 |\n|---|---|";
  for (std::size_t i = 0; i < Es.size() + 2; ++i)
    md << "---|";
  md << "\n";
  int above = 0, cells = 0;
  for (const auto& [method, A] : keys) {
    md << "| " << method << " | " << shortest(A) << " | ";
    for (double E : Es) {
      const auto it = values.find({method, A, E});
      if (it == values.end() || it->second.empty()) {
        md << "– | ";
        continue;
      }
      const double m = quantile(it->second, 0.5);
      md << fixed(m, 3) << " | ";
      for (const auto& s : schemes) {
        if (s.name != method || !s.limit()) continue;
        ++cells;
        above += m > *s.limit() ? 1 : 0;
      }
    }
    md << limit_of(method) << " | " << eq108_of(method) << " |\n";
  }
  md << "\n**Reading** (computed from the rows). " << above << " of " << cells
     << " of the paper's medians lie above the spectral limit of their method (a step the "
        "linearised scheme amplifies at a tiny amplitude).\n\n";
  return md.str();
}

std::string spectral_markdown(const ReportContext& c) {
  const std::vector<ojson>& rows = c.rows;
  const std::vector<Scheme> schemes = schemes_of(rows);
  const auto edges = measured_edges(c.inputs);
  const ojson& first = rows.front();
  std::ostringstream md;
  md << "![The spectral limit against the particles per cell](spectral.png)\n\n"
     << "Each scheme's spectral limit: the largest c dt / h at which its one-step map, "
        "linearised about rest with the particles frozen at the bar's initial layout, amplifies "
        "nothing (docs/design.md, \"The spectral limit\"): the Bloch limit of the interior for a "
        "uniform layout, the dense map of the whole bar for a jittered one. Beside it, two runs "
        "of the bar under the spectral policy at s = 0.95 and s = 1.05 times the limit, at A = "
     << shortest(first["A"].get<double>()) << ", E = " << shortest(first["E"].get<double>())
     << " and T = " << shortest(first["T"].get<double>())
     << " (c T / L = " << shortest(std::sqrt(first["E"].get<double>()) * first["T"].get<double>())
     << " crossings of the bar), " << first["cells"].get<int>()
     << " cells. A run is *bounded* when it reaches T with an error over time of at most 3 A "
        "(a bounded run's error, its phase error included, is at most 2 A; one that reaches A "
        "is also marked meaningless); a run that grows passes 3 A or fails. Eq. (108) is "
        "defined for MPM, GIMP and cpGIMP only (`–` for the other bases). The measured edge is the "
        "spectral_edge experiment's "
        "([spectral_edge.md](spectral_edge.md)): the largest fixed dt that stays bounded, found "
        "by bisection to 0.5% without reading the limit. Eq. (108) is the minimum of our bound "
        "over the run at 0.95 times the limit. The CFL number is 1 in these units.\n\n"
     << reading(schemes, edges)
     << "| scheme | spectral limit (c dt / h) | analysis | measured edge | eq. (108) at the same "
        "state | run at 0.95 x | run at 1.05 x | confirmed |\n|---|---|---|---|---|---|---|---|\n";
  for (const auto& s : schemes) {
    const auto limit = s.limit();
    const auto edge = edges.find(s.name);
    const auto eq = s.eq108();
    md << "| " << s.name << " | " << (limit ? fixed(*limit, 4) : std::string("none up to 8"))
       << " | "
       << (s.row()["spectral_analysis"].is_string()
               ? s.row()["spectral_analysis"].get<std::string>()
               : std::string("–"))
       << " | " << (edge != edges.end() ? fixed(edge->second, 4) : std::string("–")) << " | "
       << (eq ? fixed(*eq, 4) : std::string("–")) << " | " << (s.below ? run_text(*s.below) : "–")
       << " | " << (s.above ? run_text(*s.above) : "–") << " | "
       << (s.confirmed() ? "yes" : "**no**") << " |\n";
  }
  md << "\n" << paper_table(c.spec.reference, schemes);
  return md.str();
}

// The figure: MPM and GIMP (USL, FLIP, uniform layout) against the particles per cell.
std::string spectral_data(const ReportContext& c) {
  const auto edges = measured_edges(c.inputs);
  std::ostringstream csv;
  csv << c.csv_header
      << "# method: 0 mpm, 1 gimp (USL, FLIP, uniform layout); in c dt / h: limit the spectral "
         "limit, edge the measured edge (empty: not measured), eq108 our eq. (108) at the same "
         "state\nmethod,ppc,limit,edge,eq108\n";
  for (const auto& s : schemes_of(c.rows)) {
    const ojson& r = s.row();
    const std::string method = r["method"].get<std::string>();
    if ((method != "mpm" && method != "gimp") || method_label(r) != method ||
        layout_of(r, "shift") != 0 || layout_of(r, "jitter") != 0 || !s.limit()) {
      continue;
    }
    const auto edge = edges.find(s.name);
    const auto eq = s.eq108();
    csv << (method == "gimp" ? 1 : 0) << ',' << s.ppc() << ',' << shortest(*s.limit()) << ','
        << (edge != edges.end() ? shortest(edge->second) : std::string()) << ','
        << (eq ? shortest(*eq) : std::string()) << '\n';
  }
  return csv.str();
}

std::string spectral_index(const Spec& spec, const std::vector<ojson>& rows) {
  const std::vector<Scheme> schemes = schemes_of(rows);
  const auto confirmed =
      std::count_if(schemes.begin(), schemes.end(), [](const Scheme& s) { return s.confirmed(); });
  std::ostringstream md;
  md << "![" << spec.title << "](" << spec.name
     << ".png)\n\n**What it shows.** The spectral limit of " << schemes.size()
     << " schemes (basis x transfer x update order, particles per cell and layout), each checked "
        "by "
        "two runs at a tiny amplitude just below and just above it: confirmed for "
     << confirmed << " of " << schemes.size() << ": [" << spec.name << ".md](" << spec.name
     << ".md).\n\n";
  return md.str();
}

const StudyRegistration kSpectral{{
    .name = "spectral",
    .summary = "each scheme's spectral limit, checked by runs just below and above it, beside "
               "the measured edge, eq. (108) and the paper's dt stable",
    .records = {.error_over_time = true, .dt_stable = true},
    .inputs = {{.name = "spectral_edge"}},
    .figure = true,
    .report =
        [](const ReportContext& c) {
          return StudyReport{.markdown = spectral_markdown(c), .data_csv = spectral_data(c)};
        },
    .index = spectral_index,
    .figure_subtitle =
        [](const Spec&, const ojson&) {
          return std::string("USL, FLIP, uniform layout, 50 cells; the CFL number is 1");
        },
}};

}  // namespace

}  // namespace mpmstab
