// The edge search and its study: the survival edge and the accuracy edge of a case, the flips
// of a survival that is not monotone in dt, the columns they add to a row, and the report and
// figure data written from the rows.
#include <gtest/gtest.h>

#include <cmath>
#include <sstream>

#include "base/accuracy.hpp"
#include "report.hpp"
#include "result_json.hpp"
#include "run/edge.hpp"
#include "study_rows.hpp"

namespace mpmstab {
namespace {

using ojson = nlohmann::ordered_json;
using test_support::study_row;

constexpr double kCfl = 0.005;  // h/c of the bar at E = 4

// A synthetic case in units of h/c: survives below `edge` except in [fail_low, fail_high);
// error at T 1e-5 up to `accurate`, 1e-2 above it.
struct SyntheticCase {
  double edge = 0.82, accurate = 0.79, fail_low = 10, fail_high = 10;
  bool reference_meaningless = false;
  std::vector<bool> outcome_asked;

  EdgeProbe operator()(double dt, bool outcome) {
    outcome_asked.push_back(outcome);
    const double x = dt / kCfl;
    EdgeProbe p;
    p.dt = dt;
    p.survived = x <= edge && !(x >= fail_low && x < fail_high);
    p.steps = std::int64_t(std::ceil(1 / dt));
    if (!p.survived) {
      p.reason = FailureReason::nonpositive_F;
      p.outcome = Outcome::unstable;
      return p;
    }
    p.max_error = x <= accurate ? 1e-5 : 1e-2;
    if (outcome) p.outcome = reference_meaningless ? Outcome::meaningless : Outcome::stable;
    return p;
  }
};

// The runs go to T = 1 (2 wave passes at A = 0.015); the largest dt tried takes 10 steps.
EdgeResult search(SyntheticCase& c, double top = 0.1) {
  return find_edge(EdgeAxis{.unit = kCfl, .top = top, .wave_passes = 2, .A = 0.015},
                   [&](double dt, bool outcome) { return c(dt, outcome); });
}

TEST(EdgeSearch, AccuracyEdgeBelowTheSurvivalEdge) {
  SyntheticCase c;
  const EdgeResult e = search(c);
  ASSERT_TRUE(e.dt_edge && e.dt_fail && e.dt_accurate && e.dt_inaccurate);
  // Survival: the largest survivor within 2% of 0.82 h/c.
  EXPECT_LE(*e.dt_edge, 0.82 * kCfl);
  EXPECT_GT(*e.dt_fail, 0.82 * kCfl);
  EXPECT_LE(*e.dt_fail / *e.dt_edge, 1.02);
  // Accuracy: the last dt with the reference's error, within 2% of 0.79 h/c, below dt_edge.
  EXPECT_LE(*e.dt_accurate, 0.79 * kCfl);
  EXPECT_GT(*e.dt_inaccurate, 0.79 * kCfl);
  EXPECT_LE(*e.dt_inaccurate / *e.dt_accurate, 1.02);
  EXPECT_LT(*e.dt_accurate * 1.02, *e.dt_edge);
  EXPECT_EQ(*e.dt_reference, kCfl / 16);
  EXPECT_EQ(*e.max_error_reference, 1e-5);
  EXPECT_TRUE(e.flips.empty());
  // Only the reference (the first probe, which survives) is asked for its outcome.
  ASSERT_FALSE(c.outcome_asked.empty());
  EXPECT_TRUE(c.outcome_asked.front());
  EXPECT_EQ(std::count(c.outcome_asked.begin(), c.outcome_asked.end(), true), 1);

  const ojson j = edge_to_json(e);
  EXPECT_EQ(j["accuracy_factor"], 2.0);
  EXPECT_EQ(j["dt_accurate"], *e.dt_accurate);
  EXPECT_EQ(j["max_error_at_accurate"], 1e-5);
  EXPECT_EQ(j["monotone"], true);
  EXPECT_EQ(j["probes"].size(), e.probes.size());
  EXPECT_TRUE(j["probes"][0].contains("max_error"));
  const ojson row = edge_columns(j);
  EXPECT_EQ(row["dt_accurate_over_cfl"], *e.dt_accurate / kCfl);
  EXPECT_EQ(row["dt_inaccurate"], *e.dt_inaccurate);
  EXPECT_EQ(row["survival_flips"].get<std::string>(), "");
  EXPECT_EQ(j["wave_passes"], 2.0);
  EXPECT_EQ(j["A"], 0.015);
  // The dense scan below each edge: at least 8 runs from 0.9x the edge up to it.
  for (const double edge : {*e.dt_edge, *e.dt_accurate}) {
    int below = 0;
    for (const auto& p : e.probes)
      below += p.dt >= 0.9 * edge * (1 - 1e-12) && p.dt < edge;
    EXPECT_GE(below, 8) << edge / kCfl;
  }
}

TEST(EdgeSearch, NoAccuracyEdgeWhenTheReferenceIsMeaningless) {
  SyntheticCase c;
  c.reference_meaningless = true;
  const EdgeResult e = search(c);
  ASSERT_TRUE(e.dt_edge);
  EXPECT_EQ(*e.dt_reference, kCfl / 16);
  EXPECT_FALSE(e.dt_accurate);
  const ojson row = edge_columns(edge_to_json(e));
  EXPECT_TRUE(row["dt_accurate"].is_null());
  EXPECT_TRUE(row["outcome_at_accurate"].is_null());
}

TEST(EdgeSearch, TheLowestFailureIsTheEdgeAndNonMonotoneSurvivalIsSaid) {
  // Fails between 0.3 and 0.4 h/c: the scan's 0.354 h/c fails, 0.5 h/c to 0.82 h/c survive
  // again. The edge is the lowest failure: below 0.3 h/c, not 0.82 h/c.
  SyntheticCase c;
  c.fail_low = 0.3;
  c.fail_high = 0.4;
  const EdgeResult e = search(c);
  ASSERT_TRUE(e.dt_edge && e.dt_fail && e.survives_above);
  EXPECT_LT(*e.dt_edge, 0.3 * kCfl);
  EXPECT_GE(*e.dt_fail, 0.3 * kCfl);
  EXPECT_LE(*e.dt_fail / *e.dt_edge, 1.02);
  EXPECT_FALSE(e.monotone());
  EXPECT_LE(*e.survives_above, 0.82 * kCfl);
  EXPECT_GE(*e.survives_above, 0.5 * kCfl);
  // Every dt tried up to the edge survives.
  for (const auto& p : e.probes)
    if (p.dt <= *e.dt_edge) {
      EXPECT_TRUE(p.survived) << p.dt / kCfl;
    }
  ASSERT_GE(e.flips.size(), 2u);
  EXPECT_FALSE(e.flips[0].survives);
  EXPECT_TRUE(e.flips[1].survives);
  // The accuracy edge stops below the first failure above the reference.
  ASSERT_TRUE(e.dt_accurate);
  EXPECT_LE(*e.dt_accurate, *e.dt_edge);

  const ojson j = edge_to_json(e);
  EXPECT_EQ(j["monotone"], false);
  EXPECT_EQ(j["dt_survives_above"], *e.survives_above);
  const ojson row = edge_columns(j);
  EXPECT_EQ(row["monotone"], false);
  EXPECT_EQ(row["dt_survives_above"], *e.survives_above);
  EXPECT_NE(row["survival_flips"].get<std::string>(), "");
}

TEST(EdgeSearch, AFailureAFewPercentBelowTheBisectedEdgeMovesTheEdgeBelowIt) {
  // Survives to 0.82 h/c but fails in [0.78, 0.79) h/c, which neither the scan (0.707, 1) nor
  // the bisection visits: the dense scan below 0.82 finds it.
  SyntheticCase c;
  c.fail_low = 0.78;
  c.fail_high = 0.79;
  const EdgeResult e = search(c);
  ASSERT_TRUE(e.dt_edge && e.dt_fail && e.survives_above);
  EXPECT_LT(*e.dt_edge, 0.78 * kCfl);
  EXPECT_LT(*e.dt_fail, 0.79 * kCfl);
  EXPECT_FALSE(e.monotone());
  EXPECT_GT(*e.survives_above, 0.8 * kCfl);
}

TEST(EdgeSearch, NoEdgeWhereTheSmallestDtFails) {
  // Fails at the bottom of the scan (h/16c), survives from 0.1 h/c: no dt below survives, so
  // there is no edge, and survival is not monotone.
  SyntheticCase c;
  c.fail_low = 0;
  c.fail_high = 0.1;
  const EdgeResult e = search(c);
  EXPECT_FALSE(e.dt_edge);
  ASSERT_TRUE(e.dt_fail && e.survives_above);
  EXPECT_EQ(*e.dt_fail, kCfl / 16);
  EXPECT_FALSE(e.monotone());
}

TEST(EdgeLine, TheLowestFailureIsTheEdgeAndRunsWithoutAVerdictAreLeftOut) {
  using V = EdgeVerdict;
  // Holds at 1 to 3, fails at 4, holds at 5, no verdict at 6 (too short).
  const EdgeLine l =
      edge_line({{5, V::holds}, {1, V::holds}, {4, V::fails}, {2, V::holds}, {6, V::none}});
  EXPECT_EQ(l.edge, 2.0);
  EXPECT_EQ(l.fail, 4.0);
  EXPECT_EQ(l.holds_above, 5.0);
  EXPECT_FALSE(l.monotone());
  // A run too short for a verdict is neither a survival nor a failure.
  const EdgeLine s = edge_line({{1, V::holds}, {2, V::none}, {3, V::fails}});
  EXPECT_EQ(s.edge, 1.0);
  EXPECT_EQ(s.fail, 3.0);
  EXPECT_TRUE(s.monotone());
  EXPECT_FALSE(edge_line({{1, V::none}}).edge);
}

TEST(EdgeSearch, ARunTooShortForAVerdictIsNotASurvival) {
  // Survives at every dt; above dt = 0.1 a run to T = 1 takes fewer than kMinStepsToJudge steps.
  // With the top at T, those runs are tried but give no verdict: the edge is the largest dt
  // whose run has one.
  SyntheticCase c;
  c.edge = 1e9;
  c.accurate = 1e9;
  const EdgeResult e = search(c, 1.0);
  ASSERT_TRUE(e.dt_edge);
  EXPECT_LE(*e.dt_edge, 0.1 + 1e-12);
  EXPECT_FALSE(e.dt_fail);
  for (const auto& p : e.probes)
    if (p.dt == *e.dt_edge) {
      EXPECT_GE(p.steps, kMinStepsToJudge);
    }
}

TEST(EdgeSearch, RunsUnderAWavePassFindNoEdge) {
  RunParams p;
  p.method = Method::gimp;
  p.E = 4;
  p.A = 0.015;
  p.T = 0.2;  // c T = 0.4 wave passes
  const EdgeResult e = find_edge(p);
  EXPECT_TRUE(e.too_short);
  EXPECT_FALSE(e.dt_edge);
  EXPECT_TRUE(e.probes.empty());
  EXPECT_DOUBLE_EQ(e.wave_passes, 0.4);
  EXPECT_EQ(edge_to_json(e)["too_short"], true);
}

// A small real case: GIMP at E = 4 survives to about 0.82 h/c, but the run there is meaningless;
// the accuracy edge lies below it, its run stable with the error of the smallest dt.
TEST(EdgeSearch, GimpAtE4SurvivesFurtherThanItStaysAccurate) {
  RunParams p;
  p.method = Method::gimp;
  p.E = 4;
  p.A = 0.015;
  const EdgeResult e = find_edge(p);
  ASSERT_TRUE(e.dt_edge && e.dt_accurate && e.at_edge);
  EXPECT_EQ(e.at_edge->outcome, Outcome::meaningless);
  EXPECT_LT(*e.dt_accurate, *e.dt_edge);
  const ojson j = edge_to_json(e);
  EXPECT_EQ(j["outcome_at_accurate"].get<std::string>(), "stable");
  EXPECT_LE(j["max_error_at_accurate"].get<double>(), 2 * *e.max_error_reference);
  EXPECT_EQ(j["search_particle_steps"], e.particle_steps);
  std::int64_t probe_steps = 0;
  for (const auto& probe : e.probes)
    probe_steps += probe.steps * 200;
  EXPECT_GT(e.particle_steps, probe_steps);  // the measured runs at both edges count too
}

// Rows of the bar at E = 4: gimp with both edges (the survival edge meaningless), gimp whose
// survival flips, mpm without a surviving dt.
std::vector<ojson> edge_rows() {
  ojson a = study_row("gimp", 4);
  test_support::meaningless_row(a);
  a["dt_edge"] = 0.0041;
  a["dt_fail"] = 0.00416;
  a["dt_edge_over_cfl"] = 0.82;
  a["dt_stable_min_at_edge"] = 1e-4;
  a["dt_edge_over_stable"] = 41.0;
  a["monotone"] = true;
  a["dt_reference"] = 0.0003125;
  a["max_error_reference"] = 1e-5;
  a["dt_accurate"] = 0.00394;
  a["dt_inaccurate"] = 0.00398;
  a["dt_accurate_over_cfl"] = 0.788;
  a["max_error_at_accurate"] = 6e-6;
  a["outcome_at_accurate"] = "stable";
  a["search_particle_steps"] = 2.4e6;
  a["dt_survives_above"] = nullptr;
  a["survival_flips"] = "";
  a["probes"] = 20;
  ojson b = a;
  b["A"] = 0.05;
  b["outcome"] = "stable";
  b["dt_edge"] = 0.0035;
  b["dt_edge_over_cfl"] = 0.7;
  b["dt_accurate"] = b["dt_accurate_over_cfl"] = b["max_error_at_accurate"] = nullptr;
  b["outcome_at_accurate"] = nullptr;
  b["monotone"] = false;
  b["dt_survives_above"] = 0.0042;
  b["survival_flips"] = "fails 0.0035355339059327; survives 0.00420448207626857";
  a["courant_spectral"] = 0.7564;  // recorded for the first row only
  ojson none = study_row("mpm", 4);
  test_support::fail_row(none, "nonpositive_F");
  for (const char* k :
       {"dt_edge", "dt_fail", "dt_edge_over_cfl", "dt_stable_min_at_edge", "dt_edge_over_stable",
        "dt_reference", "max_error_reference", "dt_accurate", "dt_inaccurate",
        "dt_accurate_over_cfl", "max_error_at_accurate", "outcome_at_accurate"})
    none[k] = nullptr;
  none["monotone"] = true;
  none["dt_survives_above"] = nullptr;
  none["survival_flips"] = "";
  none["probes"] = 13;
  none["search_particle_steps"] = 2.8e6;
  return {a, b, none};
}

TEST(EdgeStudy, ReportStatesTheRuleAndReadsBothEdgesFromTheRows) {
  const std::string md = test_support::study_report("edge", edge_rows()).markdown;
  // The rule.
  EXPECT_NE(md.find("dt_accurate is the last dt tried before the first that fails or has an "
                    "error over time more than 2 times the reference's"),
            std::string::npos)
      << md;
  EXPECT_NE(md.find("An accuracy edge is one only where its reference run and its own run are "
                    "accurate (their error over time below 0.1 A"),
            std::string::npos)
      << md;
  // The reading, computed from the rows: per method and amplitude, each range with the run
  // lengths it spans.
  EXPECT_NE(
      md.find("Of 3 searches (A = 0.015 and 0.05; c T = 2; 100 cells), 2 found a survival "
              "edge and 1 none (no dt of the scan survives, or the smallest dt tried fails)."),
      std::string::npos)
      << md;
  EXPECT_NE(md.find("gimp at A = 0.015: the survival edge is 0.820 h/c over c T = 2, and the run "
                    "there is meaningless in 1 of 1 cases; the accuracy edge is 0.788 h/c over c "
                    "T = 2, below the survival edge in 1 of 1 cases (down to 0.96 times it); eq. "
                    "(108) at the survival edge is 41 times below it. gimp at A = 0.05: the "
                    "survival edge is 0.700 h/c over c T = 2, and the run there is meaningless in "
                    "0 of 1 cases; 1 has no accuracy edge"),
            std::string::npos)
      << md;
  EXPECT_NE(md.find("mpm at A = 0.015: no edge at c T = 2: no dt of the scan survives, or the "
                    "smallest dt tried fails."),
            std::string::npos)
      << md;
  EXPECT_NE(
      md.find("1 of 3 searches found survival not monotone in dt (a dt above the lowest "
              "failure survives; the edge is below that failure): gimp, A = 0.05, E = 4 (c T = 2) "
              "(**not monotone**: survives again at up to 4.20e-3 (fails from 3.54e-3, survives "
              "from 4.20e-3))."),
      std::string::npos)
      << md;
  // The table: A / h and c T, the spectral limit (where recorded), both edges with h/c, the
  // bracket, the margins to the limit (no run for length given: said so), the flips, the cost
  // without wall times.
  EXPECT_NE(md.find("| gimp | 0.015 | 1.5 | 4 | 2 | 5.00e-3 | 0.756 | 4.10e-3 (0.820; fails at "
                    "0.832) | 1.084 x limit; not tested for length | meaningless (survived; "
                    "error over time reached A) | 1.0e-6 | "
                    "3.94e-3 (0.788) | 1.042 x limit; not tested for length | 1.0e-5 → 6.0e-6 | "
                    "1.0e-4 (41) | monotone | – | 20 | 2.4e6 |"),
            std::string::npos)
      << md;
  EXPECT_NE(md.find("none (reference meaningless)"), std::string::npos);
  EXPECT_NE(md.find("| **not monotone**: survives again at up to 4.20e-3 (fails from 3.54e-3, "
                    "survives from 4.20e-3) |"),
            std::string::npos);
  EXPECT_NE(md.find("| mpm | 0.015 | 1.5 | 4 | 2 | 5.00e-3 | – | none in the scan |"),
            std::string::npos);
  EXPECT_EQ(md.find("seconds"), std::string::npos);
  EXPECT_EQ(md.find(" ms "), std::string::npos);
}

// Every quoted edge is rerun on perturbed layouts, at dt_edge and at dt_fail: robust when every
// member survives at the edge and fails above it, sensitive otherwise; the claim counts them.
TEST(EdgeStudy, EdgesAreRerunOnPerturbedLayoutsAndASensitiveOneIsMarked) {
  const std::vector<ojson> rows = edge_rows();  // two edges (gimp), one case without
  ojson survives = study_row("gimp", 4), fails = survives;
  test_support::fail_row(fails, "nonpositive_F");
  std::vector<ojson> follow_up;
  for (int k = 0; k < 8; ++k)
    follow_up.push_back(survives);  // first edge: all 8 survive at dt_edge
  for (int k = 0; k < 8; ++k)
    follow_up.push_back(fails);  // ... and fail above it
  for (int k = 0; k < 8; ++k)
    follow_up.push_back(k < 5 ? survives : fails);  // second: 5 of 8 survive at dt_edge
  for (int k = 0; k < 8; ++k)
    follow_up.push_back(fails);
  const auto report = test_support::study_report("edge", rows, follow_up);
  EXPECT_NE(report.markdown.find("| robust: 8 of 8 survive, 8 of 8 fail above |"),
            std::string::npos)
      << report.markdown;
  EXPECT_NE(report.markdown.find("| **sensitive**: 5 of 8 survive, 8 of 8 fail above |"),
            std::string::npos)
      << report.markdown;
  bool found = false;
  for (const auto& c : report.claims) {
    if (c.id != "edges-robust") continue;
    found = true;
    EXPECT_FALSE(c.holds);
    EXPECT_EQ(render(c, c.evidence), "1 of 2 edges rerun are robust; 2 edges found");
    EXPECT_EQ(c.measured_on, "A = 0.015 and 0.05; c T = 2; 100 cells; bar");  // the edges' rows
  }
  EXPECT_TRUE(found);
}

// Every edge, below the spectral limit too, is rerun after the ensembles at 10 and 100 times its
// wave passes: printed as holding to the longest it passed or as transient with the length at
// which it failed (a survival edge by failing, an accuracy edge by leaving the accuracy class),
// and counted by the claims on each kind of edge.
TEST(EdgeStudy, EveryEdgeIsRerunForLengthAndATransientOneSaysWhereItFails) {
  const std::vector<ojson> rows = edge_rows();  // c T = 2: rerun to 20 and 200 wave passes
  ojson survives = study_row("gimp", 4), fails = survives;
  test_support::fail_row(fails, "nonpositive_F");
  std::vector<ojson> follow_up;
  for (int k = 0; k < 32; ++k)  // the ensembles of both edges: all robust
    follow_up.push_back(k % 16 < 8 ? survives : fails);
  auto length = [](ojson r, double cT) {
    r["cT"] = cT;
    return r;
  };
  ojson fails_late = fails;  // the first row's survival edge fails at t = 31.5: c t = 63
  fails_late["failure_time"] = 31.5;
  ojson meaningless = survives;
  test_support::meaningless_row(meaningless);
  // The first row: its survival edge, then its accuracy edge, each to 20 and 200 passes; the
  // second row's survival edge (it has no accuracy edge) holds to both.
  for (const ojson& r : {length(survives, 20), fails_late, length(survives, 20),
                         length(meaningless, 200), length(survives, 20), length(survives, 200)})
    follow_up.push_back(r);
  ojson twin = survives;  // the periodic twin at the first row's accuracy edge
  twin["bc"] = "periodic";
  twin["max_error_over_time"] = 3e-6;
  follow_up.push_back(twin);
  const auto report = test_support::study_report("edge", rows, follow_up);
  const std::string& md = report.markdown;
  // The twin's error over time beside the Dirichlet run's, and per method in the walls paragraph.
  EXPECT_NE(md.find("| 1.0e-5 → 6.0e-6 (periodic 3.0e-6) |"), std::string::npos) << md;
  EXPECT_NE(md.find("gimp at A = 0.015: 0.5 times the Dirichlet one (median 0.5, 1 of 1 twins)"),
            std::string::npos)
      << md;
  EXPECT_NE(md.find("| 1.084 x limit; **transient**: fails at c T = 63 |"), std::string::npos)
      << md;
  EXPECT_NE(md.find("| 1.042 x limit; **transient**: not accurate at c T = 200 (meaningless) |"),
            std::string::npos)
      << md;
  EXPECT_NE(md.find("| holds to c T = 200 |"), std::string::npos) << md;
  int found = 0;
  for (const auto& c : report.claims) {
    if (c.id == "accurate-edges-at-most-the-limit") {
      ++found;
      EXPECT_FALSE(c.holds);
      EXPECT_EQ(render(c, c.evidence), "1 of 1 lie above it");
    }
    if (c.id == "survival-edges-hold-for-length") {
      ++found;
      EXPECT_FALSE(c.holds);
      EXPECT_EQ(render(c, c.evidence), "1 of 2 hold; the others fail at c T = 63");
      EXPECT_EQ(c.measured_on, "A = 0.015 and 0.05; c T = 2; 100 cells; bar");
    }
    if (c.id == "accuracy-edges-hold-for-length") {
      ++found;
      EXPECT_EQ(c.status(), Claim::Status::fails);
    }
  }
  EXPECT_EQ(found, 3);
}

TEST(EdgeStudy, FigureDataHasARowPerDrawnCaseAndTheTitleCountsThem) {
  std::vector<ojson> rows = edge_rows();
  ojson steffen = rows[0];
  steffen["scene"] = "steffen";
  rows.push_back(steffen);
  ojson cpgimp = rows[0];
  cpgimp["method"] = "cpgimp";
  rows.push_back(cpgimp);
  const StudyReport report = test_support::study_report("edge", rows);
  ASSERT_TRUE(report.data_csv);
  const std::string& csv = *report.data_csv;
  // Drawn: the two gimp cases of the bar and the one of the second scene.
  EXPECT_EQ(test_support::data_lines(csv).size(), 3u) << csv;
  // Beside each edge, the spectral limit (where recorded) and eq. (108) at the edge, in h/c.
  EXPECT_NE(csv.find("panel,series,cT,dt_edge_over_cfl,dt_accurate_over_cfl,meaningless_at_edge,"
                     "limit_over_cfl,eq108_over_cfl\n"
                     "0,1,2,0.82,0.788,1,0.7564,0.02\n0,2,2,0.7,,0,,0.02\n"
                     "1,1,2,0.82,0.788,1,0.7564,0.02\n"),
            std::string::npos)
      << csv;
  // Not drawn, each with its reason, in the data and in the report.
  EXPECT_NE(csv.find("# not drawn, no edge (none in the scan): bar: mpm, A = 0.015, c T = 2\n"),
            std::string::npos)
      << csv;
  EXPECT_NE(csv.find("# not drawn, no series in the figure: bar: cpgimp, A = 0.015, c T = 2\n"),
            std::string::npos)
      << csv;
  EXPECT_NE(report.markdown.find("**Drawn.** 3 of 5 cases (A = 0.015 and 0.05; c T = 2; 100 "
                                 "cells), 2 of them with their accuracy edge. "
                                 "Not drawn, no edge (none in the scan) (1): bar: mpm, A = "
                                 "0.015, c T = 2. Not drawn, no series in the figure (1): bar: "
                                 "cpgimp, A = 0.015, c T = 2. Drawn "
                                 "without an accuracy edge"),
            std::string::npos)
      << report.markdown;
  // The title's count is the data's.
  Spec spec;
  spec.name = std::string("edge");
  ojson doc;
  doc["cases"] = rows;
  const std::string subtitle = find_study("edge")->figure_subtitle(spec, doc);
  EXPECT_EQ(subtitle.rfind(std::to_string(test_support::data_lines(csv).size()) +
                               " of 5 cases drawn (A = 0.015 and 0.05, c T = 2, 100 cells, 2 "
                               "with an accuracy edge)",
                           0),
            0u)
      << subtitle;
  EXPECT_NE(subtitle.find("each listed in edge.md"), std::string::npos);
}

// The accuracy classes decide whether a search's dt_accurate is an accuracy edge: both its
// reference run and its own run must be accurate (error over time below 0.1 A).
TEST(EdgeStudy, AnAccuracyEdgeIsOneOnlyWhereItsReferenceAndItsRunAreAccurate) {
  auto row = [](double reference, double at_accurate) {
    ojson r;
    r["max_error_over_time"] = 0.5e-3;
    r["max_error_reference"] = reference;
    r["max_error_at_accurate"] = at_accurate;
    r["dt_accurate"] = 1e-4;
    r["dt_accurate_over_cfl"] = 0.5;
    add_accuracy_classes(r, 0.01);  // A = 0.01: accurate below 1e-3
    return r;
  };
  const ojson kept = row(0.4e-3, 0.8e-3);
  EXPECT_EQ(kept["dt_accurate"], 1e-4);
  EXPECT_FALSE(kept["accuracy_edge_withheld"].get<bool>());
  EXPECT_DOUBLE_EQ(kept["error_reference_over_A"].get<double>(), 0.04);
  EXPECT_DOUBLE_EQ(kept["error_at_accurate_over_A"].get<double>(), 0.08);
  EXPECT_DOUBLE_EQ(kept["error_at_edge_over_A"].get<double>(), 0.05);
  for (const ojson& withheld : {row(1.5e-3, 2e-3), row(0.6e-3, 1.1e-3), row(0.02, 0.03)}) {
    EXPECT_TRUE(withheld["dt_accurate"].is_null()) << withheld.dump();
    EXPECT_TRUE(withheld["dt_accurate_over_cfl"].is_null()) << withheld.dump();
    EXPECT_TRUE(withheld["accuracy_edge_withheld"].get<bool>()) << withheld.dump();
  }
  EXPECT_EQ(accuracy_class(0.99e-3, 0.01), Accuracy::accurate);
  EXPECT_EQ(accuracy_class(1.01e-3, 0.01), Accuracy::inaccurate);
  EXPECT_EQ(accuracy_class(0.01, 0.01), Accuracy::meaningless);
}

}  // namespace
}  // namespace mpmstab
