// The speed/accuracy trade: error against cost across methods, time-step policies and their
// parameters; the cheapest setting for each accuracy, and advice computed from the rows.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <map>
#include <optional>
#include <set>
#include <sstream>

#include "csv.hpp"
#include "report.hpp"
#include "report_util.hpp"
#include "scenes.hpp"
#include "study.hpp"

namespace mpmstab {

namespace {

using ojson = nlohmann::ordered_json;

// A setting's name: "gimp cfl C=0.5", "mpm adaptive s=2", "gimp fixed dt=1e-4".
std::string setting(const ojson& r) {
  const std::string policy = r["policy"].get<std::string>();
  std::string s = r["method"].get<std::string>() + " " + policy;
  if (policy == "fixed") s += " dt=" + param(r["dt"].get<double>());
  if (policy == "cfl" || policy == "min") s += " C=" + shortest(r["cfl_factor"].get<double>());
  if (policy == "adaptive" || policy == "min") s += " s=" + shortest(r["safety"].get<double>());
  if (r["cells"].get<int>() != 100) s += ", " + r["cells"].dump() + " cells";
  return s;
}

// The accuracy of a run: its max error over time, when the run is stable and meaningful.
std::optional<double> accuracy(const ojson& r) {
  if (r["stable"] != true || r["meaningless"] == true || !r["max_error_over_time"].is_number()) {
    return std::nullopt;
  }
  return r["max_error_over_time"].get<double>();
}

// Indices of the runs on the Pareto front of (wall time, error): no other run is both cheaper
// and more accurate.
std::set<std::size_t> pareto_front(const std::vector<ojson>& rows,
                                   const std::vector<std::size_t>& idx) {
  std::set<std::size_t> front;
  for (std::size_t i : idx) {
    const auto ei = accuracy(rows[i]);
    if (!ei) continue;
    const double ci = rows[i]["wall_seconds"].get<double>();
    bool dominated = false;
    for (std::size_t j : idx) {
      const auto ej = accuracy(rows[j]);
      if (j == i || !ej) continue;
      const double cj = rows[j]["wall_seconds"].get<double>();
      if (cj <= ci && *ej <= *ei && (cj < ci || *ej < *ei)) dominated = true;
    }
    if (!dominated) front.insert(i);
  }
  return front;
}

const std::vector<double> kTargets = {1e-3, 1e-4, 1e-5};

// The cheapest run (by wall time) of `idx` reaching each target error.
std::vector<std::optional<std::size_t>> cheapest(const std::vector<ojson>& rows,
                                                 const std::vector<std::size_t>& idx) {
  std::vector<std::optional<std::size_t>> best(kTargets.size());
  for (std::size_t t = 0; t < kTargets.size(); ++t) {
    for (std::size_t i : idx) {
      const auto e = accuracy(rows[i]);
      if (!e || *e > kTargets[t]) continue;
      if (!best[t] ||
          rows[i]["wall_seconds"].get<double>() < rows[*best[t]]["wall_seconds"].get<double>()) {
        best[t] = i;
      }
    }
  }
  return best;
}

// As edge_markdown: the first scene's section has the figure and the definitions.
std::string tradeoff_markdown(const Spec& spec, const std::vector<ojson>& rows, bool first = true) {
  std::vector<double> Es;
  for (const auto& r : rows) {
    const double E = r["E"].get<double>();
    if (std::find(Es.begin(), Es.end(), E) == Es.end()) Es.push_back(E);
  }
  std::ostringstream md, advice;
  const std::string scene = rows.front()["scene"].get<std::string>();
  const std::string of_scene = first ? "" : " (" + scene + ")";
  if (!first) {
    md << "\n## " << scene_title(scene) << "\n\n";
  } else {
    md << "## Results\n\nAccuracy is the max error over time (the largest particle displacement "
          "error after any step), since for most E the exact displacement at T is zero. Cost is "
          "the wall time of the run (and its number of steps). A run that failed or whose error "
          "reached A reaches no accuracy. Pareto front: no other setting at the same E is both "
          "cheaper and more accurate.\n\n!["
       << spec.title << "](" << spec.name << ".png)\n\n"
       << "Vector version: [" << spec.name << ".svg](" << spec.name << ".svg); data: [" << spec.name
       << "_data.csv](" << spec.name << "_data.csv).\n\n";
  }

  md << "### The cheapest setting for each accuracy" << of_scene << "\n\n| E |";
  for (double t : kTargets)
    md << " max error <= " << sci(t, 1) << " |";
  md << "\n|---|";
  for (std::size_t t = 0; t < kTargets.size(); ++t)
    md << "---|";
  md << "\n";
  std::map<std::string, int> winners;  // method + policy -> how often cheapest
  for (double E : Es) {
    std::vector<std::size_t> idx;
    for (std::size_t i = 0; i < rows.size(); ++i) {
      if (rows[i]["E"].get<double>() == E) idx.push_back(i);
    }
    const auto best = cheapest(rows, idx);
    md << "| " << shortest(E) << " |";
    for (const auto& b : best) {
      if (!b) {
        md << " not reached |";
        continue;
      }
      const ojson& r = rows[*b];
      md << " " << setting(r) << ": " << sci(r["max_error_over_time"].get<double>()) << " in "
         << seconds(r["wall_seconds"].get<double>()) << ", " << r["steps"].dump() << " steps |";
      ++winners[r["method"].get<std::string>() + " " + r["policy"].get<std::string>()];
    }
    md << "\n";
  }

  // Every sentence below is computed from the rows.
  auto find = [&](double E, const char* method, const char* policy, double param_value,
                  int cells) -> const ojson* {
    for (const auto& r : rows) {
      if (r["E"].get<double>() != E || r["method"] != method || r["policy"] != policy ||
          r["cells"].get<int>() != cells) {
        continue;
      }
      const double v = std::string(policy) == "adaptive" ? r["safety"].get<double>()
                                                         : r["cfl_factor"].get<double>();
      if (v == param_value) return &r;
    }
    return nullptr;
  };
  advice << "**What to pick.** ";
  if (!winners.empty()) {
    const auto top =
        std::max_element(winners.begin(), winners.end(),
                         [](const auto& a, const auto& b) { return a.second < b.second; });
    int reached = 0;
    for (const auto& [k, n] : winners)
      reached += n;
    advice << "The cheapest setting for a target accuracy is " << top->first << " in "
           << top->second << " of the " << reached
           << " (E, target) pairs that some setting reaches. ";
  }
  // GIMP: how much the error moves with dt on 100 cells, and with the grid.
  for (double E : Es) {
    std::vector<double> errs;
    for (const auto& r : rows) {
      if (r["E"].get<double>() == E && r["method"] == "gimp" && r["cells"].get<int>() == 100 &&
          (r["policy"] == "cfl" || r["policy"] == "fixed") && accuracy(r)) {
        errs.push_back(*accuracy(r));
      }
    }
    const ojson* g200 = find(E, "gimp", "cfl", 0.5, 200);
    const ojson* g400 = find(E, "gimp", "cfl", 0.5, 400);
    if (errs.empty()) continue;
    const auto [lo, hi] = std::minmax_element(errs.begin(), errs.end());
    advice << "E = " << shortest(E) << ": every stable fixed or CFL step of GIMP on 100 cells "
           << "gives an error between " << sci(*lo) << " and " << sci(*hi);
    if (g200 && g400 && accuracy(*g200) && accuracy(*g400)) {
      advice << "; the grid moves it: " << sci(*accuracy(*g200)) << " on 200 cells and "
             << sci(*accuracy(*g400)) << " on 400 (CFL, C = 0.5)";
    }
    advice << ". ";
  }
  int refined_better = 0, refined_total = 0;
  for (double E : Es) {
    const ojson* g100 = find(E, "gimp", "cfl", 0.5, 100);
    const ojson* g400 = find(E, "gimp", "cfl", 0.5, 400);
    if (g100 && g400 && accuracy(*g100) && accuracy(*g400)) {
      ++refined_total;
      refined_better += *accuracy(*g400) < *accuracy(*g100);
    }
  }
  advice << "Below the real edge the error is set by the grid, not by dt: a smaller step costs "
            "time and buys nothing. A finer grid lowered GIMP's error at "
         << refined_better << " of " << refined_total
         << " values of E (400 against 100 cells); where it did not, the cause is not established "
            "here, so refinement is worth checking, not assuming. ";
  // Stepping at the eq. (108) bound against the CFL rule.
  std::vector<double> step_ratio, error_ratio;
  for (double E : Es) {
    for (const char* m : {"gimp", "mpm"}) {
      const ojson* a = find(E, m, "adaptive", 1.0, 100);
      const ojson* c = find(E, m, "cfl", 0.5, 100);
      if (a && c && accuracy(*a) && accuracy(*c)) {
        step_ratio.push_back((*a)["steps"].get<double>() / (*c)["steps"].get<double>());
        error_ratio.push_back(*accuracy(*a) / *accuracy(*c));
      }
    }
  }
  if (!step_ratio.empty()) {
    const auto [slo, shi] = std::minmax_element(step_ratio.begin(), step_ratio.end());
    const auto [elo, ehi] = std::minmax_element(error_ratio.begin(), error_ratio.end());
    advice << "Stepping at the eq. (108) bound (adaptive, s = 1) takes " << ratio(*slo) << " to "
           << ratio(*shi) << " times the steps of the CFL rule at C = 0.5 for " << ratio(*elo)
           << " to " << ratio(*ehi)
           << " times its error: the bound buys a stability margin, not accuracy. ";
  }
  // The largest safety factor that survived at every E, per method.
  for (const char* m : {"gimp", "mpm"}) {
    double largest = 0;
    for (double s_value : {1.0, 2.0, 4.0, 8.0, 16.0}) {
      bool all = true;
      for (double E : Es) {
        const ojson* a = find(E, m, "adaptive", s_value, 100);
        all = all && a && (*a)["stable"] == true;
      }
      if (all) largest = s_value;
    }
    advice << "The adaptive step survives at every E up to s = " << shortest(largest) << " for "
           << m << ". ";
  }
  // MPM against GIMP: the best accuracy each reaches.
  for (double E : Es) {
    std::optional<double> best_gimp, best_mpm;
    for (const auto& r : rows) {
      if (r["E"].get<double>() != E || !accuracy(r)) continue;
      auto& best = r["method"] == "gimp" ? best_gimp : best_mpm;
      if (!best || *accuracy(r) < *best) best = accuracy(r);
    }
    if (best_gimp && best_mpm) {
      advice << "E = " << shortest(E) << ": the best MPM error is " << sci(*best_mpm) << ", GIMP's "
             << sci(*best_gimp) << ". ";
    }
  }
  advice << "So: use GIMP; pick the grid for the accuracy you need, then the largest step that "
            "is safely stable, which the CFL rule with C around 0.5 gives at a known wave speed "
            "(the real edge is at C = 0.5 to 0.8, see [edge.md](edge.md)); where the wave speed "
            "is not known in advance, the adaptive eq. (108) step with s up to the value above "
            "is a safe, if cautious, substitute.";
  md << "\n" << advice.str() << "\n\n";

  for (double E : Es) {
    std::vector<std::size_t> idx;
    for (std::size_t i = 0; i < rows.size(); ++i) {
      if (rows[i]["E"].get<double>() == E) idx.push_back(i);
    }
    const auto front = pareto_front(rows, idx);
    md << "### E = " << shortest(E) << of_scene
       << "\n\n| setting | steps | dt range | verdict | max error "
          "over time | wall time | ns / particle-step | Pareto "
          "|\n|---|---|---|---|---|---|---|---|\n";
    for (std::size_t i : idx) {
      const ojson& r = rows[i];
      md << "| " << setting(r) << " | " << r["steps"].dump() << " | "
         << sci(r["dt_min"].get<double>()) << " to " << sci(r["dt_max"].get<double>()) << " | "
         << verdict(r) << " | " << opt_sci(r["max_error_over_time"]) << " | "
         << seconds(r["wall_seconds"].get<double>()) << " | "
         << fixed(r["ns_per_particle_step"].get<double>(), 1) << " | "
         << (front.count(i) ? "**yes**" : "") << " |\n";
    }
    md << "\n";
  }
  return md.str();
}

std::string tradeoff_data_csv(const std::vector<ojson>& rows, const std::string& header_lines) {
  std::ostringstream csv;
  csv << header_lines
      << "# method: 0 mpm, 1 gimp; policy: 0 fixed, 1 cfl, 2 adaptive, 3 min; error empty when "
         "the run failed or its error reached A\nE,method,policy,steps,wall_seconds,error\n";
  for (const auto& r : rows) {
    const std::string p = r["policy"].get<std::string>();
    const int policy = p == "fixed" ? 0 : p == "cfl" ? 1 : p == "adaptive" ? 2 : 3;
    const auto e = accuracy(r);
    csv << shortest(r["E"].get<double>()) << ',' << (r["method"] == "gimp" ? 1 : 0) << ',' << policy
        << ',' << r["steps"].dump() << ',' << csv_cell(r["wall_seconds"]) << ','
        << (e ? shortest(*e) : "") << '\n';
  }
  return csv.str();
}

// The figure draws the first scene; every scene has its own tables.
StudyReport tradeoff_report(const ReportContext& c) {
  StudyReport report;
  const auto scenes = by_scene(c.rows);
  for (std::size_t i = 0; i < scenes.size(); ++i)
    report.markdown += tradeoff_markdown(c.spec, scenes[i].rows, i == 0);
  report.data_csv = tradeoff_data_csv(scenes.front().rows, c.csv_header);
  return report;
}

const StudyRegistration kTradeoff{{
    .name = "tradeoff",
    .summary = "error against cost across methods, time-step policies and their parameters",
    .records = {.error_over_time = true},
    .figure = true,
    .report = tradeoff_report,
    .index =
        [](const Spec& spec, const std::vector<ojson>&) {
          return "![" + spec.title + "](" + spec.name + ".png)\n\n**What it shows.** The cost of " +
                 "each accuracy across methods, time-step policies and their parameters, the "
                 "Pareto "
                 "front and the cheapest setting for each target: [" +
                 spec.name + ".md](" + spec.name + ".md).\n\n";
        },
    .figure_subtitle = [](const Spec& spec,
                          const ojson& doc) { return first_scene_subtitle(spec.name, doc); },
}};

}  // namespace

}  // namespace mpmstab
