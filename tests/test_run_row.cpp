// The row vocabulary (experiments/engine/run_row.hpp): a result row read once into a RunRow, the
// one tally of how runs ended (VerdictTally), and the one rule of agreement of a Table 1 cell
// with the paper (cell_agreement(), shared/paper_table1.hpp), as table1 and the comparison use it.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "agreement/comparison.hpp"
#include "run_row.hpp"
#include "shared/paper_table1.hpp"

namespace mpmstab {
namespace {

using ojson = nlohmann::ordered_json;

ojson stable_row(double cT, double error_over_A) {
  return {{"outcome", "stable"},
          {"method", "gimp"},
          {"A", 0.01},
          {"max_error", 0.5 * error_over_A * 0.01},
          {"max_error_over_time", error_over_A * 0.01},
          {"cT", cT},
          {"courant", 0.2},
          {"courant_spectral", 1.0},
          {"particles", 200},
          {"steps", 500},
          {"failure_reason", nullptr},
          {"failure_step", nullptr},
          {"failure_time", nullptr}};
}

TEST(RunRow, ReadsARowOnce) {
  const RunRow r(stable_row(2, 0.05));
  EXPECT_EQ(r.outcome, "stable");
  EXPECT_FALSE(r.failure_reason);
  EXPECT_DOUBLE_EQ(*r.error_over_A(), 0.05);
  EXPECT_EQ(r.accuracy(), Accuracy::accurate);
  EXPECT_TRUE(r.stable_over_a_wave_pass());
  EXPECT_TRUE(r.accurate());
  EXPECT_EQ(r.ending(), Ending::stable);
  EXPECT_FALSE(r.above_spectral_limit());
  EXPECT_DOUBLE_EQ(r.particle_steps(), 200.0 * 500);
  EXPECT_EQ(r.method_label, "gimp");
  ojson above = stable_row(2, 0.05);
  above["courant"] = 1.5;
  EXPECT_TRUE(RunRow(above).above_spectral_limit());
  above.erase("courant_spectral");  // no limit recorded: not above one
  EXPECT_FALSE(RunRow(above).above_spectral_limit());
}

// A run the solver calls stable over fewer than kMinWavePasses wave passes is not stable: not in
// the tally's stable count, not accurate (no order is fitted on it), no stable error over time.
TEST(RunRow, ARunUnderAWavePassIsNotStable) {
  const RunRow r(stable_row(0.5 * kMinWavePasses, 0.05));
  EXPECT_TRUE(r.under_a_wave_pass());
  EXPECT_FALSE(r.stable_over_a_wave_pass());
  EXPECT_FALSE(r.accurate());
  EXPECT_FALSE(r.stable_error_over_time());
  EXPECT_EQ(r.ending(), Ending::under_a_wave_pass);
  EXPECT_EQ(r.accuracy(), Accuracy::accurate);  // its class is measured all the same
  VerdictTally t;
  t.add(r);
  EXPECT_EQ(t.stable, 0);
  EXPECT_EQ(t.accurate, 0);
  EXPECT_EQ(t.under_a_wave_pass, 1);
  EXPECT_EQ(t.survived(), 1);
  EXPECT_EQ(under_a_wave_pass_word(0.5),
            "survived, c T = 5e-1 < 1 wave pass: too short to count "
            "as stable");
  EXPECT_EQ(verdict_word(stable_row(0.5, 0.05)), under_a_wave_pass_word(0.5));
}

// Where a set of runs lies: its amplitudes, run lengths, grids and scenes, each value once; one
// amplitude reads as that one, so a claim measured there cannot pass for one across amplitudes.
TEST(Coverage, SaysWhichAmplitudesLengthsGridsAndScenesTheRunsSpan) {
  std::vector<ojson> rows;
  for (double cT : {2.0, 8.0, 31.6, 2.0}) {
    ojson r = stable_row(cT, 0.01);
    r["cells"] = 100;
    rows.push_back(r);
  }
  EXPECT_EQ(coverage_of(rows).text(), "A = 0.01; c T = 2, 8 and 31.6; 100 cells; bar");
  rows[1]["A"] = 0.05;
  rows[2]["cells"] = 200;
  rows[3]["scene"] = "steffen";
  rows.push_back(stable_row(100, 0.01));
  EXPECT_EQ(coverage_of(rows).text(),
            "A = 0.01 and 0.05; c T = 2 to 100 (4 values); 100 and 200 cells; bar and steffen");
  EXPECT_EQ(Coverage{}.text(), "");
}

TEST(VerdictTally, CountsEachEndingOnce) {
  ojson meaningless = stable_row(2, 1.5);
  meaningless["outcome"] = "meaningless";
  ojson unstable = stable_row(2, 0.05);
  unstable["outcome"] = "unstable";
  unstable["failure_reason"] = "nonpositive_F";
  unstable["failure_step"] = 96;
  unstable["failure_time"] = 0.01;
  unstable["max_error_over_time"] = nullptr;
  ojson too_short = stable_row(2, 0.05);
  too_short["outcome"] = "too_short";
  too_short["steps"] = 3;
  ojson unmeasured = stable_row(2, 0.05);
  unmeasured["max_error_over_time"] = nullptr;
  const VerdictTally t =
      verdict_tally({stable_row(2, 0.05), stable_row(2, 0.4), stable_row(0.6, 0.05), meaningless,
                     unstable, too_short, unmeasured, ojson::object()});
  EXPECT_EQ(t.runs, 8);
  EXPECT_EQ(t.stable, 3);
  EXPECT_EQ(t.accurate, 1);
  EXPECT_EQ(t.inaccurate, 1);
  EXPECT_EQ(t.unmeasured, 1);
  ASSERT_EQ(t.inaccurate_errors.size(), 1u);
  EXPECT_DOUBLE_EQ(t.inaccurate_errors.front(), 0.4);
  EXPECT_EQ(t.under_a_wave_pass, 1);
  EXPECT_EQ(t.meaningless, 1);
  EXPECT_EQ(t.unstable, 1);
  EXPECT_EQ(t.reasons.at("nonpositive_F"), 1);
  EXPECT_EQ(t.too_short, 1);
  EXPECT_EQ(t.unknown, 1);
  EXPECT_EQ(t.survived(), 6);
  // A meaningless run is not stable, not accurate, and has no stable error over time.
  const RunRow m(meaningless);
  EXPECT_EQ(m.accuracy(), Accuracy::meaningless);
  EXPECT_FALSE(m.stable_over_a_wave_pass());
  EXPECT_FALSE(m.stable_error_over_time());
  EXPECT_TRUE(m.survived());
  EXPECT_EQ(verdict_word(unstable), "\\* nonpositive_F at step 96 (t = 1.0e-2)");
  EXPECT_FALSE(RunRow(unstable).survived());
  EXPECT_EQ(RunRow(unstable).failure_reason, "nonpositive_F");
}

// One rule decides whether a Table 1 cell agrees with the paper; a run without a verdict agrees
// with neither of the paper's verdicts, and the comparison classes it without reading a failure.
TEST(CellAgreement, OneRuleForEveryTable1Cell) {
  PaperCell stable, unstable, missing;
  stable.max_error = paper_value("1.2e-4");
  unstable.max_error = paper_value("*");
  missing.max_error = paper_value("");
  ojson failed = stable_row(2, 0.05);
  failed["outcome"] = "unstable";
  failed["failure_reason"] = "left_domain";
  ojson too_short = stable_row(2, 0.05);
  too_short["outcome"] = "too_short";
  too_short["steps"] = 3;
  ojson meaningless = stable_row(2, 1.5);
  meaningless["outcome"] = "meaningless";
  using enum CellAgreement;
  EXPECT_EQ(cell_agreement(RunRow(stable_row(2, 0.05)), &stable), both_stable);
  EXPECT_EQ(cell_agreement(RunRow(stable_row(2, 0.05)), &unstable), paper_unstable_ours_stable);
  EXPECT_EQ(cell_agreement(RunRow(failed), &unstable), both_unstable);
  EXPECT_EQ(cell_agreement(RunRow(failed), &stable), paper_stable_ours_unstable);
  EXPECT_EQ(cell_agreement(RunRow(meaningless), &stable), ours_meaningless);
  EXPECT_EQ(cell_agreement(RunRow(too_short), &stable), ours_too_short);
  EXPECT_EQ(cell_agreement(RunRow(too_short), &unstable), ours_too_short);
  EXPECT_EQ(cell_agreement(RunRow(stable_row(0.5, 0.05)), &stable), ours_too_short);
  EXPECT_EQ(cell_agreement(RunRow(failed), &missing), unreadable);
  EXPECT_EQ(cell_agreement(RunRow(failed), nullptr), unreadable);
  EXPECT_TRUE(verdicts_agree(both_stable));
  EXPECT_TRUE(verdicts_agree(both_unstable));
  EXPECT_FALSE(verdicts_agree(ours_meaningless));
  EXPECT_FALSE(verdicts_agree(ours_too_short));
  EXPECT_FALSE(compared(unreadable));
  EXPECT_TRUE(compared(ours_too_short));
  // The comparison's classes follow the same rule: a too-short run is neither agreeing nor a
  // failure, whatever the paper says (its failure reason is null: none is read).
  for (const PaperCell* paper : {&stable, &unstable}) {
    const CellVerdict v = classify(too_short, paper, {}, ErrorAt::T);
    EXPECT_EQ(v.cls, "ours-too-short");
    EXPECT_FALSE(v.same_verdict());
    EXPECT_TRUE(v.compared());
  }
  EXPECT_EQ(failure_class(too_short, {}), "other-failure");
  EXPECT_EQ(classify(failed, &unstable, {}, ErrorAt::T).cls, "agree-unstable");
  EXPECT_EQ(classify(stable_row(2, 0.05), &stable, {}, ErrorAt::T).cls, "agree-stable");
}

}  // namespace
}  // namespace mpmstab
