// The extremes study: every run has a verdict, counted in its Courant band; a measured output
// that is not finite is counted as such, one not measured is not; a run too short to judge and a
// survivor above its spectral limit are counted apart.
#include <gtest/gtest.h>

#include "study_rows.hpp"

namespace mpmstab {
namespace {

using ojson = nlohmann::ordered_json;
using test_support::study_row;

TEST(ExtremesStudy, EveryRunHasAVerdictCountedInItsBand) {
  std::vector<ojson> rows;
  ojson stable = study_row("gimp", 4);  // Courant 0.02, A/h 1.5
  ojson meaningless = stable;
  test_support::meaningless_row(meaningless);
  ojson unstable = stable;
  unstable["courant"] = 3.0;
  test_support::fail_row(unstable, "left_domain");
  ojson nan_output = stable;  // eq. (108) is measured for GIMP: null there is a NaN written
  nan_output["dt_stable_min"] = nullptr;
  ojson too_short = stable;  // reached T in 3 steps: no verdict on its stability
  too_short["outcome"] = "too_short";
  too_short["steps"] = 3;
  rows = {stable, meaningless, unstable, nan_output, too_short};
  const auto report = test_support::study_report("extremes", rows);
  EXPECT_NE(report.markdown.find("5 cases, 5 with a verdict: 2 stable, 1 meaningless "
                                 "(survived, but the error over time reached A), 1 unstable "
                                 "(left_domain 1), 1 too short to judge (they reached T in 3 to 3 "
                                 "steps, fewer than 10: no verdict on their stability). Runs that "
                                 "reached T with a measured quantity that is a NaN or an "
                                 "infinity: 1 of 4."),
            std::string::npos)
      << report.markdown;
  EXPECT_NE(report.markdown.find("| c dt/h < 0.5 | 4 | 2 | 1 | 1 | none |"), std::string::npos)
      << report.markdown;
  EXPECT_NE(report.markdown.find("| 1 <= c dt/h < 10 | 1 | 0 | 0 | 0 | left_domain 1 |"),
            std::string::npos)
      << report.markdown;
  // The figure's data: one row per spot and verdict code (0, 1, 2 or 3), with its number of
  // runs: the two stable runs at one spot are drawn once, counted 2. The one method is panel 0.
  EXPECT_NE(report.data_csv->find("0,2e-2,1.5,0,2,gimp\n0,2e-2,1.5,1,1,gimp\n0,2e-2,1.5,3,1,gimp\n"
                                  "0,3,1.5,2,1,gimp\n"),
            std::string::npos)
      << *report.data_csv;
}

// The claim's value of `name` in the claim `id`.
std::string claim_value(const StudyReport& report, const std::string& id, const std::string& name) {
  for (const auto& c : report.claims) {
    if (c.id != id) continue;
    for (const auto& [n, v] : c.values)
      if (n == name) return v;
  }
  return "(none)";
}

bool claim_holds(const StudyReport& report, const std::string& id) {
  for (const auto& c : report.claims)
    if (c.id == id) return c.holds;
  ADD_FAILURE() << "no claim " << id;
  return false;
}

// Null is "not measured" where the quantity is not defined (eq. (108) for a B-spline), and "not
// finite" where it is: the count of outputs holding a NaN or an infinity tells them apart.
TEST(ExtremesStudy, NullIsNotMeasuredWhereEq108IsNotDefinedAndNotFiniteWhereItIs) {
  ojson spline = study_row("bspline2", 4);
  spline["dt_stable_min"] = nullptr;  // not measured: eq. (108) is not defined for the basis
  const auto clean = test_support::study_report("extremes", {spline, spline});
  EXPECT_EQ(claim_value(clean, "outputs-finite", "bad"), "0");
  EXPECT_EQ(claim_value(clean, "outputs-finite", "unmeasured"), "2");
  EXPECT_TRUE(claim_holds(clean, "outputs-finite"));

  ojson gimp = study_row("gimp", 4);
  gimp["dt_stable_min"] = nullptr;  // measured for GIMP: null is a NaN or an infinity
  ojson inf_error = study_row("bspline2", 4);
  inf_error["max_error_over_time"] = nullptr;
  const auto dirty = test_support::study_report("extremes", {spline, gimp, inf_error});
  EXPECT_EQ(claim_value(dirty, "outputs-finite", "bad"), "2");
  EXPECT_FALSE(claim_holds(dirty, "outputs-finite"));
}

// A run above its scheme's spectral limit that survives makes the claim fail; one too short to
// judge is counted apart; a stable verdict never rests on fewer than 10 steps.
TEST(ExtremesStudy, AboveTheLimitClaimCountsSurvivorsAndRunsTooShortApart) {
  ojson below = study_row("gimp", 4);
  below["courant_spectral"] = 0.75;
  ojson failed = below;
  failed["courant"] = 1.5;
  test_support::fail_row(failed, "nonpositive_F");
  ojson too_short = below;
  too_short["courant"] = 10.0;
  too_short["outcome"] = "too_short";
  too_short["steps"] = 1;
  const auto holds = test_support::study_report("extremes", {below, failed, too_short});
  EXPECT_TRUE(claim_holds(holds, "above-limit-fails"));
  EXPECT_EQ(claim_value(holds, "above-limit-fails", "judged"), "1");
  EXPECT_EQ(claim_value(holds, "above-limit-fails", "short"), "1");
  EXPECT_TRUE(claim_holds(holds, "verdicts-rest-on-enough-steps"));

  ojson survivor = below;
  survivor["courant"] = 0.9;
  survivor["steps"] = 12;
  const auto fails = test_support::study_report("extremes", {below, failed, survivor});
  EXPECT_FALSE(claim_holds(fails, "above-limit-fails"));
  EXPECT_EQ(claim_value(fails, "above-limit-fails", "steps"), "12");
  EXPECT_EQ(claim_value(fails, "above-limit-fails", "ratio"), "1.20000");

  ojson few = below;  // a stable verdict on 5 steps would be a defect of the solver's outcome
  few["steps"] = 5;
  EXPECT_FALSE(
      claim_holds(test_support::study_report("extremes", {few}), "verdicts-rest-on-enough-steps"));
}

}  // namespace
}  // namespace mpmstab
