// The paper's Table 1: E blocks, dt rows, MPM and GIMP, the paper's dt stable and max error
// beside ours, with a summary of where the stability verdicts and errors agree.
#include <algorithm>
#include <map>
#include <optional>
#include <sstream>
#include <vector>

#include "base/accuracy.hpp"
#include "claims.hpp"
#include "csv.hpp"
#include "report_util.hpp"
#include "run_row.hpp"
#include "shared/ensemble.hpp"
#include "shared/paper_table1.hpp"
#include "study.hpp"

namespace mpmstab::studies::table1 {
namespace {

using ojson = nlohmann::ordered_json;
namespace fs = std::filesystem;

// What the study finds: the paper's cells beside ours, how our runs ended, the ensembles of the
// cells near their edge, and every count the summary, the claims and the index paragraph give.
struct Findings {
  std::map<Table1Key, PaperCell> paper;   // the paper's cells, as transcribed
  std::vector<EnsembleResult> ensembles;  // one per row
  int cells = 0, paper_stable = 0, paper_unstable = 0, paper_unknown = 0;
  // How our runs ended (run_row.hpp), over every cell and per method (in row order).
  VerdictTally ours;
  std::vector<std::pair<std::string, VerdictTally>> by_method;
  // The stability verdicts against the paper's (cell_agreement(), shared/paper_table1.hpp), over
  // every cell with a readable paper value, as comparison.md counts them.
  int verdicts_agree = 0, verdicts_compared = 0;
  // Of the cells whose verdicts are the same: both stable (ours accurate or inaccurate), both
  // unstable.
  int both_stable = 0, both_stable_accurate = 0, both_stable_inaccurate = 0, both_unstable = 0;
  // Compared cells whose ensemble disagrees with their verdict: counted by their verdict as run.
  int sensitive = 0, sensitive_agree = 0;
  int paper_stable_ours_not = 0, paper_stable_ours_not_above_limit = 0;
  int paper_stable_ours_meaningless = 0, paper_unstable_ours_meaningless = 0;
  int paper_stable_ours_too_short = 0, paper_unstable_ours_too_short = 0;
  int errors_within_factor = 0, errors_compared = 0, errors_compared_accurate = 0;
  // Every cell run above its scheme's spectral limit, and those ending stable; every cell rerun
  // as an ensemble, and those sensitive; the near cells rerun in ensembles.md, and not at all.
  int above = 0, stable_above = 0, rerun = 0, rerun_sensitive = 0, in_studies = 0, costly = 0;
  Coverage above_on, rerun_on, stable_on;  // the runs of those above the limit, rerun, stable
  bool over_time = false;  // some case compares its error over time with the paper's
};

// The findings from the rows and the ensembles' runs (none for the index, which counts only the
// cells).
Findings find(const Spec& spec, const std::vector<ojson>& rows,
              const std::vector<ojson>& follow_up) {
  Findings s;
  s.paper = read_paper_table1(spec);
  s.ensembles = ensemble_results(rows, follow_up, EnsembleNeed::near);
  const auto method_tally = [&](const std::string& method) -> VerdictTally& {  // in row order
    for (auto& [m, a] : s.by_method)
      if (m == method) return a;
    return s.by_method.emplace_back(method, VerdictTally{}).second;
  };
  for (std::size_t i = 0; i < rows.size(); ++i) {
    s.over_time = s.over_time || spec.cases[i].error_at == ErrorAt::max_over_time;
    const RunRow r(rows[i]);
    const EnsembleResult& e = s.ensembles[i];
    ++s.cells;
    s.ours.add(r);
    if (r.outcome == "stable") method_tally(r.method).add(r);
    if (r.ending() == Ending::stable) s.stable_on.add(r);
    if (e.members > 0) s.rerun_on.add(r);
    if (r.above_spectral_limit()) {
      s.above_on.add(r);
      ++s.above;
      s.stable_above += r.ending() == Ending::stable;
    }
    s.rerun += e.members > 0;
    s.rerun_sensitive += e.sensitive();
    s.costly += e.need == EnsembleNeed::too_costly;
    s.in_studies += e.need == EnsembleNeed::in_studies;
    const auto it = s.paper.find(paper_key(spec.cases[i]));
    const PaperCell* pc = it == s.paper.end() ? nullptr : &it->second;
    const CellAgreement agreement = cell_agreement(r, pc);
    if (!compared(agreement)) {
      ++s.paper_unknown;
      continue;
    }
    const bool stable_in_paper = paper_says_stable(*pc);
    (stable_in_paper ? s.paper_stable : s.paper_unstable) += 1;
    ++s.verdicts_compared;
    s.verdicts_agree += verdicts_agree(agreement);
    if (e.sensitive()) {
      ++s.sensitive;
      s.sensitive_agree += verdicts_agree(agreement);
    }
    // The cell, by how it stands against the paper's verdict.
    using enum CellAgreement;
    s.both_unstable += agreement == both_unstable;
    if (agreement == paper_stable_ours_unstable) {
      ++s.paper_stable_ours_not;
      s.paper_stable_ours_not_above_limit += r.above_spectral_limit();
    }
    if (agreement == ours_meaningless)
      ++(stable_in_paper ? s.paper_stable_ours_meaningless : s.paper_unstable_ours_meaningless);
    if (agreement == ours_too_short)
      ++(stable_in_paper ? s.paper_stable_ours_too_short : s.paper_unstable_ours_too_short);
    if (agreement != both_stable) continue;
    ++s.both_stable;
    (r.accurate() ? s.both_stable_accurate : s.both_stable_inaccurate) += 1;
    if (const auto ours = compared_error(rows[i], spec.cases[i].error_at)) {
      ++s.errors_compared;
      s.errors_compared_accurate += r.accurate();
      s.errors_within_factor += within_agreement_factor(*ours, pc->max_error.value);
    }
  }
  return s;
}

std::vector<Claim> table1_claims(const Findings& f) {
  Claim a = claim("none-stable-above-limit",
                  "No cell run at a Courant number c dt/h above its scheme's spectral limit ends "
                  "stable",
                  "{stable_above} of {above} such cells end stable");
  a.count("stable_above", f.stable_above).count("above", f.above).over(f.above).on(f.above_on);
  a.holds = f.stable_above == 0;
  Claim b = claim("verdicts-robust",
                  "The verdict of every cell near its edge survives a perturbation of its layout "
                  "by a few {unit} of the particle spacing",
                  "{sensitive} of {tested} cells rerun as an ensemble of {members} are sensitive; "
                  "{in_studies} cells near their edge are rerun in ensembles.md (make studies), "
                  "{costly} were not rerun (cost)");
  b.value("unit", sci(kEnsemblePerturbation, 1))
      .count("sensitive", f.rerun_sensitive)
      .count("tested", f.rerun)
      .count("members", kEnsembleMembers)
      .count("in_studies", f.in_studies)
      .count("costly", f.costly)
      .over(f.rerun);
  b.holds = f.rerun_sensitive == 0;
  b.on(f.rerun_on);
  Claim c = claim("stable-cells-accurate",
                  "Every cell that ends stable is accurate: its error over time stays below "
                  "{fraction} A",
                  "{accurate} of {stable} stable cells are accurate; {inaccurate} are inaccurate, "
                  "with an error over time of {range} A");
  c.value("fraction", shortest(kAccurateFraction))
      .every("accurate", f.ours.accurate, "stable", f.ours.stable)
      .count("inaccurate", f.ours.inaccurate)
      .value("range", f.ours.inaccurate_errors.empty() ? std::string("–")
                                                       : span(f.ours.inaccurate_errors, 2))
      .on(f.stable_on);
  return {a, b, c};
}

// "23 accurate and 17 inaccurate (error over time 0.1 to 0.89 A)".
std::string accuracy_split(const VerdictTally& a) {
  std::string t =
      std::to_string(a.accurate) + " accurate and " + std::to_string(a.inaccurate) + " inaccurate";
  if (!a.inaccurate_errors.empty())
    t += " (error over time " + span(a.inaccurate_errors, 2) + " A)";
  if (a.unmeasured)
    t += ", " + std::to_string(a.unmeasured) + " without a recorded error over time";
  return t;
}

// The stability verdicts against the paper's, over the cells comparison.md counts.
std::string table1_agreement_text(const Findings& s) {
  std::ostringstream md;
  md << "Of the " << s.verdicts_compared
     << " cells with a readable paper value (the cells comparison.md counts), the paper's "
        "stability verdict and ours are the same in "
     << s.verdicts_agree << " of " << s.verdicts_compared << " (" << s.both_stable
     << " stable in both, ours " << s.both_stable_accurate << " accurate and "
     << s.both_stable_inaccurate << " inaccurate; " << s.both_unstable
     << " unstable in both); the paper lists as stable " << s.paper_stable_ours_not
     << " cells that are unstable here, " << s.paper_stable_ours_not_above_limit
     << " of them at a Courant number c dt / h above the scheme's spectral limit (the linear "
        "limit of the step at the uniform layout: spectral.md). Meaningless here, counted with "
        "neither verdict: "
     << s.paper_stable_ours_meaningless << " cells the paper lists as stable and "
     << s.paper_unstable_ours_meaningless << " it marks `*`.";
  if (s.paper_stable_ours_too_short + s.paper_unstable_ours_too_short > 0)
    md << " Without a verdict here (too few steps, or under a wave pass), counted with neither: "
       << s.paper_stable_ours_too_short << " cells the paper lists as stable and "
       << s.paper_unstable_ours_too_short << " it marks `*`.";
  md << " Sensitive here (a perturbed layout changes the verdict: column *ensemble*): "
     << s.sensitive << " of these " << s.verdicts_compared << " cells, of which "
     << s.sensitive_agree
     << " match the paper's verdict as run; each is counted above by its verdict as run. Where "
        "both are stable (ours: stable, not meaningless; "
     << s.errors_compared_accurate << " of these " << s.errors_compared
     << " accurate here, the others inaccurate), our max error is within a factor "
     << agreement_factor() << " of the paper's in " << s.errors_within_factor << " of "
     << s.errors_compared << " cells.";
  return md.str();
}

std::string table1_summary_text(const Findings& s) {
  std::ostringstream md;
  md << s.cells << " cells. Paper: " << s.paper_stable << " stable, " << s.paper_unstable
     << " unstable (`*`), " << s.paper_unknown
     << " unreadable in the transcription. Ours: " << s.ours.stable
     << " stable (survived to T with an error over time below A): " << accuracy_split(s.ours)
     << " by the accuracy classes (accurate below " << shortest(kAccurateFraction)
     << " A, inaccurate from there up to A)";
  if (s.by_method.size() > 1) {
    md << "; per method, ";
    for (const auto& [method, a] : s.by_method)
      md << (method == s.by_method.front().first ? "" : "; ") << method << " " << a.stable
         << " stable: " << accuracy_split(a);
  }
  md << ". " << s.ours.meaningless << " meaningless (survived, but the error over time reached A), "
     << s.ours.unstable << " unstable";
  if (!s.ours.reasons.empty()) {
    md << " (";
    for (const auto& [reason, count] : s.ours.reasons)
      md << (reason == s.ours.reasons.begin()->first ? "" : ", ") << reason << " " << count;
    md << ")";
  }
  if (s.ours.too_short) md << ", " << s.ours.too_short << " too short to judge";
  if (s.ours.under_a_wave_pass)
    md << ", " << s.ours.under_a_wave_pass << " under a wave pass (survived in fewer than "
       << shortest(kMinWavePasses) << " wave pass c T / L: not counted as stable)";
  md << ". " << table1_agreement_text(s);
  return md.str();
}

// What the marks and columns mean, with the source of the paper values, and the ensembles.
std::string table1_legend(const Spec& spec, const fs::path& out, bool over_time) {
  return "Legend: `*` unstable (ours: the reason and the step where the run stopped); *stable* "
         "(ours): the run survived to T with an error over time below the amplitude A; "
         "*meaningless*: the run survived but its error over time reached A; *error over time / "
         "A*: the largest displacement error over the steps and particles of a run that reached T, "
         "per A; *accuracy*: its class (docs/studies.md, \"Accuracy classes\"): accurate below " +
         shortest(kAccurateFraction) +
         " A, inaccurate from there up to A, meaningless from A, given beside each stable verdict; "
         "*inferred*: the paper does not print this cell's dt; *transcription*: the confidence of "
         "the paper value as transcribed in [" +
         link(out, spec.reference) + "](" + link(out, spec.reference) +
         ") (low-confidence cells are data, not truth). dt_stable is the minimum over the run of "
         "eq. (108) (stress " +
         std::string(to_string(spec.cases.front().params.stable.sigma)) + ", ||v|| " +
         std::string(to_string(spec.cases.front().params.stable.vnorm)) +
         "). Work: particles x steps of the run (deterministic; wall times are in "
         "[performance.md](performance.md)). Quantities are defined in docs/theory.md." +
         (over_time ? " Max error ours: at T, or the largest over the run where marked (over "
                      "time), as the case's error_at chooses."
                    : "") +
         "\n\n*ensemble*: a cell near its edge (unstable below its spectral limit, meaningless, or "
         "stable with an error over time of at least " +
         shortest(kNearErrorFraction) + " A or c dt/h above the limit / " +
         shortest(kNearLimitMargin) + ") is rerun with " + std::to_string(kEnsembleMembers) +
         " layouts shifted or jittered by a few " + sci(kEnsemblePerturbation, 1) +
         " of the particle spacing, far below the discretisation error; it is *robust* when "
         "every member ends as it does, **sensitive** otherwise (with the members' outcomes). A "
         "near cell whose members would each cost more than " +
         sci(kPaperEnsembleBudget, 2) +
         " particle-steps is rerun in the studies tier, [ensembles.md](ensembles.md) (`make "
         "studies`), up to " +
         sci(kEnsembleMemberBudget, 2) +
         " each; above that it is not rerun (cost), and says so (docs/studies.md, "
         "\"Ensembles\").\n\n";
}

// One cell of the table: the paper's dt_stable and max error beside ours, our verdict, the
// confidence of the transcription and the work.
std::string table1_row(const CaseSpec& cs, const ojson& r,
                       const std::map<Table1Key, PaperCell>& paper, const std::string& ensemble) {
  const auto& p = cs.params;
  const auto it = paper.find(paper_key(cs));
  const PaperCell* pc = it == paper.end() ? nullptr : &it->second;
  const auto ours = compared_error(r, cs.error_at);
  std::string ratio_text = "–";
  if (pc && pc->max_error.kind == PaperValue::number && ours)
    ratio_text = ratio(*ours / pc->max_error.value);
  // The error over time / A and accuracy class of a run that reached T stable or meaningless.
  const RunRow run(r);
  const bool classed = run.outcome == "stable" || run.outcome == "meaningless";
  const auto e = classed ? run.error_over_A() : std::nullopt;
  const auto a = classed ? run.accuracy() : std::nullopt;
  std::ostringstream md;
  md << "| " << param(p.dt) << (cs.dt_inferred ? " (inferred)" : "") << " | " << to_string(p.method)
     << " | " << sci(RunRow(r).courant.value()) << " | " << (pc ? show(pc->dt_stable) : "–")
     << " | " << (survived(r) ? opt_sci(r["dt_stable_min"]) : "\\*") << " | "
     << (pc ? show(pc->max_error) : "–") << " | "
     << (!survived(r) ? std::string("\\*")
         : ours       ? sci(*ours)
                      : std::string("–"))
     << (cs.error_at == ErrorAt::max_over_time ? " (over time)" : "") << " | " << ratio_text
     << " | " << verdict_word(r) << " | " << (e && a ? significant(*e, 2) : std::string("–"))
     << " | " << (a ? std::string(to_string(*a)) : std::string("–")) << " | "
     << (pc ? pc->confidence : "not in the paper") << " | " << work(r) << " | " << ensemble
     << " |\n";
  return md.str();
}

// The summary, the legend, then one table per (E, A) block in the order the spec lists them,
// under a heading per E.
std::string table1_markdown(const Spec& spec, const std::vector<ojson>& rows, const fs::path& out,
                            const Findings& f) {
  std::ostringstream md;
  md << "## Results\n\n**Summary.** " << table1_summary_text(f) << "\n\n"
     << table1_legend(spec, out, f.over_time);
  std::vector<std::pair<double, double>> blocks;  // (E, A), each at its first case
  for (const auto& c : spec.cases) {
    const double E = c.params.E, A = c.params.A;
    if (std::find(blocks.begin(), blocks.end(), std::pair{E, A}) != blocks.end()) continue;
    // The block in the coordinates that fix a run: c T for E (at the spec's T), A / h for A.
    if (blocks.empty() || E != blocks.back().first)
      md << "### E = " << shortest(E) << " (c T = " << significant(wave_passes(c.params), 3)
         << " wave passes)\n\n";
    blocks.emplace_back(E, A);
    md << "**A = " << shortest(A) << " (A / h = " << significant(amplitude_per_cell(c.params), 3)
       << ")**\n\n";
    md << "| dt | method | c dt/h | dt_stable paper | dt_stable ours | max error paper | max error "
          "ours | ours / paper | ours: verdict | error over time / A | accuracy | transcription | "
          "particle-steps | ensemble |\n"
       << "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n";
    for (std::size_t i = 0; i < rows.size(); ++i) {
      const auto& p = spec.cases[i].params;
      if (p.E == E && p.A == A)
        md << table1_row(spec.cases[i], rows[i], f.paper, ensemble_text(rows[i], f.ensembles[i]));
    }
    md << "\n";
  }
  return md.str();
}

// The report: the findings once (with the ensembles), and from them the summary, the table, the
// claims and the ensembles in the study's JSON.
StudyReport table1_report(const ReportContext& c) {
  const Findings f = find(c.spec, c.rows, c.follow_up);
  ojson json = {{"ensemble", ojson::array()}};
  for (std::size_t i = 0; i < c.rows.size(); ++i)
    json["ensemble"].push_back(ensemble_json(c.rows[i], f.ensembles[i]));
  return StudyReport{.markdown = table1_markdown(c.spec, c.rows, c.out, f),
                     .json = json,
                     .claims = table1_claims(f)};
}

std::string table1_index(const Spec& spec, const std::vector<ojson>& rows, const ojson&) {
  return "**What it shows.** The " + std::to_string(find(spec, rows, {}).cells) +
         " cells of the paper's Table 1 beside ours, each with its verdict, its errors, its error "
         "over time / A and accuracy class, the paper's values and whether its verdict "
         "survives a perturbed layout. Full table, counts and conclusions: [" +
         spec.name + ".md](" + spec.name + ".md).\n\n";
}

const StudyRegistration kTable1{{
    .name = "table1",
    .summary = "Table 1 of the paper: accuracy and stability per E, A, dt and method",
    .needs_reference = true,
    .records = {.error_over_time = true, .dt_stable = true},
    // The ensembles of the cells near their edge (ensemble.hpp), in row order.
    .follow_up = [](const FollowUpContext& c) { return ensemble_follow_up(c, EnsembleNeed::near); },
    .report = table1_report,
    .index = table1_index,
}};

}  // namespace
}  // namespace mpmstab::studies::table1
