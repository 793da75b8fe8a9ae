// The paper's Table 1: E blocks, dt rows, MPM and GIMP, the paper's dt stable and max error
// beside ours, with a summary of where the stability verdicts and errors agree.
#include <algorithm>
#include <cmath>
#include <map>
#include <sstream>

#include "csv.hpp"
#include "paper_table1.hpp"
#include "report_util.hpp"
#include "study.hpp"

namespace mpmstab {

namespace {

using ojson = nlohmann::ordered_json;
namespace fs = std::filesystem;

struct Table1Summary {
  int cells = 0, paper_stable = 0, paper_unstable = 0, paper_unknown = 0;
  int ours_stable = 0, ours_meaningless = 0, ours_unstable = 0;
  int verdicts_agree = 0, verdicts_compared = 0;
  int paper_stable_ours_not = 0, paper_stable_ours_not_courant_ge1 = 0;
  int paper_stable_ours_meaningless = 0, paper_unstable_ours_meaningless = 0;
  int errors_within_3 = 0, errors_compared = 0;
  std::map<std::string, int> reasons;
};

Table1Summary summarize_table1(const Spec& spec, const std::vector<ojson>& rows,
                               const std::map<Table1Key, PaperCell>& paper) {
  Table1Summary s;
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const ojson& r = rows[i];
    ++s.cells;
    const std::string ours_outcome = outcome(r);
    if (ours_outcome == "stable") {
      ++s.ours_stable;
    } else if (ours_outcome == "meaningless") {
      ++s.ours_meaningless;
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
    // A meaningless run agrees with neither verdict of the paper: it is counted on its own.
    if (ours_outcome == "meaningless") {
      (paper_stable ? s.paper_stable_ours_meaningless : s.paper_unstable_ours_meaningless) += 1;
    } else if (paper_stable == (ours_outcome == "stable")) {
      ++s.verdicts_agree;
    } else if (paper_stable) {
      ++s.paper_stable_ours_not;
      if (r["courant"].get<double>() >= 1.0) ++s.paper_stable_ours_not_courant_ge1;
    }
    const auto ours = compared_error(r, spec.cases[i].error_at);
    if (paper_stable && ours && ours_outcome == "stable") {
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
     << " unreadable in the transcription. Ours: " << s.ours_stable << " stable, "
     << s.ours_meaningless << " meaningless (survived, but the error over time reached A), "
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
     << " of them at a Courant number c dt / h >= 1. Meaningless here, counted as agreeing with "
        "neither verdict: "
     << s.paper_stable_ours_meaningless << " cells the paper lists as stable and "
     << s.paper_unstable_ours_meaningless
     << " it marks `*`. Where both are stable (ours: stable, not meaningless), our max error is "
        "within a factor 3 of the paper's in "
     << s.errors_within_3 << " of " << s.errors_compared << " cells.";
  return md.str();
}

// What the marks and columns mean, with the source of the paper values.
std::string table1_legend(const Spec& spec, const fs::path& out) {
  bool over_time = false;
  for (const auto& c : spec.cases)
    over_time = over_time || c.error_at == ErrorAt::max_over_time;
  std::ostringstream md;
  md << "Legend: `*` unstable (ours: the reason and the step where the run stopped); "
        "*meaningless*: the run survived but its error over time reached the amplitude A; "
        "*inferred*: the paper does not print this cell's dt; *transcription*: the confidence of "
        "the paper value as transcribed in ["
     << link(out, spec.reference) << "](" << link(out, spec.reference)
     << ") (low-confidence cells are data, not truth). dt_stable is the minimum over the run of "
        "eq. (108) (stress "
     << to_string(spec.cases.front().params.stable.sigma) << ", ||v|| "
     << to_string(spec.cases.front().params.stable.vnorm)
     << "). Work: particles x steps of the run (deterministic; wall times are in "
        "[performance.md](performance.md)). Quantities are defined in docs/design.md."
     << (over_time ? " Max error ours: at T, or the largest over the run where marked (over time), "
                     "as the case's error_at chooses."
                   : "")
     << "\n\n";
  return md.str();
}

// One cell of the table: the paper's dt_stable and max error beside ours, our verdict, the
// confidence of the transcription and the work.
std::string table1_row(const CaseSpec& cs, const ojson& r,
                       const std::map<Table1Key, PaperCell>& paper) {
  const auto& p = cs.params;
  const auto it = paper.find(paper_key(cs));
  const PaperCell* pc = it == paper.end() ? nullptr : &it->second;
  const auto ours = compared_error(r, cs.error_at);
  std::string ratio_text = "–";
  if (pc && pc->max_error.kind == PaperValue::number && ours) {
    ratio_text = ratio(*ours / pc->max_error.value);
  }
  std::ostringstream md;
  md << "| " << param(p.dt) << (cs.dt_inferred ? " (inferred)" : "") << " | " << to_string(p.method)
     << " | " << sci(r["courant"].get<double>()) << " | " << (pc ? show(pc->dt_stable) : "–")
     << " | " << (survived(r) ? opt_sci(r["dt_stable_min"]) : "\\*") << " | "
     << (pc ? show(pc->max_error) : "–") << " | "
     << (!survived(r) ? std::string("\\*")
         : ours       ? sci(*ours)
                      : std::string("–"))
     << (cs.error_at == ErrorAt::max_over_time ? " (over time)" : "") << " | " << ratio_text
     << " | " << verdict(r) << " | " << (pc ? pc->confidence : "not in the paper") << " | "
     << work(r) << " |\n";
  return md.str();
}

// The summary, the legend, then one table per (E, A) block in the order the spec lists them,
// under a heading per E.
std::string table1_markdown(const Spec& spec, const std::vector<ojson>& rows, const fs::path& out) {
  const auto paper = read_paper_table1(spec);
  std::ostringstream md;
  md << "## Results\n\n**Summary.** " << table1_summary_text(summarize_table1(spec, rows, paper))
     << "\n\n"
     << table1_legend(spec, out);
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
          "ours | ours / paper | ours: verdict | transcription | particle-steps |\n";
    md << "|---|---|---|---|---|---|---|---|---|---|---|\n";
    for (std::size_t i = 0; i < rows.size(); ++i) {
      const auto& p = spec.cases[i].params;
      if (p.E == E && p.A == A) md << table1_row(spec.cases[i], rows[i], paper);
    }
    md << "\n";
  }
  return md.str();
}

std::string table1_index(const Spec& spec, const std::vector<ojson>& rows) {
  const auto paper = read_paper_table1(spec);
  return "**What it shows.** " + table1_summary_text(summarize_table1(spec, rows, paper)) +
         " Full table with the paper's values beside ours: [" + spec.name + ".md](" + spec.name +
         ".md).\n\n";
}

const StudyRegistration kTable1{{
    .name = "table1",
    .summary = "Table 1 of the paper: accuracy and stability per E, A, dt and method",
    .needs_reference = true,
    .records = {.error_over_time = true, .dt_stable = true},
    .report =
        [](const ReportContext& c) {
          return StudyReport{.markdown = table1_markdown(c.spec, c.rows, c.out)};
        },
    .index = table1_index,
}};

}  // namespace

}  // namespace mpmstab
