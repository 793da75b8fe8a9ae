// The speed/accuracy trade: error against cost (particle-steps, deterministic; wall times are
// performance.md's) across methods, time-step policies and their parameters. It recommends
// nothing (advice.md does). Each parameter's stable range with a margin; per scene the cheapest
// setting for each accuracy that passes its verifying runs, how the runs ended, every setting.
#include <algorithm>
#include <array>
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

// What the sentences and claims compare: the paper's grid (kCoarse) and the finest (kFine) under
// the CFL rule at kCflRef; the eq. (108) bound at safety kBoundSafety, which "buys no accuracy"
// when its error is within kNoGainFactor of the CFL rule's.
constexpr int kCoarse = 100, kFine = 400;
constexpr double kCflRef = 0.5, kBoundSafety = 1.0, kNoGainFactor = 2.0;

// ---------------------------------------------------------------------------------------------
// Follow-ups. What the walls cost: each run of the bar under the CFL rule at kCflRef is rerun with
// periodic boundaries; the twin's error is the interior's own.

// The rows whose periodic twin is run, in row order.
std::vector<std::size_t> twin_rows(const std::vector<ojson>& rows) {
  std::vector<std::size_t> idx;
  for (std::size_t i = 0; i < rows.size(); ++i)
    if (text(rows[i], "scene") == "bar" && text(rows[i], "bc") == "dirichlet" &&
        text(rows[i], "policy") == "cfl" && rows[i]["cfl_factor"].get<double>() == kCflRef)
      idx.push_back(i);
  return idx;
}

// The cheapest settings, verified as `mpmstab advise` verifies: per scene, E and target the
// kVerified cheapest runs reaching it run again at the paper's largest amplitude (the target read
// as the same error over time / A) and over length_factor x c T (kAdviceDomain).
const std::vector<double> kTargets = {1e-3, 1e-4, 1e-5};
constexpr std::size_t kVerified = 3;

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

// The follow-up runs: the periodic twins, then the verifying runs.
constexpr const char* kPeriodicTwin = "periodic twin";
std::vector<FollowUp> tradeoff_follow_ups(const FollowUpContext& c) {
  std::vector<FollowUp> runs;
  for (const std::size_t i : twin_rows(c.rows)) {
    RunParams p = c.spec.cases.at(i).params;
    p.bc = Boundary::periodic;
    runs.push_back({.of = i, .role = kPeriodicTwin, .params = p});
  }
  std::map<std::pair<std::string, Key>, std::vector<std::size_t>> groups;  // per scene and E
  for (std::size_t i = 0; i < c.rows.size(); ++i)
    groups[{text(c.rows[i], "scene"), Key(c.rows[i]["E"].get<double>(), "E")}].push_back(i);
  std::set<std::size_t> verified;
  for (const auto& [scene_E, idx] : groups)
    for (const double target : kTargets) {
      const auto r = reaching(c.rows, idx, target);
      verified.insert(r.begin(), r.begin() + std::ptrdiff_t(std::min(r.size(), kVerified)));
    }
  for (const std::size_t i : verified)
    for (auto& [role, p] : verifying_runs(c.spec.cases.at(i).params))
      runs.push_back({.of = i, .role = role, .params = p});
  return runs;
}

// ---------------------------------------------------------------------------------------------
// Findings: settings and their parameters (docs/studies.md, "Time-step policies")

const std::vector<std::string> kPolicies = {"fixed", "cfl", "adaptive", "min", "spectral"};

// The parameter a policy is advised on, its column and its symbol: the fixed dt, the CFL factor
// C or the safety factor s (the min policy: s, at its C).
std::pair<const char*, const char*> parameter_of(const std::string& policy) {
  if (policy == "fixed") return {"dt", "dt"};
  return policy == "cfl" ? std::pair{"cfl_factor", "C"} : std::pair{"safety", "s"};
}

double parameter(const ojson& r) {
  return r[parameter_of(text(r, "policy")).first].get<double>();
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

// The index of `key` in `seen`, appended when new (things in the order they first appear).
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

// The runs on the Pareto front of (particle-steps, error); runs equal in both are both on it.
std::set<std::size_t> pareto_front(const std::vector<ojson>& rows,
                                   const std::vector<std::size_t>& idx) {
  std::set<std::size_t> front;
  for (std::size_t i : idx) {
    const auto ei = stable_error_over_time(rows[i]);
    const double ci = particle_steps(rows[i]);
    if (ei && std::none_of(idx.begin(), idx.end(), [&](std::size_t j) {
          const auto ej = stable_error_over_time(rows[j]);
          const double cj = particle_steps(rows[j]);
          return j != i && ej && cj <= ci && *ej <= *ei && (cj < ci || *ej < *ei);
        }))
      front.insert(i);
  }
  return front;
}

// Rows, the values of E they hold (in the order they first appear) and look-ups into them.
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

  // The run at E of `method` under `policy` on `cells` cells at parameter `value`, or null.
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
// Stable ranges with a margin (a description; advice_table() states the rule): the largest v run
// at every E with some p >= 1.5 v, every run up to p stable and within its spectral limit.

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
    return std::string(parameter_of(policy).second) + " = " + parameter_text(policy, v);
  }
};

// The groups of a scene: by method in the order they first appear, then by policy.
std::vector<AdviceGroup> advice_groups(const std::vector<ojson>& rows) {
  std::vector<AdviceGroup> groups;
  for (const auto& m : methods_of(rows))
    for (const auto& p : kPolicies) {
      std::set<Key> Cs;  // the min policy's values of C; one group (C = 0) for another policy
      for (const auto& r : rows)
        if (method_label(r) == m && text(r, "policy") == p)
          Cs.insert(Key(p == "min" ? r["cfl_factor"].get<double>() : 0.0, "cfl_factor"));
      for (double C : Cs)
        groups.push_back({m, p, p == "min" ? std::optional(C) : std::nullopt});
    }
  return groups;
}

// The rule applied to one value v of a group's parameter.
struct ValueCheck {
  double value = 0;
  bool advised = false;
  std::string rests_on;  // the group's runs up to the checking value, where advised
  double checked_lo = 0, checked_hi = 0;  // over E, the smallest value run at or beyond 1.5 v
  std::string why_not;                    // why it is not advised
};

// Whether v is advised, and the rows it rests on or why not: first a run up to the checking value
// that is not stable or steps above its spectral limit, then a value not run at some E, then a
// margin no run checks.
ValueCheck check_value(const TradeRows& t, const AdviceGroup& g, double v) {
  // "gimp cfl C=0.7 at E = 4 (bar): \* nonpositive_F at step 258 (t = 9.0e-1)".
  const auto row_verdict = [](const ojson& r) {
    return setting(r) + " at E = " + shortest(r["E"].get<double>()) + " (" + text(r, "scene") +
           "): " + verdict(r);
  };
  ValueCheck c{.value = v};
  std::vector<std::size_t> rests_on;
  std::vector<double> checked, not_run, unchecked;  // the values checked; the values of E
  for (double E : t.Es) {
    std::vector<std::size_t> idx;  // the group's runs at E, by parameter (then row order)
    for (std::size_t i : t.at(E))
      if (g.holds(t.rows[i])) idx.push_back(i);
    std::stable_sort(idx.begin(), idx.end(), [&](std::size_t a, std::size_t b) {
      return TotalLess()(parameter(t.rows[a]), parameter(t.rows[b]));
    });
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
    if (std::none_of(idx.begin(), idx.end(),
                     [&](std::size_t i) { return parameter(t.rows[i]) == v; }))
      not_run.push_back(E);
    (p ? checked : unchecked).push_back(p.value_or(E));
  }
  if (c.why_not.empty() && !not_run.empty()) c.why_not = "not run at E = " + listing(not_run);
  if (c.why_not.empty() && !unchecked.empty()) {
    c.why_not = "no row at " + shortest(kMargin) + "x (" + g.value(kMargin * v) +
                ") at E = " + listing(unchecked) + "; margin not checked";
  }
  c.advised = c.why_not.empty();
  if (!c.advised) return c;
  // "36 rows: gimp cfl C = 0.05..0.5 at E = 4, 64 and 1000 (A = 0.015; c T = 2, 8 and 31.6;
  // 100, 200 and 400 cells; bar and steffen)": their count, values, E and coverage.
  std::set<Key> values;
  std::vector<const ojson*> read;
  std::vector<double> Es;
  for (std::size_t i : rests_on) {
    values.insert(Key(parameter(t.rows[i]), "the policy's parameter"));
    read.push_back(&t.rows[i]);
    Es.push_back(t.rows[i]["E"].get<double>());
  }
  c.rests_on = std::to_string(rests_on.size()) + " rows: " + g.name() +
               (g.cfl_factor ? ", " : " ") + g.value(*values.begin()) +
               (values.size() > 1 ? ".." + parameter_text(g.policy, *values.rbegin()) : "") +
               " at E = " + listing(Es) + " (" + coverage_of(read).text() + ")";
  c.checked_lo = *std::min_element(checked.begin(), checked.end(), TotalLess());
  c.checked_hi = *std::max_element(checked.begin(), checked.end(), TotalLess());
  return c;
}

// One group's range: the largest value advised (if any) and the next value run, not advised.
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
  std::size_t next = 0;
  for (double v : values) {
    checks.push_back(check_value(t, g, v));
    if (checks.back().advised) a.advised = checks.back(), next = checks.size();
  }
  // The largest value has no run at 1.5 times it: some value is always left not advised.
  static_assert(kMargin > 1);
  a.next = checks.at(next);
  return a;
}

// ---------------------------------------------------------------------------------------------
// Findings: what each scene's rows show

// How far GIMP's error moves at one E: with dt (stable fixed and CFL steps, paper's grid) and
// with the grid (CFL at kCflRef).
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

// GIMP on kCoarse against kFine cells, CFL at kCflRef, at every E where both are stable: at how
// many the finer grid lowered the error, and the least factor it did (below one: it rose).
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

// The eq. (108) bound (adaptive, kBoundSafety) against CFL at kCflRef on the paper's grid, MPM
// and GIMP at every E where both have an error: the ranges of their step and error ratios.
struct BoundAgainstCfl {
  std::size_t pairs = 0;
  double steps_lo = 0, steps_hi = 0, errors_lo = 0, errors_hi = 0;  // where there are pairs
  std::vector<const ojson*> read;                                   // the runs of both policies
};

BoundAgainstCfl bound_against_cfl(const TradeRows& t) {
  std::vector<double> steps, errors;
  std::vector<const ojson*> read;
  for (double E : t.Es)
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

// Where run r lies beyond its method and policy's stable range with a margin ("" within it).
std::string beyond_range(const std::vector<MarginRange>& ranges, const ojson& r) {
  for (const auto& a : ranges) {
    if (!a.group.holds(r)) continue;
    if (!a.advised) return a.group.name() + " has no stable range with margin";
    if (parameter(r) <= a.advised->value) return "";
    return "outside " + a.group.name() + "'s stable range with margin (" +
           parameter_of(a.group.policy).second + " up to " +
           parameter_text(a.group.policy, a.advised->value) + ")";
  }
  return "";
}

// One target at one E: the runs reaching it, and those tried (cheapest first) until one passed.
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

// What one scene's rows show.
struct SceneFindings {
  TradeRows t;
  std::vector<std::size_t> global;                  // each row's index among every scene's
  std::vector<std::vector<CheapestCell>> cheapest;  // per E (t.Es), per target
  // The method and policy most often the cheapest verified (first by name on a tie) and in how
  // many pairs; the pairs reached, verified, and with a setting beyond its stable range.
  std::string top;
  int top_wins = 0, reached = 0, verified = 0, beyond = 0;
  std::vector<const ojson*> verifying_read;  // every verifying run read
  std::vector<StepSpread> spreads;
  GridRefinement refinement;
  BoundAgainstCfl bound;
  std::vector<BestOfMethods> best;
  // How each policy's runs ended; the failure reasons: dt_collapse, then every other one met.
  std::map<std::string, VerdictTally> endings;
  std::vector<std::string> reasons;
  std::set<std::size_t> front;  // the runs on the Pareto front of their E
};

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
      // Read as `mpmstab advise` reads its runs, the target per the run's A.
      for (std::size_t k = 0; k < std::min(r.size(), kVerified) && !cell.chosen(); ++k) {
        CheapestCell::Tried& tried = cell.tried.emplace_back(CheapestCell::Tried{.row = r[k]});
        const double over_A = target / *RunRow(rows[r[k]]).A;
        for (const auto& [role, params] : verifying_runs({})) {
          const auto asked = follow_ups_of(follow_up, s.global[r[k]], role);
          if (!asked.empty()) s.verifying_read.push_back(asked.front());
          const VerifyingRun& v = tried.runs.emplace_back(
              asked.empty() ? VerifyingRun{.what = role, .outcome = "not run"}
                            : verifying_run_of(role, *asked.front(), over_A));
          if (!v.passes && tried.passed) tried.why = failure_words(v, over_A);
          tried.passed = tried.passed && v.passes;
        }
      }
      s.reached += !r.empty();
      if (const auto* c = cell.chosen()) {
        ++wins[method_label(rows[c->row]) + " " + text(rows[c->row], "policy")];
        ++s.verified;
        s.beyond += !beyond_range(ranges, rows[c->row]).empty();
      }
    }
    const auto front = pareto_front(rows, at);
    s.front.insert(front.begin(), front.end());
  }
  for (const auto& [name, n] : wins)
    if (n > s.top_wins) s.top = name, s.top_wins = n;
  s.spreads = step_spreads(s.t);
  s.refinement = grid_refinement(s.t);
  s.bound = bound_against_cfl(s.t);
  s.best = best_of_methods(s.t);
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

// The runs of a scene the figure draws, and how all of them ended.
struct FigureCount {
  std::string scene;
  VerdictTally ended;
  int drawn = 0;
  int no_error() const { return ended.runs - drawn - ended.unstable - ended.meaningless; }
};

// What the report, its claims and the subtitle say, found once.
struct Findings {
  TradeRows all;                     // every scene's rows
  std::vector<SceneRows> scenes;     // the paper's bar first (never copied: `scene` refers into it)
  std::vector<SceneFindings> scene;  // what each scene's rows show
  std::vector<MarginRange> ranges;   // each parameter's stable range, over every scene
  int gimp_better = 0, compared = 0;  // (scene, E) pairs where GIMP's best error is below MPM's
  double spread_max = 0;              // the bar: the largest factor the step moves GIMP's error by
  // The twins by method, E and cells; at how many E GIMP's is lower on kFine than kCoarse cells.
  std::vector<std::pair<std::size_t, const ojson*>> twins;
  int twins_lowered = 0, twins_compared = 0;
  FigureCount figure;  // of the first scene
};

// The findings from the rows and the follow-up runs (none for the subtitle).
Findings find(const std::vector<ojson>& rows, const std::vector<ojson>& follow_up) {
  Findings f{.all = TradeRows(rows), .scenes = by_scene(rows)};
  for (const auto& g : advice_groups(rows))
    f.ranges.push_back(stable_range(f.all, g));
  for (const auto& sc : f.scenes) {
    std::vector<std::size_t> global;  // the scene's rows among all (by_scene keeps their order)
    for (std::size_t i = 0; i < rows.size(); ++i)
      if (text(rows[i], "scene") == sc.scene) global.push_back(i);
    f.scene.push_back(scene_findings(sc.rows, std::move(global), follow_up, f.ranges));
    for (const auto& b : f.scene.back().best)
      f.gimp_better += *stable_error_over_time(*b.gimp) < *stable_error_over_time(*b.mpm);
    f.compared += int(f.scene.back().best.size());
  }
  for (const auto& s : f.scene.front().spreads)
    f.spread_max = std::max(f.spread_max, s.hi / s.lo);
  // The twins in the walls' table order, and GIMP's without walls against the grid.
  std::map<std::size_t, const ojson*> twins;  // each twin by the index of its row
  for (const std::size_t i : twin_rows(rows))
    for (const ojson* twin : follow_ups_of(follow_up, i, kPeriodicTwin))
      twins[i] = twin;
  std::map<Key, std::array<std::optional<double>, 2>> gimp;  // per E, on kCoarse and kFine cells
  for (const auto& [i, twin] : twins) {
    const int cells = rows[i]["cells"].get<int>();
    if (method_label(rows[i]) == "gimp" && (cells == kCoarse || cells == kFine))
      gimp[Key(rows[i]["E"].get<double>(), "E")][cells == kFine] = stable_error_over_time(*twin);
  }
  for (const auto& [E, e] : gimp) {
    f.twins_compared += e[0] && e[1];
    f.twins_lowered += e[0] && e[1] && *e[1] < *e[0];
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
  f.figure = {.scene = f.scenes.front().scene, .ended = verdict_tally(f.scenes.front().rows)};
  for (const auto& r : f.scenes.front().rows)
    f.figure.drawn += drawn(r);
  return f;
}

// ---------------------------------------------------------------------------------------------
// Claims: GIMP against MPM; on the bar, the step against the grid, a finer grid, the eq. (108)
// bound against the CFL rule; per scene, the cheapest verified setting.

// One method and policy is the cheapest verified setting at every pair some run reaches.
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
  Coverage read = coverage_of(sc.rows);  // the ranking's rows and the verifying runs read
  for (const ojson* r : s.verifying_read)
    read.add(*r);
  return c.on(read);
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
  Claim spread =
      claim("step-moves-error-less-than-grid",
            "For GIMP on the paper's bar, below the edge the time step moves the error "
            "over time less than the grid does, at every E: a smaller step costs work "
            "and buys no accuracy",
            "the step moves it by a factor of at most {spread} (every stable fixed and "
            "CFL step on {coarse} cells); going from {coarse} to {fine} cells divides it "
            "by {grid} at the least (below one: the finer grid's error is larger); "
            "{total} values of E");
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
  const auto pair_ratio = [&](double r) { return b.pairs > 0 ? ratio(r) : std::string("–"); };
  bound.value("slo", pair_ratio(b.steps_lo))
      .value("shi", pair_ratio(b.steps_hi))
      .value("elo", pair_ratio(b.errors_lo))
      .value("ehi", pair_ratio(b.errors_hi));
  bound.holds = b.pairs > 0 && b.steps_lo > 1 && b.errors_lo > 1 / kNoGainFactor;
  std::vector<Claim> claims = {gimp, spread, finer, bound};
  for (std::size_t k = 0; k < f.scenes.size(); ++k)
    claims.push_back(cheapest_claim(f.scenes[k], f.scene[k]));
  return claims;
}

// ---------------------------------------------------------------------------------------------
// Text

// The stable ranges: the rule, and per method and policy the value advised, the rows it rests
// on, the value checked beyond it and why the next value run is not advised.
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
        "by runs on it; advice.md). A value v of a parameter (a fixed dt, the CFL factor C, the "
        "safety factor s) is stable with a "
     << shortest(kMargin) << "x margin for a method and policy if, at every E the study runs ("
     << listing(t.Es) << "), they were run at v and at some p >= " << shortest(kMargin)
     << " v, and every one of their runs with the parameter up to p (on every grid, in every "
        "scene) is stable: not unstable, not meaningless, and none of its steps above the "
        "scheme's spectral limit (where the run records it: a run that survives above the limit "
        "survives at this amplitude and run length only). The largest such v is shown; p is the "
        "value checked beyond it. A value with no run at "
     << shortest(kMargin)
     << " times it or beyond is not shown: its margin is not checked. These runs lie at "
     << coverage_of(t.rows).text() << ", and a range is checked there only.\n\n"
     << "| method and policy | stable with margin | rests on | checked to | the next value run, "
        "not stable with margin |\n|---|---|---|---|---|\n";
  for (const auto& a : f.ranges) {
    md << "| " << a.group.name() << " | ";
    if (a.advised) {
      // "C up to 0.25 | <rows> | C = 0.5 (1.5x = 0.375)" (a range where it differs with E).
      const ValueCheck& v = *a.advised;
      const std::string& policy = a.group.policy;
      md << parameter_of(policy).second << " up to " << parameter_text(policy, v.value) << " | "
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

// How a target is read and verified; per E and target the cheapest setting that passes.
std::string cheapest_table(const SceneFindings& s, const std::string& of_scene,
                           const std::vector<MarginRange>& ranges) {
  const double A = *RunRow(s.t.rows.front()).A;
  std::vector<std::string> per_A;
  for (double target : kTargets)
    per_A.push_back(significant(target / A, 3));
  std::ostringstream md;
  md << "### The cheapest setting for each accuracy, verified" << of_scene
     << "\n\nA target is a max error over time at the amplitude of these runs, A = "
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
  std::string head = "| E |", line = "|---|";
  for (double target : kTargets)
    head += " max error <= " + sci(target, 1) + " |", line += "---|";
  md << head << "\n" << line << "\n";
  for (std::size_t e = 0; e < s.t.Es.size(); ++e) {
    md << "| " << shortest(s.t.Es[e]) << " |";
    // The setting that passed (or none), the cheaper ones that failed and the run each failed.
    for (const auto& cell : s.cheapest[e]) {
      std::string failed;
      for (const auto& tried : cell.tried)
        if (!tried.passed)
          failed +=
              (failed.empty() ? "" : "; ") + setting(s.t.rows[tried.row]) + " (" + tried.why + ")";
      const CheapestCell::Tried* c = cell.chosen();
      if (cell.reaching == 0 || !c) {
        md << (cell.reaching == 0
                   ? " not reached |"
                   : " none passed of the " + std::to_string(cell.tried.size()) + " cheapest of " +
                         std::to_string(cell.reaching) + " reaching it: " + failed + " |");
        continue;
      }
      const ojson& r = s.t.rows[c->row];
      md << " " << setting(r) << ": " << sci(*stable_error_over_time(r)) << " in " << work(r)
         << " particle-steps (" << r["steps"].dump() << " steps); verified";
      for (const VerifyingRun& v : c->runs)
        md << ", " << v.what << ": " << sci(*v.error_over_A) << " A";
      const std::string beyond = beyond_range(ranges, r);
      md << (beyond.empty() ? "" : "; " + beyond)
         << (failed.empty() ? "" : "; cheaper, failed: " + failed) << " |";
    }
    md << "\n";
  }
  return md.str();
}

// What one scene's rows show: the cheapest verified method and policy, GIMP's error against the
// step and the grid, the eq. (108) bound against the CFL rule, MPM's best against GIMP's.
std::string what_the_rows_show(const SceneFindings& f) {
  std::ostringstream s;
  s << "**What the rows show** (runs at " << coverage_of(f.t.rows).text() << "). ";
  if (f.reached == 0) s << "No setting reaches any of the target accuracies. ";
  if (f.reached > 0)
    s << "The cheapest setting for a target accuracy, in particle-steps, that passes its "
         "verifying runs is "
      << (f.verified > 0 ? f.top : "none") << " in " << f.top_wins << " of the " << f.reached
      << " (E, target) pairs some run reaches; at " << f.reached - f.verified
      << " of them none of the " << kVerified << " cheapest passes (verified on "
      << coverage_of(f.verifying_read).text() << "). In " << f.beyond << " of the " << f.verified
      << " pairs with one, the setting named lies beyond its method and policy's stable range "
         "with a margin. ";
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

// Every setting at one E, the Pareto front marked.
std::string settings_table(const SceneFindings& s, std::size_t e, const std::string& of_scene) {
  const TradeRows& t = s.t;
  const double E = t.Es[e];
  std::vector<const ojson*> at;
  for (std::size_t i : t.at(E))
    at.push_back(&t.rows[i]);
  std::ostringstream md;
  md << "### E = " << shortest(E) << " (c T = " << span(coverage_of(at).wave_passes, 3)
     << " wave passes)" << of_scene
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

// The study's JSON: the stable ranges, how each scene's runs ended, what the figure draws.
ojson tradeoff_json(const Findings& f) {
  ojson ranges = ojson::array(), endings = ojson::object();
  for (const auto& a : f.ranges) {
    const auto advised = [&](auto v) { return a.advised ? ojson(v(*a.advised)) : ojson(nullptr); };
    ranges.push_back(
        {{"method", a.group.method},
         {"policy", a.group.policy},
         {"cfl_factor", a.group.cfl_factor ? ojson(*a.group.cfl_factor) : ojson(nullptr)},
         {"parameter", parameter_of(a.group.policy).first},
         {"advised", advised([](const ValueCheck& v) { return v.value; })},
         {"rests_on", advised([](const ValueCheck& v) { return v.rests_on; })},
         {"checked_to", advised([](const ValueCheck& v) { return v.checked_hi; })},
         {"next_value", a.next.value},
         {"next_not_advised", a.next.why_not}});
  }
  for (std::size_t k = 0; k < f.scenes.size(); ++k)
    for (const auto& [p, e] : f.scene[k].endings) {
      ojson reasons = {{"dt_collapse", 0}};
      for (const auto& [reason, n] : e.reasons)
        reasons[reason] = n;
      endings[f.scenes[k].scene][p] = {{"runs", e.runs},
                                       {"stable", e.stable},
                                       {"meaningless", e.meaningless},
                                       {"unstable", e.unstable},
                                       {"failure_reasons", reasons}};
    }
  const FigureCount& n = f.figure;
  return {{"margin", kMargin},
          {"stable_ranges", ranges},
          {"endings", endings},
          {"figure",
           {{"scene", n.scene},
            {"runs", n.ended.runs},
            {"drawn", n.drawn},
            {"unstable", n.ended.unstable},
            {"meaningless", n.ended.meaningless},
            {"stable_without_error", n.no_error()}}}};
}

// ---------------------------------------------------------------------------------------------
// Figure: the first scene's stable runs, error against particle-steps

// "120 of 136 runs of the scene bar drawn; left out: 14 unstable, 2 meaningless". No single
// quotes: it is handed to gnuplot inside them.
std::string figure_count_text(const FigureCount& n) {
  std::string s = std::to_string(n.drawn) + " of " + std::to_string(n.ended.runs) +
                  " runs of the scene " + n.scene +
                  " drawn; left out: " + std::to_string(n.ended.unstable) + " unstable, " +
                  std::to_string(n.ended.meaningless) + " meaningless";
  if (n.no_error() > 0)
    s += ", " + std::to_string(n.no_error()) + " stable without an error to draw";
  return s;
}

// The methods the figure names (tradeoff.gp's method_name), in its order; any other is drawn as
// "other" (the code after the last).
const std::vector<std::string> kFigureMethods = {"mpm",       "gimp",         "cpgimp",
                                                 "bspline2",  "bspline3",     "cpdi",
                                                 "gimp/apic", "gimp/xpic(2)", "gimp/fmpm(2)"};

// One row per run drawn: panel (E), series, method, policy, grid, cost and error.
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
    csv << shortest(E) << ',' << panel << ',' << k << ','
        << std::ranges::find(kFigureMethods, method_label(r)) - kFigureMethods.begin() << ','
        << std::ranges::find(kPolicies, text(r, "policy")) - kPolicies.begin() << ',' << cells
        << ',' << std::distance(grids.begin(), grids.find(cells)) << ','
        << static_cast<long long>(particle_steps(r)) << ',' << r["steps"].dump() << ','
        << shortest(*stable_error_over_time(r)) << ',' << (s.front.count(i) ? 1 : 0) << '\n';
  }
  return csv.str();
}

// The report: the definitions and the figure, the stable ranges, the walls, each scene.
StudyReport tradeoff_report(const ReportContext& c) {
  const Findings f = find(c.rows, c.follow_up);
  StudyReport report{.claims = tradeoff_claims(f)};
  const Spec& spec = c.spec;
  // What accuracy and cost mean here, where the wall times are, and the figure.
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
  md << advice_table(f) << walls_cost_section(f);
  for (std::size_t i = 0; i < f.scenes.size(); ++i) {
    // One scene's section, headed by the scene; a further scene's tables name it.
    const SceneFindings& s = f.scene[i];
    const std::string of_scene = i == 0 ? "" : " (" + f.scenes[i].scene + ")";
    md << "## " << scene_title(f.scenes[i].scene) << "\n\n"
       << cheapest_table(s, of_scene, f.ranges) << "\n"
       << what_the_rows_show(s) << "\n\n"
       << endings_table(s, of_scene);
    for (std::size_t e = 0; e < s.t.Es.size(); ++e)
      md << settings_table(s, e, of_scene);
  }
  report.markdown = md.str();
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
        [](const Spec& spec, const std::vector<ojson>&, const ojson&) {
          return "![" + spec.title + "](" + spec.name + ".png)\n\n**What it shows.** The cost of " +
                 "each accuracy in particle-steps across methods, time-step policies and their "
                 "parameters, the Pareto front, each parameter's stable range and the cheapest "
                 "setting for each target that passes its runs at A = " +
                 value_text(kPaperLargestA) + " and over " + shortest(kAdviceDomain.length_factor) +
                 " x c T; the recommendations are advice.md's: [" + spec.name + ".md](" +
                 spec.name + ".md).\n\n";
        },
    // What the figure draws and leaves out of the first scene.
    .figure_subtitle =
        [](const Spec& spec, const ojson& doc) {
          const std::vector<ojson> rows(doc["cases"].begin(), doc["cases"].end());
          return figure_count_text(find(rows, {}).figure) + "; every run of every scene is in " +
                 spec.name + ".md";
        },
}};

}  // namespace
}  // namespace mpmstab::studies::tradeoff
