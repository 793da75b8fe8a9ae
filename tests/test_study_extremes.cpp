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
  EXPECT_NE(report.markdown.find(
                "5 cases, 5 with a verdict. 2 reached T in at least 10 steps with an error over "
                "time below A (the solver's outcome stable); of these, 2 ran at least c T = 1 "
                "wave pass and are counted as stable here: 2 accurate (error over time below 0.1 "
                "A) and 0 inaccurate; the other 0 ran fewer wave passes, too short to count as "
                "stable, and are counted apart. 1 meaningless (survived, but the error over time "
                "reached A), 1 unstable (left_domain 1), 1 too short to judge (they reached T in "
                "3 to 3 steps, fewer than 10: no verdict on their stability). Runs that reached T "
                "with a measured quantity that is a NaN or an infinity: 1 of 4."),
            std::string::npos)
      << report.markdown;
  EXPECT_NE(report.markdown.find("| c dt/h < 0.5 | 4 | 2 | 0 | 0 | 1 | 1 | – |"), std::string::npos)
      << report.markdown;
  EXPECT_NE(report.markdown.find("| 1 <= c dt/h < 10 | 1 | 0 | 0 | 0 | 0 | 0 | left_domain 1 |"),
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

// A run the solver calls stable counts as stable here only over at least one wave pass, with its
// accuracy class: a stable run of c T = 1e-4 is counted apart, one at 0.5 A is inaccurate.
TEST(ExtremesStudy, StableRunsUnderOneWavePassAreCountedApartAndTheOthersByAccuracyClass) {
  const ojson accurate = study_row("gimp", 4);  // c T = 2, error over time 1e-5 / 0.015 A
  ojson inaccurate = accurate;
  inaccurate["max_error_over_time"] = 0.5 * 0.015;
  ojson brief = accurate;  // the solver's stable, in 50 steps over c T = 1e-4
  brief["cT"] = 1e-4;
  brief["steps"] = 50;
  const auto report = test_support::study_report("extremes", {accurate, inaccurate, brief});
  const std::string& md = report.markdown;
  EXPECT_NE(md.find("3 reached T in at least 10 steps with an error over time below A (the "
                    "solver's outcome stable); of these, 2 ran at least c T = 1 wave pass and are "
                    "counted as stable here: 1 accurate (error over time below 0.1 A) and 1 "
                    "inaccurate (error over time 0.5 A); the other 1 ran fewer wave passes (c T "
                    "1e-4), too short to count as stable, and are counted apart."),
            std::string::npos)
      << md;
  EXPECT_NE(md.find("| c dt/h < 0.5 | 3 | 1 | 1 | 1 | 0 | 0 | – |"), std::string::npos) << md;
  const std::string row = test_support::line_with(md, "c T = 1e-4 < 1 wave pass");
  EXPECT_NE(row.find("| survived, c T = 1e-4 < 1 wave pass: too short to count as stable |"),
            std::string::npos)
      << row;
  EXPECT_NE(test_support::line_with(md, "| 5.0e-1 | inaccurate |").find("| stable |"),
            std::string::npos)
      << md;
  EXPECT_FALSE(claim_holds(report, "stable-runs-accurate"));
  EXPECT_EQ(claim_value(report, "stable-runs-accurate", "stable"), "2");
  EXPECT_EQ(claim_value(report, "stable-runs-accurate", "apart"), "1");
  // Without the inaccurate run, every run counted stable is accurate; the brief one is apart.
  const auto holds = test_support::study_report("extremes", {accurate, brief});
  EXPECT_TRUE(claim_holds(holds, "stable-runs-accurate"));
  EXPECT_EQ(claim_value(holds, "stable-runs-accurate", "stable"), "1");
}

// A scene-edge row for the scene_edges study: its survival edge `edge` and failing dt `fail` (0
// for none) in c dt/h, the outcome and error over time per A of the run at the edge, and the
// reference's error over time per A.
ojson edge_row(const char* scene, double edge, double fail, const char* outcome, double edge_error,
               double reference_error) {
  const double dt_cfl = 0.0015625;
  ojson r = study_row("gimp", 100);
  r["scene"] = scene;
  r["small_mass"] = nullptr;
  r["dt_cfl"] = dt_cfl;
  r["courant_spectral"] = 0.756;
  r["outcome"] = outcome;
  r["steps"] = std::string(outcome) == "too_short" ? 1 : 500;
  r["dt_edge"] = edge * dt_cfl;
  r["dt_fail"] = fail > 0 ? ojson(fail * dt_cfl) : ojson(nullptr);
  r["error_at_edge_over_A"] = edge_error;
  r["error_reference_over_A"] = reference_error;
  r["dt_accurate"] = 0.0625 * dt_cfl;  // the reference itself
  r["error_at_accurate_over_A"] = reference_error;
  return r;
}

// A row that survives to the top of the scan, or whose run at its largest surviving dt is too
// short to judge, has no survival edge inside the scan; no accuracy edge is read where the
// reference's error over time is at round-off.
TEST(SceneEdgesStudy, AnEdgeInsideTheScanNeedsAFailureAboveItAndAVerdictAndRoundOffReadsNoEdge) {
  const ojson inside = edge_row("vibration", 0.685, 0.692, "stable", 0.2, 1e-3);
  const ojson to_top = edge_row("block", 640, 0, "stable", 1e-15, 8.9e-16);
  // A run at the top of the scan with no verdict gives no edge either: too short, not a survivor.
  const ojson short_top = edge_row("block", 640, 0, "too_short", 0, 8.9e-16);
  const ojson short_edge = edge_row("block", 2, 2.05, "too_short", 0, 1e-3);
  const auto report =
      test_support::study_report("scene_edges", {inside, to_top, short_top, short_edge});
  EXPECT_FALSE(claim_holds(report, "every-case-has-an-edge"));
  EXPECT_EQ(claim_value(report, "every-case-has-an-edge", "with"), "1");
  EXPECT_EQ(claim_value(report, "every-case-has-an-edge", "cases"), "4");
  EXPECT_EQ(claim_value(report, "every-case-has-an-edge", "top"), "1");
  EXPECT_EQ(claim_value(report, "every-case-has-an-edge", "short"), "2");
  EXPECT_EQ(claim_value(report, "edges-at-or-below-limit", "compared"), "1");
  EXPECT_EQ(claim_value(report, "edges-meaningful", "with"), "1");
  const std::string& md = report.markdown;
  const std::string top = test_support::line_with(md, "it survives to its top");
  EXPECT_NE(top.find("none: the reference error is at round-off (8.9e-16 A)"), std::string::npos)
      << top;
  EXPECT_EQ(top.find("0.062"), std::string::npos) << top;
  EXPECT_NE(md.find("none in the scan: the run at c dt/h 2 is too short to judge"),
            std::string::npos)
      << md;
  EXPECT_NE(md.find("none in the scan: the run at c dt/h 640, the top of the scan (a step of T), "
                    "is too short to judge"),
            std::string::npos)
      << md;
  const std::string edge = test_support::line_with(md, "| vibration |");
  EXPECT_NE(edge.find("| 0.685 | 0.692 | stable, inaccurate (0.2 A) |"), std::string::npos) << edge;
  EXPECT_NE(edge.find("| 0.062 |"), std::string::npos) << edge;  // a reference above round-off
  // Every row with an edge inside the scan: the claim holds (over three rows, enough support).
  const auto all = test_support::study_report("scene_edges", {inside, inside, inside});
  EXPECT_TRUE(claim_holds(all, "every-case-has-an-edge"));
}

}  // namespace
}  // namespace mpmstab
