#include "sweep.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <cstdio>
#include <deque>
#include <exception>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <numeric>
#include <optional>
#include <set>
#include <stop_token>
#include <thread>

#include "analysis/spectral.hpp"
#include "cache.hpp"
#include "csv.hpp"
#include "key.hpp"
#include "progress.hpp"
#include "provenance.hpp"
#include "report.hpp"
#include "result_json.hpp"
#include "run/edge.hpp"
#include "run/run.hpp"
#include "scenes/scene_registry.hpp"

namespace mpmstab {

namespace {

using Clock = std::chrono::steady_clock;

// Work of a case, for scheduling and the time estimate: particle-steps.
// An edge search costs about as much as 40 runs at the speed-of-sound step h / c.
}  // namespace

bool position_update_is_moot(const RunParams& p) {
  // FMPM's g2p is PIC's with the series velocity in the grid (transfers.cpp).
  return p.transfer == Transfer::pic || p.transfer == Transfer::apic ||
         p.transfer == Transfer::fmpm;
}

double dense_analysis_cost(const RunParams& p) {
  const double n = double(spectral_state_size(p));
  return kDenseAnalysisCost * n * n * n;
}

double estimated_work(const RunParams& p, const std::string& search, CaseWork work,
                      const std::map<std::string, double>& published) {
  if (const auto it = published.find(case_key(p, search)); it != published.end()) return it->second;
  // A perturbed layout (an ensemble's member, a follow-up of the same name) does about the work
  // of the published case it perturbs.
  if (p.layout.shift != 0 || p.layout.jitter != 0) {
    RunParams unperturbed = p;
    unperturbed.layout = Layout{};
    for (const bool spectral : {false, true}) {
      unperturbed.observe.spectral = spectral;
      if (const auto it = published.find(case_key(unperturbed, search)); it != published.end())
        return it->second;
    }
  }
  return case_cost(p, work);
}

double case_cost(const RunParams& p, CaseWork work) {
  const double h_over_c = (1.0 / p.cells) / std::sqrt(p.E);
  // The adaptive policies step at about s / 20 of h / c (eq. 108 sits 5 to 200 times below it).
  const double dt = work == CaseWork::edge_search
                        ? h_over_c / 40
                        : fixed_step(p).value_or(p.stepping.safety * h_over_c / 20);
  return p.T / dt * double(p.cells) * double(p.ppc);
}

namespace {

nlohmann::ordered_json final_state_json(const FinalState& f) {
  auto column = [](const Eigen::ArrayXd& a) {
    auto out = nlohmann::ordered_json::array();
    for (double v : a)
      out.push_back(std::isfinite(v) ? nlohmann::ordered_json(v) : nullptr);
    return out;
  };
  return {{"time", f.time},
          {"X", column(f.X)},
          {"x", column(f.x)},
          {"v", column(f.v)},
          {"F", column(f.F)},
          {"sigma", column(f.sigma)},
          {"u_exact", column(f.u_exact)},
          {"v_exact", column(f.v_exact)},
          {"sigma_exact", column(f.sigma_exact)}};
}

// An edge search that found no surviving dt: report the run at the smallest dt it tried.
RunResult run_at_smallest_probe(const RunParams& p, const EdgeResult& e) {
  RunParams q = p;
  q.stepping.policy = TimeStepPolicy::fixed;
  q.dt = e.probes.empty() ? p.dt : e.probes.front().dt;
  return run(q);
}

// Progress of one sweep or of several in one queue. On a terminal, one line redrawn as cases
// finish and every second; off a terminal, a line per case for one sweep, or for several a line
// every kPeriodicSeconds. The line is ProgressCounter's (progress.hpp).
class Progress {
 public:
  static constexpr double kPeriodicSeconds = 10;

  Progress(std::string label, std::size_t runs, double total_cost, bool line, bool per_case)
      : label_(std::move(label)), line_(line), per_case_(per_case), counter_(runs, total_cost) {}

  // Tasks added to the queue while it runs (follow-up runs), replacing `retire` of the work
  // expected.
  void add(std::size_t runs, double cost, double retire) {
    std::lock_guard lock(mutex_);
    counter_.add(runs, cost, retire);
  }
  void expect(double cost) {
    std::lock_guard lock(mutex_);
    counter_.expect(cost);
  }
  // What reads the work done so far by the running tasks.
  void running_work(std::function<double()> read) {
    std::lock_guard lock(mutex_);
    running_ = std::move(read);
  }
  // The account of the runs the reports make themselves: their work counts as running until
  // reports_rendered moves it into the work done.
  void report_work(const RunAccount* account) {
    std::lock_guard lock(mutex_);
    reports_ = account;
  }
  void reports_rendered(double retire) {
    std::lock_guard lock(mutex_);
    const double made = report_work_not_done();
    reports_counted_ += made;
    counter_.finished_work(made, retire);
  }
  // A line of the caller's: on a terminal, over the progress line, which the next redraw puts
  // back below it.
  void say(const std::string& text) {
    std::lock_guard lock(mutex_);
    std::fprintf(stderr, "%s%s", line_ ? "\r\033[K" : "", text.c_str());
    std::fflush(stderr);
  }

  void done(const Spec& spec, const RunParams& p, const nlohmann::ordered_json& rec,
            bool from_cache, double cost) {
    std::lock_guard lock(mutex_);
    const auto& result = rec["result"];
    const bool unstable = result["outcome"] == "unstable";
    counter_.finished(from_cache, cost, from_cache ? 0.0 : record_particle_steps(rec), unstable);
    sample();
    if (line_) {
      draw('\r');
    } else if (per_case_) {
      std::string verdict = unstable
                                ? "unstable (" + result["failure_reason"].get<std::string>() + ")"
                                : result["outcome"].get<std::string>();
      std::fprintf(stderr, "[%s] %zu/%zu %s: %s%s\n", spec.name.c_str(), counter_.done(),
                   counter_.runs(), describe_case(p, case_search(spec)).c_str(), verdict.c_str(),
                   from_cache ? " [cached]" : "");
    }
    std::fflush(stderr);
  }

  // Redraws the line (elapsed time moves on during long cases), or prints it when the period
  // has passed.
  void tick() {
    std::lock_guard lock(mutex_);
    sample();
    if (counter_.finished()) return;
    if (line_) {
      draw('\r');
    } else if (!per_case_ && elapsed() >= last_print_ + kPeriodicSeconds) {
      last_print_ = elapsed();
      draw('\n');
    }
    std::fflush(stderr);
  }

  void finish() {
    std::lock_guard lock(mutex_);
    if (line_ || !per_case_) draw('\n');
    std::fflush(stderr);
  }

  // The time to go the line showed, at most once a second: (seconds elapsed, seconds to go).
  std::vector<std::pair<double, double>> estimates() const {
    std::lock_guard lock(mutex_);
    return estimates_;
  }

 private:
  void sample() {
    const double now = elapsed();
    if (now < last_sample_ + 1 || counter_.finished()) return;
    last_sample_ = now;
    counter_.running(running_work());
    if (const auto to_go = counter_.seconds_to_go(now)) estimates_.emplace_back(now, *to_go);
  }

  double elapsed() const { return std::chrono::duration<double>(Clock::now() - start_).count(); }

  // The work of the report runs made since the last report was written: the one rendering now.
  double report_work_not_done() const {
    return reports_ ? reports_->particle_steps.load() - reports_counted_ : 0.0;
  }
  // The running tasks' work so far, and that of the report rendering now.
  double running_work() const { return (running_ ? running_() : 0.0) + report_work_not_done(); }

  void draw(char end) {
    counter_.running(running_work());
    std::fprintf(stderr, "%s%s   %s", end == '\r' ? "\r" : "",
                 counter_.text(label_, elapsed()).c_str(), end == '\n' ? "\n" : "");
  }

  mutable std::mutex mutex_;
  std::string label_;
  bool line_, per_case_;
  ProgressCounter counter_;
  std::function<double()> running_;
  const RunAccount* reports_ = nullptr;
  double reports_counted_ = 0;  // of reports_'s work, moved into the work done
  double last_print_ = 0;
  double last_sample_ = 0;
  std::vector<std::pair<double, double>> estimates_;
  Clock::time_point start_ = Clock::now();
};

}  // namespace

std::string describe_case(const RunParams& p, const std::string& search) {
  std::string s = std::string(to_string(p.method)) + " E=" + shortest(p.E) + " A=" + shortest(p.A);
  if (!search.empty()) return s + " (dt searched)";
  switch (p.stepping.policy) {
    case TimeStepPolicy::fixed:
      return s + " dt=" + shortest(p.dt);
    case TimeStepPolicy::cfl:
      return s + " cfl C=" + shortest(p.stepping.cfl_factor);
    case TimeStepPolicy::adaptive:
      return s + " adaptive s=" + shortest(p.stepping.safety);
    case TimeStepPolicy::min:
      return s + " min C=" + shortest(p.stepping.cfl_factor) + " s=" + shortest(p.stepping.safety);
    case TimeStepPolicy::spectral:
      return s + " spectral s=" + shortest(p.stepping.safety);
  }
  return s;
}

double record_particle_steps(const nlohmann::ordered_json& rec) {
  if (rec.contains("edge")) return rec["edge"]["search_particle_steps"].get<double>();
  const auto& r = rec["result"];
  const double run = r["steps"].get<double>() * r["particles"].get<double>();
  const auto& t = rec["timing"];
  return t.contains("records_of_run") ? run / t["records_of_run"].get<double>() : run;
}

int shard_of(const std::string& case_key, int count) {
  // The key is 64 bits of FNV-1a; a splitmix64 finalizer spreads them before the modulo.
  std::uint64_t x = std::stoull(case_key, nullptr, 16);
  x += 0x9e3779b97f4a7c15ull;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ull;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebull;
  x ^= x >> 31;
  return static_cast<int>(x % static_cast<std::uint64_t>(count));
}

void omit_machine_measurements(SweepOutcome& outcome) {
  for (auto& rec : outcome.records) {
    if (rec.is_null()) continue;
    rec["timing"] = {{"wall_seconds", 0.0}, {"ns_per_particle_step", 0.0}};
    rec["provenance"]["date"] = "omitted";
    rec["provenance"]["threads"] = "omitted";
  }
  outcome.wall_seconds = 0;
  outcome.timing_omitted = true;
}

nlohmann::ordered_json deterministic_part(const nlohmann::ordered_json& record) {
  nlohmann::ordered_json d = record;
  d.erase("provenance");
  d.erase("canonical");
  d.erase("checksum");  // covers the provenance and timing, which may differ
  d.erase("timing");
  return d;
}

std::string case_search(const Spec& spec) {
  // The search's name is part of an edge case's key: a search that measures more (the accuracy
  // edge) must not reuse the records of an older one.
  if (spec.study->work != CaseWork::edge_search) return "";
  const EdgeOptions& o = spec.study->edge;
  const EdgeOptions d;
  std::ostringstream s;
  // "over-time": the accuracy edge compares the error over time, not the error at T; "edge2":
  // the lowest failure found is the edge, after a dense scan below it.
  s << "edge2-accuracy-over-time";
  if (o.tolerance != d.tolerance || o.scan_low != d.scan_low || o.scan_high != d.scan_high ||
      o.per_octave != d.per_octave || o.accuracy_factor != d.accuracy_factor) {
    s << ";tolerance=" << shortest(o.tolerance) << ";scan=" << shortest(o.scan_low) << ","
      << shortest(o.scan_high) << "," << o.per_octave
      << ";accuracy=" << shortest(o.accuracy_factor);
  }
  if (o.bound) s << ";bound=" << shortest(*o.bound);
  return s.str();
}

namespace {

// Which cases a sweep computes: one run per distinct key (a case repeating an earlier one
// shares its record), and in a shard only the keys that fall in it; longest first.
struct SweepPlan {
  std::vector<std::size_t> same_as;  // the case whose record case i shares (i itself if first)
  std::vector<char> elsewhere;       // case i belongs to another shard
  std::vector<std::size_t> order;    // the cases to compute, longest first
  std::vector<double> cost;          // particle-steps of each case to compute
  double total_cost = 0;
};

// `published`: the cases' work as last published (published_work), which estimates it.
SweepPlan plan_sweep(const Spec& spec, const SweepOptions& options,
                     const std::map<std::string, double>& published) {
  const std::size_t n = spec.cases.size();
  const std::string search = case_search(spec);
  SweepPlan plan;
  plan.same_as.resize(n);
  plan.elsewhere.assign(n, 0);
  plan.cost.assign(n, 0);
  std::map<std::string, std::size_t> first;
  for (std::size_t i = 0; i < n; ++i) {
    const std::string key = case_key(spec.cases[i].params, search);
    const auto [it, fresh] = first.emplace(key, i);
    plan.same_as[i] = it->second;
    plan.elsewhere[i] =
        options.shard && shard_of(key, options.shard->count) != options.shard->index;
    if (fresh && !plan.elsewhere[i]) plan.order.push_back(i);
  }
  // A case's work as last published where it was, else the estimate from its parameters (a run
  // to T, which an unstable run falls short of).
  for (std::size_t i : plan.order) {
    plan.cost[i] = estimated_work(spec.cases[i].params, search, spec.study->work, published);
    plan.total_cost += plan.cost[i];
  }
  std::stable_sort(plan.order.begin(), plan.order.end(), [&](std::size_t a, std::size_t b) {
    return TotalLess()(plan.cost[b], plan.cost[a]);
  });
  return plan;
}

}  // namespace

nlohmann::ordered_json run_record(const RunResult& r) {
  nlohmann::ordered_json rec;
  rec["result"] = to_json(r);
  rec["timing"] = timing_json(r);
  if (r.params.observe.history) rec["history"] = history_to_json(r);
  if (r.final_state) rec["final_state"] = final_state_json(*r.final_state);
  return rec;
}

namespace {

// Computes one case: its record, or null when it was interrupted (neither cached nor reported).
nlohmann::ordered_json compute_case(const RunParams& p, const Study& study,
                                    const std::atomic<bool>* cancel) {
  if (study.work == CaseWork::edge_search) {
    nlohmann::ordered_json rec;
    const EdgeResult e = find_edge(p, study.edge, cancel);
    if (e.interrupted) return nullptr;
    const RunResult at = e.at_edge ? *e.at_edge : run_at_smallest_probe(p, e);
    rec["result"] = to_json(at);
    rec["edge"] = edge_to_json(e);
    // The cost of an edge case is its whole search.
    rec["timing"] = timing_json(at);
    rec["timing"]["wall_seconds"] = e.wall_seconds;
    return rec;
  }
  const RunResult r = run(p, cancel);
  if (r.interrupted) return nullptr;
  return run_record(r);
}

// Cases that differ only in eq. (108)'s options share their trajectory when the policy does not
// read eq. (108), and so do PIC and APIC cases that differ only in the position update
// (position_update_is_moot): one run observes the bound under every option and gives each case its
// record, the same as its own run would (the same state, the same functions; only the timing
// differs). Edge searches and histories (whose rows carry the bound of one option) run alone.
bool shares_trajectory(const RunParams& p, const std::string& search) {
  const TimeStepPolicy policy = p.stepping.policy;
  return search.empty() && !p.observe.history && policy != TimeStepPolicy::adaptive &&
         policy != TimeStepPolicy::min;
}

std::string trajectory_key(const RunParams& p) {
  RunParams q = p;
  q.stable = StableDtOptions{};
  if (position_update_is_moot(p)) q.position_update = PositionUpdate::grid;
  return case_key(q, "trajectory");
}

// The records of cases that share one trajectory (shares_trajectory, the same trajectory_key),
// from one run; nulls when it was interrupted. Each record's timing has its share of the run's
// wall time and the number of records the run gave (records_of_run).
std::vector<nlohmann::ordered_json> compute_shared(const std::vector<const RunParams*>& cases,
                                                   const std::atomic<bool>* cancel) {
  RunParams q = *cases.front();
  q.observe.dt_stable_every_option = true;
  const RunResult r = run(q, cancel);
  if (r.interrupted) return std::vector<nlohmann::ordered_json>(cases.size());
  std::vector<nlohmann::ordered_json> records;
  for (const RunParams* p : cases) {
    RunResult own = r;
    own.params = *p;
    own.params.observe.dt_stable_every_option = false;
    if (own.dt_stable_min) own.dt_stable_min = r.dt_stable_min_of_option[option_index(p->stable)];
    nlohmann::ordered_json rec = run_record(own);
    rec["timing"]["wall_seconds"] = r.wall_seconds / double(cases.size());
    rec["timing"]["records_of_run"] = cases.size();
    records.push_back(std::move(rec));
  }
  return records;
}

// Shares the records of repeated cases and counts what was computed, cached and unstable.
void tally(const SweepPlan& plan, const std::vector<char>& from_cache, SweepOutcome& out) {
  for (std::size_t i = 0; i < out.records.size(); ++i) {
    if (plan.elsewhere[i]) {
      ++out.other_shards;
      continue;
    }
    const std::size_t first = plan.same_as[i];
    if (first != i) out.records[i] = out.records[first];
    if (out.records[i].is_null()) {
      out.interrupted = true;  // a case that never finished
      continue;
    }
    if (first != i) {
      ++out.shared;
    } else {
      (from_cache[i] ? out.cached : out.computed) += 1;
    }
    if (out.records[i]["result"]["outcome"] == "unstable") ++out.unstable;
  }
}

}  // namespace

namespace {

// A distinct case to compute, and the cases of the specs that share its record.
struct Task {
  const Spec* spec = nullptr;  // of its first use
  std::size_t index = 0;
  std::string search;
  double cost = 0;  // particle-steps; 0 for a task computed by another's run
  std::vector<std::pair<std::size_t, std::size_t>> uses;  // (batch, case)
  // Tasks whose trajectory is this one's (shares_trajectory): computed by the same run.
  std::vector<std::size_t> partners;
  bool started = false;  // taken by a worker (or computed by its lead's run)
  std::optional<nlohmann::ordered_json> record;  // once finished
  bool hit = false;                              // its record came from the cache

  const RunParams& params() const { return spec->cases[index].params; }
};

// One spec added to the queue: its plan and what its cases have given so far.
struct Batch {
  const Spec* spec = nullptr;
  SweepPlan plan;
  SweepOutcome out;
  std::vector<char> from_cache;
  std::size_t remaining = 0;
  double first_start = -1, last_end = 0;
  bool delivered = false;
};

}  // namespace

struct SweepQueue::State {
  State(const SweepOptions& o, std::string l) : options(o), label(std::move(l)), cache(o.cache) {}

  const SweepOptions options;
  const std::string label;
  const ResultCache cache;
  const Provenance provenance = current_provenance(options.jobs);
  const Clock::time_point start = Clock::now();
  double since_start() const { return std::chrono::duration<double>(Clock::now() - start).count(); }

  std::mutex mutex;
  std::condition_variable work_changed;  // a task to take, or stop
  std::condition_variable done_changed;  // a batch complete, an error, or the workers gone
  std::deque<Task> tasks;
  std::deque<Batch> batches;
  std::map<std::string, std::size_t> task_of;  // case key -> task
  std::map<std::string, std::size_t> lead_of;  // trajectory key -> a task not yet started
  std::set<std::string> analysed;              // dense analyses counted in a task's cost
  // Tasks to take, longest first (ties: the first added first).
  std::vector<std::size_t> ready;
  std::vector<std::size_t> finished;  // batches complete, not yet handed over
  std::unique_ptr<Progress> progress;
  std::size_t runs = 0;  // tasks in the progress line
  double total_cost = 0;
  double expected = 0;  // work expected to be added (expect), before run
  // The work each worker's running task has done so far (count_work_on_this_thread).
  std::unique_ptr<std::atomic<double>[]> running;
  std::size_t workers = 0;
  bool stop = false;
  std::size_t workers_running = 0;
  std::atomic<int> rejected{0};
  std::exception_ptr error;
  RunAccount reports;  // the runs the reports rendered on the caller's thread make themselves

  bool cancelled() const { return options.cancel && options.cancel->load(); }
  bool before(std::size_t a, std::size_t b) const {  // heap order: b is taken before a
    if (tasks[a].cost != tasks[b].cost) return TotalLess()(tasks[a].cost, tasks[b].cost);
    return a > b;
  }
  void push_ready(std::size_t k) {
    ready.push_back(k);
    std::push_heap(ready.begin(), ready.end(), [this](auto a, auto b) { return before(a, b); });
  }
  std::size_t pop_ready() {
    std::pop_heap(ready.begin(), ready.end(), [this](auto a, auto b) { return before(a, b); });
    const std::size_t k = ready.back();
    ready.pop_back();
    return k;
  }

  // Hands a finished task's record to every case that uses it (the lock held).
  void deliver(Task& task, const nlohmann::ordered_json& record, bool hit, double began) {
    task.record = record;
    task.hit = hit;
    if (!options.quiet && progress)
      progress->done(*task.spec, task.params(), record, hit, task.cost);
    const double ended = since_start();
    for (const auto& [b, i] : task.uses)
      give(b, i, record, hit, began, ended);
    done_changed.notify_all();
  }
  void give(std::size_t b, std::size_t i, const nlohmann::ordered_json& record, bool hit,
            double began, double ended) {
    Batch& batch = batches[b];
    batch.out.records[i] = record;
    batch.from_cache[i] = hit;
    if (batch.first_start < 0 || began < batch.first_start) batch.first_start = began;
    batch.last_end = std::max(batch.last_end, ended);
    if (--batch.remaining == 0) finished.push_back(b);
  }

  void work(std::size_t w);
  void start_progress(bool several);

  // The thread that redraws the progress line every second, also while `complete` renders a
  // report on the caller's thread (none when quiet); stopped and joined when destroyed.
  std::jthread start_ticker() {
    if (options.quiet) return {};
    return std::jthread([this](std::stop_token halt) {
      std::mutex m;
      std::condition_variable_any wake;
      std::unique_lock lock(m);
      for (;;) {
        wake.wait_for(lock, halt, std::chrono::seconds(1), [] { return false; });
        if (halt.stop_requested()) return;
        progress->tick();
      }
    });
  }
};

SweepQueue::SweepQueue(const SweepOptions& options, std::string label)
    : state_(std::make_unique<State>(options, std::move(label))) {}

SweepQueue::~SweepQueue() = default;

std::vector<std::pair<double, double>> SweepQueue::estimates() const {
  return state_->progress ? state_->progress->estimates()
                          : std::vector<std::pair<double, double>>{};
}

void SweepQueue::expect(double cost) {
  State& st = *state_;
  std::lock_guard lock(st.mutex);
  if (st.progress) {
    st.progress->expect(cost);
  } else {
    st.expected += std::max(0.0, cost);
  }
}

RunAccount& SweepQueue::report_account() {
  return state_->reports;
}

void SweepQueue::reports_rendered(double retire) {
  State& st = *state_;
  if (st.progress) {
    st.progress->reports_rendered(retire);
  } else {
    this->retire(retire);
  }
}

void SweepQueue::say(const std::string& line) {
  if (state_->progress) {
    state_->progress->say(line);
  } else {
    std::fputs(line.c_str(), stderr);
  }
}

void SweepQueue::retire(double cost) {
  State& st = *state_;
  std::lock_guard lock(st.mutex);
  if (st.progress) {
    st.progress->add(0, 0, cost);
  } else {
    st.expected = std::max(0.0, st.expected - cost);
  }
}

std::size_t SweepQueue::add(const Spec& spec, double retire) {
  State& st = *state_;
  // Read before taking the lock, which the workers wait on: a results file of a few MB.
  const bool plan = spec.study->has_cases;
  const std::map<std::string, double> published = plan && !st.options.published.empty()
                                                      ? published_work(spec, st.options.published)
                                                      : std::map<std::string, double>{};
  std::lock_guard lock(st.mutex);
  const std::size_t b = st.batches.size();
  Batch& batch = st.batches.emplace_back();
  batch.spec = &spec;
  batch.plan = plan ? plan_sweep(spec, st.options, published) : SweepPlan{};
  batch.out.records.resize(spec.cases.size());
  batch.from_cache.assign(spec.cases.size(), 0);
  batch.remaining = batch.plan.order.size();
  if (batch.remaining == 0) st.finished.push_back(b);
  const std::string search = case_search(spec);
  std::size_t new_runs = 0;
  double new_cost = 0;
  for (std::size_t i : batch.plan.order) {
    const std::string key = case_key(spec.cases[i].params, search);
    const auto [it, fresh] = st.task_of.emplace(key, st.tasks.size());
    if (!fresh) {  // the same case in another spec: one record for both
      Task& same = st.tasks[it->second];
      same.uses.emplace_back(b, i);
      if (same.record) st.give(b, i, *same.record, same.hit, st.since_start(), st.since_start());
      continue;
    }
    const std::size_t k = st.tasks.size();
    Task& task = st.tasks.emplace_back();
    task.spec = &spec;
    task.index = i;
    task.search = search;
    task.cost = batch.plan.cost[i];
    // The dense analyses it asks for: the first of each layout is computed once in the process
    // (spectral_courant), the spectral policy's later ones start near the last (half a search).
    const DenseAnalyses analyses = dense_analyses(spec.cases[i].params);
    if (analyses.initial_key && st.analysed.insert(*analyses.initial_key).second)
      task.cost += dense_analysis_cost(spec.cases[i].params);
    task.cost += 0.5 * analyses.later * dense_analysis_cost(spec.cases[i].params);
    task.cost += kCaseOverhead;
    task.uses.emplace_back(b, i);
    ++new_runs;
    // A task whose trajectory is a waiting task's goes with it (and costs nothing more).
    const RunParams& p = task.params();
    if (shares_trajectory(p, search)) {
      const auto [lead, first] = st.lead_of.emplace(trajectory_key(p), k);
      if (!first) {
        st.tasks[lead->second].partners.push_back(k);
        task.cost = 0;
        task.started = true;
        continue;
      }
    }
    new_cost += task.cost;
    st.push_ready(k);
  }
  st.runs += new_runs;
  st.total_cost += new_cost;
  if (st.progress) {
    st.progress->add(new_runs, new_cost, retire);
  } else {
    st.expected = std::max(0.0, st.expected - retire);
  }
  st.work_changed.notify_all();
  st.done_changed.notify_all();
  return b;
}

void SweepQueue::State::work(std::size_t w) {
  const bool cached = !options.cache.empty();
  count_work_on_this_thread(&running[w]);
  for (;;) {
    std::size_t k;
    std::vector<std::size_t> members_k;
    {
      std::unique_lock lock(mutex);
      while (!work_changed.wait_for(lock, std::chrono::milliseconds(200),
                                    [&] { return !ready.empty() || stop || cancelled(); })) {
      }
      if (ready.empty() || cancelled() || error) break;
      k = pop_ready();
      Task& lead = tasks[k];
      lead.started = true;
      if (shares_trajectory(lead.params(), lead.search))
        lead_of.erase(trajectory_key(lead.params()));
      members_k.push_back(k);
      for (std::size_t m : lead.partners)
        members_k.push_back(m);
    }
    const double began = since_start();
    running[w].store(0.0);
    try {
      // The lead and its partners: each from the cache if there, the rest computed by one run.
      std::vector<const Task*> members;
      for (std::size_t m : members_k)
        members.push_back(&tasks[m]);
      std::vector<std::optional<nlohmann::ordered_json>> records(members.size());
      std::vector<std::size_t> missing;
      for (std::size_t m = 0; m < members.size(); ++m) {
        const Task& task = *members[m];
        if (cached && !options.force) {
          CacheLookup found = cache.lookup(task.params(), task.search);
          if (found.rejected) ++rejected;
          records[m] = std::move(found.record);
        }
        if (!records[m]) missing.push_back(m);
      }
      std::vector<nlohmann::ordered_json> computed;
      if (missing.size() == 1) {
        const Task& task = *members[missing.front()];
        computed.push_back(compute_case(task.params(), *task.spec->study, options.cancel));
      } else if (missing.size() > 1) {
        std::vector<const RunParams*> params;
        for (std::size_t m : missing)
          params.push_back(&members[m]->params());
        computed = compute_shared(params, options.cancel);
      }
      for (std::size_t c = 0; c < missing.size(); ++c) {
        nlohmann::ordered_json& rec = computed[c];
        if (rec.is_null()) continue;  // interrupted
        const Task& task = *members[missing[c]];
        rec["provenance"] = to_json(provenance);
        if (cached) cache.store(task.params(), rec, task.search);
        records[missing[c]] = std::move(rec);
      }
      std::lock_guard lock(mutex);
      running[w].store(0.0);  // its work is the finished tasks' now
      for (std::size_t m = 0; m < members.size(); ++m) {
        if (!records[m]) continue;
        const bool hit = std::find(missing.begin(), missing.end(), m) == missing.end();
        deliver(tasks[members_k[m]], *records[m], hit, began);
      }
    } catch (...) {
      std::lock_guard lock(mutex);
      if (!error) error = std::current_exception();
      work_changed.notify_all();
      done_changed.notify_all();
      break;
    }
  }
  count_work_on_this_thread(nullptr);
  std::lock_guard lock(mutex);
  running[w].store(0.0);
  --workers_running;
  done_changed.notify_all();
}

// The progress line and the workers' running counters, before the workers start.
void SweepQueue::State::start_progress(bool several) {
  {
    std::lock_guard lock(mutex);
    // An empty queue (no spec added) runs nothing and is named by its label.
    progress =
        std::make_unique<Progress>(several || batches.empty() ? label : batches.front().spec->name,
                                   runs, total_cost, options.progress_line, !several);
    progress->expect(expected);
  }
  workers = std::size_t(std::max(1, options.jobs));
  running = std::make_unique<std::atomic<double>[]>(workers);
  for (std::size_t w = 0; w < workers; ++w)
    running[w].store(0.0);
  progress->report_work(&reports);
  progress->running_work([this] {
    double sum = 0;
    for (std::size_t w = 0; w < workers; ++w)
      sum += running[w].load(std::memory_order_relaxed);
    return sum;
  });
}

std::vector<SweepOutcome> SweepQueue::run(
    const std::function<void(std::size_t, SweepOutcome&)>& complete) {
  State& st = *state_;
  const bool several = st.batches.size() > 1;
  st.start_progress(several);
  std::vector<std::thread> threads;
  st.workers_running = st.workers;
  for (std::size_t w = 0; w < st.workers; ++w)
    threads.emplace_back([&st, w] { st.work(w); });
  auto stop_workers = [&] {
    {
      std::lock_guard lock(st.mutex);
      st.stop = true;
    }
    st.work_changed.notify_all();
    for (auto& t : threads)
      if (t.joinable()) t.join();
  };

  std::jthread ticker = st.start_ticker();
  // The caller's thread hands each complete batch over (its records counted and shared) while
  // the workers go on. `complete` may add batches.
  try {
    for (;;) {
      std::unique_lock lock(st.mutex);
      const auto all_delivered = [&] {
        return std::all_of(st.batches.begin(), st.batches.end(),
                           [](const Batch& b) { return b.delivered; });
      };
      if (st.finished.empty() && all_delivered()) break;
      st.done_changed.wait_for(lock, std::chrono::seconds(1), [&] {
        return !st.finished.empty() || st.error || st.workers_running == 0;
      });
      if (st.error) break;
      if (st.finished.empty()) {
        if (st.workers_running == 0) break;  // interrupted: some batches never finish
        continue;
      }
      const std::size_t b = st.finished.front();
      st.finished.erase(st.finished.begin());
      Batch& batch = st.batches[b];
      batch.delivered = true;
      lock.unlock();
      tally(batch.plan, batch.from_cache, batch.out);
      batch.out.wall_seconds = batch.first_start < 0 ? 0 : batch.last_end - batch.first_start;
      batch.out.rejected = st.rejected.load();  // so far, over the whole queue
      if (complete) complete(b, batch.out);
    }
  } catch (...) {
    ticker = {};
    stop_workers();
    throw;
  }
  ticker = {};  // stopped and joined
  stop_workers();
  if (st.error) std::rethrow_exception(st.error);
  if (!st.options.quiet && several) st.progress->finish();
  std::vector<SweepOutcome> out;
  for (Batch& batch : st.batches) {
    batch.out.rejected = st.rejected.load();  // over the whole queue
    if (!batch.delivered) {
      tally(batch.plan, batch.from_cache, batch.out);
      batch.out.interrupted = true;
    }
    out.push_back(std::move(batch.out));
  }
  if (!several && !out.empty()) out.front().wall_seconds = st.since_start();
  return out;
}

std::vector<SweepOutcome> run_sweeps(
    const std::vector<const Spec*>& specs, const SweepOptions& options,
    const std::function<void(std::size_t, SweepOutcome&)>& complete) {
  SweepQueue queue(options, "reproduce");
  for (const Spec* spec : specs)
    queue.add(*spec);
  return queue.run(complete);
}

SweepOutcome run_sweep(const Spec& spec, const SweepOptions& options) {
  return std::move(run_sweeps({&spec}, options, nullptr).front());
}

}  // namespace mpmstab
