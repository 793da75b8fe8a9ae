#include "sweep.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <cstdio>
#include <exception>
#include <map>
#include <mutex>
#include <numeric>
#include <stop_token>
#include <thread>

#include "cache.hpp"
#include "csv.hpp"
#include "edge.hpp"
#include "provenance.hpp"
#include "result_json.hpp"
#include "run.hpp"

namespace mpmstab {

namespace {

using Clock = std::chrono::steady_clock;

// Work of a case, for scheduling and the time estimate: particle-steps.
// An edge search costs about as much as 40 runs at the speed-of-sound step h / c.
}  // namespace

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

class Progress {
 public:
  Progress(const Spec& spec, std::size_t runs, bool line, double total_cost)
      : name_(spec.name),
        search_(case_search(spec)),
        total_(runs),
        line_(line),
        total_cost_(total_cost) {}

  void done(const RunParams& p, const nlohmann::ordered_json& result, bool from_cache,
            double cost) {
    std::lock_guard lock(mutex_);
    ++done_;
    if (result["outcome"] == "unstable") ++unstable_;
    if (from_cache) {
      total_cost_ -= cost;  // cached cases take no time: leave them out of the estimate
    } else {
      done_cost_ += cost;
    }
    if (line_) {
      draw();
      if (done_ == total_) std::fputc('\n', stderr);
    } else {
      std::string verdict = result["outcome"] == "unstable"
                                ? "unstable (" + result["failure_reason"].get<std::string>() + ")"
                                : result["outcome"].get<std::string>();
      std::fprintf(stderr, "[%s] %zu/%zu %s: %s%s\n", name_.c_str(), done_, total_,
                   describe_case(p, search_).c_str(), verdict.c_str(),
                   from_cache ? " [cached]" : "");
    }
    std::fflush(stderr);
  }

  // Redraws the terminal line (elapsed time moves on during long cases).
  void tick() {
    std::lock_guard lock(mutex_);
    if (line_ && done_ < total_) {
      draw();
      std::fflush(stderr);
    }
  }

 private:
  void draw() const {
    const double elapsed = std::chrono::duration<double>(Clock::now() - start_).count();
    const double rate = done_cost_ > 0 ? done_cost_ / elapsed : 0;
    char left[48] = "estimating";
    if (rate > 0) {
      std::snprintf(left, sizeof left, "~%.0f s left", (total_cost_ - done_cost_) / rate);
    }
    std::fprintf(stderr, "\r[%s] %zu/%zu cases, %zu unstable, %.0f s elapsed, %s   ", name_.c_str(),
                 done_, total_, unstable_, elapsed, left);
  }

  std::mutex mutex_;
  std::string name_;
  std::string search_;
  std::size_t total_, done_ = 0, unstable_ = 0;
  bool line_;
  double total_cost_, done_cost_ = 0;
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
  s << "edge-accuracy";
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

SweepPlan plan_sweep(const Spec& spec, const SweepOptions& options) {
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
  for (std::size_t i : plan.order)
    plan.total_cost += plan.cost[i] = case_cost(spec.cases[i].params, spec.study->work);
  std::stable_sort(plan.order.begin(), plan.order.end(),
                   [&](std::size_t a, std::size_t b) { return plan.cost[a] > plan.cost[b]; });
  return plan;
}

// Computes one case: its record, or null when it was interrupted (neither cached nor reported).
nlohmann::ordered_json compute_case(const RunParams& p, const Study& study,
                                    const std::atomic<bool>* cancel) {
  nlohmann::ordered_json rec;
  if (study.work == CaseWork::edge_search) {
    const EdgeResult e = find_edge(p, study.edge, cancel);
    if (e.interrupted) return nullptr;
    const RunResult at = e.at_edge ? *e.at_edge : run_at_smallest_probe(p, e);
    rec["result"] = to_json(at);
    rec["edge"] = edge_to_json(e);
    // The cost of an edge case is its whole search.
    rec["timing"] = timing_json(at);
    rec["timing"]["wall_seconds"] = e.wall_seconds;
  } else {
    const RunResult r = run(p, cancel);
    if (r.interrupted) return nullptr;
    rec["result"] = to_json(r);
    rec["timing"] = timing_json(r);
    if (p.observe.history) rec["history"] = history_to_json(r);
    if (r.final_state) rec["final_state"] = final_state_json(*r.final_state);
  }
  return rec;
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

SweepOutcome run_sweep(const Spec& spec, const SweepOptions& options) {
  const auto start = Clock::now();
  const ResultCache cache(options.cache);
  const Provenance provenance = current_provenance(options.jobs);
  const std::string search = case_search(spec);
  const SweepPlan plan = plan_sweep(spec, options);

  SweepOutcome out;
  out.records.resize(spec.cases.size());
  std::vector<char> from_cache(spec.cases.size(), 0);
  Progress progress(spec, plan.order.size(), options.progress_line, plan.total_cost);
  std::atomic<std::size_t> next{0};
  std::atomic<int> rejected{0};
  const std::size_t m = plan.order.size();
  std::exception_ptr error;
  std::mutex error_mutex;

  auto cancelled = [&] { return options.cancel && options.cancel->load(); };
  auto worker = [&] {
    for (std::size_t k; !cancelled() && (k = next.fetch_add(1)) < m;) {
      const std::size_t i = plan.order[k];
      const RunParams& p = spec.cases[i].params;
      try {
        std::optional<nlohmann::ordered_json> record;
        const bool cached = !options.cache.empty();
        if (cached && !options.force) {
          CacheLookup found = cache.lookup(p, search);
          if (found.rejected) ++rejected;
          record = std::move(found.record);
        }
        from_cache[i] = record.has_value();
        if (!record) {
          nlohmann::ordered_json rec = compute_case(p, *spec.study, options.cancel);
          if (rec.is_null()) continue;
          rec["provenance"] = to_json(provenance);
          if (cached) cache.store(p, rec, search);
          record = std::move(rec);
        }
        if (!options.quiet) progress.done(p, (*record)["result"], from_cache[i], plan.cost[i]);
        out.records[i] = std::move(*record);
      } catch (...) {
        std::lock_guard lock(error_mutex);
        if (!error) error = std::current_exception();
        next = m;  // stop handing out cases
      }
    }
  };
  const int jobs = std::max(1, std::min<int>(options.jobs, static_cast<int>(m)));
  std::vector<std::thread> threads;
  for (int t = 1; t < jobs; ++t)
    threads.emplace_back(worker);
  worker();
  for (auto& t : threads)
    t.join();
  if (error) std::rethrow_exception(error);
  tally(plan, from_cache, out);
  out.rejected = rejected.load();
  out.wall_seconds = std::chrono::duration<double>(Clock::now() - start).count();
  return out;
}

}  // namespace mpmstab
