#include "choice/advice_verify.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <future>
#include <random>
#include <sstream>
#include <tuple>

#include "csv.hpp"
#include "report_util.hpp"
#include "run_row.hpp"

namespace mpmstab {

namespace studies::advice_verify {
namespace {

// ---------------------------------------------------------------------------------------------
// The prediction (docs/studies.md, "Advice: verified on the problem")

// The corner kinds whose runs differ from a problem's scene, boundary and layout least: the corner
// of each attribute in which it differs from the bar with walls and a uniform layout.
std::vector<CornerKind> nearest_kinds(const VerifyProblem& vp) {
  const Problem& p = vp.problem;
  std::vector<CornerKind> kinds;
  if (p.bc == "periodic") kinds.push_back(CornerKind::periodic);
  if (p.scene == "steffen") kinds.push_back(CornerKind::other_scene);
  if (vp.jitter > 0) kinds.push_back(CornerKind::jittered);
  if (kinds.empty()) kinds = {CornerKind::base, CornerKind::smallest_A, CornerKind::largest_A};
  return kinds;
}

bool bar_kind(CornerKind k) {
  return k == CornerKind::base || k == CornerKind::smallest_A || k == CornerKind::largest_A;
}

// Of the runs of `kinds` to `length`, the nearest in log A (ties: the larger amplitude).
const CornerRun* nearest(const CheckedSetting& s, const std::vector<CornerKind>& kinds,
                         double length, double A) {
  const CornerRun* best = nullptr;
  for (const auto& c : s.corners) {
    if (c.length != length || std::find(kinds.begin(), kinds.end(), c.kind) == kinds.end())
      continue;
    const double d = std::abs(std::log(c.A / A));
    if (!best || d < std::abs(std::log(best->A / A)) - 1e-12 ||
        (std::abs(d - std::abs(std::log(best->A / A))) <= 1e-12 && c.A > best->A))
      best = &c;
  }
  return best;
}

// A run in words: "periodic A/L = 0.05, c T/L = 10".
std::string run_words(const CornerRun& c) {
  return (bar_kind(c.kind) ? std::string() : std::string(corner_words(c.kind)) + " ") +
         "A/L = " + value_text(c.A) + ", c T/L = " + value_text(c.length);
}

struct Prediction {
  std::optional<double> error_over_A;
  bool matching = false;
  std::string from;
};

// a and b within a factor f of each other.
bool within(double a, double b, double f) {
  return a <= b * f * (1 + 1e-12) && b <= a * f * (1 + 1e-12);
}

// A corner run matches the problem: the same scene, boundary and layout (uniform with uniform; a
// jitter within match_jitter_factor of the problem's), an amplitude within match_A_factor of its
// A, and a run length covering its c T.
bool matches(const CornerRun& c, const VerifyProblem& vp, const AdviceDomain& d) {
  const Problem& p = vp.problem;
  const std::string scene = c.kind == CornerKind::other_scene ? "steffen" : "bar";
  const std::string bc = c.kind == CornerKind::periodic ? "periodic" : "dirichlet";
  const bool layout = vp.jitter > 0
                          ? c.jitter > 0 && within(c.jitter, vp.jitter, d.match_jitter_factor)
                          : c.jitter == 0;
  return scene == p.scene && bc == p.bc && layout && within(c.A, p.A, d.match_A_factor) &&
         c.length >= p.cT;
}

// The run of the candidate itself (a setting's method and C with its particles per cell, on
// `cells` cells, from the exact start; any setting's corner) matching the problem: the shortest
// covering c T, then the nearest in log A (ties: the larger amplitude).
const CornerRun* matching_run(const std::vector<CheckedSetting>& settings, const CheckedSetting& s,
                              int cells, const VerifyProblem& vp, const AdviceDomain& d) {
  const CornerRun* best = nullptr;
  auto key = [&](const CornerRun& c) {
    return std::tuple(c.length, std::abs(std::log(c.A / vp.problem.A)), -c.A);
  };
  for (const auto& t : settings) {
    if (t.method_text() != s.method_text() || t.courant != s.courant || t.ppc != s.ppc) continue;
    for (const auto& c : t.corners)
      if (c.cells == cells && matches(c, vp, d) && (!best || key(c) < key(*best))) best = &c;
  }
  return best;
}

// The distant prediction on the setting's own grid: the largest error of the runs of the kinds
// nearest the problem, each the nearest in amplitude, to the shorter length covering c T (else
// the longer, and beyond it grown in proportion to c T, as a phase error). None where no such run
// exists or one did not end stable.
Prediction distant_own(const CheckedSetting& s, const VerifyProblem& vp, const RegionRule& rule) {
  const Problem& p = vp.problem;
  const double shorter = rule.lengths.front(), longer = rule.lengths.back();
  const double length = p.cT <= shorter ? shorter : longer;
  const std::vector<CornerKind> kinds = nearest_kinds(vp);
  std::vector<const CornerRun*> used;
  if (bar_kind(kinds.front())) {
    if (const CornerRun* c = nearest(s, kinds, length, p.A)) used.push_back(c);
  } else {
    for (const CornerKind k : kinds)
      if (const CornerRun* c = nearest(s, {k}, length, p.A)) used.push_back(c);
  }
  Prediction out;
  if (used.empty() || (!bar_kind(kinds.front()) && used.size() < kinds.size())) {
    out.from =
        "no run of " + setting_name(s) + " is near the problem to c T/L = " + value_text(length);
    return out;
  }
  double e = 0;
  std::vector<std::string> words;
  for (const CornerRun* c : used) {
    if (c->outcome != "stable" || !c->error_over_A) {
      out.from = "its run at " + run_words(*c) + " was " + c->outcome;
      return out;
    }
    e = std::max(e, *c->error_over_A);
    words.push_back(run_words(*c));
  }
  std::ostringstream from;
  from << "the run" << (used.size() > 1 ? "s" : "") << " at " << list_of(words);
  if (p.cT > longer) {
    e *= p.cT / longer;
    from << ", grown in proportion to c T (x " << value_text(p.cT / longer) << ")";
  }
  out.error_over_A = e;
  out.from = from.str();
  return out;
}

// The distant prediction on a finer grid: the own grid's, scaled by (cells / n)^q, q (at least
// zero) the order its finer run measured against its base run.
Prediction distant(const CheckedSetting& s, int cells, const VerifyProblem& vp,
                   const RegionRule& rule) {
  Prediction own = distant_own(s, vp, rule);
  if (cells == s.cells || !own.error_over_A) return own;
  const CornerRun* base = s.corner(CornerKind::base, rule.lengths.front());
  const CornerRun* finer = s.corner(CornerKind::finer, rule.lengths.front());
  if (!base || !finer || !base->passes() || !finer->passes() || !(*base->error_over_A > 0) ||
      !(*finer->error_over_A > 0)) {
    return {std::nullopt, false,
            setting_name(s) + " has no passing run on " + std::to_string(s.cells * rule.refine) +
                " cells to scale it by"};
  }
  const double q =
      std::max(0.0, std::log(*base->error_over_A / *finer->error_over_A) / std::log(rule.refine));
  const double scale = std::pow(double(s.cells) / cells, q);
  own.error_over_A = *own.error_over_A * scale;
  own.from += ", scaled to " + std::to_string(cells) + " cells by (" + std::to_string(s.cells) +
              "/" + std::to_string(cells) + ")^" + significant(q, 2) + " (the order its run on " +
              std::to_string(s.cells * rule.refine) + " cells measured)";
  return own;
}

// A candidate's prediction: matching where a run of the candidate itself matches the problem,
// else distant, saying why.
Prediction predict(const std::vector<CheckedSetting>& settings, const CheckedSetting& s,
                   const Candidate& c, const VerifyProblem& vp, const AdviceDomain& d) {
  const bool own_runs = c.ppc == s.ppc && c.start == VelocityStart::exact;
  if (const CornerRun* m = own_runs ? matching_run(settings, s, c.cells, vp, d) : nullptr) {
    Prediction out{.matching = true, .from = "its run at " + run_words(*m)};
    if (m->outcome == "stable" && m->error_over_A)
      out.error_over_A = *m->error_over_A;
    else
      out.from += ", which ended " + m->outcome;
    return out;
  }
  Prediction out = distant(s, c.cells, vp, kRegionRule);
  const std::string why =
      c.ppc != s.ppc ? "the study's runs have " + std::to_string(s.ppc) + " ppc"
      : c.start != VelocityStart::exact
          ? "the study's runs start exactly"
          : "no run of this method and C on " + std::to_string(c.cells) +
                " cells matches the problem's scene, boundary, layout, A and c T";
  out.from = "distant (" + why + "): " + out.from;
  return out;
}

double steps_of(double cT, int cells, double courant) {
  return std::max(1.0, std::ceil(cT * cells / courant - 1e-9));
}

// A verifying run passes: it ended stable, with an error over time / A at most the target.
bool meets(const VerifyingRun& v, double target) {
  return v.outcome == "stable" && v.error_over_A && *v.error_over_A <= target;
}

VerifyingRun verifying_run(std::string what, const RunParams& params, double target,
                           const RunFn& run_fn) {
  VerifyingRun v{.what = std::move(what), .params = params};
  const auto start = std::chrono::steady_clock::now();
  const RunResult r = run_fn(params);
  v.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  v.outcome = r.outcome ? std::string(to_string(*r.outcome)) : std::string("no verdict");
  if (r.max_error_over_time) v.error_over_A = *r.max_error_over_time / params.A;
  v.particle_steps = double(r.particles) * double(r.steps);
  v.passes = meets(v, target);
  return v;
}

// A verifying run stable over fewer than kMinWavePasses wave passes: not called stable.
bool under_a_pass(const VerifyingRun& r) {
  return stable_under_a_wave_pass(r.outcome == "stable", wave_passes(r.params));
}

// A verifying run's outcome in the reports' words.
std::string outcome_words(const VerifyingRun& r) {
  return under_a_pass(r) ? under_a_wave_pass_word(wave_passes(r.params)) : r.outcome;
}

// The margins on the problem (ProblemEdges), unmeasured where a probe would take the
// particle-steps of the probes past `budget_left`.
struct OverBudget {};

ProblemEdges problem_edges(const Candidate& c, const VerifyProblem& vp, double budget_left,
                           const RunFn& run_fn, const AdviceDomain& d) {
  ProblemEdges e;
  const double target = vp.problem.target;
  RunParams params = run_params(c, vp);
  params.T *= d.length_factor;
  params.observe.error_over_time = true;
  const double C0 = params.stepping.cfl_factor;
  e.cT = wave_passes(params);
  e.A = params.A;
  const EdgeSurvey survey = [&](double C, bool) {
    const double work = double(params.ppc) * params.cells * steps_of(params.T, params.cells, C);
    if (e.particle_steps + work > budget_left) throw OverBudget{};
    params.stepping.cfl_factor = C;
    const VerifyingRun r = verifying_run("edge", params, target, run_fn);
    e.particle_steps += r.particle_steps;
    e.seconds += r.seconds;
    EdgeProbe p{.dt = C, .survived = r.outcome != "unstable" && r.outcome != "no verdict"};
    // A run too short for a verdict neither survives nor fails (the search reads its steps).
    p.steps = r.outcome == "too_short" ? 0 : kMinStepsToJudge;
    if (r.error_over_A) p.max_error = *r.error_over_A;  // per A, as the target
    for (const Outcome o :
         {Outcome::unstable, Outcome::meaningless, Outcome::stable, Outcome::too_short})
      if (r.outcome == to_string(o)) p.outcome = o;
    return p;
  };
  EdgeOptions o{.tolerance = d.edge_tolerance - 1,
                .scan_low = 1,
                .scan_high = d.edge_top / C0,
                .per_octave = static_cast<int>(std::lround(1 / std::log2(d.edge_step))),
                .accuracy_bound = target,
                .below_from = C0};
  try {
    e.search = find_edge(EdgeAxis{.unit = C0, .top = d.edge_top, .wave_passes = e.cT, .A = e.A},
                         survey, o);
  } catch (const OverBudget&) {
    e.not_measured = "not measured: its next probe would pass the budget (" +
                     sci(e.particle_steps) + " particle-steps of probes made, " + sci(budget_left) +
                     " left)";
    return e;
  }
  e.measured = true;
  e.scan_top = d.edge_top;
  return e;
}

// The refusal when no candidate is offered: too short for a verdict, or no method offered.
void refuse_without_candidates(Verified& v, const std::vector<CheckedSetting>& settings,
                               const Problem& p, const AdviceDomain& d) {
  double shortest_cT = INFINITY;
  for (const auto& s : settings)
    if (advice_selected(s, p.methods))
      shortest_cT =
          std::min(shortest_cT, double(kMinStepsToJudge) * s.courant / double(d.cells.back()));
  v.bound = std::isfinite(shortest_cT) ? "too_short" : "methods";
  v.refusal = std::isfinite(shortest_cT)
                  ? "--cT: c T/L = " + value_text(p.cT) +
                        " is too short for a verdict (fewer than " +
                        std::to_string(kMinStepsToJudge) +
                        " steps on every grid offered); the shortest that gets one is c T/L = " +
                        value_text(shortest_cT)
                  : "--methods: no setting of the methods asked for is offered";
}

// "3 tried, 12 skipped (10 predicted to fail by runs that match the problem, 2 shown unable to
// pass by the problem's own runs)".
std::string tried_words(const Verified& v) {
  const std::size_t tried = v.rejected.size() + (v.answer ? 1 : 0);
  std::ostringstream s;
  s << tried << " tried, " << v.skipped_predicted + v.skipped_own_runs << " skipped ("
    << v.skipped_predicted << " predicted to fail by runs that match the problem, "
    << v.skipped_own_runs << " shown unable to pass by the problem's own runs)";
  return s.str();
}

// "; the smallest error over time the search measured on the problem is 2.3e-3 A, by ...".
std::string smallest_words(const Verified& v) {
  if (!v.smallest) return "; no run of the problem the search made ended stable";
  return "; the smallest error over time the search measured on the problem is " +
         sci(v.smallest->error_over_A) + " A, by " + candidate_name(v.smallest->candidate);
}

// The refusal when the next candidate's verifying runs would pass the budget.
std::string budget_refusal(const Verified& v, const Candidate& c, double budget) {
  std::ostringstream s;
  s << "--budget: the next candidate, " << candidate_name(c) << ", needs "
    << sci(c.verify_particle_steps) << " particle-steps of verifying runs; with the "
    << sci(v.particle_steps) << " spent (" << tried_words(v) << ") that passes the budget of "
    << sci(budget) << " particle-steps";
  if (!v.rejected.empty()) s << smallest_words(v);
  return s.str();
}

// The refusal when every candidate was skipped or failed.
std::string target_refusal(const Verified& v, const Problem& p) {
  return "--error: no candidate meets " + value_text(p.target) + " A: of " +
         std::to_string(v.candidates) + ", " + tried_words(v) + smallest_words(v);
}

// A trial's runs counted into the search: their particle-steps and seconds, the runs of the
// problem itself (the first and the grid check; not the longer run), the smallest error measured.
void account(Verified& v, std::vector<VerifyingRun>& problem_runs, const Trial& t) {
  for (std::size_t i = 0; i < t.runs.size(); ++i) {
    v.particle_steps += t.runs[i].particle_steps;
    v.seconds += t.runs[i].seconds;
    if (i != 1) problem_runs.push_back(t.runs[i]);
  }
  const VerifyingRun& first = t.runs.front();
  if (first.outcome == "stable" && first.error_over_A &&
      (!v.smallest || *first.error_over_A < v.smallest->error_over_A))
    v.smallest = Measured{.error_over_A = *first.error_over_A, .candidate = t.candidate};
}

// ---------------------------------------------------------------------------------------------
// Output

using ojson = nlohmann::ordered_json;

std::string problem_line(const VerifyProblem& vp) {
  const Problem& p = vp.problem;
  std::ostringstream s;
  s << "mpmstab advise: A/L = " << value_text(p.A) << ", c T/L = " << value_text(p.cT)
    << ", target error over time " << value_text(p.target) << " A, " << p.scene << ", " << p.bc
    << ", " << (vp.jitter > 0 ? "jittered " + value_text(vp.jitter) : std::string("uniform"))
    << "\n";
  return s.str();
}

std::string run_line(const VerifyingRun& r, bool with_seconds) {
  std::ostringstream s;
  s << "    " << r.what << " (" << r.params.cells << " cells, c T/L = " << value_text(r.params.T)
    << "): " << outcome_words(r);
  if (r.error_over_A) s << ", error over time " << sci(*r.error_over_A) << " A";
  s << ", " << sci(r.particle_steps) << " particle-steps";
  if (with_seconds) s << ", " << significant(r.seconds, 2) << " s";
  s << ": " << (r.passes ? "passes" : "FAILS") << "\n";
  return s.str();
}

std::string prediction_words(const Candidate& c) {
  if (c.matching)
    return c.predicted_error_over_A
               ? sci(*c.predicted_error_over_A) + " A from " + c.predicted_from + " (matching)"
               : "fails: " + c.predicted_from + " (matching)";
  return c.predicted_error_over_A ? sci(*c.predicted_error_over_A) + " A, " + c.predicted_from
                                  : "none (" + c.predicted_from + ")";
}

// "C = 0.79 (1.6x the setting's C), fails at C = 0.8; monotone", "none: fails at the setting's
// C = 0.5", with the highest C that holds above a failure where not monotone.
std::string edge_words(const std::optional<double>& low, const std::optional<double>& high,
                       const std::optional<double>& above, double C0, double top) {
  std::ostringstream s;
  if (!low) {
    s << "none: "
      << (high ? "fails at the setting's C = " + significant(*high, 3) : std::string("no verdict"));
  } else {
    s << "C = " << significant(*low, 3) << " (" << ratio(*low / C0) << "x the setting's C)";
    if (high)
      s << ", fails at C = " << significant(*high, 3);
    else
      s << ", not reached up to C = " << significant(top, 3);
  }
  s << (above ? "; not monotone: holds again at up to C = " + significant(*above, 3)
              : std::string(low ? "; monotone" : ""));
  return s.str();
}

// "  particle-steps spent    9.0e4 of verifying runs and 1.2e6 of the margins' probes, of a
// budget of 2.0e9 (1.2 s of runs)": the seconds where asked for, beside, never deciding.
std::string spent_line(const Verified& v, bool with_seconds) {
  std::ostringstream s;
  s << "  particle-steps spent    " << sci(v.particle_steps) << " of verifying runs";
  if (v.edges.particle_steps > 0)
    s << " and " << sci(v.edges.particle_steps) << " of the margins' probes";
  s << ", of a budget of " << sci(v.budget);
  if (with_seconds) s << " (" << significant(v.seconds + v.edges.seconds, 2) << " s of runs)";
  s << "\n";
  return s.str();
}

// The answer's margins, as lines.
std::string margins_text(const Verified& v, const CheckedSetting& s) {
  std::ostringstream out;
  const EdgeResult& m = v.edges.search;
  if (v.edges.measured && m.too_short) {
    out << "  margins                 none: runs of c T = " << value_text(v.edges.cT) << " < "
        << shortest(kMinWavePasses) << " wave pass are too short for a verdict\n";
  } else if (v.edges.measured) {
    out << "  margins measured at     c T = " << value_text(v.edges.cT) << " (the length the "
        << "answer is verified at), A = " << value_text(v.edges.A) << "\n"
        << "  survival edge           "
        << edge_words(m.dt_edge, m.dt_fail, m.survives_above, s.courant, v.edges.scan_top)
        << " (on this problem)\n"
        << "  accuracy edge           "
        << edge_words(m.dt_accurate, m.dt_inaccurate, m.accurate_above, s.courant, v.edges.scan_top)
        << " (within the target on this problem)\n";
  } else {
    out << "  margins                 " << v.edges.not_measured << "\n";
  }
  return out.str();
}

ojson opt(const std::optional<double>& x) {
  return x ? ojson(*x) : ojson(nullptr);
}

ojson run_json(const VerifyingRun& r) {
  return {{"what", r.what},
          {"cells", r.params.cells},
          {"cT", r.params.T},
          {"outcome", r.outcome},
          {"under_a_wave_pass", under_a_pass(r)},
          {"error_over_A", opt(r.error_over_A)},
          {"particle_steps", r.particle_steps},
          {"passes", r.passes}};
}

ojson candidate_json(const Candidate& c, const VerifyProblem& vp) {
  const CheckedSetting& s = *c.from;
  return {{"method", s.method},
          {"transfer", s.transfer},
          {"update", s.update},
          {"cells", c.cells},
          {"ppc", c.ppc},
          {"courant", s.courant},
          {"start", std::string(c.start == VelocityStart::exact ? "exact" : "half_step")},
          {"predicted_error_over_A", opt(c.predicted_error_over_A)},
          {"prediction_matching", c.matching},
          {"predicted_from", c.predicted_from},
          {"particle_steps", c.particle_steps},
          {"run", run_command(c, vp)}};
}

ojson problem_json(const VerifyProblem& vp) {
  const Problem& p = vp.problem;
  return {{"A", p.A},         {"cT", p.cT}, {"error", p.target},
          {"scene", p.scene}, {"bc", p.bc}, {"jitter", vp.jitter}};
}

}  // namespace
}  // namespace studies::advice_verify

VerifyingRun verifying_run_of(std::string what, const nlohmann::ordered_json& row, double target) {
  using namespace studies::advice_verify;
  const RunRow r(row);
  VerifyingRun v{.what = std::move(what),
                 .outcome = r.outcome.empty() ? "no verdict" : r.outcome,
                 .error_over_A = r.error_over_A(),
                 .particle_steps = r.particle_steps()};
  for (const auto& [key, field] :
       {std::pair{"E", &v.params.E}, {"A", &v.params.A}, {"T", &v.params.T}})
    if (has_number(row, key)) *field = row[key].get<double>();
  v.params.cells = r.cells ? int(*r.cells) : 0;
  v.passes = meets(v, target);
  return v;
}

std::string failure_words(const VerifyingRun& r, double target) {
  using namespace studies::advice_verify;
  std::ostringstream s;
  s << r.what << ": " << outcome_words(r);
  if (r.outcome == "too_short")
    s << " (" << r.params.cells << " cells at C = " << shortest(r.params.stepping.cfl_factor)
      << " take fewer than " << kMinStepsToJudge << " steps)";
  else if (r.error_over_A)
    s << ", error over time " << sci(*r.error_over_A) << " A"
      << (r.outcome == "stable"
              ? " > the target " + value_text(std::stod(significant(target, 3))) + " A"
              : "");
  return s.str();
}

std::string outside_domain(const VerifyProblem& vp, const AdviceDomain& d) {
  const Problem& p = vp.problem;
  std::ostringstream s;
  if (p.A < d.A_min || p.A > d.A_max)
    s << "--A: A/L = " << value_text(p.A) << " is outside the domain advise answers (A/L "
      << value_text(d.A_min) << " to " << value_text(d.A_max) << ")";
  else if (p.cT > d.cT_max)
    s << "--cT: c T/L = " << value_text(p.cT) << " is longer than the domain advise answers (c T/L "
      << "to " << value_text(d.cT_max) << ")";
  else if (p.target < d.target_min || p.target > d.target_max)
    s << "--error: a target of " << value_text(p.target) << " A is outside the domain advise "
      << "answers (" << value_text(d.target_min) << " A to " << value_text(d.target_max) << " A)";
  else if (vp.jitter < 0 || vp.jitter > d.jitter_max)
    s << "--jitter: " << value_text(vp.jitter) << " is outside the domain advise answers (at most "
      << value_text(d.jitter_max) << ")";
  return s.str();
}

std::string candidate_name(const Candidate& c) {
  std::ostringstream t;
  t << c.from->method_text() << ", " << c.cells << " cells x " << c.ppc
    << " ppc, C = " << shortest(c.from->courant);
  if (c.start == VelocityStart::half_step) t << ", half-step start";
  return t.str();
}

RunParams run_params(const Candidate& c, const VerifyProblem& vp) {
  const CheckedSetting& s = *c.from;
  const Problem& p = vp.problem;
  const std::string transfer = transfer_name(s.transfer);
  RunParams r{.method = *parse_method(s.method),
              .E = kAdviceE,
              .A = p.A,
              .T = p.cT,
              .cells = c.cells,
              .ppc = c.ppc,
              .bc = *parse_boundary(p.bc),
              .scene = *parse_scene(p.scene),
              .transfer = *parse_transfer(transfer),
              .update = *parse_update_order(s.update),
              .start = c.start,
              .stepping = {.policy = TimeStepPolicy::cfl, .cfl_factor = s.courant},
              .observe = {.dt_stable = false, .crossings = false}};
  if (transfer != s.transfer) {
    const double order = std::stod(s.transfer.substr(transfer.size() + 1));
    if (r.transfer == Transfer::fmpm) r.fmpm_order = int(order);
    if (r.transfer == Transfer::xpic) r.xpic_order = int(order);
    if (r.transfer == Transfer::blend) r.flip_fraction = order;
  }
  r.layout.jitter = vp.jitter;
  return r;
}

std::string run_command(const Candidate& c, const VerifyProblem& vp) {
  const CheckedSetting& s = *c.from;
  const Problem& p = vp.problem;
  std::ostringstream out;
  out << "mpmstab run --method " << s.method << " " << transfer_options(s.transfer) << " --update "
      << s.update << " --cells " << c.cells << " --ppc " << c.ppc << " --policy cfl --cfl-factor "
      << shortest(s.courant) << " --E " << value_text(kAdviceE) << " --A " << value_text(p.A)
      << " --T " << value_text(p.cT);
  if (c.start == VelocityStart::half_step) out << " --start half_step";
  if (p.scene != "bar") out << " --scene " << p.scene;
  if (p.bc != "dirichlet") out << " --bc " << p.bc;
  if (vp.jitter > 0) out << " --jitter " << value_text(vp.jitter);
  return out.str();
}

bool predicted_to_fail(const Candidate& c, double target) {
  return c.matching && (!c.predicted_error_over_A || *c.predicted_error_over_A > target);
}

std::vector<Candidate> candidates(const std::vector<CheckedSetting>& settings,
                                  const VerifyProblem& vp, const AdviceDomain& d) {
  using namespace studies::advice_verify;
  const Problem& p = vp.problem;
  std::vector<Candidate> out;
  for (const CheckedSetting& s : settings) {
    if (!advice_selected(s, p.methods)) continue;
    for (const int cells : d.cells) {
      // A finer grid rests on the setting of the same method and C with the most cells not
      // above it; the study's own grids on themselves.
      if (cells < s.cells) continue;
      bool coarser_than_another = false;
      for (const auto& t : settings)
        if (&t != &s && t.method_text() == s.method_text() && t.courant == s.courant &&
            t.cells > s.cells && t.cells <= cells)
          coarser_than_another = true;
      if (coarser_than_another) continue;
      const double steps = steps_of(p.cT, cells, s.courant);
      if (steps < double(kMinStepsToJudge)) continue;  // too short for a verdict
      std::vector<int> ppcs{s.ppc};
      if (d.more_ppc != s.ppc) ppcs.push_back(d.more_ppc);
      for (const int ppc : ppcs) {
        for (const VelocityStart start : {VelocityStart::exact, VelocityStart::half_step}) {
          Candidate c{.from = &s, .cells = cells, .ppc = ppc, .start = start};
          Prediction pr = predict(settings, s, c, vp, d);
          c.predicted_error_over_A = pr.error_over_A;
          c.matching = pr.matching;
          c.predicted_from = std::move(pr.from);
          c.particle_steps = double(ppc) * cells * steps;
          c.verify_particle_steps =
              c.particle_steps +
              double(ppc) * cells * steps_of(d.length_factor * p.cT, cells, s.courant) +
              double(ppc) * cells * d.grid_factor *
                  steps_of(p.cT, cells * d.grid_factor, s.courant);
          out.push_back(std::move(c));
        }
      }
    }
  }
  std::stable_sort(out.begin(), out.end(), [&](const Candidate& a, const Candidate& b) {
    if (a.particle_steps != b.particle_steps) return a.particle_steps < b.particle_steps;
    const bool ma = a.matching && !predicted_to_fail(a, p.target);
    const bool mb = b.matching && !predicted_to_fail(b, p.target);
    if (ma != mb) return ma;
    const double pa = a.predicted_error_over_A.value_or(INFINITY);
    const double pb = b.predicted_error_over_A.value_or(INFINITY);
    if (pa != pb) return pa < pb;
    return a.start == VelocityStart::exact && b.start != VelocityStart::exact;
  });
  return out;
}

std::vector<std::pair<std::string, RunParams>> verifying_params(const Candidate& c,
                                                                const VerifyProblem& vp,
                                                                const AdviceDomain& d) {
  const RunParams base = run_params(c, vp);
  RunParams longer = base;
  longer.T = base.T * d.length_factor;
  RunParams finer = base;
  finer.cells = base.cells * d.grid_factor;
  return {{"the problem", base},
          {shortest(d.length_factor) + " x c T", longer},
          {std::to_string(d.grid_factor) + " x the cells", finer}};
}

Trial verify(const Candidate& c, const VerifyProblem& vp, const RunFn& run_fn,
             const AdviceDomain& d) {
  using namespace studies::advice_verify;
  const double target = vp.problem.target;
  Trial t{.candidate = c};
  const auto runs = verifying_params(c, vp, d);
  t.runs.push_back(verifying_run(runs[0].first, runs[0].second, target, run_fn));
  if (!t.runs.back().passes) {
    t.why = failure_words(t.runs.back(), target);
    return t;
  }
  // The two others are independent: side by side, each its own run (no sum is shared).
  auto later = std::async(std::launch::async, [&] {
    return verifying_run(runs[1].first, runs[1].second, target, run_fn);
  });
  VerifyingRun grid = verifying_run(runs[2].first, runs[2].second, target, run_fn);
  t.runs.push_back(later.get());
  t.runs.push_back(std::move(grid));
  const auto failed =
      std::find_if(t.runs.begin(), t.runs.end(), [](const VerifyingRun& r) { return !r.passes; });
  t.passed = failed == t.runs.end();
  if (!t.passed) t.why = failure_words(*failed, target);
  return t;
}

std::string shown_unable(const Candidate& c, const VerifyProblem& vp,
                         const std::vector<VerifyingRun>& problem_runs) {
  const RunParams q = run_params(c, vp);
  const double target = vp.problem.target;
  for (const VerifyingRun& r : problem_runs) {
    const RunParams& o = r.params;
    if (o.method != q.method || o.transfer != q.transfer || o.fmpm_order != q.fmpm_order ||
        o.xpic_order != q.xpic_order || o.flip_fraction != q.flip_fraction ||
        o.update != q.update || o.ppc != q.ppc || o.start != q.start || o.T != q.T)
      continue;
    const double C = o.stepping.cfl_factor;
    const std::string at =
        "its run on " + std::to_string(o.cells) + " cells at C = " + shortest(C) + " ";
    if (r.outcome == "unstable") {
      if (q.cells == o.cells && q.stepping.cfl_factor >= C) return at + "was unstable";
    } else if (r.error_over_A && *r.error_over_A > target && q.cells <= o.cells &&
               q.stepping.cfl_factor >= C) {
      return at + "measured an error over time of " + sci(*r.error_over_A) + " A";
    }
  }
  return "";
}

Verified verified_advice(const std::vector<CheckedSetting>& settings, const VerifyProblem& vp,
                         double budget_particle_steps, bool edges, const RunFn& run_fn,
                         const AdviceDomain& d) {
  using namespace studies::advice_verify;
  const Problem& p = vp.problem;
  Verified v;
  v.budget = budget_particle_steps;
  const std::vector<Candidate> list = candidates(settings, vp, d);
  v.candidates = list.size();
  if (list.empty()) {
    refuse_without_candidates(v, settings, p, d);
    return v;
  }
  std::vector<VerifyingRun> problem_runs;  // of the candidates tried: the problem, the grid check
  for (const Candidate& c : list) {
    if (predicted_to_fail(c, p.target)) {
      ++v.skipped_predicted;
      continue;
    }
    if (!shown_unable(c, vp, problem_runs).empty()) {
      ++v.skipped_own_runs;
      continue;
    }
    // Decided on particle-steps alone, counted from the candidate's parameters before it runs.
    if (v.particle_steps + c.verify_particle_steps > budget_particle_steps) {
      v.bound = "budget";
      v.refusal = budget_refusal(v, c, budget_particle_steps);
      return v;
    }
    Trial t = verify(c, vp, run_fn, d);
    account(v, problem_runs, t);
    if (t.passed) {
      v.answer = std::move(t);
      break;
    }
    v.rejected.push_back(std::move(t));
  }
  if (!v.answer) {
    v.bound = "target";
    v.refusal = target_refusal(v, p);
    return v;
  }
  if (edges)
    v.edges =
        problem_edges(v.answer->candidate, vp, budget_particle_steps - v.particle_steps, run_fn, d);
  else
    v.edges.not_measured = "not measured (--no-margins)";
  return v;
}

const Candidate* predicted_cheapest(const std::vector<Candidate>& list, double target) {
  const Candidate* distant = nullptr;
  for (const Candidate& c : list) {
    if (!c.predicted_error_over_A || *c.predicted_error_over_A > target) continue;
    if (c.matching) return &c;
    if (!distant) distant = &c;
  }
  return distant;
}

std::vector<VerifyProblem> draw_problems(const SampleRule& rule, const AdviceDomain& d) {
  std::mt19937_64 gen(rule.seed);
  auto u = [&] { return double(gen() >> 11) * 0x1.0p-53; };
  auto rounded = [](double x, double low, double high) {
    return std::clamp(std::stod(significant(x, 2)), low, high);
  };
  auto log_uniform = [&](double low, double high) {
    return rounded(std::exp(std::log(low) + u() * (std::log(high) - std::log(low))), low, high);
  };
  std::vector<VerifyProblem> out;
  for (int i = 0; i < rule.problems; ++i) {
    VerifyProblem vp;
    Problem& p = vp.problem;
    p.A = log_uniform(d.A_min, d.A_max);
    p.cT = log_uniform(rule.cT_low, d.cT_max);
    p.target = log_uniform(d.target_min, d.target_max);
    p.scene = u() < 0.5 ? "bar" : "steffen";
    p.bc = u() < 0.5 ? "dirichlet" : "periodic";
    const bool jittered = u() >= 0.5;
    const double j = u();
    if (jittered)
      vp.jitter = rounded(rule.jitter_low + j * (d.jitter_max - rule.jitter_low), rule.jitter_low,
                          d.jitter_max);
    out.push_back(std::move(vp));
  }
  return out;
}

std::string verified_text(const Verified& v, const VerifyProblem& vp, bool with_seconds) {
  using namespace studies::advice_verify;
  std::ostringstream out;
  out << problem_line(vp) << "  candidates              " << v.candidates
      << ", cheapest first in particle-steps of the run of the problem; a candidate is skipped "
         "only where a matching run predicts it fails or the problem's own runs show it cannot "
         "pass\n";
  for (const Trial& t : v.rejected) {
    out << "  rejected " << candidate_name(t.candidate) << ": " << t.why << "\n";
    for (const auto& r : t.runs)
      out << run_line(r, with_seconds);
  }
  if (!v.answer) {
    out << "  search                  " << tried_words(v) << "\n"
        << spent_line(v, with_seconds) << "  refused (" << v.bound << "): " << v.refusal << "\n";
    return out.str();
  }
  const Candidate& c = v.answer->candidate;
  const CheckedSetting& s = *c.from;
  out << "  setting                 " << candidate_name(c) << ", verified on this problem\n"
      << "  verifying runs          each reaching T with an error over time at most "
      << value_text(vp.problem.target) << " A (stable where it covers at least "
      << shortest(kMinWavePasses) << " wave pass)\n";
  for (const auto& r : v.answer->runs)
    out << run_line(r, with_seconds);
  out << "  passed                  the answer alone (the search stops at the first candidate "
         "that passes: the cheapest that passes among those not skipped)\n"
      << "  search                  " << tried_words(v) << "\n"
      << "  predicted error / A     " << prediction_words(c) << "\n"
      << "  particle-steps          " << sci(c.particle_steps) << " (the run of the problem)\n"
      << spent_line(v, with_seconds) << margins_text(v, s) << "  small-amplitude limit   "
      << (s.courant_spectral ? "C = " + significant(*s.courant_spectral, 3) + " (" +
                                   ratio(*s.courant_spectral / s.courant) +
                                   "x; the Bloch limit of the uniform layout at rest)"
                             : std::string("not measured"))
      << "\n  run it with             " << run_command(c, vp) << "\n";
  return out.str();
}

nlohmann::ordered_json verified_json(const Verified& v, const VerifyProblem& vp) {
  using namespace studies::advice_verify;
  ojson rejected = ojson::array();
  for (const Trial& t : v.rejected) {
    ojson runs = ojson::array();
    for (const auto& r : t.runs)
      runs.push_back(run_json(r));
    rejected.push_back(
        {{"candidate", candidate_json(t.candidate, vp)}, {"why", t.why}, {"runs", runs}});
  }
  ojson smallest = nullptr;
  if (v.smallest)
    smallest = {{"error_over_A", v.smallest->error_over_A},
                {"candidate", candidate_json(v.smallest->candidate, vp)}};
  ojson out = {{"problem", problem_json(vp)},
               {"verified", true},
               {"candidates", v.candidates},
               {"tried", v.rejected.size() + (v.answer ? 1 : 0)},
               {"skipped_predicted_to_fail", v.skipped_predicted},
               {"skipped_by_own_runs", v.skipped_own_runs},
               {"rejected", rejected},
               {"smallest_measured", smallest},
               {"budget_particle_steps", v.budget},
               {"particle_steps", v.particle_steps},
               {"margins_particle_steps", v.edges.particle_steps}};
  if (!v.answer) {
    out["refused"] = v.refusal;
    out["bound"] = v.bound;
    return out;
  }
  ojson runs = ojson::array();
  for (const auto& r : v.answer->runs)
    runs.push_back(run_json(r));
  out["answer"] = candidate_json(v.answer->candidate, vp);
  out["verifying_runs"] = runs;
  out["passed"] = ojson::array({out["answer"]});
  const auto& s = *v.answer->candidate.from;
  const EdgeResult& m = v.edges.search;
  out["margins"] = {{"measured", v.edges.measured},
                    {"cT", v.edges.cT},
                    {"A", v.edges.A},
                    {"too_short", m.too_short},
                    {"survival_courant", opt(m.dt_edge)},
                    {"survival_fails_at", opt(m.dt_fail)},
                    {"survival_monotone", m.monotone()},
                    {"survives_above", opt(m.survives_above)},
                    {"accuracy_courant", opt(m.dt_accurate)},
                    {"accuracy_fails_at", opt(m.dt_inaccurate)},
                    {"accuracy_monotone", m.accuracy_monotone()},
                    {"accurate_above", opt(m.accurate_above)},
                    {"scan_top", v.edges.measured ? ojson(v.edges.scan_top) : ojson(nullptr)},
                    {"small_amplitude_limit", opt(s.courant_spectral)}};
  return out;
}

std::string unverified_text(const Candidate& c, const VerifyProblem& vp) {
  using namespace studies::advice_verify;
  std::ostringstream out;
  out << problem_line(vp) << "  UNVERIFIED (--no-verify): no run of this problem was made; the "
      << "setting is the cheapest whose prediction meets the target\n"
      << "  setting                 " << candidate_name(c) << "\n"
      << "  predicted error / A     " << prediction_words(c) << "\n"
      << "  particle-steps          " << sci(c.particle_steps) << "\n"
      << "  run it with             " << run_command(c, vp) << "\n";
  return out.str();
}

nlohmann::ordered_json unverified_json(const Candidate& c, const VerifyProblem& vp) {
  using namespace studies::advice_verify;
  return {{"problem", problem_json(vp)}, {"verified", false}, {"answer", candidate_json(c, vp)}};
}

}  // namespace mpmstab
