// Running the cases of a spec: in parallel, from the cache where possible, with progress.
#pragma once

#include <atomic>
#include <filesystem>
#include <functional>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "base/result.hpp"
#include "cached_run.hpp"
#include "spec.hpp"

namespace mpmstab {

// A case in one line for messages: "gimp E=4 A=0.015 dt=0.001", with the step its policy uses
// ("cfl C=0.5", "adaptive s=2"), or "(dt searched)" for a case whose dt a search finds (`search`
// as case_search gives it).
std::string describe_case(const RunParams& p, const std::string& search = "");

// One part of a sweep split over machines: shard `index` of `count`, 0 <= index < count.
struct Shard {
  int index = 0;
  int count = 1;
};

// The shard a case belongs to: a hash of its cache key (canonical parameters, solver version
// and search), so that a case always lands in the same shard whatever the order of the cases
// in the spec, and identical cases land together.
int shard_of(const std::string& case_key, int count);

struct SweepOptions {
  int jobs = 1;                 // cases run at once
  std::optional<Shard> shard;   // run only this shard's cases (the others stay null)
  bool force = false;           // compute every case again, ignoring the cache
  std::filesystem::path cache;  // cache folder; empty: compute every case, store nothing
  bool progress_line = false;   // one updating line (terminal) instead of a line per case
  bool quiet = false;           // no progress at all
  // Set (by a signal handler) to stop: no new case starts, running cases stop within a few
  // thousand steps, finished cases stay in the cache.
  const std::atomic<bool>* cancel = nullptr;
  // The results folder whose last published records estimate each case's work (its
  // particle-steps there, for the progress line and the longest-first order; results never
  // depend on it); empty, or a case not published there: the estimate from its parameters.
  std::filesystem::path published;
};

struct SweepOutcome {
  // One record per case, in spec order: {"result", "provenance"[, "history"][, "final_state"]}.
  std::vector<nlohmann::ordered_json> records;
  int computed = 0;
  int cached = 0;
  // Cases whose run (canonical parameters and search) repeats an earlier case of the same spec,
  // for example two variants that differ only in what they compare: run once, record shared.
  int shared = 0;
  int unstable = 0;
  // Cache files that failed their checks (see ResultCache) and were computed again.
  int rejected = 0;
  int other_shards = 0;  // cases left to the other shards (their records are null)
  double wall_seconds = 0;
  bool interrupted = false;  // stopped by `cancel`: records of unfinished cases are null
  // Gathered from shard outputs (mpmstab merge) rather than run here: wall_seconds is the
  // longest shard's.
  bool merged = false;
  // The machine measurements were removed (omit_machine_measurements).
  bool timing_omitted = false;
};

// Removes what measures the machine rather than the computation from every record and from the
// outcome: wall times and ns per particle-step read 0, the date and thread count "omitted".
// Reports written from the result are the same bytes for the same spec on any machine, in any
// number of shards (--timing omit).
void omit_machine_measurements(SweepOutcome& outcome);

// A record without its machine measurements and provenance: what two computations of the same
// case must agree on.
nlohmann::ordered_json deterministic_part(const nlohmann::ordered_json& record);

// The deterministic work of a finished case's record: particles x steps of its run, or of every
// run of its search.
double record_particle_steps(const nlohmann::ordered_json& record);

// The work of a case in particle-steps (an estimate for the adaptive policies and for edge
// searches), for scheduling, progress and the fast subset of make check.
double case_cost(const RunParams& p, CaseWork work);
// The work of a case for scheduling and progress: its record's particle-steps in `published`
// (key -> work, published_work in report.hpp), or those of the published case whose layout it
// perturbs (an ensemble's member), else case_cost.
double estimated_work(const RunParams& p, const std::string& search, CaseWork work,
                      const std::map<std::string, double>& published);

// The time of one dense analysis of p's spectral limit (spectral.hpp: four maps of the step and
// about twenty eigenvalue solves of its state of n values), in the particle-steps that take as
// long: kDenseAnalysisCost n^3. Measured on a 2-core Xeon (AVX-512): 2.1 s at n = 400 (the bar
// on 100 cells, 2 per cell, jittered), 7.7 s at n = 600, against about 8 ns per particle-step
// of the paper's GIMP on that machine. The queue counts it in a case's cost (once per layout),
// so that a case that asks for one is scheduled early and the time to go includes it.
inline constexpr double kDenseAnalysisCost = 4.0;
// What a computed case costs beyond its particle-steps (its scene, its observers' set-up, its
// Bloch limit, its record and cache file), in the particle-steps that take as long. Measured: the
// studies tier from an empty cache on that machine took 1110 s of CPU for 8758 computed cases
// and 7.9e10 particle-steps, 207 s more than those particle-steps at the variants study's
// 11.4 ns each, about 24 ms a case. Without it the queue's thousands of short cases, which run
// last (longest first), were left out of the time to go: it showed 103 s to go where 274 s were.
// The queue counts it in every task's cost (not in case_cost, which make check's budget reads).
inline constexpr double kCaseOverhead = 2e6;
double dense_analysis_cost(const RunParams& p);

// Whether p's position update cannot change its run: PIC, APIC and FMPM set the particle's
// velocity to sum_i S_ip v_i (FMPM's v_i being its series velocity), the very value the grid
// update adds, so x_p += dt v_p (particle) and
// x_p += dt sum_i S_ip v_i (grid) are one operation on the same operands (transfers.cpp,
// transfer_particle; docs/engineering.md, "Work done once"). Such cases share one run.
bool position_update_is_moot(const RunParams& p);

// The cases of several specs in one queue, to which specs can be added while it runs (make
// reproduce adds each experiment's follow-up runs as soon as its cases are done): every case not
// in the cache, over every spec, runs once (a case repeated within or across specs shares one
// record; cases that differ only in what run_sweeps' sharing allows follow one run), longest
// first among those waiting, on options.jobs threads. One progress line covers all, its total
// growing as specs are added.
class SweepQueue {
 public:
  // `label` names the progress line of several specs.
  SweepQueue(const SweepOptions& options, std::string label);
  ~SweepQueue();
  SweepQueue(const SweepQueue&) = delete;
  SweepQueue& operator=(const SweepQueue&) = delete;

  // Adds a spec's cases (the spec must outlive the queue) and returns its index. Before `run`,
  // or from `complete` on the caller's thread while it runs. `retire`: the work expected (below)
  // that these cases replace.
  std::size_t add(const Spec& spec, double retire = 0);
  // Work expected to be added later, in particle-steps (an experiment's follow-up runs as its
  // last published results ask for them): counted in the progress line's total until retired.
  void expect(double cost);
  // Removes `cost` of the work expected (what was expected and will not come).
  void retire(double cost);

  // The runs the reports make themselves while they render on the caller's thread (cached_run.hpp):
  // the caller opens this account there (RunAccountScope) around `run`, and every report's
  // account counts into it. The progress line counts their work as it is done, and
  // `reports_rendered` moves what they made into the work done, retiring `retire` of the work
  // expected (an experiment's report runs as its last published timings count them).
  RunAccount& report_account();
  void reports_rendered(double retire);
  // Prints a line of the caller's between the progress line's redraws (a finished experiment).
  void say(const std::string& line);

  // Runs until every spec added is complete, calling complete(index, outcome) on the caller's
  // thread as each one's last case finishes (the caller may take the outcome, and may add
  // specs). The outcomes, by index; a spec that never completed (interrupted) has `interrupted`
  // set. An outcome's wall_seconds is the span from its first case's start to its last case's
  // end.
  std::vector<SweepOutcome> run(const std::function<void(std::size_t, SweepOutcome&)>& complete);

  // The time to go the progress line estimated as the queue ran, at most once a second:
  // (seconds since the queue started, seconds to go). Empty before `run`.
  std::vector<std::pair<double, double>> estimates() const;

 private:
  struct State;
  std::unique_ptr<State> state_;
};

// Several specs' cases in one queue (make reproduce): every case not in the cache, over every
// spec, runs once (a case repeated within or across specs shares one record), longest first on
// options.jobs threads, so that no thread idles while another finishes a long case. As each
// spec's last case finishes, complete(index, outcome) is called on the caller's thread with its
// final outcome (the caller may take it) while the workers go on; a spec without cases to run
// is complete at once. The outcome's wall_seconds is the span from its first case's start to
// its last case's end; `rejected` counts over the whole queue. One progress line covers all.
// Returns the outcomes (those taken by `complete` left as it left them); a spec that never
// completed (interrupted) has `interrupted` set.
std::vector<SweepOutcome> run_sweeps(
    const std::vector<const Spec*>& specs, const SweepOptions& options,
    const std::function<void(std::size_t, SweepOutcome&)>& complete);

// What a spec's cases compute beyond one run, as the cache keys it: "" or "edge".
std::string case_search(const Spec& spec);

// Results do not depend on `jobs`: every case is an independent, deterministic computation and
// the records are returned in spec order. Cases with the same canonical parameters are computed
// (or read from the cache) once.
SweepOutcome run_sweep(const Spec& spec, const SweepOptions& options);

// The record of a run's result as the cache stores it (its result, timing, and history and final
// state where observed), without its provenance.
nlohmann::ordered_json run_record(const RunResult& r);

}  // namespace mpmstab
