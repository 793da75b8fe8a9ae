#include "progress.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace mpmstab {

ProgressCounter::ProgressCounter(std::size_t runs, double estimated_cost)
    : runs_(runs), estimated_cost_(std::max(0.0, estimated_cost)) {}

void ProgressCounter::add(std::size_t runs, double cost, double retire) {
  runs_ += runs;
  estimated_cost_ += std::max(0.0, cost);
  expected_ = std::max(0.0, expected_ - retire);
}

void ProgressCounter::expect(double cost) {
  expected_ += std::max(0.0, cost);
}

void ProgressCounter::finished_work(double work, double retire) {
  work = std::max(0.0, work);
  estimated_cost_ += work;
  done_cost_ += work;
  done_work_ += work;
  expected_ = std::max(0.0, expected_ - retire);
}

void ProgressCounter::finished(bool from_cache, double cost, double work, bool unstable) {
  ++done_;
  unstable_ += unstable;
  if (from_cache) {
    ++cached_;
    estimated_cost_ -= cost;  // a cached task takes no time: out of the estimate
  } else {
    done_cost_ += cost;
    done_work_ += work;
  }
}

double ProgressCounter::remaining_cost() const {
  if (finished()) return 0;
  // The subtractions leave a rounding residue where every estimate is gone: below a
  // millionth of the largest sum, the rest is nothing.
  const double total = estimated_cost_ + expected_;
  const double rest = total - done_cost_ - running_;
  const double scale = std::max(total, done_cost_);
  return rest > 1e-6 * scale ? rest : 0.0;
}

std::optional<double> ProgressCounter::seconds_to_go(double elapsed) const {
  if (finished()) return 0.0;
  const double done_estimate = done_cost_ + running_;
  const double done_work = done_work_ + running_;
  if (!(done_estimate > 0) || !(done_work > 0) || !(elapsed >= 1)) return std::nullopt;
  // Two rates bracket the truth when runs stop before T (unstable runs, most of them among the
  // longest, which go first): the estimates of the tasks done per second run ahead of the queue
  // (a run estimated to T that stopped half-way counts in full), the work done per second lags
  // it (the tasks left will stop early too). The line shows the geometric mean of the two.
  const double left = remaining_cost();
  const double by_estimate = left / (done_estimate / elapsed);
  const double by_work = left / (done_work / elapsed);
  const double to_go = std::sqrt(by_estimate * by_work);
  if (!std::isfinite(to_go) || to_go > kMaxHorizon * elapsed) return std::nullopt;
  return to_go;
}

std::string ProgressCounter::text(const std::string& label, double elapsed) const {
  char work[96];
  if (finished()) {
    std::snprintf(work, sizeof work, "%.2g particle-steps computed, %zu cases from the cache",
                  done_work_, cached_);
  } else {
    std::snprintf(work, sizeof work, "%.2g of ~%.2g particle-steps", done_work_ + running_,
                  done_work_ + running_ + remaining_cost());
  }
  char left[48] = "estimating";
  if (finished()) {
    std::snprintf(left, sizeof left, "done");
  } else if (const auto to_go = seconds_to_go(elapsed)) {
    std::snprintf(left, sizeof left, "~%.0f s to go", *to_go);
  }
  char line[320];
  std::snprintf(line, sizeof line, "[%s] %zu/%zu cases, %zu unstable, %s, %.0f s elapsed, %s",
                label.c_str(), done_, runs_, unstable_, work, std::max(0.0, elapsed), left);
  return line;
}

EstimateAccuracy estimate_accuracy(const std::vector<std::pair<double, double>>& estimates,
                                   double wall) {
  EstimateAccuracy a;
  if (!(wall > 0)) return a;
  for (const auto& [elapsed, to_go] : estimates) {
    const double truth = wall - elapsed;
    if (elapsed < EstimateAccuracy::kSkip * wall || truth < EstimateAccuracy::kTail * wall ||
        !(to_go > 0))
      continue;
    ++a.samples;
    a.worst = std::max(a.worst, std::max(to_go / truth, truth / to_go));
  }
  for (const double fraction : {0.1, 0.25, 0.5, 0.75}) {
    const std::pair<double, double>* nearest = nullptr;
    for (const auto& e : estimates) {
      if (e.first < fraction * wall) continue;
      nearest = &e;
      break;
    }
    if (nearest != nullptr)
      a.at.push_back({nearest->first / wall, nearest->second, wall - nearest->first});
  }
  return a;
}

}  // namespace mpmstab
