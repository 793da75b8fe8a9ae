#include "publish/documents.hpp"

#include <algorithm>
#include <sstream>

#include "agreement/comparison.hpp"
#include "choice/advice_rule.hpp"
#include "choice/advice_verify.hpp"
#include "csv.hpp"
#include "files.hpp"
#include "performance.hpp"
#include "publish/verdicts.hpp"
#include "report_util.hpp"
#include "run/run.hpp"
#include "run_summary.hpp"
#include "strict_json.hpp"

namespace mpmstab {

namespace studies::documents {
namespace {

using ojson = nlohmann::ordered_json;

// The results file `name` of `results`, or null where it is absent.
ojson results_file(const std::filesystem::path& results, const std::string& name) {
  const auto path = results / name;
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) return nullptr;
  return read_json_file(path);
}

// ---------------------------------------------------------------------------------------------
// The blocks

// README.md: the last published fresh build (`make`) and each tier's last published wall time and
// work, from results/timings.json.
std::string tier_times(const std::filesystem::path& results) {
  const ojson t = results_file(results, "timings.json");
  if (t.is_null())
    return "results/timings.json is not published yet: `make timings` publishes the timings of "
           "the last runs.\n";
  std::ostringstream md;
  md << "| command | wall time | work | CPU time | cores | CPU | commit |\n"
        "|---|---|---|---|---|---|---|\n";
  // Each command's last run on this machine, then its last run on each other machine that
  // published ("(make reproduce on <cpu>)", performance.cpp).
  const std::vector<std::string> commands = {"make", "make reproduce", "make studies"};
  std::vector<std::pair<std::string, const ojson*>> runs;
  for (const std::string& tier : commands) {
    const std::string key = "(" + tier + ")";
    if (t.contains(key) && t[key].is_object()) runs.emplace_back("`" + tier + "`", &t[key]);
  }
  for (const std::string& tier : commands)
    for (const auto& [key, e] : t.items())
      if (key.starts_with("(" + tier + " on ") && e.is_object())
        runs.emplace_back("`" + tier + "`", &e);
  for (const auto& [name, entry] : runs) {
    const ojson& e = *entry;
    auto number = [&](const char* key) { return number_or_zero(e, key); };
    md << "| " << name << " | " << seconds(number("wall_seconds")) << " | ";
    if (name == "`make`") {
      md << "a fresh build of the tool | – | ";
    } else {
      md << sci(number("particle_steps")) << " particle-steps; "
         << static_cast<long long>(number("computed")) << " of "
         << static_cast<long long>(number("cases")) << " cases computed";
      if (const ReportRuns reports = report_runs_of(e); reports.recorded)
        md << ", and " << reports.runs << " runs of its reports";
      md << " | " << seconds(number("compute_seconds")) << " | ";
    }
    md << static_cast<long long>(number("threads")) << " | "
       << (e.contains("cpu") ? machine_of(e) : "–") << " | "
       << (e.contains("commit") && e["commit"].is_string()
               ? e["commit"].get<std::string>().substr(0, 7)
               : "–")
       << " |\n";
  }
  md << "\nA tier's wall time runs from the start of its queue of runs to its last report; the "
        "figures, the index and the documents that `make` writes after it are not counted. Its "
        "work and CPU time sum the runs it computed: the cases and follow-up runs of its queue "
        "and, where its row counts them, the runs its reports make themselves (the advice "
        "sample's searches); a row that does not count them was measured before they were "
        "counted, and leaves them out. "
        "`make`'s runs from configuring a new build folder to the linked tool, the installation "
        "of Debian packages excluded.\n";
  // The studies tier's largest experiments by CPU time: where its time goes.
  std::vector<std::pair<double, std::string>> cpu;
  double total = 0;
  for (const auto& [name, e] : t.items()) {
    if (name.empty() || name.front() == '(' || !e.is_object() || !e.contains("compute_seconds") ||
        !e["compute_seconds"].is_number())
      continue;
    cpu.emplace_back(e["compute_seconds"].get<double>(), name);
    total += e["compute_seconds"].get<double>();
  }
  std::sort(cpu.rbegin(), cpu.rend());
  if (total > 0 && !cpu.empty()) {
    md << "\nThe experiments with the most CPU time in those runs: ";
    for (std::size_t k = 0; k < cpu.size() && k < 3; ++k)
      md << (k ? ", " : "") << cpu[k].second << " " << fixed(100 * cpu[k].first / total, 0) << "%";
    md << " of the " << seconds(total)
       << " of CPU time that the experiments' cases took in their last published runs (their "
          "follow-up runs not included; [results/performance.md](results/performance.md) counts "
          "them).\n";
  }
  return md.str();
}

// README.md: `mpmstab advise` on the example problem, answered from results/advice.json.
std::string advise_example(const std::filesystem::path& results) {
  const ojson doc = results_file(results, "advice.json");
  const Problem p{.A = 0.015, .cT = 8, .target = 0.01};  // the problem of README.md's example
  std::ostringstream md;
  md << "```\n$ build/mpmstab advise --A " << value_text(p.A) << " --cT " << value_text(p.cT)
     << " --error " << value_text(p.target) << "\n";
  if (doc.is_null() || !doc.contains("study") || !doc["study"].contains("settings")) {
    md << "(results/advice.json is not there yet: make studies writes it)\n```\n";
    return md.str();
  }
  const std::vector<CheckedSetting> settings = checked_settings_of(doc);
  // The search with the default budget (particle-steps: the same answer on any machine). The
  // seconds, which vary, are left out.
  const VerifyProblem vp{.problem = p};
  const Verified v = verified_advice(settings, vp, kAdviceDomain.budget_particle_steps, true,
                                     [](const RunParams& params) { return run(params); });
  md << verified_text(v, vp, false) << "```\n";
  return md.str();
}

// README.md: `mpmstab run` on one case of Table 1, its text summary as the command prints it
// (without the wall time, which varies from run to run).
std::string run_example() {
  const RunParams p{.method = Method::gimp, .E = 4, .A = 0.015, .dt = 1e-3};
  std::ostringstream md;
  md << "```\n$ build/mpmstab run --method " << to_string(p.method) << " --E " << shortest(p.E)
     << " --A " << shortest(p.A) << " --dt " << value_text(p.dt) << "\n"
     << text_summary(run(p), false)
     << "  (then wall_seconds and ns/particle-step, which vary from run to run)\n```\n";
  return md.str();
}

// docs/studies.md: the domain and the constants of the verified advice, from AdviceDomain.
std::string advice_domain_table() {
  const AdviceDomain& d = kAdviceDomain;
  std::ostringstream md;
  std::string grids;
  for (const int n : d.cells)
    grids += (grids.empty() ? "" : ", ") + std::to_string(n);
  md << "| what | value |\n|---|---|\n"
     << "| A / L | " << value_text(d.A_min) << " to " << value_text(d.A_max) << " |\n"
     << "| c T / L | at most " << value_text(d.cT_max) << ", and a verdict: at least "
     << kMinStepsToJudge << " steps |\n"
     << "| target error over time / A | " << value_text(d.target_min) << " to "
     << value_text(d.target_max) << " |\n"
     << "| jitter, of the particle spacing | at most " << value_text(d.jitter_max) << " |\n"
     << "| grids, cells | " << grids << " |\n"
     << "| a verifying run's length: `length_factor` x c T | " << shortest(d.length_factor)
     << " |\n"
     << "| the grid check: `grid_factor` x the cells | " << d.grid_factor << " |\n"
     << "| candidates' particles per cell: the setting's and `more_ppc` | " << d.more_ppc << " |\n"
     << "| a matching run: A within a factor; a jitter within a factor | "
     << shortest(d.match_A_factor) << "; " << shortest(d.match_jitter_factor) << " |\n"
     << "| the default budget, particle-steps | " << sci(d.budget_particle_steps) << " |\n"
     << "| the margins: C stepped by, up to; bisected to a factor | " << significant(d.edge_step, 4)
     << ", " << shortest(d.edge_top) << "; " << shortest(d.edge_tolerance) << " |\n";
  return md.str();
}

// docs/studies.md: what the advice study found, in counts.
std::string advice_counts(const std::filesystem::path& results) {
  const ojson doc = results_file(results, "advice.json");
  if (doc.is_null() || !doc.contains("study") || !doc["study"].contains("settings"))
    return "(results/advice.json is not there yet: make studies writes it.)\n";
  int settings = 0, checked = 0, longest = 0;
  for (const auto& j : doc["study"]["settings"]) {
    const CheckedSetting s = checked_setting_from_json(j);
    ++settings;
    checked += s.corners.size() > 1;
    longest += !s.regions.empty() && s.regions.back().length == kRegionRule.lengths.back();
  }
  std::ostringstream md;
  md << "In the last run of the advice study, " << checked << " of its " << settings
     << " settings had an accurate base run within the margin and were run at their corners, "
        "and "
     << longest << " have a region to c T/L = " << value_text(kRegionRule.lengths.back())
     << " (results/advice.md).\n";
  return md.str();
}

// docs/theory.md: cells per wavelength for a 1% phase error, per scheme and C, from
// results/dispersion.json.
std::string cells_per_wavelength(const std::filesystem::path& results) {
  const ojson doc = results_file(results, "dispersion.json");
  if (doc.is_null() || !doc.contains("study") || !doc["study"].contains("cells_per_wavelength"))
    return "(results/dispersion.json is not there yet: make studies writes it.)\n";
  std::vector<std::string> schemes;
  std::vector<double> courants;
  std::map<std::pair<std::string, double>, std::string> cell;
  for (const auto& e : doc["study"]["cells_per_wavelength"]) {
    if (!e.is_object() || !e.contains("method") || !e["method"].is_string() ||
        !e.contains("courant") || !e["courant"].is_number())
      continue;
    const std::string m = e["method"].get<std::string>();
    const double C = e["courant"].get<double>();
    add_unique(schemes, m);
    add_unique(courants, C);
    const bool below = e.value("below_limit", false);
    cell[{m, C}] = !below ? "above the limit"
                   : e["cells_per_wavelength_1pct"].is_number()
                       ? fixed(e["cells_per_wavelength_1pct"].get<double>(), 1)
                       : "none";
  }
  std::sort(courants.begin(), courants.end());
  std::ostringstream md;
  md << "| scheme |";
  for (const double C : courants)
    md << " C = " << shortest(C) << " |";
  md << "\n|---|" << rule_cells(courants.size()) << "\n";
  for (const auto& m : schemes) {
    md << "| " << m << " |";
    for (const double C : courants) {
      const auto it = cell.find({m, C});
      md << " " << (it == cell.end() ? std::string("–") : it->second) << " |";
    }
    md << "\n";
  }
  return md.str();
}

// ---------------------------------------------------------------------------------------------
// Markers

const std::string kBegin = "<!-- generated: ";
const std::string kBeginTail =
    " (mpmstab documents writes this block from results/; do not edit) -->";
const std::string kEnd = "<!-- end generated: ";
const std::string kEndTail = " -->";

}  // namespace
}  // namespace studies::documents

std::map<std::string, std::string> document_blocks(const std::filesystem::path& results) {
  using namespace studies::documents;
  return {{"readme-tier-times", tier_times(results)},
          {"readme-speed", kernel_brief(results / "benchmark_step.json")},
          {"readme-advise-example", advise_example(results)},
          {"readme-run-example", run_example()},
          {"design-advice-counts", advice_counts(results)},
          {"design-advice-domain", advice_domain_table()},
          {"design-outcomes", outcomes_table()},
          {"design-failure-reasons", failure_reasons_table()},
          {"design-accuracy-classes", accuracy_classes_table()},
          {"design-comparison-classes", comparison_classes_markdown()},
          {"design-cells-per-wavelength", cells_per_wavelength(results)}};
}

std::string fill_document(const std::string& text, const std::map<std::string, std::string>& blocks,
                          const std::string& file, std::vector<std::string>* found) {
  using namespace studies::documents;
  std::string out;
  std::size_t at = 0;
  while (true) {
    const std::size_t begin = text.find(kBegin, at);
    if (begin == std::string::npos) {
      if (text.find(kEnd, at) != std::string::npos)
        throw InputError(file + ": an end marker of a generated block without its start");
      out += text.substr(at);
      return out;
    }
    const std::size_t name_end = text.find(kBeginTail, begin + kBegin.size());
    const std::size_t line_end = text.find('\n', begin);
    if (name_end == std::string::npos || line_end == std::string::npos || name_end > line_end)
      throw InputError(file + ": a generated block's start marker is malformed");
    const std::string name = text.substr(begin + kBegin.size(), name_end - begin - kBegin.size());
    const auto it = blocks.find(name);
    if (it == blocks.end()) throw InputError(file + ": no generated block is named '" + name + "'");
    const std::string end_marker = kEnd + name + kEndTail;
    const std::size_t end = text.find(end_marker, line_end);
    const std::size_t next_begin = text.find(kBegin, line_end);
    if (end == std::string::npos || (next_begin != std::string::npos && next_begin < end))
      throw InputError(file + ": the generated block '" + name + "' has no end marker");
    out += text.substr(at, line_end + 1 - at);
    out += it->second;
    out += end_marker;
    at = end + end_marker.size();
    if (found) found->push_back(name);
  }
}

}  // namespace mpmstab
