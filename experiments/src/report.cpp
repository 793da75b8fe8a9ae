#include "report.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

#include "atomic_file.hpp"
#include "cache.hpp"
#include "csv.hpp"
#include "report_util.hpp"
#include "result_json.hpp"
#include "variants.hpp"

namespace mpmstab {

namespace {

using ojson = nlohmann::ordered_json;
namespace fs = std::filesystem;

// ---------------------------------------------------------------------------------------------
// Flat rows: the same columns in the CSV and in the JSON "cases" array.

const std::vector<std::string> kColumns = {
    "method", "E", "A", "dt", "dt_inferred", "T", "cells", "ppc", "bc", "position_update", "scene",
    "walls", "transfer", "flip_fraction", "update", "body_force_time", "policy", "cfl_factor",
    "safety", "dt_stable_sigma", "dt_stable_vnorm", "stable", "failure_reason", "failure_step",
    "failure_time", "meaningless", "steps", "dt_min", "dt_max", "max_error", "max_error_over_time",
    "crossings", "dt_stable_min", "dt_cfl", "dt_sound", "courant", "key",
    // Measurements of the machine: the only columns that differ between identical runs.
    "wall_seconds", "ns_per_particle_step"};
// Before those, in a variants experiment or where a case compares another error than the one at
// T: the variant, the paper's column and which error is compared with it.
const std::vector<std::string> kStudyColumns = {"variant", "paper_method", "error_at"};

// ---------------------------------------------------------------------------------------------
// Provenance of a set of cases: each field's distinct values, in spec order.

ojson aggregate_provenance(const std::vector<ojson>& records) {
  std::vector<std::string> fields = {"commit", "dirty", "compiler", "flags",
                                     "eigen",  "cpu",   "threads"};
  ojson out;
  for (const auto& f : fields) {
    std::vector<std::pair<std::string, int>> values;
    for (const auto& rec : records) {
      const ojson& v = rec["provenance"][f];
      const std::string s = v.is_string() ? v.get<std::string>() : v.dump();
      auto it =
          std::find_if(values.begin(), values.end(), [&](const auto& e) { return e.first == s; });
      if (it == values.end()) {
        values.emplace_back(s, 1);
      } else {
        ++it->second;
      }
    }
    std::string text;
    for (const auto& [value, count] : values) {
      if (!text.empty()) text += "; ";
      text += value;
      if (values.size() > 1) text += " (" + std::to_string(count) + " cases)";
    }
    out[f] = text;
  }
  std::string first, last;
  for (const auto& rec : records) {
    const std::string d = rec["provenance"]["date"].get<std::string>();
    if (first.empty() || d < first) first = d;
    if (last.empty() || d > last) last = d;
  }
  out["date"] = first == last ? first : first + " .. " + last;
  return out;
}

struct Table1Summary {
  int cells = 0, paper_stable = 0, paper_unstable = 0, paper_unknown = 0;
  int ours_stable = 0, ours_meaningless = 0, ours_unstable = 0;
  int verdicts_agree = 0, verdicts_compared = 0;
  int paper_stable_ours_not = 0, paper_stable_ours_not_courant_ge1 = 0;
  int errors_within_3 = 0, errors_compared = 0;
  std::map<std::string, int> reasons;
};

Table1Summary summarize_table1(const Spec& spec, const std::vector<ojson>& rows,
                               const std::map<Table1Key, PaperCell>& paper) {
  Table1Summary s;
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const ojson& r = rows[i];
    ++s.cells;
    const bool ours_stable = r["stable"].get<bool>();
    if (ours_stable) {
      ++s.ours_stable;
      if (r["meaningless"] == true) ++s.ours_meaningless;
    } else {
      ++s.ours_unstable;
      ++s.reasons[r["failure_reason"].get<std::string>()];
    }
    const auto it = paper.find(paper_key(spec.cases[i]));
    if (it == paper.end()) {
      ++s.paper_unknown;
      continue;
    }
    const PaperValue& pe = it->second.max_error;
    if (pe.kind == PaperValue::unreadable) {
      ++s.paper_unknown;
      continue;
    }
    const bool paper_stable = pe.kind == PaperValue::number;
    (paper_stable ? s.paper_stable : s.paper_unstable) += 1;
    ++s.verdicts_compared;
    if (paper_stable == ours_stable) ++s.verdicts_agree;
    if (paper_stable && !ours_stable) {
      ++s.paper_stable_ours_not;
      if (r["courant"].get<double>() >= 1.0) ++s.paper_stable_ours_not_courant_ge1;
    }
    const auto ours = compared_error(r, spec.cases[i].error_at);
    if (paper_stable && ours) {
      ++s.errors_compared;
      if (within_factor_3(*ours, pe.value)) ++s.errors_within_3;
    }
  }
  return s;
}

std::string table1_summary_text(const Table1Summary& s) {
  std::ostringstream md;
  md << s.cells << " cells. Paper: " << s.paper_stable << " stable, " << s.paper_unstable
     << " unstable (`*`), " << s.paper_unknown
     << " unreadable in the transcription. Ours: " << s.ours_stable << " stable ("
     << s.ours_meaningless << " of them meaningless: the error over time reached A), "
     << s.ours_unstable << " unstable";
  if (!s.reasons.empty()) {
    md << " (";
    bool first = true;
    for (const auto& [reason, count] : s.reasons) {
      md << (first ? "" : ", ") << reason << " " << count;
      first = false;
    }
    md << ")";
  }
  md << ". Stability verdicts agree in " << s.verdicts_agree << " of " << s.verdicts_compared
     << " cells; the paper lists as stable " << s.paper_stable_ours_not
     << " cells that are unstable here, " << s.paper_stable_ours_not_courant_ge1
     << " of them at a Courant number c dt / h >= 1. Where both are stable, our max error is "
        "within a factor 3 of the paper's in "
     << s.errors_within_3 << " of " << s.errors_compared << " cells.";
  return md.str();
}

std::string table1_markdown(const Spec& spec, const std::vector<ojson>& rows, const fs::path& out) {
  const auto paper = read_paper_table1(spec);
  bool over_time = false;
  for (const auto& c : spec.cases)
    over_time = over_time || c.error_at == ErrorAt::max_over_time;
  std::ostringstream md;
  md << "## Results\n\n**Summary.** " << table1_summary_text(summarize_table1(spec, rows, paper))
     << "\n\n";
  md << "Legend: `*` unstable (ours: the reason and the step where the run stopped); "
        "*meaningless*: the run survived but its error over time reached the amplitude A; "
        "*inferred*: the paper does not print this cell's dt; *transcription*: the confidence of "
        "the paper value as transcribed in ["
     << link(out, spec.reference) << "](" << link(out, spec.reference)
     << ") (low-confidence cells are data, not truth). dt_stable is the minimum over the run of "
        "eq. (108) (stress "
     << to_string(spec.cases.front().params.stable.sigma) << ", ||v|| "
     << to_string(spec.cases.front().params.stable.vnorm)
     << "). Cost: wall time of the run and ns per particle-step."
     << (over_time ? " Max error ours: at T, or the largest over the run where marked (over time), "
                     "as the case's error_at chooses."
                   : "")
     << "\n\n";

  // Blocks in the order the spec lists them: E, then A.
  std::vector<std::pair<double, double>> blocks;
  for (const auto& c : spec.cases) {
    const std::pair<double, double> b{c.params.E, c.params.A};
    if (std::find(blocks.begin(), blocks.end(), b) == blocks.end()) blocks.push_back(b);
  }
  double current_E = std::nan("");
  for (const auto& [E, A] : blocks) {
    if (E != current_E) {
      md << "### E = " << shortest(E) << "\n\n";
      current_E = E;
    }
    md << "**A = " << shortest(A) << "**\n\n";
    md << "| dt | method | c dt/h | dt_stable paper | dt_stable ours | max error paper | max error "
          "ours | ours / paper | ours: verdict | transcription | cost |\n";
    md << "|---|---|---|---|---|---|---|---|---|---|---|\n";
    for (std::size_t i = 0; i < rows.size(); ++i) {
      const auto& cs = spec.cases[i];
      const auto& p = cs.params;
      if (p.E != E || p.A != A) continue;
      const ojson& r = rows[i];
      const auto it = paper.find(paper_key(cs));
      const PaperCell* pc = it == paper.end() ? nullptr : &it->second;
      const auto ours = compared_error(r, cs.error_at);
      std::string ratio_text = "–";
      if (pc && pc->max_error.kind == PaperValue::number && ours) {
        ratio_text = ratio(*ours / pc->max_error.value);
      }
      md << "| " << param(p.dt) << (cs.dt_inferred ? " (inferred)" : "") << " | "
         << to_string(p.method) << " | " << sci(r["courant"].get<double>()) << " | "
         << (pc ? show(pc->dt_stable) : "–") << " | "
         << (r["stable"].get<bool>() ? opt_sci(r["dt_stable_min"]) : "\\*") << " | "
         << (pc ? show(pc->max_error) : "–") << " | "
         << (!r["stable"].get<bool>() ? std::string("\\*")
             : ours                   ? sci(*ours)
                                      : std::string("–"))
         << (cs.error_at == ErrorAt::max_over_time ? " (over time)" : "") << " | " << ratio_text
         << " | " << verdict(r) << " | " << (pc ? pc->confidence : "not in the paper") << " | "
         << cost(r) << " |\n";
    }
    md << "\n";
  }
  return md.str();
}

// ---------------------------------------------------------------------------------------------
// Table 2.

// Per method: the range of ours / paper over the stable cases, and how many cases failed.
std::string table2_summary_text(const Spec& spec, const std::vector<ojson>& rows) {
  const CsvTable paper = read_csv(spec.reference);
  std::map<std::string, std::pair<double, double>> range;  // method -> min, max ratio
  std::map<std::string, int> compared, unstable;
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const auto& p = spec.cases[i].params;
    const std::string m(to_string(p.method));
    if (!rows[i]["stable"].get<bool>()) {
      ++unstable[m];
      continue;
    }
    for (const auto& row : paper.rows) {
      const std::string col = "crossings_A" + shortest(p.A);
      if (std::stod(row.at("E")) != p.E || !row.count(col)) continue;
      const double r = rows[i]["crossings"].get<double>() / std::stod(row.at(col));
      auto [it, fresh] = range.try_emplace(m, r, r);
      it->second.first = std::min(it->second.first, r);
      it->second.second = std::max(it->second.second, r);
      ++compared[m];
    }
  }
  std::ostringstream md;
  for (const auto& [m, lr] : range) {
    md << "Ours with " << m << " count " << ratio(lr.first) << " to " << ratio(lr.second)
       << " times the paper's crossings in the " << compared[m] << " cases that reach T";
    if (unstable[m]) md << " (" << unstable[m] << " more became unstable before T)";
    md << ". ";
  }
  md << "The paper's dt_sound column is 1/c in every row but E = 1000 (0.03132 printed, 1/c = "
        "0.03162); the grid's speed-of-sound step h/c is 100 times smaller.";
  return md.str();
}

std::string table2_markdown(const Spec& spec, const std::vector<ojson>& rows, const fs::path& out) {
  const CsvTable paper = read_csv(spec.reference);
  std::map<double, std::map<std::string, std::string>> paper_by_E;
  for (const auto& row : paper.rows)
    paper_by_E[std::stod(row.at("E"))] = row;

  std::vector<double> Es, As;
  std::vector<std::string> methods;
  for (const auto& c : spec.cases) {
    if (std::find(Es.begin(), Es.end(), c.params.E) == Es.end()) Es.push_back(c.params.E);
    if (std::find(As.begin(), As.end(), c.params.A) == As.end()) As.push_back(c.params.A);
    const std::string m(to_string(c.params.method));
    if (std::find(methods.begin(), methods.end(), m) == methods.end()) methods.push_back(m);
  }
  auto find_row = [&](double E, double A, const std::string& m) -> const ojson* {
    for (std::size_t i = 0; i < rows.size(); ++i) {
      const auto& p = spec.cases[i].params;
      if (p.E == E && p.A == A && to_string(p.method) == m) return &rows[i];
    }
    return nullptr;
  };
  auto crossings = [](const ojson* r) -> std::string {
    if (!r || !(*r)["crossings"].is_number()) return "–";
    std::string s = std::to_string((*r)["crossings"].get<std::int64_t>());
    if (!(*r)["stable"].get<bool>()) {
      s = "\\* " + s + " (to step " + std::to_string((*r)["failure_step"].get<std::int64_t>()) +
          ")";
    }
    return s;
  };

  std::ostringstream md;
  md << "## Results\n\n**Summary.** " << table2_summary_text(spec, rows)
     << "\n\nCrossings: the number of cell boundaries passed by all particles over the "
        "run (DESIGN.md section 3). `*`: the run became unstable; the count is up to the failure. "
        "The paper's counts are \"approximate\"; its dt and method for them are not stated. Ours "
        "use dt = "
     << param(spec.cases.front().params.dt)
     << " for every E. dt_sound: the paper's column equals 1/c; the speed-of-sound limit of "
        "the grid is h/c. Paper values from ["
     << link(out, spec.reference) << "](" << link(out, spec.reference) << ").\n\n";
  md << "| E |";
  for (double A : As) {
    md << " A = " << shortest(A) << ": paper |";
    for (const auto& m : methods)
      md << " ours " << m << " | " << m << " / paper |";
  }
  md << " dt_sound paper | 1/c | h/c |\n|---|";
  for (std::size_t k = 0; k < As.size() * (1 + 2 * methods.size()); ++k)
    md << "---|";
  md << "---|---|---|\n";
  for (double E : Es) {
    const auto pit = paper_by_E.find(E);
    md << "| " << shortest(E) << " |";
    for (double A : As) {
      std::string paper_count = "–";
      double paper_n = 0;
      if (pit != paper_by_E.end()) {
        const std::string col = "crossings_A" + shortest(A);
        if (pit->second.count(col)) {
          paper_count = pit->second.at(col);
          paper_n = std::stod(paper_count);
        }
      }
      md << " " << paper_count << " |";
      for (const auto& m : methods) {
        const ojson* r = find_row(E, A, m);
        std::string ratio_text = "–";
        if (r && (*r)["stable"].get<bool>() && (*r)["crossings"].is_number() && paper_n > 0) {
          ratio_text = ratio((*r)["crossings"].get<double>() / paper_n);
        }
        md << " " << crossings(r) << " | " << ratio_text << " |";
      }
    }
    const ojson* any = find_row(E, As.front(), methods.front());
    md << " " << (pit != paper_by_E.end() ? pit->second.at("dt_sound") : "–") << " | "
       << (any ? sci((*any)["dt_sound"].get<double>(), 4) : "–") << " | "
       << (any ? sci((*any)["dt_cfl"].get<double>(), 4) : "–") << " |\n";
  }
  md << "\nNotes from the transcription: ";
  for (const auto& row : paper.rows) {
    if (!row.at("note").empty()) md << "E = " << row.at("E") << ": " << row.at("note") << ". ";
  }
  md << "\n\nEvery case: its verdict and cost.\n\n| E | A | method | dt | c dt/h | verdict | "
        "crossings | cost |\n|---|---|---|---|---|---|---|---|\n";
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const auto& p = spec.cases[i].params;
    md << "| " << shortest(p.E) << " | " << shortest(p.A) << " | " << to_string(p.method) << " | "
       << param(p.dt) << " | " << sci(rows[i]["courant"].get<double>()) << " | " << verdict(rows[i])
       << " | " << crossings(&rows[i]) << " | " << cost(rows[i]) << " |\n";
  }
  return md.str();
}

// ---------------------------------------------------------------------------------------------
// A plain table of every case: the parameters that vary, then the measured quantities.

std::string cases_markdown(const Spec& spec, const std::vector<ojson>& rows) {
  // Parameter columns shown: always method, E, A, dt; the others only where cases differ.
  std::vector<std::string> params = {"method", "E", "A", "dt"};
  for (const char* col :
       {"T", "cells", "ppc", "bc", "position_update", "scene", "walls", "transfer", "flip_fraction",
        "update", "body_force_time", "dt_stable_sigma", "dt_stable_vnorm"}) {
    for (const auto& r : rows) {
      if (r[col] != rows.front()[col]) {
        params.push_back(col);
        break;
      }
    }
  }
  const auto& observe = spec.cases.front().params.observe;
  std::ostringstream md;
  int unstable = 0, meaningless = 0;
  for (const auto& r : rows) {
    unstable += r["stable"] == false;
    meaningless += r["meaningless"] == true;
  }
  md << "## Results\n\n"
     << rows.size() << " cases: " << rows.size() - unstable << " stable (" << meaningless
     << " meaningless: the error over time reached A), " << unstable << " unstable.";
  std::string fixed_params;
  for (const char* col :
       {"T", "cells", "ppc", "bc", "position_update", "scene", "walls", "transfer", "flip_fraction",
        "update", "body_force_time", "dt_stable_sigma", "dt_stable_vnorm"}) {
    if (std::find(params.begin(), params.end(), col) != params.end()) continue;
    const ojson& v = rows.front()[col];
    if (v.is_null()) continue;  // not applicable to these runs (flip_fraction without a blend)
    fixed_params += std::string(fixed_params.empty() ? "" : ", ") + col + " = " +
                    (v.is_string() ? v.get<std::string>() : shortest(v.get<double>()));
  }
  md << " Common to all: " << fixed_params << ".\n\n|";
  for (const auto& p : params)
    md << " " << p << " |";
  md << " c dt/h | verdict | max error |";
  if (observe.error_over_time) md << " max error over time | over time / A |";
  if (observe.dt_stable) md << " dt_stable min |";
  if (observe.crossings) md << " crossings |";
  md << " cost |\n|";
  const std::size_t n_cols = params.size() + 4 + (observe.error_over_time ? 2 : 0) +
                             (observe.dt_stable ? 1 : 0) + (observe.crossings ? 1 : 0);
  for (std::size_t k = 0; k < n_cols; ++k)
    md << "---|";
  md << "\n";
  for (const auto& r : rows) {
    md << "|";
    for (const auto& p : params) {
      const ojson& v = r[p];
      md << " "
         << (v.is_string() ? v.get<std::string>()
             : v.is_null() ? std::string("–")
             : p == "dt"   ? param(v.get<double>())
                           : shortest(v.get<double>()))
         << " |";
    }
    md << " " << sci(r["courant"].get<double>()) << " | " << verdict(r) << " | "
       << opt_sci(r["max_error"]) << " |";
    if (observe.error_over_time) {
      md << " " << opt_sci(r["max_error_over_time"]) << " | "
         << (r["max_error_over_time"].is_number() && r["A"].get<double>() > 0
                 ? ratio(r["max_error_over_time"].get<double>() / r["A"].get<double>())
                 : "–")
         << " |";
    }
    if (observe.dt_stable) md << " " << opt_sci(r["dt_stable_min"]) << " |";
    if (observe.crossings) {
      md << " " << (r["crossings"].is_null() ? std::string("–") : r["crossings"].dump()) << " |";
    }
    md << " " << cost(r) << " |\n";
  }
  return md.str();
}

// ---------------------------------------------------------------------------------------------
// Scenes: studies that run more than one scene report each scene in its own section, the first
// scene of the spec (the paper's bar) first and in the figure.

struct SceneRows {
  std::string scene;
  std::vector<ojson> rows;
};

std::vector<SceneRows> by_scene(const std::vector<ojson>& rows) {
  std::vector<SceneRows> groups;
  for (const auto& r : rows) {
    const std::string scene = r["scene"].get<std::string>();
    auto it = std::find_if(groups.begin(), groups.end(),
                           [&](const SceneRows& g) { return g.scene == scene; });
    if (it == groups.end()) it = groups.insert(groups.end(), SceneRows{scene, {}});
    it->rows.push_back(r);
  }
  return groups;
}

std::string scene_title(const std::string& scene) {
  if (scene == "steffen") {
    return "Second scene: Steffen et al. (2008), neo-Hookean, u = A sin(2 pi X) cos(c pi t)";
  }
  if (scene == "bar") return "The paper's bar";
  return "Scene " + scene;
}

// ---------------------------------------------------------------------------------------------
// Stability edge.

std::string edge_summary_text(const std::vector<ojson>& rows) {
  std::map<std::string, std::vector<double>> over_cfl, over_bound;
  int non_monotone = 0, none = 0;
  for (const auto& r : rows) {
    if (!r["dt_edge"].is_number()) {
      ++none;
      continue;
    }
    const std::string m = r["method"].get<std::string>();
    over_cfl[m].push_back(r["dt_edge_over_cfl"].get<double>());
    if (r["dt_edge_over_stable"].is_number()) {
      over_bound[m].push_back(r["dt_edge_over_stable"].get<double>());
    }
    non_monotone += r["monotone"] == false;
  }
  std::ostringstream md;
  for (const auto& [m, v] : over_cfl) {
    const auto [lo, hi] = std::minmax_element(v.begin(), v.end());
    const auto& b = over_bound[m];
    md << m << ": the largest surviving fixed dt is " << ratio(*lo) << " to " << ratio(*hi)
       << " times h/c";
    if (!b.empty()) {
      const auto [blo, bhi] = std::minmax_element(b.begin(), b.end());
      md << " and " << ratio(*blo) << " to " << ratio(*bhi)
         << " times the eq. (108) bound of that run";
    }
    md << ". ";
  }
  md << non_monotone << " of " << rows.size()
     << " searches found stability not monotone in dt (a smaller dt failed where a larger one "
        "survived)";
  if (none) md << "; " << none << " found no surviving dt in the scan";
  md << ".";
  return md.str();
}

std::string opt_ratio(const ojson& v) {
  return v.is_number() ? ratio(v.get<double>()) : "–";
}

// The first scene's section has the figure and explains the search; a further scene's section
// (`first` false) has its own summary and table.
std::string edge_markdown(const Spec& spec, const std::vector<ojson>& rows, bool first = true) {
  std::ostringstream md;
  if (!first) {
    md << "\n## " << scene_title(rows.front()["scene"].get<std::string>()) << "\n\n**Summary.** "
       << edge_summary_text(rows)
       << "\n\n| method | A | E | dt_edge | h/c | dt_edge / (h/c) | eq. (108) at dt_edge | "
          "dt_edge / eq. (108) | max error at dt_edge | monotone | runs | search time |\n"
          "|---|---|---|---|---|---|---|---|---|---|---|---|\n";
  } else {
    md << "## Results\n\n**Summary.** " << edge_summary_text(rows) << "\n\n![" << spec.title << "]("
       << spec.name
       << ".png)\n\nThe search: a scan of dt = (h/c) 2^(k/2) from h/(16c) "
          "to 4h/c, then bisection between the largest surviving and the smallest failing dt to "
          "within 2%. dt_edge is the largest dt found to survive to T; \"eq. (108)\" is the "
          "minimum of the bound over the run at dt_edge. Vector version: ["
       << spec.name << ".svg](" << spec.name << ".svg); data: [" << spec.name << "_data.csv]("
       << spec.name << "_data.csv).\n\n"
       << "| method | A | E | dt_edge | h/c | dt_edge / (h/c) | eq. (108) at dt_edge | dt_edge / "
          "eq. (108) | max error at dt_edge | monotone | runs | search time |\n"
          "|---|---|---|---|---|---|---|---|---|---|---|---|\n";
  }
  for (const auto& r : rows) {
    const bool found = r["dt_edge"].is_number();
    std::string monotone = r["monotone"] == true ? "yes" : "**no**";
    if (r["failed_below_edge"].get<int>() > 0) {
      monotone += " (" + std::to_string(r["failed_below_edge"].get<int>()) + " smaller dt failed)";
    }
    md << "| " << r["method"].get<std::string>() << " | " << shortest(r["A"].get<double>()) << " | "
       << shortest(r["E"].get<double>()) << " | "
       << (found ? sci(r["dt_edge"].get<double>(), 3) : "none") << " | "
       << sci(r["dt_cfl"].get<double>(), 3) << " | " << opt_ratio(r["dt_edge_over_cfl"]) << " | "
       << opt_sci(r["dt_stable_min_at_edge"]) << " | " << opt_ratio(r["dt_edge_over_stable"])
       << " | " << (found ? opt_sci(r["max_error"]) : "–") << " | " << monotone << " | "
       << r["probes"].dump() << " | " << seconds(r["search_seconds"].get<double>()) << " |\n";
  }
  return md.str();
}

std::string edge_data_csv(const std::vector<ojson>& rows, const std::string& header_lines) {
  std::ostringstream csv;
  csv << header_lines
      << "# method: 0 mpm, 1 gimp\nE,method,A,dt_edge,dt_cfl,dt_stable_min_at_edge\n";
  for (const auto& r : rows) {
    csv << shortest(r["E"].get<double>()) << ',' << (r["method"] == "gimp" ? 1 : 0) << ','
        << shortest(r["A"].get<double>()) << ',' << csv_cell(r["dt_edge"]) << ','
        << csv_cell(r["dt_cfl"]) << ',' << csv_cell(r["dt_stable_min_at_edge"]) << '\n';
  }
  return csv.str();
}

// ---------------------------------------------------------------------------------------------
// The speed/accuracy trade.

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

// ---------------------------------------------------------------------------------------------
// The extremes: where and why each method fails.

// 0 stable, 1 stable but meaningless, 2 unstable.
int verdict_code(const ojson& r) {
  if (r["stable"] != true) return 2;
  return r["meaningless"] == true ? 1 : 0;
}

// A stable run's measured quantities must all be finite numbers (JSON has no NaN: a NaN would
// have been written as null).
bool stable_output_is_finite(const ojson& r) {
  for (const char* key : {"max_error", "max_error_over_time", "dt_stable_min", "dt_min", "dt_max",
                          "courant", "wall_seconds"}) {
    if (!r[key].is_number() || !std::isfinite(r[key].get<double>())) return false;
  }
  return r["crossings"].is_number();
}

std::string extremes_markdown(const Spec& spec, const std::vector<ojson>& rows) {
  int stable = 0, meaningless = 0, bad_output = 0;
  double slowest = 0;
  std::string slowest_case;
  std::map<std::string, int> reasons;
  for (const auto& r : rows) {
    const int v = verdict_code(r);
    stable += v == 0;
    meaningless += v == 1;
    if (v == 2) ++reasons[r["failure_reason"].get<std::string>()];
    if (v < 2 && !stable_output_is_finite(r)) ++bad_output;
    if (r["wall_seconds"].get<double>() > slowest) {
      slowest = r["wall_seconds"].get<double>();
      slowest_case = r["method"].get<std::string>() + " E=" + shortest(r["E"].get<double>()) +
                     " A=" + shortest(r["A"].get<double>()) +
                     " dt=" + param(r["dt"].get<double>()) + " cells=" + r["cells"].dump() +
                     " ppc=" + r["ppc"].dump();
    }
  }
  std::ostringstream md;
  md << "## Results\n\n**Summary.** " << rows.size()
     << " cases, every one with a verdict: " << stable << " stable, " << meaningless
     << " stable but meaningless (the error over time "
     << "reached A), " << rows.size() - stable - meaningless << " unstable (";
  bool first = true;
  for (const auto& [reason, n] : reasons) {
    md << (first ? "" : ", ") << reason << " " << n;
    first = false;
  }
  md << "). Stable outputs holding a NaN or an infinity: " << bad_output
     << ". The slowest case took " << seconds(slowest) << " (" << slowest_case << ").\n\n"
     << "![" << spec.title << "](" << spec.name << ".png)\n\nVector version: [" << spec.name
     << ".svg](" << spec.name << ".svg); data: [" << spec.name << "_data.csv](" << spec.name
     << "_data.csv).\n\n";

  // Where and why, per method: by Courant number and by amplitude in cells.
  struct Band {
    const char* name;
    double lo, hi;
  };
  const std::vector<Band> courant_bands = {{"c dt/h < 0.5", 0, 0.5},
                                           {"0.5 <= c dt/h < 1", 0.5, 1},
                                           {"1 <= c dt/h < 10", 1, 10},
                                           {"c dt/h >= 10", 10, 1e300}};
  const std::vector<Band> amplitude_bands = {{"A/h < 1e-3", 0, 1e-3},
                                             {"1e-3 <= A/h < 0.1", 1e-3, 0.1},
                                             {"0.1 <= A/h < 1", 0.1, 1},
                                             {"A/h >= 1 (particles cross cells)", 1, 1e300}};
  auto table = [&](const std::string& method, const std::vector<Band>& bands, bool by_courant) {
    md << "| " << (by_courant ? "Courant number" : "amplitude in cells")
       << " | runs | stable | "
          "meaningless | unstable: reasons |\n|---|---|---|---|---|\n";
    for (const auto& b : bands) {
      int n = 0, s = 0, m = 0;
      std::map<std::string, int> why;
      for (const auto& r : rows) {
        if (r["method"] != method) continue;
        const double x = by_courant ? r["courant"].get<double>()
                                    : r["A"].get<double>() * r["cells"].get<double>();
        if (x < b.lo || x >= b.hi) continue;
        ++n;
        const int v = verdict_code(r);
        s += v == 0;
        m += v == 1;
        if (v == 2) ++why[r["failure_reason"].get<std::string>()];
      }
      md << "| " << b.name << " | " << n << " | " << s << " | " << m << " | ";
      bool f = true;
      for (const auto& [reason, k] : why) {
        md << (f ? "" : ", ") << reason << " " << k;
        f = false;
      }
      md << (why.empty() ? "none" : "") << " |\n";
    }
    md << "\n";
  };
  for (const char* method : {"gimp", "mpm"}) {
    md << "### " << method << "\n\n";
    table(method, courant_bands, true);
    table(method, amplitude_bands, false);
  }
  // The reading, computed: what happens at and above Courant 1, and what the failures below
  // it have in common.
  md << "Reading (computed from the rows): ";
  for (const char* method : {"gimp", "mpm"}) {
    int above = 0, above_failed = 0, below_failed = 0, below_failed_crossing = 0;
    std::int64_t longest_survivor = 0;
    for (const auto& r : rows) {
      if (r["method"] != method) continue;
      const bool failed = r["stable"] != true;
      if (r["courant"].get<double>() >= 1) {
        ++above;
        above_failed += failed;
        if (!failed) longest_survivor = std::max(longest_survivor, r["steps"].get<std::int64_t>());
      } else if (failed) {
        ++below_failed;
        below_failed_crossing += r["A"].get<double>() * r["cells"].get<double>() >= 1;
      }
    }
    md << method << ": " << above_failed << " of " << above
       << " runs at c dt/h >= 1 fail; the ones that survive ran " << longest_survivor
       << " steps at most (T is short there), too few for the instability to grow. Below "
          "Courant 1, "
       << below_failed << " runs fail, " << below_failed_crossing << " of them with A/h >= 1, "
       << "where particles cross cells. ";
  }
  md << "\n\n";
  md << "### Every case\n\n| method | bc | E | A | dt | T | cells | ppc | c dt/h | verdict | "
        "max error over time | cost |\n|---|---|---|---|---|---|---|---|---|---|---|---|\n";
  for (const auto& r : rows) {
    md << "| " << r["method"].get<std::string>() << " | " << r["bc"].get<std::string>() << " | "
       << shortest(r["E"].get<double>()) << " | " << shortest(r["A"].get<double>()) << " | "
       << param(r["dt"].get<double>()) << " | " << param(r["T"].get<double>()) << " | "
       << r["cells"].dump() << " | " << r["ppc"].dump() << " | " << sci(r["courant"].get<double>())
       << " | " << verdict(r) << " | " << opt_sci(r["max_error_over_time"]) << " | " << cost(r)
       << " |\n";
  }
  return md.str();
}

std::string extremes_data_csv(const std::vector<ojson>& rows, const std::string& header_lines) {
  std::ostringstream csv;
  csv << header_lines
      << "# method: 0 mpm, 1 gimp; verdict: 0 stable, 1 meaningless, 2 unstable\n"
         "method,courant,A_over_h,verdict\n";
  for (const auto& r : rows) {
    csv << (r["method"] == "gimp" ? 1 : 0) << ',' << shortest(r["courant"].get<double>()) << ','
        << shortest(r["A"].get<double>() * r["cells"].get<double>()) << ',' << verdict_code(r)
        << '\n';
  }
  return csv.str();
}

// ---------------------------------------------------------------------------------------------
// Figures.

std::string figure_markdown(const Spec& spec, const std::vector<ojson>& rows) {
  const ojson& r = rows.front();
  const auto& p = spec.cases.front().params;
  std::ostringstream md;
  md << "## Results\n\n![" << spec.title << "](" << spec.name << ".png)\n\n";
  md << "Vector version: [" << spec.name << ".svg](" << spec.name << ".svg); data: [" << spec.name
     << "_data.csv](" << spec.name << "_data.csv).\n\n";
  md << "| method | E | A | dt | c dt/h | steps | verdict | max error at end | max error over "
        "time | dt_stable min | crossings | cost |\n|---|---|---|---|---|---|---|---|---|---|---|"
        "---|\n";
  md << "| " << to_string(p.method) << " | " << shortest(p.E) << " | " << shortest(p.A) << " | "
     << param(p.dt) << " | " << sci(r["courant"].get<double>()) << " | " << r["steps"].dump()
     << " of " << *step_count(p.T, p.dt) << " | " << verdict(r) << " | " << opt_sci(r["max_error"])
     << " | " << opt_sci(r["max_error_over_time"]) << " | " << opt_sci(r["dt_stable_min"]) << " | "
     << (r["crossings"].is_null() ? std::string("–") : r["crossings"].dump()) << " | " << cost(r)
     << " |\n";
  return md.str();
}

std::string figure_data_csv(const ojson& record, const std::string& header_lines) {
  std::ostringstream csv;
  csv << header_lines;
  auto cell = [](const ojson& v) {
    return v.is_null() ? std::string() : shortest(v.get<double>());
  };
  if (record.contains("final_state")) {
    const ojson& f = record["final_state"];
    csv << "# particle state at t = " << shortest(f["time"].get<double>()) << "\n";
    csv << "X,x,u,u_exact,v,v_exact,sigma,sigma_exact\n";
    for (std::size_t i = 0; i < f["X"].size(); ++i) {
      const ojson& x = f["x"][i];
      const std::string u =
          x.is_null() ? std::string() : shortest(x.get<double>() - f["X"][i].get<double>());
      csv << cell(f["X"][i]) << ',' << cell(x) << ',' << u << ',' << cell(f["u_exact"][i]) << ','
          << cell(f["v"][i]) << ',' << cell(f["v_exact"][i]) << ',' << cell(f["sigma"][i]) << ','
          << cell(f["sigma_exact"][i]) << '\n';
    }
  } else if (record.contains("history")) {
    csv << "step,time,error,dt_stable,crossings\n";
    for (const auto& h : record["history"]) {
      csv << h["step"].dump() << ',' << cell(h["time"]) << ',' << cell(h["error"]) << ','
          << cell(h["dt_stable"]) << ',' << (h["crossings"].is_null() ? "" : h["crossings"].dump())
          << '\n';
    }
  }
  return csv.str();
}

std::string provenance_lines(const ojson& prov) {
  std::ostringstream s;
  s << "# commit: " << prov["commit"].get<std::string>()
    << (prov["dirty"] == "false" ? "" : " (dirty: " + prov["dirty"].get<std::string>() + ")")
    << "\n# compiler: " << prov["compiler"].get<std::string>()
    << "\n# flags: " << prov["flags"].get<std::string>()
    << "\n# eigen: " << prov["eigen"].get<std::string>()
    << "\n# date: " << prov["date"].get<std::string>()
    << "\n# cpu: " << prov["cpu"].get<std::string>()
    << "\n# threads: " << prov["threads"].get<std::string>() << "\n";
  return s.str();
}

std::string provenance_markdown(const ojson& prov, const ojson& sweep) {
  std::ostringstream md;
  md << "## Provenance\n\n| | |\n|---|---|\n";
  for (const auto& [k, v] : prov.items())
    md << "| " << k << " | " << v.get<std::string>() << " |\n";
  md << "| compute time | " << seconds(sweep["compute_seconds"].get<double>())
     << " summed over the cases (each timed when it was computed) |\n";
  md << "| sweep wall time | " << seconds(sweep["wall_seconds"].get<double>())
     << " (the last sweep that computed a case) |\n";
  return md.str();
}

}  // namespace

// Extra columns of an edge experiment (the search), after the columns of the run at dt_edge.
const std::vector<std::string> kEdgeColumns = {"dt_edge",
                                               "dt_fail",
                                               "dt_edge_over_cfl",
                                               "dt_stable_min_at_edge",
                                               "dt_edge_over_stable",
                                               "monotone",
                                               "failed_below_edge",
                                               "probes",
                                               "search_seconds"};

ojson flat_row(const CaseSpec& c, const ojson& record) {
  const ojson& r = record["result"];
  ojson row, params;
  row["variant"] = c.variant;
  row["paper_method"] = to_string(c.paper_method);
  row["error_at"] = to_string(c.error_at);
  for (const auto& col : kColumns) {
    if (col == "dt_inferred") {
      row[col] = c.dt_inferred;
    } else if (col == "failure_reason" || col == "failure_step" || col == "failure_time") {
      row[col] = r["failure"].is_null() ? ojson(nullptr) : r["failure"][col.substr(8)];
    } else if (col == "key") {
      row[col] = case_key(c.params);
    } else if (r.contains(col)) {
      row[col] = r[col];
    } else {
      // A record cached before this column existed: a parameter is read from the case (the
      // cache key guarantees the record ran with it), a measurement stays missing.
      if (params.is_null()) {
        RunResult with_params;
        with_params.params = c.params;
        params = to_json(with_params);
      }
      const auto& names = parameter_names();
      const bool is_param = std::find(names.begin(), names.end(), col) != names.end();
      row[col] = is_param && params.contains(col) ? params[col] : ojson(nullptr);
    }
  }
  if (record.contains("edge")) {
    const ojson& e = record["edge"];
    for (const auto& col : kEdgeColumns) {
      if (col == "failed_below_edge") {
        row[col] = e[col].size();
      } else if (col == "probes") {
        row[col] = e[col].size();
      } else if (col == "search_seconds") {
        row[col] = e["wall_seconds"];
      } else {
        row[col] = e[col];
      }
    }
  }
  return row;
}

std::string csv_cell(const ojson& v) {
  if (v.is_null()) return "";
  if (v.is_boolean()) return v.get<bool>() ? "true" : "false";
  if (v.is_number_float()) return shortest(v.get<double>());
  if (v.is_number()) return v.dump();
  return csv_field(v.get<std::string>());
}

namespace {

bool has_study_columns(const Spec& spec) {
  if (spec.report == ReportKind::variants) return true;
  for (const auto& c : spec.cases) {
    if (c.error_at != ErrorAt::T) return true;
  }
  return false;
}

}  // namespace

std::vector<std::string> result_columns(const Spec& spec) {
  std::vector<std::string> columns;
  if (has_study_columns(spec)) columns = kStudyColumns;
  columns.insert(columns.end(), kColumns.begin(), kColumns.end());
  return columns;
}

void write_if_changed(const fs::path& path, const std::string& content) {
  if (fs::exists(path) && read_file(path) == content) return;
  write_file_atomically(path, content);
}

void write_reports(const Spec& spec, const SweepOutcome& outcome, const fs::path& out) {
  fs::create_directories(out);
  std::vector<ojson> rows;
  const bool study_columns = has_study_columns(spec);
  for (std::size_t i = 0; i < spec.cases.size(); ++i) {
    rows.push_back(flat_row(spec.cases[i], outcome.records[i]));
    if (!study_columns) {
      for (const auto& col : kStudyColumns)
        rows.back().erase(col);
    }
  }
  const std::vector<std::string> columns = result_columns(spec);
  const ojson prov = aggregate_provenance(outcome.records);

  // Timing of the sweep: a rerun served from the cache keeps the figure of the sweep that
  // computed the results, so that reports do not change when nothing was computed.
  double compute_seconds = 0;
  for (const auto& r : rows) {
    // An edge case's cost is its whole search, not the one run at dt_edge.
    compute_seconds +=
        (r.contains("search_seconds") ? r["search_seconds"] : r["wall_seconds"]).get<double>();
  }
  double sweep_wall = outcome.wall_seconds;
  const fs::path json_path = out / (spec.name + ".json");
  if (outcome.computed == 0 && !outcome.merged && !outcome.timing_omitted) {
    try {
      const ojson previous = ojson::parse(read_file(json_path));
      sweep_wall = previous.at("sweep").at("wall_seconds").get<double>();
    } catch (const std::exception&) {
    }
  }
  const ojson sweep = {
      {"cases", rows.size()}, {"compute_seconds", compute_seconds}, {"wall_seconds", sweep_wall}};

  const std::string spec_path = spec.path.generic_string();
  std::string header = "# experiment: " + spec.name + " (" + spec_path +
                       ")\n# title: " + spec.title + "\n" + provenance_lines(prov);

  // CSV: one row per case.
  std::ostringstream csv;
  csv << header
      << (outcome.timing_omitted
              ? "# machine measurements omitted (--timing omit): wall_seconds and "
                "ns_per_particle_step read 0.\n"
              : "# wall_seconds and ns_per_particle_step are measurements of the machine; every "
                "other column is the same for the same spec whatever the number of jobs.\n");
  for (std::size_t c = 0; c < columns.size(); ++c)
    csv << (c ? "," : "") << columns[c];
  csv << "\n";
  for (const auto& row : rows) {
    for (std::size_t c = 0; c < columns.size(); ++c) {
      csv << (c ? "," : "") << csv_cell(row[columns[c]]);
    }
    csv << "\n";
  }
  write_if_changed(out / (spec.name + ".csv"), csv.str());

  // The variants study reads the courant scan of the same folder (for the class above-our-edge).
  std::optional<VariantsStudy> study;
  bool have_courant = false;
  if (spec.report == ReportKind::variants) {
    CourantEdges edges;
    if (const std::string text = read_file(out / "courant.json"); !text.empty()) {
      const ojson courant = ojson::parse(text);
      edges = courant_edges(std::vector<ojson>(courant["cases"].begin(), courant["cases"].end()));
      have_courant = true;
    }
    study = study_variants(spec, rows, read_paper_table1(spec), edges);
  }

  // JSON: the same content.
  ojson doc;
  doc["experiment"] = spec.name;
  doc["title"] = spec.title;
  doc["spec"] = spec_path;
  doc["report"] = to_string(spec.report);
  doc["provenance"] = prov;
  doc["sweep"] = sweep;
  doc["cases"] = rows;
  if (study) doc["study"] = study_to_json(*study);
  write_if_changed(json_path, doc.dump(2) + "\n");

  // Markdown.
  std::ostringstream md;
  md << "# " << spec.title << "\n\n"
     << spec.description << "\n\nSpec: [`" << spec_path << "`](" << link(out, spec.path)
     << ") · data: [" << spec.name << ".csv](" << spec.name << ".csv), [" << spec.name << ".json]("
     << spec.name << ".json) · generated by `make reproduce`.\n\n";
  switch (spec.report) {
    case ReportKind::table1:
      md << table1_markdown(spec, rows, out);
      break;
    case ReportKind::table2:
      md << table2_markdown(spec, rows, out);
      break;
    case ReportKind::cases:
      md << cases_markdown(spec, rows);
      break;
    case ReportKind::extremes:
      md << extremes_markdown(spec, rows);
      write_if_changed(out / (spec.name + "_data.csv"), extremes_data_csv(rows, header));
      break;
    case ReportKind::tradeoff: {
      // The figure draws the first scene; every scene has its own tables.
      const auto scenes = by_scene(rows);
      for (std::size_t i = 0; i < scenes.size(); ++i)
        md << tradeoff_markdown(spec, scenes[i].rows, i == 0);
      write_if_changed(out / (spec.name + "_data.csv"),
                       tradeoff_data_csv(scenes.front().rows, header));
      break;
    }
    case ReportKind::edge: {
      const auto scenes = by_scene(rows);
      for (std::size_t i = 0; i < scenes.size(); ++i)
        md << edge_markdown(spec, scenes[i].rows, i == 0);
      write_if_changed(out / (spec.name + "_data.csv"), edge_data_csv(scenes.front().rows, header));
      break;
    }
    case ReportKind::variants:
      md << variants_markdown(spec, *study, have_courant);
      write_if_changed(out / (spec.name + "_data.csv"), variants_data_csv(*study, header));
      break;
    case ReportKind::figure:
      md << figure_markdown(spec, rows);
      write_if_changed(out / (spec.name + "_data.csv"),
                       figure_data_csv(outcome.records.front(), header));
      break;
  }
  md << "\n" << provenance_markdown(prov, sweep);
  write_if_changed(out / (spec.name + ".md"), md.str());
}

void write_index(const std::vector<Spec>& specs, const fs::path& out) {
  std::ostringstream md;
  md << "# mpmstab results\n\n"
        "Regenerated by `make reproduce` from the specs in [`experiments/`](../experiments/): "
        "the experiments of M. Berzins, *Nonlinear stability and time step selection for the MPM "
        "method*, rerun with this project's solver and set beside the paper's values. Every "
        "number below is read from the files it links to.\n\n";
  md << "**Performance:** [performance.md](performance.md): the step kernel's benchmark, what "
        "each measured quantity costs, and the wall time of every experiment.\n\n";
  md << "**Against the paper:** [comparison.md](comparison.md) sets every Table 1 cell beside "
        "the paper's, with a verdict, and explains each class of disagreement with an "
        "experiment.\n\n";
  md << "| experiment | report | data | cases | unstable | compute time | sweep wall time |\n"
        "|---|---|---|---|---|---|---|\n";
  std::vector<std::pair<const Spec*, ojson>> docs;
  for (const auto& spec : specs) {
    const std::string text = read_file(out / (spec.name + ".json"));
    if (text.empty()) {
      md << "| " << spec.title << " | not generated | | | | | |\n";
      continue;
    }
    const ojson doc = ojson::parse(text);
    int unstable = 0;
    for (const auto& c : doc["cases"])
      unstable += c["stable"] == false;
    md << "| " << spec.title << " | [" << spec.name << ".md](" << spec.name << ".md) | ["
       << spec.name << ".csv](" << spec.name << ".csv), [" << spec.name << ".json](" << spec.name
       << ".json) | " << doc["cases"].size() << " | " << unstable << " | "
       << seconds(doc["sweep"]["compute_seconds"].get<double>()) << " | "
       << seconds(doc["sweep"]["wall_seconds"].get<double>()) << " |\n";
    docs.emplace_back(&spec, doc);
  }
  md << "\n";
  for (const auto& [spec, doc] : docs) {
    md << "## " << spec->title << "\n\n" << spec->description << "\n\n";
    std::vector<ojson> rows(doc["cases"].begin(), doc["cases"].end());
    if (spec->report == ReportKind::table1) {
      const auto paper = read_paper_table1(*spec);
      md << "**What it shows.** " << table1_summary_text(summarize_table1(*spec, rows, paper))
         << " Full table with the paper's values beside ours: [" << spec->name << ".md]("
         << spec->name << ".md).\n\n";
    } else if (spec->report == ReportKind::table2) {
      md << "**What it shows.** Our crossing counts beside the paper's approximate ones, per E "
            "and A, and both readings of dt_sound: ["
         << spec->name << ".md](" << spec->name << ".md).\n\n";
    } else if (spec->report == ReportKind::extremes) {
      int unstable = 0;
      for (const auto& r : rows)
        unstable += r["stable"] == false;
      md << "![" << spec->title << "](" << spec->name << ".png)\n\n**What it shows.** "
         << rows.size() << " cases at the extremes, each with a verdict (" << unstable
         << " unstable); per method, where and why it fails: [" << spec->name << ".md]("
         << spec->name << ".md).\n\n";
    } else if (spec->report == ReportKind::tradeoff) {
      md << "![" << spec->title << "](" << spec->name << ".png)\n\n**What it shows.** The cost "
         << "of each accuracy across methods, time-step policies and their parameters, the "
            "Pareto front and the cheapest setting for each target: ["
         << spec->name << ".md](" << spec->name << ".md).\n\n";
    } else if (spec->report == ReportKind::edge) {
      md << "![" << spec->title << "](" << spec->name << ".png)\n\n**What it shows.** ";
      for (const auto& scene : by_scene(rows))
        md << "*" << scene_title(scene.scene) << ".* " << edge_summary_text(scene.rows) << " ";
      md << "Details: [" << spec->name << ".md](" << spec->name << ".md).\n\n";
    } else if (spec->report == ReportKind::variants) {
      md << "![" << spec->title << "](" << spec->name << ".png)\n\n**What it shows.** "
         << spec->variants.size()
         << " variants of Table 1's cells, each a documented implementation choice (or a pair) "
            "changed from the default; per variant and method the agreement with the paper and "
            "the cost, and which choices can or cannot account for each class of disagreement: ["
         << spec->name << ".md](" << spec->name << ".md).\n\n";
    } else if (spec->report == ReportKind::cases) {
      int unstable = 0, meaningless = 0;
      for (const auto& r : rows) {
        unstable += r["stable"] == false;
        meaningless += r["meaningless"] == true;
      }
      md << "**What it shows.** " << rows.size() << " cases, " << unstable << " unstable, "
         << meaningless << " meaningless; it supports the explanations in [comparison.md]"
         << "(comparison.md). Full table: [" << spec->name << ".md](" << spec->name << ".md).\n\n";
    } else {
      const ojson& r = rows.front();
      md << "![" << spec->title << "](" << spec->name << ".png)\n\n**What it shows.** This run "
         << (r["stable"] == true ? "reached T" : "did not reach T") << ": " << verdict(r) << "; "
         << r["steps"].dump() << " steps, max error over time " << opt_sci(r["max_error_over_time"])
         << ", eq. (108) minimum " << opt_sci(r["dt_stable_min"])
         << " against dt = " << param(r["dt"].get<double>()) << ". Details: [" << spec->name
         << ".md](" << spec->name << ".md).\n\n";
    }
    md << "Provenance: commit " << doc["provenance"]["commit"].get<std::string>() << ", "
       << doc["provenance"]["date"].get<std::string>() << ", "
       << doc["provenance"]["cpu"].get<std::string>() << ", "
       << doc["provenance"]["threads"].get<std::string>() << " threads; computed in "
       << seconds(doc["sweep"]["compute_seconds"].get<double>()) << " of case time.\n\n";
  }
  write_if_changed(out / "README.md", md.str());
}

}  // namespace mpmstab
