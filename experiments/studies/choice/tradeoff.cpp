// The speed/accuracy trade: error against cost across methods, time-step policies and their
// parameters. Cost is the deterministic work of a run, particles x steps (particle-steps); the
// machine's wall times are kept apart (performance.md, timings.json), so a rerun writes the same
// report. It recommends nothing: every recommendation is advice.md's (advice_verify.hpp).
// From the rows of every scene, each parameter's stable range with a margin, and the rows it
// rests on. Per scene: the cheapest setting for each accuracy that passes its verifying runs (at
// the paper's largest amplitude and over a longer run), how the runs of each policy ended, and
// per E every setting with the Pareto front marked.
#include <algorithm>
#include <iomanip>
#include <limits>
#include <map>
#include <optional>
#include <set>
#include <sstream>
#include <tuple>

#include "base/params.hpp"
#include "choice/advice_rule.hpp"
#include "choice/advice_verify.hpp"
#include "claims.hpp"
#include "csv.hpp"
#include "key.hpp"
#include "report_util.hpp"
#include "run_row.hpp"
#include "shared/by_scene.hpp"
#include "study.hpp"

namespace mpmstab::studies::tradeoff {
namespace {

using ojson = nlohmann::ordered_json;

// The settings the sentences and claims compare: the paper's grid (kCoarse) against the finest
// (kFine), both under the CFL rule at kCflRef; stepping at the eq. (108) bound with safety
// kBoundSafety; the bound "buys no accuracy" when its error is within kNoGainFactor of the CFL
// rule's.
constexpr int kCoarse = 100, kFine = 400;
constexpr double kCflRef = 0.5, kBoundSafety = 1.0, kNoGainFactor = 2.0;

// ---------------------------------------------------------------------------------------------
// Follow-ups. What the walls cost: every run of the paper's bar under the CFL rule at kCflRef
// (every method, and GIMP and MPM on every grid) is rerun with periodic boundaries, which the
// periodic manufactured solution allows. The twin has no wall: its error is the interior's own,
// and the ratio of the two is what the Dirichlet walls' treatment adds.

// The rows whose periodic twin is run, in row order.
std::vector<std::size_t> twin_rows(const std::vector<ojson>& rows) {
  std::vector<std::size_t> idx;
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const ojson& r = rows[i];
    if (text(r, "scene") == "bar" && text(r, "bc") == "dirichlet" && text(r, "policy") == "cfl" &&
        r["cfl_factor"].get<double>() == kCflRef)
      idx.push_back(i);
  }
  return idx;
}

// The cheapest settings, verified as `mpmstab advise` verifies an answer: per scene, E and target
// error, the kVerified cheapest runs reaching the target are run again at the paper's largest
// amplitude (where the target is read as the same error over time / A) and over length_factor x
// c T (kAdviceDomain); a setting passes where both end stable within the target.
const std::vector<double> kTargets = {1e-3, 1e-4, 1e-5};
constexpr std::size_t kVerified = 8;

// A case's verifying runs, by role (a default RunParams gives the roles alone).
std::vector<std::pair<std::string, RunParams>> verifying_runs(const RunParams& p) {
  RunParams larger = p, longer = p;
  larger.A = kPaperLargestA;
  longer.T *= kAdviceDomain.length_factor;
  return {{"A = " + value_text(kPaperLargestA), larger},
          {shortest(kAdviceDomain.length_factor) + " x c T", longer}};
}

// Whether run i ranks before run j on cost: fewer particle-steps, then the smaller error, then
// the earlier row. A total order, so that every ranking is the same on every rerun.
bool cheaper(const std::vector<ojson>& rows, std::size_t i, std::size_t j) {
  const TotalLess less;  // total even where a record holds a NaN
  const double ci = particle_steps(rows[i]), cj = particle_steps(rows[j]);
  if (less(ci, cj) || less(cj, ci)) return less(ci, cj);
  constexpr double kNone = std::numeric_limits<double>::infinity();
  const double ei = stable_error_over_time(rows[i]).value_or(kNone),
               ej = stable_error_over_time(rows[j]).value_or(kNone);
  if (less(ei, ej) || less(ej, ei)) return less(ei, ej);
  return i < j;
}

// The runs of `idx` reaching `target`, cheapest first (cheaper()).
std::vector<std::size_t> reaching(const std::vector<ojson>& rows, std::vector<std::size_t> idx,
                                  double target) {
  std::erase_if(idx, [&](std::size_t i) {
    const auto e = stable_error_over_time(rows[i]);
    return !e || *e > target;
  });
  std::sort(idx.begin(), idx.end(),
            [&](std::size_t i, std::size_t j) { return cheaper(rows, i, j); });
  return idx;
}

// The runs verified: per scene and E, the kVerified cheapest reaching each target.
std::set<std::size_t> verified_rows(const std::vector<ojson>& rows) {
  std::map<std::pair<std::string, Key>, std::vector<std::size_t>> groups;
  for (std::size_t i = 0; i < rows.size(); ++i)
    groups[{text(rows[i], "scene"), Key(rows[i]["E"].get<double>(), "E")}].push_back(i);
  std::set<std::size_t> out;
  for (const auto& [scene_E, idx] : groups) {
    for (const double target : kTargets) {
      const auto r = reaching(rows, idx, target);
      out.insert(r.begin(), r.begin() + std::ptrdiff_t(std::min(r.size(), kVerified)));
    }
  }
  return out;
}

// The follow-up runs: the periodic twins, then the verifying runs.
constexpr const char* kPeriodicTwin = "periodic twin";
std::vector<FollowUp> tradeoff_follow_ups(const FollowUpContext& c) {
  std::vector<FollowUp> runs;
  for (const std::size_t i : twin_rows(c.rows)) {
    RunParams p = c.spec.cases.at(i).params;
    p.bc = Boundary::periodic;
    runs.push_back({.of = i, .role = kPeriodicTwin, .params = p});
  }
  for (const std::size_t i : verified_rows(c.rows))
    for (auto& [role, p] : verifying_runs(c.spec.cases.at(i).params))
      runs.push_back({.of = i, .role = role, .params = p});
  return runs;
}

// Each twin by the index of its row (absent where the follow-up runs are).
std::map<std::size_t, const ojson*> periodic_twins(const std::vector<ojson>& rows,
                                                   const std::vector<ojson>& follow_up) {
  std::map<std::size_t, const ojson*> out;
  for (const std::size_t i : twin_rows(rows))
    for (const ojson* twin : follow_ups_of(follow_up, i, kPeriodicTwin))
      out[i] = twin;
  return out;
}

// ---------------------------------------------------------------------------------------------
// Findings: settings and their parameters (docs/studies.md, "Time-step policies")

const std::vector<std::string> kPolicies = {"fixed", "cfl", "adaptive", "min", "spectral"};

// The parameter a policy is advised on: the fixed dt, the CFL factor C or the safety factor s
// (the min policy: s, at its C).
const char* parameter_key(const std::string& policy) {
  if (policy == "fixed") return "dt";
  return policy == "cfl" ? "cfl_factor" : "safety";
}

const char* parameter_symbol(const std::string& policy) {
  if (policy == "fixed") return "dt";
  return policy == "cfl" ? "C" : "s";
}

double parameter(const ojson& r) {
  return r[parameter_key(text(r, "policy"))].get<double>();
}

// A parameter value as the report writes it: "1e-4" for a dt, "0.25", "0.375" or "1.05" for C or s.
std::string parameter_text(const std::string& policy, double v) {
  return policy == "fixed" ? param(v) : significant(v, 3);
}

// A setting's name: "gimp cfl C=0.5", "mpm adaptive s=2", "gimp fixed dt=1e-4".
std::string setting(const ojson& r) {
  const std::string policy = text(r, "policy");
  std::string s = method_label(r) + " " + policy;
  if (policy == "fixed") s += " dt=" + param(r["dt"].get<double>());
  if (policy == "cfl" || policy == "min") s += " C=" + shortest(r["cfl_factor"].get<double>());
  if (policy == "adaptive" || policy == "min" || policy == "spectral")
    s += " s=" + shortest(r["safety"].get<double>());
  if (r["cells"].get<int>() != 100) s += ", " + r["cells"].dump() + " cells";
  return s;
}

// The index of `key` in `seen`, appended when new: methods, values of E, panels and series in the
// order they first appear.
template <class T>
std::size_t index_in(std::vector<T>& seen, const T& key) {
  const auto it = std::find(seen.begin(), seen.end(), key);
  if (it != seen.end()) return static_cast<std::size_t>(it - seen.begin());
  seen.push_back(key);
  return seen.size() - 1;
}

// The methods of the rows in the order they first appear.
std::vector<std::string> methods_of(const std::vector<ojson>& rows) {
  std::vector<std::string> methods;
  for (const auto& r : rows)
    index_in(methods, method_label(r));
  return methods;
}

// Indices of the runs on the Pareto front of (particle-steps, error): no other run is both
// cheaper and more accurate. Runs equal in both are both on it.
std::set<std::size_t> pareto_front(const std::vector<ojson>& rows,
                                   const std::vector<std::size_t>& idx) {
  std::set<std::size_t> front;
  for (std::size_t i : idx) {
    const auto ei = stable_error_over_time(rows[i]);
    if (!ei) continue;
    const double ci = particle_steps(rows[i]);
    bool dominated = false;
    for (std::size_t j : idx) {
      const auto ej = stable_error_over_time(rows[j]);
      if (j == i || !ej) continue;
      const double cj = particle_steps(rows[j]);
      if (cj <= ci && *ej <= *ei && (cj < ci || *ej < *ei)) dominated = true;
    }
    if (!dominated) front.insert(i);
  }
  return front;
}

// The rows of one scene, the values of E they hold (in the order they first appear) and the
// look-ups the advice is computed from.
struct TradeRows {
  const std::vector<ojson>& rows;
  std::vector<double> Es;

  explicit TradeRows(const std::vector<ojson>& scene_rows) : rows(scene_rows) {
    for (const auto& r : rows)
      index_in(Es, r["E"].get<double>());
  }

  // Indices of the runs at E.
  std::vector<std::size_t> at(double E) const {
    std::vector<std::size_t> idx;
    for (std::size_t i = 0; i < rows.size(); ++i)
      if (rows[i]["E"].get<double>() == E) idx.push_back(i);
    return idx;
  }

  // The run at E of `method` under `policy` on `cells` cells whose parameter (parameter()) is
  // `value`; null when the sweep has none.
  const ojson* find(double E, const std::string& method, const std::string& policy, double value,
                    int cells) const {
    for (const auto& r : rows)
      if (r["E"].get<double>() == E && method_label(r) == method && text(r, "policy") == policy &&
          r["cells"].get<int>() == cells && parameter(r) == value)
        return &r;
    return nullptr;
  }
};

// ---------------------------------------------------------------------------------------------
// Stable ranges with a margin, a description of the runs (recommendations are advice.md's): a
// value v of a parameter is stable with a margin for a method and policy if, at
// every E of the scene, they were run at v and at some p >= 1.5 v, and every one of their runs
// with the parameter up to p (on every grid) is stable and takes no step above its scheme's
// spectral limit (where recorded). The largest such v is reported.

constexpr double kMargin = 1.5;

// The runs one piece of advice is about: one method under one policy (the min policy at one C).
struct AdviceGroup {
  std::string method, policy;
  std::optional<double> cfl_factor;  // the min policy's C

  bool holds(const ojson& r) const {
    return method_label(r) == method && text(r, "policy") == policy &&
           (!cfl_factor || r["cfl_factor"].get<double>() == *cfl_factor);
  }
  // "gimp cfl", "gimp min at C = 0.5".
  std::string name() const {
    std::string s = method + " " + policy;
    if (cfl_factor) s += " at C = " + shortest(*cfl_factor);
    return s;
  }
  std::string value(double v) const {
    return std::string(parameter_symbol(policy)) + " = " + parameter_text(policy, v);
  }
};

// The groups of a scene: by method in the order they first appear, then by policy.
std::vector<AdviceGroup> advice_groups(const std::vector<ojson>& rows) {
  std::vector<AdviceGroup> groups;
  for (const auto& m : methods_of(rows)) {
    for (const auto& p : kPolicies) {
      std::set<Key> Cs;
      bool any = false;
      for (const auto& r : rows) {
        if (method_label(r) != m || text(r, "policy") != p) continue;
        any = true;
        if (p == "min") Cs.insert(Key(r["cfl_factor"].get<double>(), "cfl_factor"));
      }
      if (!any) continue;
      if (p != "min") groups.push_back({m, p, std::nullopt});
      for (double C : Cs)
        groups.push_back({m, p, C});
    }
  }
  return groups;
}

// "36 rows: gimp cfl C = 0.05..0.5 at E = 4, 64 and 1000 (A = 0.015; c T = 2, 8 and 31.6; 100,
// 200 and 400 cells; bar and steffen)": their count, values, E and coverage.
std::string describe_rows(const TradeRows& t, const AdviceGroup& g,
                          const std::vector<std::size_t>& idx) {
  std::set<Key> values;
  std::vector<const ojson*> rows;
  std::vector<double> Es;
  for (std::size_t i : idx) {
    values.insert(Key(parameter(t.rows[i]), "the policy's parameter"));
    rows.push_back(&t.rows[i]);
    Es.push_back(t.rows[i]["E"].get<double>());
  }
  std::string s = std::to_string(idx.size()) + " rows: " + g.name() + (g.cfl_factor ? ", " : " ") +
                  g.value(*values.begin());
  if (values.size() > 1) s += ".." + parameter_text(g.policy, *values.rbegin());
  return s + " at E = " + listing(Es) + " (" + coverage_of(rows).text() + ")";
}

// The rule applied to one value v of a group's parameter.
struct ValueCheck {
  double value = 0;
  bool advised = false;
  std::string rests_on;  // the group's runs up to the checking value (describe_rows), where advised
  double checked_lo = 0, checked_hi = 0;  // over E, the smallest value run at or beyond 1.5 v
  std::string why_not;                    // why it is not advised
};

// The group's runs at E, by parameter (then row order).
std::vector<std::size_t> group_rows_at(const TradeRows& t, const AdviceGroup& g, double E) {
  std::vector<std::size_t> idx;
  for (std::size_t i : t.at(E))
    if (g.holds(t.rows[i])) idx.push_back(i);
  std::stable_sort(idx.begin(), idx.end(), [&](std::size_t a, std::size_t b) {
    return TotalLess()(parameter(t.rows[a]), parameter(t.rows[b]));
  });
  return idx;
}

// "gimp cfl C=0.7 at E = 4 (bar): \* nonpositive_F at step 258 (t = 9.0e-1)".
std::string row_verdict(const ojson& r) {
  return setting(r) + " at E = " + shortest(r["E"].get<double>()) + " (" + text(r, "scene") +
         "): " + verdict(r);
}

// Whether v is advised (the rule above), and the rows it rests on or why not. A run that is not
// stable up to the checking value (or, with none, among all the group's runs at E) tells first,
// then a run whose largest step lies above its scheme's spectral limit (where both are recorded:
// its survival holds for this amplitude and run length only), then a value not run at some E,
// then a margin that no run checks.
ValueCheck check_value(const TradeRows& t, const AdviceGroup& g, double v) {
  ValueCheck c;
  c.value = v;
  std::vector<std::size_t> rests_on;
  std::vector<double> checked, not_run, unchecked;  // the values checked; the values of E
  for (double E : t.Es) {
    const auto idx = group_rows_at(t, g, E);
    // The smallest parameter run at or beyond 1.5 v (a relative 1e-9 below it counts, so that
    // 1.5 x 1e-4 finds a run at 1.5e-4).
    std::optional<double> p;
    for (std::size_t i : idx)
      if (!p && parameter(t.rows[i]) >= kMargin * v * (1 - 1e-9)) p = parameter(t.rows[i]);
    const double limit = p.value_or(std::numeric_limits<double>::infinity());
    for (std::size_t i : idx) {
      if (parameter(t.rows[i]) > limit) break;
      const RunRow rr(t.rows[i]);
      if (rr.outcome != "stable" && c.why_not.empty()) c.why_not = row_verdict(t.rows[i]);
      if (rr.above_spectral_limit() && c.why_not.empty()) {
        c.why_not = row_verdict(t.rows[i]) + ", but its steps reach c dt/h " +
                    fixed(*rr.courant, 3) + ", above the spectral limit " +
                    fixed(*rr.courant_spectral, 3);
      }
      rests_on.push_back(i);
    }
    const bool run_at_v = std::any_of(idx.begin(), idx.end(),
                                      [&](std::size_t i) { return parameter(t.rows[i]) == v; });
    if (!run_at_v) not_run.push_back(E);
    if (p)
      checked.push_back(*p);
    else
      unchecked.push_back(E);
  }
  if (c.why_not.empty() && !not_run.empty()) c.why_not = "not run at E = " + listing(not_run);
  if (c.why_not.empty() && !unchecked.empty()) {
    c.why_not = "no row at " + shortest(kMargin) + "x (" + g.value(kMargin * v) +
                ") at E = " + listing(unchecked) + "; margin not checked";
  }
  c.advised = c.why_not.empty();
  if (!c.advised) return c;
  c.rests_on = describe_rows(t, g, rests_on);
  const auto [lo, hi] = std::minmax_element(checked.begin(), checked.end(), TotalLess());
  c.checked_lo = *lo;
  c.checked_hi = *hi;
  return c;
}

// The advice for one group: the largest value advised (if any) and the next value run, which
// is not.
struct MarginRange {
  AdviceGroup group;
  std::optional<ValueCheck> advised;
  ValueCheck next;
};

MarginRange stable_range(const TradeRows& t, const AdviceGroup& g) {
  std::set<Key> values;
  for (const auto& r : t.rows)
    if (g.holds(r)) values.insert(Key(parameter(r), "the policy's parameter"));
  MarginRange a{g, std::nullopt, {}};
  std::vector<ValueCheck> checks;
  for (double v : values)
    checks.push_back(check_value(t, g, v));
  std::size_t next = 0;
  for (std::size_t k = 0; k < checks.size(); ++k) {
    if (checks[k].advised) {
      a.advised = checks[k];
      next = k + 1;
    }
  }
  // The largest value (positive, as validate() asks) has no run at 1.5 times it, so some value
  // is always left not advised.
  static_assert(kMargin > 1);
  a.next = checks.at(next);
  return a;
}

// ---------------------------------------------------------------------------------------------
// Findings: what each scene's rows show

// How far GIMP's error moves at one E: with dt on the paper's grid (every stable fixed and CFL
// step), and with the grid (CFL at kCflRef, on every finer grid run).
struct StepSpread {
  double E = 0, lo = 0, hi = 0;               // the least and largest error over the steps
  std::vector<std::pair<int, double>> finer;  // cells and error, ascending in cells
  std::vector<const ojson*> read;             // the runs of both
};

// Per E where GIMP has a stable fixed or CFL step on the paper's grid, how far its error moves.
std::vector<StepSpread> step_spreads(const TradeRows& t) {
  std::vector<StepSpread> out;
  for (double E : t.Es) {
    std::vector<double> errs;
    std::vector<const ojson*> read;
    std::set<int> finer;  // the finer grids run under the CFL rule at kCflRef
    for (const auto& r : t.rows) {
      const std::string policy = text(r, "policy");
      const int cells = r["cells"].get<int>();
      if (r["E"].get<double>() == E && method_label(r) == "gimp" && cells == kCoarse &&
          (policy == "cfl" || policy == "fixed") && stable_error_over_time(r)) {
        errs.push_back(*stable_error_over_time(r));
        read.push_back(&r);
      }
      if (cells > kCoarse && t.find(E, "gimp", "cfl", kCflRef, cells) == &r) finer.insert(cells);
    }
    if (errs.empty()) continue;
    const auto [lo, hi] = std::minmax_element(errs.begin(), errs.end(), TotalLess());
    StepSpread s{.E = E, .lo = *lo, .hi = *hi, .read = read};
    for (const int cells : finer) {
      const ojson* r = t.find(E, "gimp", "cfl", kCflRef, cells);
      s.read.push_back(r);
      if (const auto e = stable_error_over_time(*r)) s.finer.emplace_back(cells, *e);
    }
    out.push_back(std::move(s));
  }
  return out;
}

// GIMP on the paper's grid (kCoarse) against the finest (kFine), both under the CFL rule at
// kCflRef, at every E where both reach T stable: at how many the finer grid lowered the error
// over time, and the least factor it lowered it by (below one: it rose). The sentence and the
// claims read this one finding.
struct GridRefinement {
  int better = 0, total = 0;
  double least_fall = 0;
  std::vector<const ojson*> read;  // the runs on both grids
};

GridRefinement grid_refinement(const TradeRows& t) {
  GridRefinement g;
  double least = 1e300;
  for (double E : t.Es) {
    const ojson* coarse = t.find(E, "gimp", "cfl", kCflRef, kCoarse);
    const ojson* fine = t.find(E, "gimp", "cfl", kCflRef, kFine);
    for (const ojson* r : {coarse, fine})
      if (r) g.read.push_back(r);
    if (!coarse || !fine || !stable_error_over_time(*coarse) || !stable_error_over_time(*fine))
      continue;
    const double change = *stable_error_over_time(*fine) / *stable_error_over_time(*coarse);
    least = std::min(least, 1 / change);
    ++g.total;
    g.better += change < 1;
  }
  g.least_fall = g.total ? least : 0;
  return g;
}

// Stepping at the eq. (108) bound (adaptive, kBoundSafety) against the CFL rule at kCflRef on
// the paper's grid, for MPM and GIMP at every E where both have an error: over the pairs, the
// ranges of the ratios of their step counts and of their errors.
struct BoundAgainstCfl {
  std::size_t pairs = 0;
  double steps_lo = 0, steps_hi = 0, errors_lo = 0, errors_hi = 0;  // where there are pairs
  std::vector<const ojson*> read;                                   // the runs of both policies
};

BoundAgainstCfl bound_against_cfl(const TradeRows& t) {
  std::vector<double> steps, errors;
  std::vector<const ojson*> read;
  for (double E : t.Es) {
    for (const char* m : {"gimp", "mpm"}) {
      const ojson* b = t.find(E, m, "adaptive", kBoundSafety, kCoarse);
      const ojson* c = t.find(E, m, "cfl", kCflRef, kCoarse);
      for (const ojson* r : {b, c})
        if (r) read.push_back(r);
      if (b && c && stable_error_over_time(*b) && stable_error_over_time(*c)) {
        steps.push_back((*b)["steps"].get<double>() / (*c)["steps"].get<double>());
        errors.push_back(*stable_error_over_time(*b) / *stable_error_over_time(*c));
      }
    }
  }
  if (steps.empty()) return {.read = read};
  const auto [slo, shi] = std::minmax_element(steps.begin(), steps.end(), TotalLess());
  const auto [elo, ehi] = std::minmax_element(errors.begin(), errors.end(), TotalLess());
  return {steps.size(), *slo, *shi, *elo, *ehi, read};
}

// Per E where both reach an accuracy, the runs with the best error of MPM and of GIMP.
struct BestOfMethods {
  double E = 0;
  const ojson *mpm = nullptr, *gimp = nullptr;
};

std::vector<BestOfMethods> best_of_methods(const TradeRows& t) {
  std::vector<BestOfMethods> out;
  for (double E : t.Es) {
    BestOfMethods b{.E = E};
    for (const auto& r : t.rows) {
      const std::string m = method_label(r);
      if (r["E"].get<double>() != E || !stable_error_over_time(r) || (m != "gimp" && m != "mpm"))
        continue;
      const ojson*& best = m == "gimp" ? b.gimp : b.mpm;
      if (!best || *stable_error_over_time(r) < *stable_error_over_time(*best)) best = &r;
    }
    if (b.gimp && b.mpm) out.push_back(b);
  }
  return out;
}

// Where run r lies beyond its method and policy's stable range with a margin, in words ("" where
// within it).
std::string beyond_range(const std::vector<MarginRange>& ranges, const ojson& r) {
  for (const auto& a : ranges) {
    if (!a.group.holds(r)) continue;
    if (!a.advised) return a.group.name() + " has no stable range with margin";
    if (parameter(r) <= a.advised->value) return "";
    return "outside " + a.group.name() + "'s stable range with margin (" +
           parameter_symbol(a.group.policy) + " up to " +
           parameter_text(a.group.policy, a.advised->value) + ")";
  }
  return "";
}

// One target at one E: how many runs reach it and, cheapest first, those of the kVerified
// cheapest tried until one passed its verifying runs (then the last).
struct CheapestCell {
  struct Tried {
    std::size_t row = 0;
    std::vector<VerifyingRun> runs;  // per role of verifying_runs()
    bool passed = true;
    std::string why;  // the first verifying run it failed (failure_words)
  };
  std::size_t reaching = 0;
  std::vector<Tried> tried;
  const Tried* chosen() const {
    return !tried.empty() && tried.back().passed ? &tried.back() : nullptr;
  }
};

// What one scene's rows show: the cheapest verified runs, how far the step and the grid move
// GIMP's error, the bound against the CFL rule, MPM against GIMP, how the runs ended, the Pareto
// front.
struct SceneFindings {
  TradeRows t;
  std::vector<std::size_t> global;                  // each row's index among every scene's
  std::vector<std::vector<CheapestCell>> cheapest;  // per E (t.Es), per target
  // The method and policy ("gimp cfl") most often the cheapest verified (the first by name on a
  // tie), in how many (E, target) pairs; the pairs some run reaches, those with a verified
  // setting, and of those how many lie beyond their stable range with a margin.
  std::string top;
  int top_wins = 0, reached = 0, verified = 0, beyond = 0;
  std::vector<const ojson*> verifying_read;  // every verifying run read
  std::vector<StepSpread> spreads;
  GridRefinement refinement;
  BoundAgainstCfl bound;
  std::vector<BestOfMethods> best;
  int gimp_better = 0;  // of `best`, where GIMP's error is the smaller
  // How the runs of each policy ended (docs/studies.md, "Outcomes"), and the failure reasons the
  // table has a column for: dt_collapse always, then every other reason some run stopped with.
  std::map<std::string, VerdictTally> endings;
  std::vector<std::string> reasons;
  std::set<std::size_t> front;              // the runs on the Pareto front of their E
  std::vector<std::vector<double>> passes;  // per E, the wave passes c T of its runs
};

// A run tried for `target`: whether its verifying runs pass, read as `mpmstab advise` reads its
// own (the target per the run's A: at the largest amplitude, the same error over time / A).
CheapestCell::Tried tried_for(SceneFindings& s, std::size_t i, double target,
                              const std::vector<ojson>& follow_up) {
  CheapestCell::Tried tried{.row = i};
  const double over_A = target / *RunRow(s.t.rows[i]).A;
  for (const auto& [role, params] : verifying_runs({})) {
    const auto asked = follow_ups_of(follow_up, s.global[i], role);
    if (!asked.empty()) s.verifying_read.push_back(asked.front());
    const VerifyingRun& v =
        tried.runs.emplace_back(asked.empty() ? VerifyingRun{.what = role, .outcome = "not run"}
                                              : verifying_run_of(role, *asked.front(), over_A));
    if (!v.passes && tried.passed) tried.why = failure_words(v, over_A);
    tried.passed = tried.passed && v.passes;
  }
  return tried;
}

SceneFindings scene_findings(const std::vector<ojson>& rows, std::vector<std::size_t> global,
                             const std::vector<ojson>& follow_up,
                             const std::vector<MarginRange>& ranges) {
  SceneFindings s{.t = TradeRows(rows), .global = std::move(global)};
  std::map<std::string, int> wins;
  for (double E : s.t.Es) {
    const std::vector<std::size_t> at = s.t.at(E);
    auto& cells = s.cheapest.emplace_back();
    for (const double target : kTargets) {
      const auto r = reaching(rows, at, target);
      CheapestCell& cell = cells.emplace_back();
      cell.reaching = r.size();
      for (std::size_t k = 0; k < std::min(r.size(), kVerified) && !cell.chosen(); ++k)
        cell.tried.push_back(tried_for(s, r[k], target, follow_up));
      s.reached += !r.empty();
      if (const auto* c = cell.chosen()) {
        ++wins[method_label(rows[c->row]) + " " + text(rows[c->row], "policy")];
        ++s.verified;
        s.beyond += !beyond_range(ranges, rows[c->row]).empty();
      }
    }
    const auto front = pareto_front(rows, at);
    s.front.insert(front.begin(), front.end());
    auto& passes = s.passes.emplace_back();
    for (std::size_t i : at)
      if (const auto cT = RunRow(rows[i]).wave_passes) passes.push_back(*cT);
  }
  for (const auto& [name, n] : wins) {
    if (n <= s.top_wins) continue;
    s.top = name;
    s.top_wins = n;
  }
  s.spreads = step_spreads(s.t);
  s.refinement = grid_refinement(s.t);
  s.bound = bound_against_cfl(s.t);
  s.best = best_of_methods(s.t);
  for (const auto& b : s.best)
    s.gimp_better += *stable_error_over_time(*b.gimp) < *stable_error_over_time(*b.mpm);
  for (const auto& p : kPolicies)
    s.endings[p];
  for (const auto& r : rows)
    s.endings[text(r, "policy")].add(r);
  std::set<std::string> others;  // the failure reasons but dt_collapse, alphabetically
  for (const auto& [p, e] : s.endings)
    for (const auto& [reason, n] : e.reasons)
      if (reason != "dt_collapse") others.insert(reason);
  s.reasons = {"dt_collapse"};
  s.reasons.insert(s.reasons.end(), others.begin(), others.end());
  return s;
}

// A run the figure draws: stable, with an error a log axis can show.
bool drawn(const ojson& r) {
  const auto e = stable_error_over_time(r);
  return e && *e > 0;
}

// The runs of a scene the figure draws and those it leaves out, by outcome.
struct FigureCount {
  std::string scene;
  std::size_t runs = 0, drawn = 0, unstable = 0, meaningless = 0, no_error = 0;
};

FigureCount figure_count(const std::vector<ojson>& rows) {
  FigureCount n;
  n.scene = rows.front()["scene"].get<std::string>();
  n.runs = rows.size();
  for (const auto& r : rows) {
    const Ending e = RunRow(r).ending();
    if (drawn(r))
      ++n.drawn;
    else if (e == Ending::unstable)
      ++n.unstable;
    else if (e == Ending::meaningless)
      ++n.meaningless;
    else
      ++n.no_error;
  }
  return n;
}

// What the report, its claims and the subtitle say, found once.
struct Findings {
  TradeRows all;                     // every scene's rows
  std::vector<double> passes;        // the wave passes c T of every run
  std::vector<SceneRows> scenes;     // the paper's bar first (never copied: `scene` refers into it)
  std::vector<SceneFindings> scene;  // what each scene's rows show
  std::vector<MarginRange> ranges;   // each parameter's stable range, over every scene
  int gimp_better = 0, compared = 0;  // (scene, E) pairs where GIMP's best error is below MPM's
  double spread_max = 0;              // the bar: the largest factor the step moves GIMP's error by
  // The periodic twins by method (in the order the rows first name it), E and cells; at how many
  // E GIMP's twin on kFine cells has a smaller error than on kCoarse, of those compared.
  std::vector<std::pair<std::size_t, const ojson*>> twins;
  int twins_lowered = 0, twins_compared = 0;
  FigureCount figure;  // of the first scene
};

// The findings from the rows and the follow-up runs (the periodic twins; none for the subtitle,
// which prints no finding of theirs).
Findings find(const std::vector<ojson>& rows, const std::vector<ojson>& follow_up) {
  Findings f{.all = TradeRows(rows), .scenes = by_scene(rows)};
  f.passes = values_of(rows, &RunRow::wave_passes);
  for (const auto& g : advice_groups(rows))
    f.ranges.push_back(stable_range(f.all, g));
  for (const auto& sc : f.scenes) {
    std::vector<std::size_t> global;  // the scene's rows among all (by_scene keeps their order)
    for (std::size_t i = 0; i < rows.size(); ++i)
      if (text(rows[i], "scene") == sc.scene) global.push_back(i);
    f.scene.push_back(scene_findings(sc.rows, std::move(global), follow_up, f.ranges));
    f.gimp_better += f.scene.back().gimp_better;
    f.compared += int(f.scene.back().best.size());
  }
  for (const auto& s : f.scene.front().spreads)
    f.spread_max = std::max(f.spread_max, s.hi / s.lo);
  // The twins in the walls' table order, and GIMP without walls against the grid: does refining
  // lower the interior's error?
  const auto twins = periodic_twins(rows, follow_up);
  for (const auto& [i, twin] : twins) {
    if (method_label(rows[i]) != "gimp" || rows[i]["cells"].get<int>() != kFine) continue;
    for (const auto& [j, coarse] : twins) {
      if (method_label(rows[j]) == "gimp" && rows[j]["cells"].get<int>() == kCoarse &&
          rows[j]["E"] == rows[i]["E"] && stable_error_over_time(*twin) &&
          stable_error_over_time(*coarse)) {
        ++f.twins_compared;
        f.twins_lowered += *stable_error_over_time(*twin) < *stable_error_over_time(*coarse);
      }
    }
  }
  const std::vector<std::string> methods = methods_of(rows);
  auto order = [&](std::size_t i) {
    const ojson& r = rows[i];
    return std::tuple(std::find(methods.begin(), methods.end(), method_label(r)) - methods.begin(),
                      Key(r["E"].get<double>(), "E"), r["cells"].get<int>());
  };
  f.twins.assign(twins.begin(), twins.end());
  std::stable_sort(f.twins.begin(), f.twins.end(),
                   [&](const auto& a, const auto& b) { return order(a.first) < order(b.first); });
  f.figure = figure_count(f.scenes.front().rows);
  return f;
}

// ---------------------------------------------------------------------------------------------
// Claims: GIMP against MPM over every scene; and what the rows of the paper's bar (the first
// scene) decide for GIMP: the step moves the error less than the grid does; a finer grid lowers
// it; stepping at the eq. (108) bound buys no accuracy over the CFL rule.

// Per scene: the cheapest setting that passes its verifying runs is one method and policy at
// every (E, target) pair some run reaches; decided by the scene's rows (the ranking) and the
// verifying runs read.
Claim cheapest_claim(const SceneRows& sc, const SceneFindings& s) {
  Claim c = claim("cheapest-verified-" + sc.scene,
                  "On the scene {scene}, {top} is the cheapest setting in particle-steps that "
                  "passes its verifying runs (stable within the target at A = {A} and over {k} x "
                  "c T) at every (E, target) pair some run reaches",
                  "{wins} of {pairs} pairs; {none} without a passing setting among their {n} "
                  "cheapest");
  c.value("scene", sc.scene)
      .value("top", s.top.empty() ? "–" : s.top)
      .value("A", value_text(kPaperLargestA))
      .value("k", shortest(kAdviceDomain.length_factor))
      .count("none", s.reached - s.verified)
      .count("n", static_cast<long long>(kVerified))
      .every("wins", s.top_wins, "pairs", s.reached);
  std::vector<const ojson*> read = s.verifying_read;
  for (const auto& r : sc.rows)
    read.push_back(&r);
  c.on(coverage_of(read));
  return c;
}

std::vector<Claim> tradeoff_claims(const Findings& f) {
  Claim gimp = claim("gimp-more-accurate-than-mpm",
                     "GIMP's best error over time is below MPM's at every (scene, E) pair where "
                     "both reach an accuracy",
                     "{better} of {compared} pairs");
  gimp.every("better", f.gimp_better, "compared", f.compared);
  std::vector<const ojson*> gimp_mpm;  // the runs the best errors are chosen from
  for (const auto& sc : f.scenes)
    for (const auto& r : sc.rows)
      if (method_label(r) == "gimp" || method_label(r) == "mpm") gimp_mpm.push_back(&r);
  gimp.on(coverage_of(gimp_mpm));
  const SceneFindings& bar = f.scene.front();
  const GridRefinement& g = bar.refinement;
  Claim spread = claim("step-moves-error-less-than-grid",
                       "For GIMP on the paper's bar, below the edge the time step moves the error "
                       "over time less than the grid does, at every E: a smaller step costs work "
                       "and buys no accuracy",
                       "the step moves it by a factor of at most {spread} (every stable fixed and "
                       "CFL step on {coarse} cells); {coarse} to {fine} cells lower it by a factor "
                       "of at least {grid} (a factor below one: it rises); {total} values of E");
  spread.number("spread", f.spread_max)
      .count("coarse", kCoarse)
      .count("fine", kFine)
      .number("grid", g.least_fall)
      .count("total", g.total);
  spread.holds = g.total > 0 && f.spread_max < g.least_fall;
  std::vector<const ojson*> spread_read = g.read;
  for (const auto& e : bar.spreads)
    spread_read.insert(spread_read.end(), e.read.begin(), e.read.end());
  spread.on(coverage_of(spread_read));
  Claim finer = claim("finer-grid-lowers-error",
                      "A finer grid lowers GIMP's error over time on the paper's bar at every E",
                      "{better} of {total} values of E ({fine} against {coarse} cells, CFL C = "
                      "{C})");
  finer.every("better", g.better, "total", g.total)
      .count("fine", kFine)
      .count("coarse", kCoarse)
      .value("C", shortest(kCflRef))
      .on(coverage_of(g.read));
  const BoundAgainstCfl& b = bar.bound;
  const auto all = static_cast<long long>(2 * bar.t.Es.size()),
             pairs = static_cast<long long>(b.pairs);
  Claim bound = claim("bound-buys-no-accuracy",
                      "Stepping at the eq. (108) bound (adaptive, s = {s}) takes more steps than "
                      "the CFL rule at C = {C} and does not lower the error over time by a factor "
                      "of {factor}, for MPM and GIMP at every E on the paper's bar where both runs "
                      "reach T below A",
                      "{pairs} pairs: {slo} to {shi} times the steps, {elo} to {ehi} times the "
                      "error; {left} of {all} (method, E) pairs left out: a run failed or was "
                      "meaningless");
  bound.value("s", shortest(kBoundSafety))
      .value("C", shortest(kCflRef))
      .value("factor", shortest(kNoGainFactor))
      .count("pairs", pairs)
      .count("left", all - pairs)
      .count("all", all)
      .on(coverage_of(b.read));
  if (b.pairs == 0) {
    bound.value("slo", "–").value("shi", "–").value("elo", "–").value("ehi", "–");
  } else {
    bound.value("slo", ratio(b.steps_lo))
        .value("shi", ratio(b.steps_hi))
        .value("elo", ratio(b.errors_lo))
        .value("ehi", ratio(b.errors_hi));
    bound.holds = b.steps_lo > 1 && b.errors_lo > 1 / kNoGainFactor;
  }
  std::vector<Claim> claims = {gimp, spread, finer, bound};
  for (std::size_t k = 0; k < f.scenes.size(); ++k)
    claims.push_back(cheapest_claim(f.scenes[k], f.scene[k]));
  return claims;
}

// ---------------------------------------------------------------------------------------------
// Text

// The first scene's opening: what accuracy and cost mean here, where the wall times are, and
// the figure.
std::string results_intro(const Spec& spec) {
  std::ostringstream md;
  md << "## Results\n\nAccuracy is the max error over time (the largest particle displacement "
        "error after any step), since for most E the exact displacement at T is zero. Cost is "
        "the work of the run in particle-steps (particles x steps), which a rerun reproduces "
        "exactly; ties are broken by the smaller error, then by the order of the spec. The wall "
        "times of these runs are measurements of the machine and are kept apart: see "
        "[performance.md](performance.md) and [timings.json](timings.json). Only a stable run "
        "reaches an accuracy: a run that failed (unstable) or whose error reached A "
        "(meaningless) reaches none. Pareto front: no other setting at the same E is both "
        "cheaper and more accurate.\n\n"
     << cost_metric_text() << "\n\n![" << spec.title << "](" << spec.name << ".png)\n\n"
     << "Vector version: [" << spec.name << ".svg](" << spec.name << ".svg); data: [" << spec.name
     << "_data.csv](" << spec.name << "_data.csv).\n\n";
  return md.str();
}

// What the runs say about picking a setting (advice.md recommends): the stable ranges of each
// policy's parameter (a description): the rule, and per method and policy the value advised, the
// rows it rests on, the value checked beyond it and why the next value run is not advised.
std::string advice_table(const Findings& f) {
  const TradeRows& t = f.all;
  std::ostringstream md;
  md << "### What the runs say about picking a setting\n\nThis study measures; it does not "
        "recommend. This project answers a user's problem with `mpmstab advise`, which runs each "
        "answer on that problem before giving it ([advice.md](advice.md)): a setting named the "
        "cheapest here is the cheapest of these runs that also passed at the paper's largest "
        "amplitude and over a longer run, and is checked nowhere else.\n\n"
     << "### Stable ranges of each policy's parameter, over every scene\n\nA description of the "
        "runs, not a recommendation (`mpmstab advise` answers a problem, and verifies the answer "
        "by runs on it; advice.md). A value v of a "
        "parameter (a fixed dt, the CFL factor C, the safety factor s) is stable with a "
     << shortest(kMargin) << "x margin for a method and policy if, at every E the study runs ("
     << listing(t.Es) << "), they were run at v and at some p >= " << shortest(kMargin)
     << " v, and every one of their runs with the parameter up to p (on every grid, in every "
        "scene) is stable: not unstable, not meaningless, and none of its steps above the "
        "scheme's spectral limit (where the run records it: a run that survives above the limit "
        "survives at this amplitude and run length only). The largest such v is shown; p is the "
        "value checked beyond it. A value with no run at "
     << shortest(kMargin)
     << " times it or beyond is not shown: its margin is not checked. These runs lie at A = "
     << listing(t.rows, "A") << " (A / h = " << listing(t.rows, "A_over_h")
     << ") and c T = " << span(f.passes, 3)
     << " wave passes, and a range is checked there only.\n\n"
     << "| method and policy | stable with margin | rests on | checked to | the next value run, "
        "not stable with margin |\n|---|---|---|---|---|\n";
  for (const auto& a : f.ranges) {
    md << "| " << a.group.name() << " | ";
    if (a.advised) {
      // "C up to 0.25 | <rows> | C = 0.5 (1.5x = 0.375)": the value advised, the rows it rests
      // on and the value checked beyond it (a range where it differs between values of E).
      const ValueCheck& v = *a.advised;
      const std::string& policy = a.group.policy;
      md << parameter_symbol(policy) << " up to " << parameter_text(policy, v.value) << " | "
         << v.rests_on << ", all stable | " << a.group.value(v.checked_lo)
         << (v.checked_hi != v.checked_lo ? " to " + parameter_text(policy, v.checked_hi) : "")
         << " (" << shortest(kMargin) << "x = " << parameter_text(policy, kMargin * v.value)
         << ") | ";
    } else {
      md << "no value | – | – | ";
    }
    md << a.group.value(a.next.value) << ": " << a.next.why_not << " |\n";
  }
  md << "\n";
  return md.str();
}

ojson advice_json(const std::vector<MarginRange>& all) {
  ojson j = ojson::array();
  for (const auto& a : all) {
    ojson g = {{"method", a.group.method},
               {"policy", a.group.policy},
               {"cfl_factor", a.group.cfl_factor ? ojson(*a.group.cfl_factor) : ojson(nullptr)},
               {"parameter", parameter_key(a.group.policy)},
               {"advised", a.advised ? ojson(a.advised->value) : ojson(nullptr)},
               {"rests_on", a.advised ? ojson(a.advised->rests_on) : ojson(nullptr)},
               {"checked_to", a.advised ? ojson(a.advised->checked_hi) : ojson(nullptr)},
               {"next_value", a.next.value},
               {"next_not_advised", a.next.why_not}};
    j.push_back(g);
  }
  return j;
}

// Per policy, the runs and how they ended; the unstable ones per failure reason.
std::string endings_table(const SceneFindings& s, const std::string& of_scene) {
  const auto& reasons = s.reasons;
  std::ostringstream md;
  md << "### How the runs ended" << of_scene
     << "\n\nPer time-step policy, the runs that were stable, meaningless (survived, but the "
        "error over time reached A) and unstable, and the unstable ones by the reason they "
        "stopped. dt_collapse: the adaptive or min policy asked for a step below "
     << sci(kDtCollapseFraction, 1) << " times the CFL step h/c.\n\n"
     << "| policy | runs | stable | meaningless | unstable |";
  for (const auto& reason : reasons)
    md << " " << reason << " |";
  md << "\n|---|---|---|---|---|";
  for (std::size_t k = 0; k < reasons.size(); ++k)
    md << "---|";
  md << "\n";
  for (const auto& p : kPolicies) {
    const VerdictTally& e = s.endings.at(p);
    md << "| " << p << " | " << e.runs << " | " << e.stable << " | " << e.meaningless << " | "
       << e.unstable << " |";
    for (const auto& reason : reasons)
      md << " " << (e.reasons.count(reason) ? e.reasons.at(reason) : 0) << " |";
    md << "\n";
  }
  md << "\n";
  return md.str();
}

ojson endings_json(const SceneFindings& s) {
  ojson j = ojson::object();
  for (const auto& [p, e] : s.endings) {
    ojson reasons = {{"dt_collapse", 0}};
    for (const auto& [reason, n] : e.reasons)
      reasons[reason] = n;
    j[p] = {{"runs", e.runs},
            {"stable", e.stable},
            {"meaningless", e.meaningless},
            {"unstable", e.unstable},
            {"failure_reasons", reasons}};
  }
  return j;
}

// How the targets are read and verified, at the amplitude of the scene's runs.
std::string cheapest_rule(const SceneFindings& s) {
  const double A = *RunRow(s.t.rows.front()).A;
  std::vector<std::string> per_A;
  for (double target : kTargets)
    per_A.push_back(significant(target / A, 3));
  std::ostringstream md;
  md << "A target is a max error over time at the amplitude of these runs, A = "
     << listing(s.t.rows, "A") << " (the targets are " << list_of(per_A)
     << " A). At each E and target the " << kVerified
     << " cheapest runs reaching it, in particle-steps, are run again as `mpmstab advise` "
        "verifies an answer: at the paper's largest amplitude, A = "
     << value_text(kPaperLargestA) << ", where a target is read as the same error over time / A ("
     << sci(kTargets.front(), 1) << " becomes " << sci(kTargets.front() * kPaperLargestA / A)
     << "), and over " << shortest(kAdviceDomain.length_factor)
     << " x c T with the same target. A setting passes when both end stable within the target. "
        "Each cell names the cheapest that passes, the cheaper ones that failed and the run "
        "each failed, and where the setting lies beyond its method and policy's stable range "
        "with a margin (the table above). Passed at these points only: the cheapest on these "
        "runs, not an answer to another problem (`mpmstab advise` verifies on the problem; "
        "advice.md).\n\n";
  return md.str();
}

// One cell: the cheapest setting that passed, or that none of those tried did, with the cheaper
// ones that failed.
std::string cheapest_cell(const SceneFindings& s, const CheapestCell& cell,
                          const std::vector<MarginRange>& ranges) {
  if (cell.reaching == 0) return "not reached";
  std::string failed;
  for (const auto& tried : cell.tried)
    if (!tried.passed)
      failed +=
          (failed.empty() ? "" : "; ") + setting(s.t.rows[tried.row]) + " (" + tried.why + ")";
  const CheapestCell::Tried* c = cell.chosen();
  if (!c) {
    return "none passed of the " + std::to_string(cell.tried.size()) + " cheapest of " +
           std::to_string(cell.reaching) + " reaching it: " + failed;
  }
  const ojson& r = s.t.rows[c->row];
  std::string text = setting(r) + ": " + sci(*stable_error_over_time(r)) + " in " + work(r) +
                     " particle-steps (" + r["steps"].dump() + " steps); verified";
  for (const VerifyingRun& v : c->runs)
    text += ", " + v.what + ": " + sci(*v.error_over_A) + " A";
  const std::string beyond = beyond_range(ranges, r);
  return text + (beyond.empty() ? "" : "; " + beyond) +
         (failed.empty() ? "" : "; cheaper, failed: " + failed);
}

// Per E and target error, the cheapest setting that reaches it and passes its verifying runs.
std::string cheapest_table(const SceneFindings& s, const std::string& of_scene,
                           const std::vector<MarginRange>& ranges) {
  std::ostringstream md;
  md << "### The cheapest setting for each accuracy, verified" << of_scene << "\n\n"
     << cheapest_rule(s) << "| E |";
  for (double target : kTargets)
    md << " max error <= " << sci(target, 1) << " |";
  md << "\n|---|";
  for (std::size_t k = 0; k < kTargets.size(); ++k)
    md << "---|";
  md << "\n";
  for (std::size_t e = 0; e < s.t.Es.size(); ++e) {
    md << "| " << shortest(s.t.Es[e]) << " |";
    for (const auto& cell : s.cheapest[e])
      md << " " << cheapest_cell(s, cell, ranges) << " |";
    md << "\n";
  }
  return md.str();
}

// What one scene's rows show: which method and policy is most often the cheapest way to a
// target accuracy; per E, how far GIMP's error moves with dt on the paper's grid (fixed and CFL
// steps) and with the grid (CFL at kCflRef, on every finer grid run); what a finer grid does;
// stepping at the eq. (108) bound against the CFL rule (the ranges of the ratios of their step
// counts and of their errors); per E, the best accuracy MPM reaches against the best GIMP
// reaches.
std::string what_the_rows_show(const SceneFindings& f) {
  std::ostringstream s;
  s << "**What the rows show** (runs at " << coverage_of(f.t.rows).text() << "). ";
  if (f.reached == 0) {
    s << "No setting reaches any of the target accuracies. ";
  } else {
    if (f.verified == 0)
      s << "No setting passes its verifying runs at any of the " << f.reached
        << " (E, target) pairs some run reaches";
    else
      s << "The cheapest setting for a target accuracy, in particle-steps, that passes its "
           "verifying runs is "
        << f.top << " in " << f.top_wins << " of the " << f.reached
        << " (E, target) pairs some run reaches";
    if (f.verified > 0 && f.reached > f.verified)
      s << "; " << f.reached - f.verified << " have none among their " << kVerified << " cheapest";
    s << " (verified on " << coverage_of(f.verifying_read).text() << "). ";
    if (f.verified > 0)
      s << "In " << f.beyond << " of the " << f.verified
        << " pairs the setting named lies beyond its method and policy's stable range with a "
           "margin. ";
  }
  for (const StepSpread& e : f.spreads) {
    s << "E = " << shortest(e.E) << ": every stable fixed or CFL step of GIMP on " << kCoarse
      << " cells gives an error between " << sci(e.lo) << " and " << sci(e.hi);
    std::string moved;
    for (const auto& [cells, error] : e.finer)
      moved += (moved.empty() ? "" : ", ") + sci(error) + " on " + std::to_string(cells) + " cells";
    if (!moved.empty())
      s << "; the grid moves it: " << moved << " (CFL, C = " << shortest(kCflRef) << ")";
    s << ". ";
  }
  const GridRefinement& g = f.refinement;
  if (g.total > 0)
    s << "A finer grid lowered GIMP's error at " << g.better << " of " << g.total
      << " values of E (" << kFine << " against " << kCoarse << " cells). ";
  const BoundAgainstCfl& b = f.bound;
  if (b.pairs > 0)
    s << "Over " << b.pairs << " (method, E) pairs of MPM and GIMP, stepping at the eq. (108) "
      << "bound (adaptive, s = " << shortest(kBoundSafety) << ") takes " << ratio(b.steps_lo)
      << " to " << ratio(b.steps_hi)
      << " times the steps of the CFL rule at C = " << shortest(kCflRef) << " for "
      << ratio(b.errors_lo) << " to " << ratio(b.errors_hi) << " times its error. ";
  // The error with its size against A and its accuracy class: the best is not always accurate.
  auto error_text = [](const ojson& r) {
    const RunRow run(r);
    const std::optional<Accuracy> a = run.accuracy();
    return sci(*run.stable_error_over_time()) +
           (a ? " (" + beside_thresholds(*run.error_over_A(), {kAccurateFraction, 1.0}) + " A, " +
                    std::string(to_string(*a)) + ")"
              : std::string());
  };
  for (const BestOfMethods& m : f.best)
    s << "E = " << shortest(m.E) << ": the best MPM error is " << error_text(*m.mpm) << ", GIMP's "
      << error_text(*m.gimp) << ". ";
  std::string text = s.str();
  while (text.back() == ' ')
    text.pop_back();
  return text;
}

// The twins beside their rows, and what the walls cost GIMP's refinement.
std::string walls_cost_section(const Findings& f) {
  const std::vector<ojson>& rows = f.all.rows;
  if (f.twins.empty()) return "";
  std::ostringstream md;
  md << "### What the walls cost\n\nEvery run of the paper's bar under the CFL rule at C = "
     << shortest(kCflRef)
     << " rerun with periodic boundaries (no wall: the interior's own error). A ratio well "
        "below one is error the Dirichlet walls' treatment adds; walls.md does the same for "
        "every Table 1 cell.\n\n";
  if (f.twins_compared > 0) {
    md << "Without walls a finer grid lowered GIMP's error at " << f.twins_lowered << " of "
       << f.twins_compared << " values of E (" << kFine << " against " << kCoarse << " cells).\n\n";
  }
  md << "| method | E | cells | Dirichlet: error over time | periodic twin | periodic / Dirichlet "
        "|\n|---|---|---|---|---|---|\n";
  for (const auto& [i, twin] : f.twins) {
    const ojson& r = rows[i];
    const auto d = stable_error_over_time(r), p = stable_error_over_time(*twin);
    md << "| " << method_label(r) << " | " << shortest(r["E"].get<double>()) << " | "
       << r["cells"].get<int>() << " | " << (d ? sci(*d) : verdict(r)) << " | "
       << (p ? sci(*p) : verdict(*twin)) << " | " << (d && p ? ratio(*p / *d) : std::string("–"))
       << " |\n";
  }
  md << "\n";
  return md.str();
}

// Every setting at one E with its steps, particle-steps, dt range, verdict and error; the
// Pareto front marked.
std::string settings_table(const SceneFindings& s, std::size_t e, const std::string& of_scene) {
  const TradeRows& t = s.t;
  const double E = t.Es[e];
  std::ostringstream md;
  md << "### E = " << shortest(E) << " (c T = " << span(s.passes[e], 3) << " wave passes)"
     << of_scene
     << "\n\n| setting | steps | particle-steps | dt range | mean dt | verdict | max error over "
        "time | Pareto |\n|---|---|---|---|---|---|---|---|\n";
  for (std::size_t i : t.at(E)) {
    const ojson& r = t.rows[i];
    md << "| " << setting(r) << " | " << r["steps"].dump() << " | " << work(r) << " | "
       << opt_sci(r["dt_min"]) << " to " << opt_sci(r["dt_max"]) << " | " << opt_sci(r["dt_mean"])
       << " | " << verdict(r) << " | " << opt_sci(RunRow(r).error_over_time) << " | "
       << (s.front.count(i) ? "**yes**" : "") << " |\n";
  }
  md << "\n";
  return md.str();
}

// One scene's section, headed by the scene; a further scene's (`first` false) tables name it.
std::string scene_markdown(const SceneRows& sc, const SceneFindings& s, bool first,
                           const std::vector<MarginRange>& ranges) {
  const std::string of_scene = first ? "" : " (" + sc.scene + ")";
  std::ostringstream md;
  md << "## " << scene_title(sc.scene) << "\n\n";
  md << cheapest_table(s, of_scene, ranges) << "\n"
     << what_the_rows_show(s) << "\n\n"
     << endings_table(s, of_scene);
  for (std::size_t e = 0; e < s.t.Es.size(); ++e)
    md << settings_table(s, e, of_scene);
  return md.str();
}

// The study's JSON: the advice from every scene's rows, per scene how the runs of each policy
// ended, and what the figure draws.
ojson tradeoff_json(const Findings& f) {
  ojson endings = ojson::object();
  for (std::size_t k = 0; k < f.scenes.size(); ++k)
    endings[f.scenes[k].scene] = endings_json(f.scene[k]);
  const FigureCount& n = f.figure;
  return {{"margin", kMargin},
          {"stable_ranges", advice_json(f.ranges)},
          {"verifying",
           {{"A", kPaperLargestA},
            {"length_factor", kAdviceDomain.length_factor},
            {"candidates", kVerified}}},
          {"endings", endings},
          {"figure",
           {{"scene", n.scene},
            {"runs", n.runs},
            {"drawn", n.drawn},
            {"unstable", n.unstable},
            {"meaningless", n.meaningless},
            {"stable_without_error", n.no_error}}}};
}

// ---------------------------------------------------------------------------------------------
// Figure: the first scene's stable runs, error against particle-steps

// "120 of 136 runs of the scene bar drawn; left out: 14 unstable, 2 meaningless". No single
// quotes: it is handed to gnuplot inside them.
std::string figure_count_text(const FigureCount& n) {
  std::string s = std::to_string(n.drawn) + " of " + std::to_string(n.runs) +
                  " runs of the scene " + n.scene +
                  " drawn; left out: " + std::to_string(n.unstable) + " unstable, " +
                  std::to_string(n.meaningless) + " meaningless";
  if (n.no_error > 0) s += ", " + std::to_string(n.no_error) + " stable without an error to draw";
  return s;
}

// The methods the figure names (tradeoff.gp's method_name), in its order; any other is drawn as
// "other" (the code after the last).
const std::vector<std::string> kFigureMethods = {"mpm",       "gimp",         "cpgimp",
                                                 "bspline2",  "bspline3",     "cpdi",
                                                 "gimp/apic", "gimp/xpic(2)", "gimp/fmpm(2)"};

int method_code(const std::string& m) {
  return static_cast<int>(std::find(kFigureMethods.begin(), kFigureMethods.end(), m) -
                          kFigureMethods.begin());
}

int policy_code(const std::string& p) {
  return static_cast<int>(std::find(kPolicies.begin(), kPolicies.end(), p) - kPolicies.begin());
}

// One row per run drawn: its panel (E), its series (method, policy, grid) and grid rank
// (0 the coarsest), its cost and its error.
std::string tradeoff_data_csv(const Findings& f, const std::string& header_lines) {
  const std::vector<ojson>& rows = f.scenes.front().rows;
  const SceneFindings& s = f.scene.front();
  std::set<int> grids;
  for (const auto& r : rows)
    grids.insert(r["cells"].get<int>());
  std::vector<std::tuple<std::string, std::string, int>> series;
  std::ostringstream csv;
  csv << header_lines << "# " << figure_count_text(f.figure) << "\n"
      << "# one row per run drawn (stable, with an error); panel: the index of E; series: the "
         "index of (method, policy, cells) in the order of the spec; method: "
      << codes(kFigureMethods) << ", " << kFigureMethods.size()
      << " another; policy: " << codes(kPolicies)
      << "; grid: the rank of cells, counting from the coarsest at zero; pareto: whether the run "
         "is on the Pareto front of its E, a boolean (no other run at that E both cheaper and "
         "more accurate)\nE,panel,series,method,policy,cells,grid,particle_steps,steps,error,"
         "pareto\n";
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const ojson& r = rows[i];
    if (!drawn(r)) continue;
    const double E = r["E"].get<double>();
    const int cells = r["cells"].get<int>();
    const std::size_t panel =
        static_cast<std::size_t>(std::find(s.t.Es.begin(), s.t.Es.end(), E) - s.t.Es.begin());
    const std::size_t k = index_in(series, {method_label(r), text(r, "policy"), cells});
    csv << shortest(E) << ',' << panel << ',' << k << ',' << method_code(method_label(r)) << ','
        << policy_code(text(r, "policy")) << ',' << cells << ','
        << std::distance(grids.begin(), grids.find(cells)) << ','
        << static_cast<long long>(particle_steps(r)) << ',' << r["steps"].dump() << ','
        << shortest(*stable_error_over_time(r)) << ',' << (s.front.count(i) ? 1 : 0) << '\n';
  }
  return csv.str();
}

// The figure's subtitle: what it draws and leaves out of the first scene.
std::string tradeoff_subtitle(const Spec& spec, const ojson& doc) {
  const std::vector<ojson> rows(doc["cases"].begin(), doc["cases"].end());
  return figure_count_text(find(rows, {}).figure) + "; every run of every scene is in " +
         spec.name + ".md";
}

// The report, from the findings: the definitions and the figure, the advice from every scene's
// rows, then one section per scene; the figure's data from the first scene (the paper's bar).
StudyReport tradeoff_report(const ReportContext& c) {
  const Findings f = find(c.rows, c.follow_up);
  StudyReport report{.claims = tradeoff_claims(f)};
  report.markdown = results_intro(c.spec) + advice_table(f) + walls_cost_section(f);
  for (std::size_t i = 0; i < f.scenes.size(); ++i)
    report.markdown += scene_markdown(f.scenes[i], f.scene[i], i == 0, f.ranges);
  report.data_csv = tradeoff_data_csv(f, c.csv_header);
  report.json = tradeoff_json(f);
  return report;
}

const StudyRegistration kTradeoff{{
    .name = "tradeoff",
    .summary = "error against cost across methods, time-step policies and their parameters",
    .records = {.error_over_time = true},
    .figure = true,
    .follow_up = tradeoff_follow_ups,
    .report = tradeoff_report,
    .index =
        [](const Spec& spec, const std::vector<ojson>&) {
          return "![" + spec.title + "](" + spec.name + ".png)\n\n**What it shows.** The cost of " +
                 "each accuracy in particle-steps across methods, time-step policies and their "
                 "parameters, the Pareto front, the cheapest setting for each target that passes "
                 "its runs at the paper's largest amplitude, A = " +
                 value_text(kPaperLargestA) + ", and over " +
                 shortest(kAdviceDomain.length_factor) +
                 " x c T, and each parameter's stable range; the recommendations are advice.md's: "
                 "[" +
                 spec.name + ".md](" + spec.name + ".md).\n\n";
        },
    .figure_subtitle = tradeoff_subtitle,
}};

}  // namespace
}  // namespace mpmstab::studies::tradeoff
