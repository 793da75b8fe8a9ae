#include "cached_run.hpp"

#include <nlohmann/json.hpp>

#include "provenance.hpp"
#include "run/run.hpp"
#include "sweep.hpp"

namespace mpmstab {

namespace {

using ojson = nlohmann::ordered_json;

std::optional<double> number(const ojson& j, const char* key) {
  const auto it = j.find(key);
  if (it == j.end() || !it->is_number()) return std::nullopt;
  return it->get<double>();
}

// A RunResult from the "result" of a record (record_defect has checked its shape).
RunResult from_record(const RunParams& p, const ojson& result) {
  RunResult r;
  r.params = p;
  r.particles = result["particles"].get<std::int64_t>();
  r.steps = result["steps"].get<std::int64_t>();
  for (const Outcome o :
       {Outcome::unstable, Outcome::meaningless, Outcome::stable, Outcome::too_short})
    if (result["outcome"].is_string() && result["outcome"].get<std::string>() == to_string(o))
      r.outcome = o;
  r.stable = r.outcome && *r.outcome != Outcome::unstable;
  r.max_error = number(result, "max_error");
  r.max_error_over_time = number(result, "max_error_over_time");
  r.error_l2_time = number(result, "error_l2_time");
  return r;
}

thread_local RunAccount* t_account = nullptr;

}  // namespace

RunAccount* open_run_account() {
  return t_account;
}

void open_run_account(RunAccount* account) {
  t_account = account;
}

RunResult cached_run(const ResultCache& cache, const RunParams& p) {
  if (const auto found = cache.load(p)) return from_record(p, (*found)["result"]);
  RunResult r = run(p);
  if (r.interrupted) return r;
  if (t_account)
    t_account->add(static_cast<double>(r.steps) * static_cast<double>(r.particles), r.wall_seconds);
  ojson record = run_record(r);
  record["provenance"] = to_json(current_provenance(1));
  cache.store(p, record);
  return from_record(p, record["result"]);
}

}  // namespace mpmstab
