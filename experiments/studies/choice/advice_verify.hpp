// Advice verified at the point of use (docs/studies.md, "Advice: verified on the problem"): the
// candidates for a problem with their predicted error and cost, the runs that verify one on the
// problem, and the search that answers with the cheapest candidate it finds to pass among those it
// does not skip, within a budget of particle-steps. `mpmstab advise` answers by it; advice_sample
// and tradeoff verify with it.
#pragma once

#include <cstdint>
#include <functional>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "base/params.hpp"
#include "base/result.hpp"
#include "choice/advice_rule.hpp"
#include "run/edge.hpp"

namespace mpmstab {

// The problems `mpmstab advise` answers, and the grids and steps it answers with.
struct AdviceDomain {
  double A_min = 1e-4, A_max = 0.05;         // A / L
  double cT_max = 1000;                      // c T / L (the shortest: a verdict, kMinStepsToJudge)
  double target_min = 1e-3, target_max = 1;  // error over time / A
  double jitter_max = 0.5;                   // of the particle spacing
  std::vector<int> cells{25, 50, 100, 200, 400, 800};
  double length_factor = 4;  // a verifying run goes to this many times c T
  int grid_factor = 2;       // the grid check: this many times the cells at the same C
  int more_ppc = 4;          // each setting's method and C also with this many particles per cell
  // A corner run matches a problem with an amplitude within this factor of its A, and a jittered
  // one a jittered problem whose jitter is within this factor of its own.
  double match_A_factor = 3, match_jitter_factor = 2;
  // The default bound on the particle-steps (particles x steps) of the verifying runs and the
  // margins' probes: the work, the same on any machine. Set so that a search spending all of it
  // takes well under a minute on two cores: on a 2-core AMD EPYC with AVX-512, searches of the
  // advice sample's problems ran at about 5e7 particle-steps per second (both cores together),
  // and those that spent it all took 32 to 38 s.
  double budget_particle_steps = 2e9;
  // The margins: C stepped up by edge_step from the answer's until a run fails or C passes
  // edge_top, then each bracket bisected until its ends are within a factor edge_tolerance.
  double edge_step = 1.4142135623730951;  // sqrt(2)
  double edge_top = 8;
  double edge_tolerance = 1.025;
};
inline const AdviceDomain kAdviceDomain{};

// A problem as `mpmstab advise` takes it: the Problem of the lookup and its particle layout.
struct VerifyProblem {
  Problem problem;
  double jitter = 0;  // particles moved by up to jitter / 2 of their spacing (0: uniform)
};

// Why a problem is outside the domain, naming the option and the bound; empty when inside.
std::string outside_domain(const VerifyProblem& p, const AdviceDomain& d = kAdviceDomain);

// A setting a problem can be answered with: a checked setting of the advice study, or that
// setting's method and C on a finer grid of the domain; with the setting's particles per cell or
// more_ppc; with the exact or the half-step start.
struct Candidate {
  const CheckedSetting* from = nullptr;  // the study's setting its prediction rests on
  int cells = 0;
  int ppc = 2;
  VelocityStart start = VelocityStart::exact;
  // The prediction (error over time / A), in words. Matching: read from a run of the candidate
  // itself (its method, C, cells, particles per cell, the exact start) on the problem's scene,
  // boundary and layout, at an amplitude and to a length that match it; none where that run did
  // not end stable (the candidate is predicted to fail). Else distant (or none): it may order
  // candidates but never excludes one.
  std::optional<double> predicted_error_over_A;
  bool matching = false;
  std::string predicted_from;
  double particle_steps = 0;         // of the run on the problem
  double verify_particle_steps = 0;  // of its verifying runs together
};

// A matching prediction says the candidate fails: its run did not end stable or its error over
// time / A is above the target.
bool predicted_to_fail(const Candidate& c, double target);

// "gimp/flip/usl, 100 cells x 2 ppc, C = 0.5" (", half-step start" where it starts so).
std::string candidate_name(const Candidate& c);
// The candidate as the parameters of a run of the problem (E = kAdviceE: c = 1, T = c T).
RunParams run_params(const Candidate& c, const VerifyProblem& p);
// The options of `mpmstab run` that run it on the problem.
std::string run_command(const Candidate& c, const VerifyProblem& p);

// Every candidate for the problem in the order tried: cheapest first in particle-steps of its run
// on the problem (ties: a matching prediction that meets the target first, then the smaller
// prediction, then the exact start).
std::vector<Candidate> candidates(const std::vector<CheckedSetting>& settings,
                                  const VerifyProblem& p, const AdviceDomain& d = kAdviceDomain);

// A candidate's verifying runs, named: the problem, length_factor x c T, grid_factor x the cells.
std::vector<std::pair<std::string, RunParams>> verifying_params(
    const Candidate& c, const VerifyProblem& p, const AdviceDomain& d = kAdviceDomain);

// One verifying run.
struct VerifyingRun {
  std::string what;  // "the problem", "4 x c T", "2 x the cells"
  RunParams params;
  std::string outcome;  // unstable, meaningless, stable, too_short, or "not run"
  std::optional<double> error_over_A;
  double particle_steps = 0;
  double seconds = 0;
  bool passes = false;  // stable, with an error over time at most the target
};

// A verifying run read back from a study's follow-up row; its params hold its E, A, T and cells.
VerifyingRun verifying_run_of(std::string what, const nlohmann::ordered_json& row, double target);

// The problem's own runs show the candidate cannot pass: a run of the problem (its c T, A, scene,
// boundary and layout) of the candidate's method, particles per cell and start, on at least its
// cells and at most its C, measured an error over time / A above the target; or one on its cells
// at most its C was unstable. That run in words, or empty.
std::string shown_unable(const Candidate& c, const VerifyProblem& p,
                         const std::vector<VerifyingRun>& problem_runs);
// Why a verifying run failed: "4 x c T: stable, error over time 0.12 A > the target 0.1 A".
std::string failure_words(const VerifyingRun& r, double target);

// A candidate tried, with its verifying runs and, where it failed, why.
struct Trial {
  Candidate candidate;
  std::vector<VerifyingRun> runs;
  bool passed = false;
  std::string why;  // the first run that failed, in words
};

// The answer's margins on the problem, in C, by the edge search (core/run/edge.hpp) from its C,
// every run at length_factor x c T: the survival edge (dt_edge) and the accuracy edge (stable
// within the target, dt_accurate).
struct ProblemEdges {
  bool measured = false;
  std::string not_measured;  // why, where not measured
  EdgeResult search;
  double cT = 0, A = 0;       // the run length and amplitude of every run of the search
  double scan_top = 0;        // the largest C the scan reaches
  double particle_steps = 0;  // of its probes
  double seconds = 0;
};

// The smallest error over time / A the search measured on the problem, and the candidate's.
struct Measured {
  double error_over_A = 0;
  Candidate candidate;
};

struct Verified {
  std::optional<Trial> answer;  // the first candidate tried whose every verifying run passed
  std::vector<Trial> rejected;  // the candidates tried before it, in order
  std::size_t candidates = 0;   // every candidate for the problem
  // Skipped before the answer: a matching prediction says it fails; the problem's own runs show it
  // cannot pass.
  std::size_t skipped_predicted = 0, skipped_own_runs = 0;
  std::optional<Measured> smallest;  // of the problem's runs of the candidates tried
  std::string refusal;               // where refused: why, naming the bound that decided it
  std::string bound;                 // "target", "budget", "too_short", "methods"
  ProblemEdges edges;
  double budget = 0;          // particle-steps
  double particle_steps = 0;  // of every run made, the margins' probes included
  double seconds = 0;         // wall time of every run made (printed, never deciding)
};

// Runs a candidate's verifying runs: the problem first (where it fails, nothing more is run),
// then 4 x c T and the grid check side by side. `target` is the error over time / A to meet.
using RunFn = std::function<RunResult(const RunParams&)>;
Trial verify(const Candidate& c, const VerifyProblem& p, const RunFn& run_fn,
             const AdviceDomain& d = kAdviceDomain);

// The search: candidates in order, each skipped (predicted_to_fail, shown_unable) or verified,
// until one passes, none is left, or the next one's verifying runs would take the particle-steps
// spent so far past `budget_particle_steps` (refused); then, with `edges`, the answer's margins
// within what is left. Every decision counts particle-steps only: the same problem gets the same
// answer or refusal on any machine.
Verified verified_advice(const std::vector<CheckedSetting>& settings, const VerifyProblem& p,
                         double budget_particle_steps, bool edges, const RunFn& run_fn,
                         const AdviceDomain& d = kAdviceDomain);

// The advice sample (docs/studies.md): problems drawn from a fixed seed (std::mt19937_64, u from
// a draw's top 53 bits), rounded to two significant digits: A / L, c T / L (from cT_low) and the
// target log-uniform; scene, boundary and layout at even odds, a jitter uniform in (jitter_low,
// jitter_max]. A lookup is verified where its runs cost at most verify_cap particle-steps.
struct SampleRule {
  std::uint64_t seed = 20261128;
  int problems = 240;
  double cT_low = 1;
  double jitter_low = 0.01;
  double verify_cap = 1e8;
};
inline constexpr SampleRule kSampleRule{};
std::vector<VerifyProblem> draw_problems(const SampleRule& rule = kSampleRule,
                                         const AdviceDomain& d = kAdviceDomain);

// The search's result as `mpmstab advise` prints it (a document's: without the seconds), and as
// JSON (without the seconds: the same on any machine).
std::string verified_text(const Verified& v, const VerifyProblem& p, bool with_seconds = true);
nlohmann::ordered_json verified_json(const Verified& v, const VerifyProblem& p);
// The lookup alone (--no-verify): the first candidate whose prediction meets the target (a matching
// one before a distant one), or nullptr; printed said plainly to be unverified.
const Candidate* predicted_cheapest(const std::vector<Candidate>& list, double target);
std::string unverified_text(const Candidate& c, const VerifyProblem& p);
nlohmann::ordered_json unverified_json(const Candidate& c, const VerifyProblem& p);

}  // namespace mpmstab
