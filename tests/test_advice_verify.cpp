// Advice verified on the problem (experiments/studies/choice/advice_verify.hpp): the prediction
// from the runs that match the problem (and the distant one, which never excludes), the order
// candidates are tried in, the skips, the verifying runs and the answer they allow, each refusal
// (domain, too short, target, budget in particle-steps), the margins, and the JSON. The search is
// driven by a stand-in for the solver whose error is a known function of the setting, so that
// which candidate must answer is known exactly; two tests run the real command.
#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <mutex>
#include <nlohmann/json.hpp>
#include <thread>

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
  if (kind == CornerKind::jittered) c.jitter = kRegionRule.jitters.front();
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
// runs, and takes `delay` of wall time over each.
struct FakeSolver {
  std::atomic<int> runs{0};
  double k = 1;
  std::chrono::microseconds delay{0};
  RunResult operator()(const RunParams& p) {
    ++runs;
    if (delay.count() > 0) std::this_thread::sleep_for(delay);
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

// The candidate of a setting on `cells` cells with `ppc` particles per cell and a start.
Candidate candidate(const CheckedSetting& s, int cells, int ppc = 2,
                    VelocityStart start = VelocityStart::exact) {
  Candidate c;
  c.from = &s;
  c.cells = cells;
  c.ppc = ppc;
  c.start = start;
  return c;
}

const Candidate* find(const std::vector<Candidate>& list, int cells, int ppc, VelocityStart start) {
  for (const auto& c : list)
    if (c.cells == cells && c.ppc == ppc && c.start == start) return &c;
  return nullptr;
}

TEST(AdviceVerify, PredictionComesFromTheRunsThatMatchAndAFailedCheckRemovesOnlyWhatItTested) {
  CheckedSetting s = setting("gimp", 50, 0.5, 0.02);
  for (auto& c : s.corners) {
    if (c.kind == CornerKind::periodic) c.outcome = "unstable";
    if (c.kind == CornerKind::jittered) c.error_over_A = 0.9;
  }
  const std::vector<CheckedSetting> settings{s};
  const VelocityStart exact = VelocityStart::exact, half = VelocityStart::half_step;
  const auto on_walls = candidates(settings, problem(0.015, 5, 0.1));
  ASSERT_FALSE(on_walls.empty());
  EXPECT_EQ(on_walls.front().cells, 50);
  ASSERT_TRUE(on_walls.front().matching && on_walls.front().predicted_error_over_A);
  EXPECT_DOUBLE_EQ(*on_walls.front().predicted_error_over_A, 0.02);
  // The half-step start, 4 particles per cell and the grids without a run of their own have
  // distant predictions (a finer grid's scaled by the order the finer run measured); the finer
  // run itself (400 cells) matches the problem on its grid.
  for (const auto& c : on_walls)
    EXPECT_EQ(c.matching, (c.cells == 50 || c.cells == 400) && c.ppc == 2 && c.start == exact)
        << candidate_name(c);
  ASSERT_TRUE(find(on_walls, 200, 2, exact) && find(on_walls, 400, 2, exact));
  EXPECT_DOUBLE_EQ(*find(on_walls, 400, 2, exact)->predicted_error_over_A, 0.02 / 4);
  const double q = std::log(4.0) / std::log(8.0);
  EXPECT_NEAR(*find(on_walls, 200, 2, exact)->predicted_error_over_A,
              0.02 * std::pow(50.0 / 200, q), 1e-15);
  // The periodic run failed: a periodic problem at an amplitude it matches is predicted to fail
  // on the setting's own grid; no other candidate is (no prediction where it rests on that run).
  VerifyProblem periodic = problem(0.03, 5, 0.1);
  periodic.problem.bc = "periodic";
  for (const auto& c : candidates(settings, periodic)) {
    EXPECT_EQ(predicted_to_fail(c, 0.1), c.cells == 50 && c.ppc == 2 && c.start == exact)
        << candidate_name(c) << ": " << c.predicted_from;
    EXPECT_FALSE(c.predicted_error_over_A) << candidate_name(c);
  }
  // A uniform problem matches no jittered run (0.9 there), a jittered one only a jitter within a
  // factor 2 of its own; an amplitude must be within a factor 3, c T within the longest run.
  EXPECT_DOUBLE_EQ(*candidates(settings, problem(0.05, 5, 0.1)).front().predicted_error_over_A,
                   0.02);
  VerifyProblem jittered = problem(0.05, 5, 0.1);
  jittered.jitter = 0.08;
  EXPECT_TRUE(find(candidates(settings, jittered), 50, 2, exact)->matching);
  EXPECT_DOUBLE_EQ(*find(candidates(settings, jittered), 50, 2, exact)->predicted_error_over_A,
                   0.9);
  jittered.jitter = 0.2;
  EXPECT_FALSE(find(candidates(settings, jittered), 50, 2, exact)->matching);
  EXPECT_TRUE(find(candidates(settings, problem(4e-4, 5, 0.1)), 50, 2, exact)->matching);
  EXPECT_FALSE(find(candidates(settings, problem(2e-4, 5, 0.1)), 50, 2, exact)->matching);
  EXPECT_TRUE(find(candidates(settings, problem(0.015, 100, 0.1)), 50, 2, exact)->matching);
  // Past the longest run: distant, grown in proportion to c T.
  const auto far_list = candidates(settings, problem(0.015, 1000, 0.5));
  const Candidate* far = find(far_list, 50, 2, exact);
  ASSERT_TRUE(far && far->predicted_error_over_A);
  EXPECT_FALSE(far->matching);
  EXPECT_DOUBLE_EQ(*far->predicted_error_over_A, 0.02 * 1000 / kRegionRule.lengths.back());
  EXPECT_NE(far->predicted_from.find("distant"), std::string::npos) << far->predicted_from;
  (void)half;
}

TEST(AdviceVerify, CandidatesGoCheapestFirstWithTheirOwnParticlesPerCell) {
  const std::vector<CheckedSetting> settings{setting("gimp", 25, 0.5, 0.3),
                                             setting("mpm", 50, 0.5, 0.01),
                                             setting("gimp", 100, 0.25, 0.001)};
  const double target = 0.05;
  const auto list = candidates(settings, problem(0.015, 5, target));
  for (std::size_t i = 1; i < list.size(); ++i) {
    const Candidate &a = list[i - 1], &b = list[i];
    ASSERT_LE(a.particle_steps, b.particle_steps) << candidate_name(b);
    if (a.particle_steps == b.particle_steps) {
      EXPECT_FALSE(b.matching && !predicted_to_fail(b, target) &&
                   !(a.matching && !predicted_to_fail(a, target)))
          << candidate_name(b) << " after " << candidate_name(a);
    }
  }
  // gimp on 25 cells comes first, though its matching run misses the target; among those of
  // mpm's cost, mpm on 50 cells (matching, 0.01), exact start before half-step.
  EXPECT_EQ(list[0].from->method, "gimp");
  EXPECT_TRUE(predicted_to_fail(list[0], target));
  const auto mpm = std::find_if(list.begin(), list.end(),
                                [](const Candidate& c) { return c.from->method == "mpm"; });
  ASSERT_NE(mpm, list.end());
  EXPECT_EQ(mpm->cells, 50);
  EXPECT_EQ(mpm->ppc, 2);
  EXPECT_TRUE(mpm->matching);
  EXPECT_EQ(mpm->start, VelocityStart::exact);
  EXPECT_EQ((mpm + 1)->start, VelocityStart::half_step);
  // Every method and C also with 4 particles per cell: its own runs, name and command.
  int four = 0;
  for (const auto& c : list) {
    if (c.ppc != 4) continue;
    ++four;
    EXPECT_FALSE(c.matching) << candidate_name(c);
    EXPECT_NE(candidate_name(c).find(" x 4 ppc"), std::string::npos) << candidate_name(c);
    EXPECT_NE(run_command(c, problem(0.015, 5, target)).find(" --ppc 4 "), std::string::npos);
    EXPECT_EQ(run_params(c, problem(0.015, 5, target)).ppc, 4);
    EXPECT_DOUBLE_EQ(c.particle_steps, 4.0 * c.cells * std::ceil(5 * c.cells / c.from->courant));
  }
  EXPECT_EQ(2 * four, int(list.size()));
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
  const Verified v = verified_advice(settings, vp, 1e12, false, fake(solver));
  ASSERT_TRUE(v.answer) << v.refusal;
  EXPECT_EQ(v.answer->candidate.from->method, "mpm");
  EXPECT_EQ(v.answer->candidate.cells, 100);
  EXPECT_EQ(v.answer->candidate.ppc, 2);
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
  // candidate of the domain's grids meets the target: refused on the target, every candidate
  // tried or skipped, naming the smallest error measured on the problem (mpm, 800 cells).
  const Verified none =
      verified_advice(settings, problem(0.015, 25, 0.012), 1e12, false, fake(solver));
  EXPECT_FALSE(none.answer);
  EXPECT_EQ(none.bound, "target");
  EXPECT_EQ(none.rejected.size() + none.skipped_predicted + none.skipped_own_runs, none.candidates);
  ASSERT_TRUE(none.smallest);
  EXPECT_DOUBLE_EQ(none.smallest->error_over_A, 2.5 / 800);
  EXPECT_NE(none.refusal.find("smallest error over time the search measured on the problem is " +
                              sci(2.5 / 800) + " A, by mpm/flip/usl, 800 cells x 2 ppc, C = 0.5"),
            std::string::npos)
      << none.refusal;
}

TEST(AdviceVerify, TheBudgetRefusesBeforeRunningAndNamesTheCandidateAndItsCost) {
  const std::vector<CheckedSetting> settings{setting("mpm", 25, 0.5, 1e-4)};
  FakeSolver solver;
  const Verified v = verified_advice(settings, problem(0.015, 100, 0.1), 1, false, fake(solver));
  EXPECT_FALSE(v.answer);
  EXPECT_EQ(v.bound, "budget");
  EXPECT_EQ(solver.runs.load(), 0);
  EXPECT_NE(v.refusal.find("mpm/flip/usl, 25 cells x 2 ppc, C = 0.5"), std::string::npos)
      << v.refusal;
  EXPECT_NE(v.refusal.find("the budget of " + sci(1) + " particle-steps"), std::string::npos)
      << v.refusal;
}

// The budget counts particle-steps from each candidate's parameters: runs that take a different
// wall time give the same answer, the same refusal and the same margins.
TEST(AdviceVerify, TheBudgetDecidesOnParticleStepsAloneNotSeconds) {
  const std::vector<CheckedSetting> settings{setting("gimp", 25, 0.5, 1e-4),
                                             setting("mpm", 25, 0.5, 1e-4)};
  const VerifyProblem vp = problem(0.015, 2.5, 0.012);
  FakeSolver probe;
  const Verified full = verified_advice(settings, vp, 1e12, false, fake(probe));
  ASSERT_TRUE(full.answer) << full.refusal;
  for (const double budget : {full.particle_steps, full.particle_steps - 1}) {
    FakeSolver fast, slow;
    slow.delay = std::chrono::microseconds(3000);
    const Verified a = verified_advice(settings, vp, budget, true, fake(fast));
    const Verified b = verified_advice(settings, vp, budget, true, fake(slow));
    EXPECT_GT(b.seconds, a.seconds);
    EXPECT_EQ(bool(a.answer), budget == full.particle_steps);
    EXPECT_EQ(verified_json(a, vp).dump(), verified_json(b, vp).dump());
    EXPECT_EQ(verified_text(a, vp, false), verified_text(b, vp, false));
    EXPECT_EQ(a.refusal, b.refusal);
    EXPECT_EQ(fast.runs.load(), slow.runs.load());
    if (a.answer) {  // no particle-step left for the margins: said so, on either machine
      EXPECT_FALSE(a.edges.measured);
      EXPECT_NE(a.edges.not_measured.find("budget"), std::string::npos);
    } else {
      EXPECT_EQ(a.bound, "budget");
    }
  }
}

// A matching prediction that fails skips its candidate; a distant one (another start, another
// amplitude, jitter or length than any run) never does.
TEST(AdviceVerify, AMatchingPredictionExcludesADistantOneNever) {
  const std::vector<CheckedSetting> settings{setting("gimp", 25, 0.5, 0.5)};
  struct Seen {
    std::vector<RunParams> runs;
    std::mutex m;
  } seen;
  FakeSolver solver;
  solver.k = 0.01;
  const RunFn run_fn = [&](const RunParams& p) {
    std::lock_guard lock(seen.m);
    seen.runs.push_back(p);
    return solver(p);
  };
  auto answer = [&](VerifyProblem vp) {
    seen.runs.clear();
    const Verified v = verified_advice(settings, vp, 1e12, false, run_fn);
    EXPECT_TRUE(v.answer) << v.refusal;
    return v;
  };
  const Verified matched = answer(problem(0.015, 2.5, 0.1));
  EXPECT_EQ(matched.skipped_predicted, 1u);
  EXPECT_EQ(matched.answer->candidate.start, VelocityStart::half_step);
  for (const auto& r : seen.runs)
    EXPECT_FALSE(r.cells == 25 && r.ppc == 2 && r.start == VelocityStart::exact);
  VerifyProblem jittered = problem(0.05, 2.5, 0.1);
  jittered.jitter = 0.08;
  EXPECT_EQ(answer(jittered).answer->candidate.start, VelocityStart::half_step);
  jittered.jitter = 0.2;
  VerifyProblem steffen = problem(0.015, 2.5, 0.1);
  steffen.problem.scene = "steffen";
  for (const VerifyProblem& vp :
       {problem(2e-4, 2.5, 0.1), problem(0.015, 150, 0.1), jittered, steffen}) {
    const Verified v = answer(vp);
    EXPECT_EQ(v.skipped_predicted, 0u);
    EXPECT_EQ(v.answer->candidate.start, VelocityStart::exact);
    EXPECT_EQ(v.answer->candidate.cells, 25);
  }
}

// A problem's own run that measured an error above the target shows that the same method,
// particles per cell and start cannot pass on fewer cells at a larger C; an unstable one, on the
// same cells at a larger C. Nothing else is skipped.
TEST(AdviceVerify, TheProblemsOwnRunsSkipOnlyWhatTheyShowCannotPass) {
  const CheckedSetting s05 = setting("gimp", 25, 0.5, 1e-4), s1 = setting("gimp", 25, 1, 1e-4),
                       s025 = setting("gimp", 25, 0.25, 1e-4), m1 = setting("mpm", 25, 1, 1e-4);
  const VerifyProblem vp = problem(0.015, 2.5, 0.1);
  const VerifyingRun inaccurate{.what = "the problem",
                                .params = run_params(candidate(s05, 50), vp),
                                .outcome = "stable",
                                .error_over_A = 0.5};
  const VelocityStart half = VelocityStart::half_step;
  for (const Candidate& c :
       {candidate(s05, 50), candidate(s05, 25), candidate(s1, 25), candidate(s1, 50)})
    EXPECT_FALSE(shown_unable(c, vp, {inaccurate}).empty()) << candidate_name(c);
  for (const Candidate& c : {candidate(s05, 100), candidate(s025, 25), candidate(s1, 25, 2, half),
                             candidate(s1, 25, 4), candidate(m1, 25)})
    EXPECT_TRUE(shown_unable(c, vp, {inaccurate}).empty()) << candidate_name(c);
  VerifyingRun accurate = inaccurate;
  accurate.error_over_A = 0.05;
  EXPECT_TRUE(shown_unable(candidate(s1, 25), vp, {accurate}).empty());
  VerifyingRun unstable = inaccurate;
  unstable.outcome = "unstable";
  EXPECT_FALSE(shown_unable(candidate(s1, 50), vp, {unstable}).empty());
  EXPECT_FALSE(shown_unable(candidate(s05, 50), vp, {unstable}).empty());
  EXPECT_TRUE(shown_unable(candidate(s1, 25), vp, {unstable}).empty());
  EXPECT_TRUE(shown_unable(candidate(s025, 50), vp, {unstable}).empty());
  // In the search: the grid check of 25 cells is the problem on 50; a solver that fails on 50
  // cells and more fails that check, and the candidates on 50 cells are skipped, never run; the
  // refusal names the smallest error measured on the problem and its candidate.
  const std::vector<CheckedSetting> settings{s05};
  std::atomic<int> on_50{0};
  const RunFn run_fn = [&](const RunParams& p) {
    FakeSolver f;
    RunResult r = f(p);
    if (p.cells == 50 && p.T == 2.5) ++on_50;
    r.max_error_over_time = (p.cells <= 25 ? 0.05 : 0.5) * p.A;
    return r;
  };
  const Verified v = verified_advice(settings, vp, 1e12, false, run_fn);
  EXPECT_FALSE(v.answer);
  EXPECT_EQ(v.skipped_own_runs, 4u);  // 50 cells: 2 and 4 ppc, each start
  EXPECT_EQ(on_50.load(), 4);         // the grid checks of 25 cells alone
  EXPECT_NE(v.refusal.find("is " + sci(0.05) + " A, by gimp/flip/usl, 25 cells x 2 ppc, C = 0.5"),
            std::string::npos)
      << v.refusal;
}

TEST(AdviceVerify, AProblemTooShortForAVerdictIsRefusedWithTheShortestThatGetsOne) {
  const std::vector<CheckedSetting> settings{setting("mpm", 25, 0.5, 1e-4)};
  FakeSolver solver;
  const Verified v =
      verified_advice(settings, problem(0.015, 1e-3, 0.1), 1e12, false, fake(solver));
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
  const Verified v = verified_advice(settings, problem(0.015, 2, 0.05), 1e12, true, fake(solver));
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
  const Verified v = verified_advice(settings, vp, 1e12, true, fake(solver));
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
  const Verified v = verified_advice(settings, vp, 1e12, false, fake(solver));
  const ojson j = verified_json(v, vp);
  EXPECT_EQ(j["verified"], true);
  EXPECT_EQ(j["answer"]["method"], "mpm");
  EXPECT_EQ(j["answer"]["cells"], 100);
  EXPECT_EQ(j["answer"]["ppc"], 2);
  ASSERT_EQ(j["verifying_runs"].size(), 3u);
  for (const auto& r : j["verifying_runs"]) {
    for (const char* key :
         {"what", "cells", "cT", "outcome", "error_over_A", "particle_steps", "passes"})
      EXPECT_TRUE(r.contains(key)) << key;
  }
  EXPECT_EQ(j["rejected"].size(), v.rejected.size());
  EXPECT_FALSE(j["rejected"][0]["why"].get<std::string>().empty());
  EXPECT_EQ(j["tried"], v.rejected.size() + 1);
  EXPECT_EQ(j["passed"].size(), 1u);
  EXPECT_EQ(j["budget_particle_steps"], 1e12);
  EXPECT_EQ(j["particle_steps"], v.particle_steps);
  // The seconds vary from machine to machine: the text prints them, the JSON does not.
  EXPECT_EQ(j.dump().find("seconds"), std::string::npos);
  const std::string text = verified_text(v, vp);
  for (const char* words : {"tried", "skipped", "particle-steps spent", "passed", " s of runs)"})
    EXPECT_NE(text.find(words), std::string::npos) << words << "\n" << text;
  const ojson u = unverified_json(candidates(settings, vp).front(), vp);
  EXPECT_EQ(u["verified"], false);
  EXPECT_NE(unverified_text(candidates(settings, vp).front(), vp).find("UNVERIFIED"),
            std::string::npos);
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

// On the committed data, a small amplitude that no run of mpm matches (the study's mpm runs are at
// A/L = 0.015, beyond a factor 3): their predictions are distant, exclude nothing, and mpm answers.
TEST(AdviceVerify, TheCommandAnswersWithTheMethodAskedForWhereNoRunMatches) {
  const std::string data = std::string(MPMSTAB_SOURCE_DIR) + "/results/advice.json";
  const auto answer = test_support::run_mpmstab(
      "advise --A 1e-3 --cT 8 --error 0.01 --methods mpm --json --no-margins --data " + data);
  ASSERT_EQ(answer.status, 0) << answer.output;
  const ojson j = ojson::parse(answer.output);
  EXPECT_EQ(j["answer"]["method"], "mpm");
  EXPECT_EQ(j["answer"]["prediction_matching"], false);
  EXPECT_EQ(j["skipped_predicted_to_fail"], 0);
  for (const auto& r : j["verifying_runs"])
    EXPECT_TRUE(r["passes"].get<bool>()) << r.dump();
}

}  // namespace
}  // namespace mpmstab
