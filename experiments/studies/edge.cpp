// The stability edge: per case, the largest fixed dt that survives to T, against h/c and the
// eq. (108) bound, one section per scene.
#include <algorithm>
#include <map>
#include <sstream>

#include "csv.hpp"
#include "report.hpp"
#include "report_util.hpp"
#include "scenes.hpp"
#include "study.hpp"

namespace mpmstab {

namespace {

using ojson = nlohmann::ordered_json;

// Per method, the range of the edge over h/c and over the eq. (108) bound; how many searches
// found stability not monotone in dt, and how many found no surviving dt.
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

// Per case: the edge found, against h/c and the eq. (108) bound at that dt, and what the search
// cost.
std::string edge_table(const std::vector<ojson>& rows) {
  std::ostringstream md;
  md << "| method | A | E | dt_edge | h/c | dt_edge / (h/c) | eq. (108) at dt_edge | "
        "dt_edge / eq. (108) | max error at dt_edge | monotone | runs | search time |\n"
        "|---|---|---|---|---|---|---|---|---|---|---|---|\n";
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

// One scene's section: the first scene's has the figure and explains the search; a further
// scene's (`first` false) is headed by the scene. Each has its own summary and table.
std::string edge_markdown(const Spec& spec, const std::vector<ojson>& rows, bool first) {
  std::ostringstream md;
  if (!first) {
    md << "\n## " << scene_title(rows.front()["scene"].get<std::string>()) << "\n\n**Summary.** "
       << edge_summary_text(rows) << "\n\n";
  } else {
    md << "## Results\n\n**Summary.** " << edge_summary_text(rows) << "\n\n![" << spec.title << "]("
       << spec.name
       << ".png)\n\nThe search: a scan of dt = (h/c) 2^(k/2) from h/(16c) "
          "to 4h/c, then bisection between the largest surviving and the smallest failing dt to "
          "within 2%. dt_edge is the largest dt found to survive to T; \"eq. (108)\" is the "
          "minimum of the bound over the run at dt_edge. Vector version: ["
       << spec.name << ".svg](" << spec.name << ".svg); data: [" << spec.name << "_data.csv]("
       << spec.name << "_data.csv).\n\n";
  }
  md << edge_table(rows);
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

std::string edge_index(const Spec& spec, const std::vector<ojson>& rows) {
  std::ostringstream md;
  md << "![" << spec.title << "](" << spec.name << ".png)\n\n**What it shows.** ";
  for (const auto& scene : by_scene(rows))
    md << "*" << scene_title(scene.scene) << ".* " << edge_summary_text(scene.rows) << " ";
  md << "Details: [" << spec.name << ".md](" << spec.name << ".md).\n\n";
  return md.str();
}

const StudyRegistration kEdge{{
    .name = "edge",
    .summary = "the largest fixed dt that survives to T, per case (a search over dt)",
    .work = CaseWork::edge_search,
    .records = {.error_over_time = true},
    .figure = true,
    .report =
        [](const ReportContext& c) { return report_by_scene(c, edge_markdown, edge_data_csv); },
    .index = edge_index,
    .figure_subtitle = first_scene_subtitle,
}};

}  // namespace

}  // namespace mpmstab
