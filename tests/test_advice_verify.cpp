// Advice verified on the problem (experiments/studies/choice/advice_verify.hpp): the prediction
// from the runs that match the problem, the order candidates are tried in, the verifying runs and
// the answer they allow, each refusal (domain, too short, target, budget), the margins, and the
// JSON. The search is driven by a stand-in for the solver whose error is a known function of the
// setting, so that which candidate must answer is known exactly; one test runs the real command.
#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <nlohmann/json.hpp>

#include "choice/advice_rule.hpp"
#include "choice/advice_verify.hpp"
#include "support.hpp"

namespace mpmstab {
namespace {

using ojson = nlohmann::ordered_json;

CornerRun corner_run(CornerKind kind, double length, double A, int cells, double error_over_A,
                     const char* outcome = "stable") {
  CornerRun c;
  c.kind = kind;
  c.length = length;
  c.A = A;
  c.cells = cells;
  c.outcome = outcome;
  c.error_over_A = error_over_A;
  return c;
}

// A setting whose every corner ran stable at `error` (the finer one at error / 4: order 2/3 in
// cells over refine = 8).
CheckedSetting setting(const char* method, int cells, double courant, double error) {
  const RegionRule& rule = kRegionRule;
  CheckedSetting s;
  s.method = method;
  s.transfer = "flip";
  s.update = "usl";
  s.cells = cells;
  s.courant = courant;
  s.courant_spectral = 1.0;
  const double A[3] = {rule.amplitudes[0], rule.amplitudes[1], rule.amplitudes[2]};
  s.corners.push_back(corner_run(CornerKind::base, rule.lengths[0], A[1], cells, error));
  for (const double L : rule.lengths) {
    if (L != rule.lengths[0])
      s.corners.push_back(corner_run(CornerKind::base, L, A[1], cells, error));
    s.corners.push_back(corner_run(CornerKind::smallest_A, L, A[0], cells, error));
    s.corners.push_back(corner_run(CornerKind::largest_A, L, A[2], cells, error));
    s.corners.push_back(corner_run(CornerKind::periodic, L, A[2], cells, error));
    s.corners.push_back(corner_run(CornerKind::other_scene, L, A[2], cells, error));
    s.corners.push_back(corner_run(CornerKind::jittered, L, A[2], cells, error));
  }
  s.corners.push_back(
      corner_run(CornerKind::finer, rule.lengths[0], A[1], cells * rule.refine, error / 4));
  s.regions = regions_of(s);
  return s;
}

VerifyProblem problem(double A, double cT, double target) {
  VerifyProblem vp;
  vp.problem.A = A;
  vp.problem.cT = cT;
  vp.problem.target = target;
  return vp;
}

// A stand-in for the solver: stable, with error over time / A = k / cells, times 2 for gimp
// (mpm is the more accurate here), growing with T past 10; unstable above C = 0.9. It counts its
// runs.
struct FakeSolver {
  std::atomic<int> runs{0};
  double k = 1;
  RunResult operator()(const RunParams& p) {
    ++runs;
    RunResult r;
    r.params = p;
    r.particles = std::int64_t(p.ppc) * p.cells;
    r.steps = std::int64_t(std::ceil(p.T * p.cells / p.stepping.cfl_factor - 1e-9));
    r.stable = p.stepping.cfl_factor <= 0.9;
    r.outcome = r.stable ? Outcome::stable : Outcome::unstable;
    double e = k / p.cells * (p.method == Method::gimp ? 2 : 1) * std::max(1.0, p.T / 10);
    r.max_error_over_time = e * p.A;
    return r;
  }
};

RunFn fake(FakeSolver& f) {
  return [&f](const RunParams& p) { return f(p); };
}

TEST(AdviceVerify, PredictionComesFromTheRunsThatMatchAndAFailedCheckRemovesOnlyWhatItTested) {
  CheckedSetting s = setting("gimp", 50, 0.5, 0.02);
  for (auto& c : s.corners)
    if (c.kind == CornerKind::periodic) c.outcome = "unstable";
  const std::vector<CheckedSetting> settings{s};
  VerifyProblem walls = problem(0.015, 5, 0.1);
  VerifyProblem periodic = walls;
  periodic.problem.bc = "periodic";
  const auto on_walls = candidates(settings, walls);
  ASSERT_FALSE(on_walls.empty());
  ASSERT_TRUE(on_walls.front().predicted_error_over_A);
  EXPECT_DOUBLE_EQ(*on_walls.front().predicted_error_over_A, 0.02);
  EXPECT_EQ(on_walls.front().cells, 50);
  // The periodic runs failed: no prediction for a periodic problem, on any grid.
  for (const auto& c : candidates(settings, periodic))
    EXPECT_FALSE(c.predicted_error_over_A) << candidate_name(c) << ": " << c.predicted_from;
  // Past the longer checked length the error grows in proportion to c T.
  VerifyProblem longer = problem(0.015, 1000, 0.5);
  const auto far = candidates(settings, longer);
  ASSERT_TRUE(far.front().predicted_error_over_A);
  EXPECT_DOUBLE_EQ(*far.front().predicted_error_over_A, 0.02 * 1000 / kRegionRule.lengths.back());
  // A finer grid: scaled by the order the finer run measured (error / 4 over 8 x the cells).
  for (const auto& c : on_walls) {
    if (c.cells == 400 && c.start == VelocityStart::exact) {
      EXPECT_NEAR(*c.predicted_error_over_A, 0.02 / 4, 1e-15);
    }
  }
}

TEST(AdviceVerify, CandidatesPredictedToMeetTheTargetComeFirstCheapestFirst) {
  const std::vector<CheckedSetting> settings{setting("gimp", 25, 0.5, 0.3),
                                             setting("mpm", 50, 0.5, 0.01),
                                             setting("gimp", 100, 0.25, 0.001)};
  const auto list = candidates(settings, problem(0.015, 5, 0.05));
  bool eligible = true;
  double last = 0;
  for (const auto& c : list) {
    const bool e = c.predicted_error_over_A && *c.predicted_error_over_A <= 0.05;
    EXPECT_FALSE(e && !eligible) << "an eligible candidate after one that is not";
    if (e != eligible) last = 0;
    eligible = e;
    EXPECT_GE(c.particle_steps, last) << candidate_name(c);
    last = c.particle_steps;
  }
  // gimp on 25 cells (0.3) is predicted to miss; mpm on 50 cells is the cheapest predicted to
  // meet it, exact start before half-step.
  EXPECT_EQ(list[0].from->method, "mpm");
  EXPECT_EQ(list[0].cells, 50);
  EXPECT_EQ(list[0].start, VelocityStart::exact);
  EXPECT_EQ(list[1].start, VelocityStart::half_step);
}

TEST(AdviceVerify, TheAnswerIsTheFirstCandidateWhoseEveryVerifyingRunPasses) {
  // Predicted fine everywhere, but the solver's error is 1 / cells (x 2 for gimp): with a target
  // of 0.012 the problem needs mpm on 100 cells (0.01), its grid check 200 cells, and to 4 x c T
  // = 20 the error doubles (0.02 > 0.012): mpm 100 fails at 4 x c T. At c T = 2.5 (4 x = 10) it
  // passes.
  const std::vector<CheckedSetting> settings{setting("gimp", 25, 0.5, 1e-4),
                                             setting("mpm", 25, 0.5, 1e-4)};
  FakeSolver solver;
  const VerifyProblem vp = problem(0.015, 2.5, 0.012);
  const Verified v = verified_advice(settings, vp, 1e9, false, fake(solver));
  ASSERT_TRUE(v.answer) << v.refusal;
  EXPECT_EQ(v.answer->candidate.from->method, "mpm");
  EXPECT_EQ(v.answer->candidate.cells, 100);
  ASSERT_EQ(v.answer->runs.size(), 3u);
  for (const auto& r : v.answer->runs)
    EXPECT_TRUE(r.passes) << r.what;
  EXPECT_EQ(v.answer->runs[1].params.T, 4 * 2.5);
  EXPECT_EQ(v.answer->runs[2].params.cells, 200);
  // Every cheaper candidate was tried and rejected, each with the run that failed it; a
  // candidate whose problem run fails makes no other run.
  ASSERT_FALSE(v.rejected.empty());
  for (const Trial& t : v.rejected) {
    EXPECT_FALSE(t.passed);
    EXPECT_LE(t.candidate.particle_steps, v.answer->candidate.particle_steps);
    EXPECT_NE(t.why.find("the problem"), std::string::npos) << t.why;
    EXPECT_EQ(t.runs.size(), 1u);
  }
  // The same problem ten times as long: 4 x c T = 100 multiplies every error by 10 and no
  // candidate of the domain's grids meets the target: refused on the target, every one tried.
  const Verified none =
      verified_advice(settings, problem(0.015, 25, 0.012), 1e9, false, fake(solver));
  EXPECT_FALSE(none.answer);
  EXPECT_EQ(none.bound, "target");
  EXPECT_EQ(none.rejected.size(), none.eligible);
}

TEST(AdviceVerify, TheBudgetRefusesBeforeRunningAndNamesTheCandidateAndItsCost) {
  const std::vector<CheckedSetting> settings{setting("mpm", 25, 0.5, 1e-4)};
  FakeSolver solver;
  const Verified v = verified_advice(settings, problem(0.015, 100, 0.1), 1e-9, false, fake(solver));
  EXPECT_FALSE(v.answer);
  EXPECT_EQ(v.bound, "budget");
  EXPECT_EQ(solver.runs.load(), 0);
  EXPECT_NE(v.refusal.find("mpm/flip/usl, 25 cells, C = 0.5"), std::string::npos) << v.refusal;
  EXPECT_NE(v.refusal.find("particle-steps"), std::string::npos) << v.refusal;
}

TEST(AdviceVerify, AProblemTooShortForAVerdictIsRefusedWithTheShortestThatGetsOne) {
  const std::vector<CheckedSetting> settings{setting("mpm", 25, 0.5, 1e-4)};
  FakeSolver solver;
  const Verified v = verified_advice(settings, problem(0.015, 1e-3, 0.1), 1e9, false, fake(solver));
  EXPECT_FALSE(v.answer);
  EXPECT_EQ(v.bound, "too_short");
  // 10 steps of C = 0.5 on the finest grid, 800 cells: c T/L = 10 x 0.5 / 800.
  EXPECT_NE(v.refusal.find(value_text(10 * 0.5 / 800)), std::string::npos) << v.refusal;
  EXPECT_EQ(solver.runs.load(), 0);
  // Every candidate offered takes at least kMinStepsToJudge steps.
  for (const auto& c : candidates(settings, problem(0.015, 0.05, 0.1)))
    EXPECT_GE(c.particle_steps / (2.0 * c.cells), double(kMinStepsToJudge));
}

TEST(AdviceVerify, TheDomainNamesTheBoundAProblemIsOutside) {
  EXPECT_NE(outside_domain(problem(0.3, 10, 0.1)).find("--A"), std::string::npos);
  EXPECT_NE(outside_domain(problem(5e-5, 10, 0.1)).find("--A"), std::string::npos);
  EXPECT_NE(outside_domain(problem(0.01, 1e6, 0.1)).find("--cT"), std::string::npos);
  EXPECT_NE(outside_domain(problem(0.01, 10, 1e-9)).find("--error"), std::string::npos);
  VerifyProblem jittered = problem(0.01, 10, 0.1);
  jittered.jitter = 0.9;
  EXPECT_NE(outside_domain(jittered).find("--jitter"), std::string::npos);
  EXPECT_TRUE(outside_domain(problem(1e-4, 1000, 1e-3)).empty());
  EXPECT_TRUE(outside_domain(problem(0.05, 1, 1)).empty());
}

TEST(AdviceVerify, TheMarginsAreTheSurvivalAndAccuracyEdgesOnTheProblem) {
  // The stand-in fails above C = 0.9 and its error does not depend on C: the survival edge lies
  // in (0.9 / 1.025, 0.9], and the accuracy edge with it.
  const std::vector<CheckedSetting> settings{setting("mpm", 100, 0.25, 1e-4)};
  FakeSolver solver;
  const Verified v = verified_advice(settings, problem(0.015, 2, 0.05), 1e9, true, fake(solver));
  ASSERT_TRUE(v.answer) << v.refusal;
  ASSERT_TRUE(v.edges.measured) << v.edges.not_measured;
  const EdgeResult& m = v.edges.search;
  ASSERT_TRUE(m.dt_edge && m.dt_fail);
  EXPECT_LE(*m.dt_edge, 0.9);
  EXPECT_GT(*m.dt_fail, 0.9);
  EXPECT_LE(*m.dt_fail / *m.dt_edge, 1.025);
  EXPECT_EQ(m.dt_accurate, m.dt_edge);
  EXPECT_TRUE(m.monotone());
  // Measured at the length the answer is verified at: 4 x c T.
  EXPECT_DOUBLE_EQ(v.edges.cT, 4 * 2.0);
  EXPECT_DOUBLE_EQ(v.edges.A, 0.015);
  // Scanned densely below the edge: at least 8 runs from 0.9x the edge up to it.
  int below = 0;
  for (const auto& p : m.probes)
    below += p.dt >= 0.9 * *m.dt_edge && p.dt < *m.dt_edge;
  EXPECT_GE(below, 8);
}

TEST(AdviceVerify, MarginsOfRunsUnderAWavePassAreNone) {
  // c T = 0.1: even 4 x c T is under a wave pass, too short for a verdict: no margin.
  const std::vector<CheckedSetting> settings{setting("mpm", 100, 0.25, 1e-4)};
  FakeSolver solver;
  const VerifyProblem vp = problem(0.015, 0.1, 0.05);
  const Verified v = verified_advice(settings, vp, 1e9, true, fake(solver));
  if (!v.answer) GTEST_SKIP() << v.refusal;
  ASSERT_TRUE(v.edges.measured);
  EXPECT_TRUE(v.edges.search.too_short);
  EXPECT_FALSE(v.edges.search.dt_edge);
  EXPECT_TRUE(v.edges.search.probes.empty());
  EXPECT_NE(verified_text(v, vp).find("too short for a verdict"), std::string::npos);
}

TEST(AdviceVerify, TheJsonCarriesEveryVerifyingRunAndEveryRejection) {
  const std::vector<CheckedSetting> settings{setting("gimp", 25, 0.5, 1e-4),
                                             setting("mpm", 25, 0.5, 1e-4)};
  FakeSolver solver;
  const VerifyProblem vp = problem(0.015, 2.5, 0.012);
  const Verified v = verified_advice(settings, vp, 1e9, false, fake(solver));
  const ojson j = verified_json(v, vp);
  EXPECT_EQ(j["verified"], true);
  EXPECT_EQ(j["answer"]["method"], "mpm");
  EXPECT_EQ(j["answer"]["cells"], 100);
  ASSERT_EQ(j["verifying_runs"].size(), 3u);
  for (const auto& r : j["verifying_runs"]) {
    for (const char* key :
         {"what", "cells", "cT", "outcome", "error_over_A", "particle_steps", "seconds", "passes"})
      EXPECT_TRUE(r.contains(key)) << key;
  }
  EXPECT_EQ(j["rejected"].size(), v.rejected.size());
  EXPECT_FALSE(j["rejected"][0]["why"].get<std::string>().empty());
  const ojson u = unverified_json(candidates(settings, vp).front(), vp);
  EXPECT_EQ(u["verified"], false);
  const std::string text = unverified_text(candidates(settings, vp).front(), vp);
  EXPECT_NE(text.find("UNVERIFIED"), std::string::npos);
}

TEST(AdviceVerify, TheSampleDrawIsSeededAndCoversTheDomain) {
  const auto a = draw_problems();
  const auto b = draw_problems();
  ASSERT_EQ(a.size(), std::size_t(kSampleRule.problems));
  const AdviceDomain& d = kAdviceDomain;
  int steffen = 0, periodic = 0, jittered = 0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    const Problem& p = a[i].problem;
    EXPECT_EQ(p.A, b[i].problem.A);
    EXPECT_EQ(p.cT, b[i].problem.cT);
    EXPECT_EQ(a[i].jitter, b[i].jitter);
    EXPECT_TRUE(outside_domain(a[i]).empty()) << outside_domain(a[i]);
    EXPECT_GE(p.cT, kSampleRule.cT_low);
    steffen += p.scene == "steffen";
    periodic += p.bc == "periodic";
    jittered += a[i].jitter > 0;
  }
  // Each attribute one of two with even odds: far from none and from all.
  for (const int n : {steffen, periodic, jittered}) {
    EXPECT_GT(n, kSampleRule.problems / 4);
    EXPECT_LT(n, 3 * kSampleRule.problems / 4);
  }
  // Another seed, another draw.
  SampleRule other = kSampleRule;
  other.seed += 1;
  EXPECT_NE(draw_problems(other).front().problem.A, a.front().problem.A);
  (void)d;
}

// The command on the committed data: the answer's "run it with" line, run again on its own at
// c T and at 4 x c T, meets the target; a problem outside the domain exits 2.
TEST(AdviceVerify, TheCommandsAnswerRunAgainIndependentlyMeetsTheTarget) {
  const std::string data = std::string(MPMSTAB_SOURCE_DIR) + "/results/advice.json";
  const auto answer = test_support::run_mpmstab(
      "advise --A 0.008 --cT 25 --error 0.05 --scene steffen --json --no-margins --data " + data);
  ASSERT_EQ(answer.status, 0) << answer.output;
  const ojson j = ojson::parse(answer.output);
  const std::string command = j["answer"]["run"].get<std::string>().substr(8);  // "mpmstab "
  for (const double factor : {1.0, 4.0}) {
    std::string c = command;
    if (factor != 1)
      c = c.substr(0, c.find(" --T ")) + " --T 100" + c.substr(c.find(" --T 25") + 7);
    const auto run = test_support::run_mpmstab(c + " --json");
    ASSERT_EQ(run.status, 0) << c << "\n" << run.output;
    const ojson r = ojson::parse(run.output);
    EXPECT_EQ(r["outcome"], "stable") << c;
    EXPECT_LE(r["max_error_over_time"].get<double>() / 0.008, 0.05) << c;
  }
  const auto outside =
      test_support::run_mpmstab("advise --A 0.3 --cT 1e6 --error 1e-9 --data " + data);
  EXPECT_EQ(outside.status, 2);
  EXPECT_NE(outside.output.find("--A"), std::string::npos) << outside.output;
}

}  // namespace
}  // namespace mpmstab
