// Synthetic result rows and a report context, for testing what a study writes from its rows
// without running the solver.
#pragma once

#include <cmath>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "spec.hpp"
#include "study.hpp"
#include "sweep.hpp"

namespace mpmstab::test_support {

// A stable row of the bar with every column the studies read; tests change what they need.
inline nlohmann::ordered_json study_row(const std::string& method, double E) {
  return {{"method", method},
          {"E", E},
          {"A", 0.015},
          {"dt", 1e-4},
          {"T", 1.0},
          {"cells", 100},
          {"ppc", 2},
          {"shift", 0.0},
          {"jitter", 0.0},
          {"bc", "dirichlet"},
          {"scene", "bar"},
          {"policy", "fixed"},
          {"cfl_factor", nullptr},
          {"safety", nullptr},
          {"outcome", "stable"},
          {"failure_reason", nullptr},
          {"failure_step", nullptr},
          {"failure_time", nullptr},
          {"failure_particle", nullptr},
          {"steps", 10000},
          {"dt_min", 1e-4},
          {"dt_max", 1e-4},
          {"dt_mean", 1e-4},
          {"max_error", 1e-6},
          {"max_error_over_time", 1e-5},
          {"crossings", 0},
          {"dt_stable_min", 1e-5},
          {"dt_cfl", 0.005},
          {"dt_sound", 0.5},
          {"courant", 0.02},
          {"A_over_h", 1.5},     // A / h at A = 0.015 on 100 cells
          {"cT", std::sqrt(E)},  // c T at T = 1
          {"particles", 200}};
}

// Makes a row unstable: `reason` at step 10.
inline void fail_row(nlohmann::ordered_json& r, const std::string& reason) {
  r["outcome"] = "unstable";
  r["failure_reason"] = reason;
  r["failure_step"] = 10;
  r["failure_time"] = 1e-3;
  r["max_error"] = r["max_error_over_time"] = nullptr;
}

// Makes a row meaningless: it survived, but its error over time reached A.
inline void meaningless_row(nlohmann::ordered_json& r) {
  r["outcome"] = "meaningless";
  r["max_error_over_time"] = r["A"];
}

// Follow-up rows given in the order the study's follow_up hook asks for its runs, each tagged
// with what its request was for (the case it serves and its role), as the engine tags them. The
// hook reads each case's parameters: E, T, A and the cells of its row. Rows already tagged stay.
inline std::vector<nlohmann::ordered_json> tagged_follow_ups(
    const Spec& spec, const std::vector<nlohmann::ordered_json>& rows,
    std::vector<nlohmann::ordered_json> follow_up) {
  if (follow_up.empty() || !spec.study->follow_up) return follow_up;
  Spec asking = spec;
  for (const auto& r : rows) {
    CaseSpec c;
    for (auto [key, field] : {std::pair{"E", &c.params.E}, {"T", &c.params.T}, {"A", &c.params.A}})
      if (r.contains(key) && r[key].is_number()) *field = r[key].get<double>();
    if (r.contains("cells") && r["cells"].is_number()) c.params.cells = r["cells"].get<int>();
    asking.cases.push_back(c);
  }
  const StudyInputs inputs;
  const std::vector<FollowUp> asked = spec.study->follow_up(FollowUpContext{asking, rows, inputs});
  for (std::size_t i = 0; i < follow_up.size() && i < asked.size(); ++i) {
    if (follow_up[i].contains(kFollowUpOf)) continue;
    follow_up[i][kFollowUpOf] = asked[i].of == FollowUp::kNoCase
                                    ? nlohmann::ordered_json(nullptr)
                                    : nlohmann::ordered_json(asked[i].of);
    follow_up[i][kFollowUpRole] = asked[i].role;
  }
  return follow_up;
}

// What the study registered under `study` writes for these rows (and these follow-up rows, in
// the order its follow_up hook asks for them).
inline StudyReport study_report(const std::string& study,
                                const std::vector<nlohmann::ordered_json>& rows,
                                const std::vector<nlohmann::ordered_json>& follow_up = {}) {
  Spec spec;
  spec.name = std::string("s");  // moved in: GCC 12 warns (-Wrestrict) on copying a literal
  spec.title = std::string("S");
  spec.study = find_study(study);
  const SweepOutcome outcome;
  const std::filesystem::path out = std::filesystem::temp_directory_path();
  const std::string header = "# header\n";
  const StudyInputs inputs;
  const std::vector<nlohmann::ordered_json> tagged = tagged_follow_ups(spec, rows, follow_up);
  return spec.study->report(ReportContext{spec, rows, outcome, out, header, inputs, tagged});
}

// The data lines of a CSV: neither its '#' lines nor its header.
inline std::vector<std::string> data_lines(const std::string& csv) {
  std::vector<std::string> lines;
  std::istringstream in(csv);
  bool header = true;
  for (std::string line; std::getline(in, line);) {
    if (line.empty() || line[0] == '#') continue;
    if (header) {
      header = false;
      continue;
    }
    lines.push_back(line);
  }
  return lines;
}

// The line of `text` that contains `needle` ("" if none).
inline std::string line_with(const std::string& text, const std::string& needle) {
  const auto at = text.find(needle);
  if (at == std::string::npos) return "";
  const auto begin = text.rfind('\n', at) + 1;
  return text.substr(begin, text.find('\n', at) - begin);
}

}  // namespace mpmstab::test_support
