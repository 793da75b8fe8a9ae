// The paper's Figs. 1-3 against our runs of them: what the paper's text states about each figure
// (reference/paper/figures.csv) beside the same observables of our figure experiments, each with
// a verdict; the figure's class by the rules of the Table 1 cells; and the runs of its case under
// each documented implementation choice, with which of them reproduce the paper's observable.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <set>
#include <sstream>
#include <stdexcept>

#include "agreement/comparison.hpp"
#include "base/params.hpp"
#include "csv.hpp"
#include "key.hpp"
#include "report_util.hpp"
#include "run_row.hpp"

namespace mpmstab {

namespace studies::comparison_figures {
namespace {

using ojson = nlohmann::ordered_json;
namespace fs = std::filesystem;

// The quantities a transcription may state, in the order a figure's table shows them.
const std::vector<std::string> kQuantities = {
    "outcome",         // survived (reached T) or unstable
    "steps",           // steps taken: to T, or to the failure
    "peak_error",      // the largest max error in u over the run
    "dt_stable_min",   // the minimum of the eq. (108) bound over the run
    "bound_min_step",  // the step at which the eq. (108) bound is smallest
    "crossings",       // grid crossings over the run
    // "more than figN" / "fewer than figN": the paper's "more grid-crossing errors" than another
    // figure's run; compared at equal times (equal_times()), its crossings and its error per
    // crossing.
    "crossing_errors",
};

// The parameters that tell a variant run from the figure's own run (the first case of its spec).
const std::vector<std::string> kChoiceParams = {
    "method",     "bc",         "walls",  "position_update", "transfer",        "flip_fraction",
    "xpic_order", "fmpm_order", "update", "body_force_time", "dt_stable_sigma", "dt_stable_vnorm"};

// ---- Our runs.

const ojson* array_at(const ojson& o, const char* key) {
  return o.is_object() && o.contains(key) && o.at(key).is_array() ? &o.at(key) : nullptr;
}

// The first case of an experiment's results, or null when it has not been run.
const ojson* first_row(const StudyInputs& inputs, const std::string& name) {
  const auto it = inputs.find(name);
  if (it == inputs.end() || !it->second.present()) return nullptr;
  const ojson* cases = array_at(it->second.doc, "cases");
  return cases && !cases->empty() ? &cases->at(0) : nullptr;
}

// A figure experiment's per-step history, wherever its results hold it: beside the cases, in
// the study's object, or in the case itself. Null when it was not recorded.
const ojson* history_of(const ojson& doc) {
  if (const ojson* h = array_at(doc, "history")) return h;
  if (doc.contains("study"))
    if (const ojson* h = array_at(doc.at("study"), "history")) return h;
  const ojson* cases = array_at(doc, "cases");
  return cases && !cases->empty() ? array_at(cases->at(0), "history") : nullptr;
}

std::optional<double> number(const ojson& row, const char* key) {
  if (!row.contains(key) || !row.at(key).is_number()) return std::nullopt;
  return row.at(key).get<double>();
}

// What the history shows: the error's peak, and the eq. (108) bound's minimum and median over
// the recorded steps.
struct Trace {
  std::optional<double> peak_error, bound_min, bound_median;
  std::int64_t peak_step = 0, bound_min_step = 0, last_step = 0;
};

Trace trace_of(const ojson* history) {
  Trace t;
  if (!history) return t;
  std::vector<double> bounds;
  for (const auto& h : *history) {
    const std::int64_t step = t.last_step = h.at("step").get<std::int64_t>();
    if (const auto e = number(h, "error"); e && (!t.peak_error || *e > *t.peak_error)) {
      t.peak_error = e;
      t.peak_step = step;
    }
    const auto b = number(h, "dt_stable");
    if (!b) continue;
    bounds.push_back(*b);
    if (!t.bound_min || *b < *t.bound_min) {
      t.bound_min = b;
      t.bound_min_step = step;
    }
  }
  if (!bounds.empty()) t.bound_median = quantile(bounds, 0.5);
  return t;
}

// Our run of a figure.
struct OurRun {
  const ojson* row = nullptr;
  Trace trace;  // empty without a history
};

std::string figure_title(const std::string& name) {
  return name.rfind("fig", 0) == 0 ? "Fig. " + name.substr(3) : name;
}

std::string case_text(const std::string& method, double E, double A, double dt) {
  return method + ", E = " + shortest(E) + ", A = " + shortest(A) + ", dt = " + param(dt);
}

// A count as the paper gives it: "100000", not "1e+05".
std::string count_text(double v) {
  return v == std::round(v) && std::abs(v) < 1e15 ? std::to_string(std::llround(v)) : shortest(v);
}

// ---- One observable: the paper's value, ours, and the verdict.

struct Line {
  std::string label, paper, ours, verdict;
};

const std::string kNotStated = "not stated";
const std::string kNoValue = "–";

std::string factor_verdict(double ours, double paper) {
  return within_agreement_factor(ours, paper) ? "agree"
                                              : "differ: ours " + ratio(ours / paper) + "x";
}

std::optional<double> paper_number(const PaperObservable* p) {
  if (!p || !p->stated()) return std::nullopt;
  const PaperValue v = paper_value(p->value);
  return v.kind == PaperValue::number ? std::optional<double>(v.value) : std::nullopt;
}

std::string paper_text(const PaperObservable* p) {
  if (!p || !p->stated()) return kNotStated;
  if (const auto v = paper_number(p)) {
    return p->quantity == "steps" || p->quantity == "bound_min_step" || p->quantity == "crossings"
               ? count_text(*v)
               : sci(*v);
  }
  return p->value;
}

// A numeric observable: the paper's number (if stated) against ours (if recorded).
Line numeric_line(const std::string& label, const PaperObservable* p, std::optional<double> ours,
                  const std::string& ours_text) {
  Line l{label, paper_text(p), ours_text, kNoValue};
  if (const auto pv = paper_number(p); pv && ours) l.verdict = factor_verdict(*ours, *pv);
  return l;
}

Line outcome_line(const PaperObservable* p, const ojson& row) {
  Line l{"run", kNotStated, verdict(row), kNoValue};
  if (!p || !p->stated()) return l;
  const std::string ours = outcome(row);
  if (p->value == "survived") {
    l.paper = "reaches T";
    l.verdict = ours == "stable"        ? "agree"
                : ours == "meaningless" ? "differ: ours meaningless"
                                        : "differ: ours fails";
  } else {
    l.paper = "fails";
    l.verdict = ours == "unstable" ? "agree" : "differ: ours reaches T";
  }
  return l;
}

// Our steps, of the steps to T.
Line steps_line(const PaperObservable* p, const ojson& row) {
  const std::int64_t steps = row.at("steps").get<std::int64_t>();
  std::string ours = std::to_string(steps);
  const auto T = number(row, "T"), dt = number(row, "dt");
  if (const auto planned = T && dt ? step_count(*T, *dt) : std::nullopt)
    ours += " of " + std::to_string(*planned);
  return numeric_line("steps", p, double(steps), ours);
}

Line peak_error_line(const PaperObservable* p, const OurRun& run) {
  const RunRow rr(*run.row);
  const auto e = rr.error_over_time;
  std::string ours = e ? sci(*e) : "not recorded";
  if (const auto over_A = rr.error_over_A(); e && over_A) ours += " = " + ratio(*over_A) + " A";
  if (e && run.trace.peak_error) ours += " (step " + std::to_string(run.trace.peak_step) + ")";
  return numeric_line("peak error over time", p, e, ours);
}

Line bound_min_line(const PaperObservable* p, const OurRun& run) {
  const auto b = number(*run.row, "dt_stable_min");
  std::string ours = b ? sci(*b) : "not recorded";
  if (b && run.trace.bound_min) ours += " (step " + std::to_string(run.trace.bound_min_step) + ")";
  return numeric_line("eq. (108) bound, minimum", p, b, ours);
}

// Where the bound is smallest: the paper's Fig. 3 has it shrink at the failure (its step where
// the paper's run fails). Where the paper says so, ours agrees when it is smallest at the last
// step its history records before our failure; otherwise the steps are compared by the factor.
Line bound_min_step_line(const PaperObservable* p, const PaperObservable* paper_steps,
                         const OurRun& run) {
  const Trace& t = run.trace;
  const ojson& row = *run.row;
  const auto pv = paper_number(p);
  const bool at_failure = pv && paper_number(paper_steps) == pv && outcome(row) == "unstable";
  Line l{"eq. (108) bound, smallest at", paper_text(p), "history not recorded", kNoValue};
  if (pv) l.paper = "step " + l.paper + (at_failure ? ", the paper's failure" : "");
  if (!t.bound_min) return l;
  const bool last = t.bound_min_step == t.last_step;
  l.ours = "step " + std::to_string(t.bound_min_step) + " (" +
           (outcome(row) == "unstable" ? "failure at step " + row.at("failure_step").dump()
                                       : "end at step " + row.at("steps").dump()) +
           (last ? "; the last step recorded" : "") + "); " +
           ratio(*t.bound_min / *t.bound_median) + " x its median over the run";
  if (at_failure) {
    l.verdict = last ? "agree: both at the failure"
                     : "differ: ours " + std::to_string(t.last_step - t.bound_min_step) +
                           " steps before the last recorded";
  } else if (pv) {
    l.verdict = factor_verdict(double(t.bound_min_step), *pv);
  }
  return l;
}

// The time a run ends: T when it reached it, the failure's time otherwise.
std::optional<double> end_time(const ojson& row) {
  if (outcome(row) == "unstable") return number(row, "failure_time");
  return number(row, "T");
}

Line crossings_line(const PaperObservable* p, const OurRun& run) {
  const auto c = number(*run.row, "crossings");
  std::string ours = c ? shortest(*c) : "not recorded";
  if (const auto t = end_time(*run.row); c && t) ours += " by t = " + sci(*t) + " (the run's end)";
  return numeric_line("grid crossings", p, c, ours);
}

// ---- Two figures at equal times: the paper's "more grid-crossing errors" than another figure.

// The paper's comparison of a figure with another ("more than fig2"): the direction and the
// other figure's name.
struct Against {
  std::string direction, other;  // "more" or "fewer"; "fig2"
};

std::optional<Against> against(const PaperObservable* p) {
  if (!p || !p->stated()) return std::nullopt;
  std::istringstream words(p->value);
  Against a;
  std::string than;
  words >> a.direction >> than >> a.other;
  if (a.other.empty()) return std::nullopt;
  return a;
}

// One time both runs of two figures record in their histories: the cumulative grid crossings
// and the error in u of each by then.
struct EqualTime {
  double t = 0;
  double crossings = 0, other_crossings = 0;
  double error = 0, other_error = 0;
};

// The times (t > 0) at which both histories hold a step with crossings and an error, matched to
// a relative 1e-9, in increasing t. Empty when either history is missing.
std::vector<EqualTime> equal_times(const ojson* history, const ojson* other_history) {
  std::vector<EqualTime> out;
  if (!history || !other_history) return out;
  for (const auto& h : *history) {
    const auto t = number(h, "time"), c = number(h, "crossings"), e = number(h, "error");
    if (!t || !c || !e || !(*t > 0)) continue;
    for (const auto& o : *other_history) {
      const auto ot = number(o, "time"), oc = number(o, "crossings"), oe = number(o, "error");
      if (!ot || !oc || !oe || std::abs(*ot - *t) > 1e-9 * std::max(*t, *ot)) continue;
      out.push_back({*t, *c, *oc, *e, *oe});
      break;
    }
  }
  std::sort(out.begin(), out.end(),
            [](const EqualTime& a, const EqualTime& b) { return a.t < b.t; });
  return out;
}

// One quantity of our run against the other figure's run at the times both record: how many
// times it is more than the agreement factor above the other's, within it, and below it.
struct EqualTimeCount {
  int more = 0, within = 0, fewer = 0;
  std::vector<double> ratios, times;  // ours / the other's, per time counted
  int total() const { return more + within + fewer; }
  void add(double t, double mine, double theirs) {
    if (!(theirs > 0) || !(mine >= 0)) return;
    times.push_back(t);
    ratios.push_back(mine / theirs);
    if (within_agreement_factor(mine, theirs)) {
      ++within;
    } else if (mine > theirs) {
      ++more;
    } else {
      ++fewer;
    }
  }
  // The count the paper's direction asks for.
  int in_direction(const std::string& direction) const {
    return direction == "fewer" ? fewer : more;
  }
};

// The two runs at the times both record, the largest error in u / A of each there, and how much
// of the paper's run of the figure (to `paper_end`: its steps times its dt) those times span.
// The paper's text is about its runs: the times test it only when they span at least
// 1 / kAgreementFactor of the paper's run (as the steps of a figure agree within the factor);
// otherwise no time is counted.
struct EqualTimeComparison {
  std::vector<EqualTime> times;
  EqualTimeCount crossings, error_per_crossing;
  double paper_end = 0, error_over_A = 0, other_error_over_A = 0;
  double share() const { return times.empty() ? 0 : times.back().t / paper_end; }
  bool tests() const { return share() * kAgreementFactor >= 1; }
};

EqualTimeComparison compare_at_equal_times(const ojson* history, const ojson* other,
                                           double paper_end, double A, double other_A) {
  EqualTimeComparison c{.times = equal_times(history, other), .paper_end = paper_end};
  for (const auto& e : c.times) {
    c.crossings.add(e.t, e.crossings, e.other_crossings);
    if (e.crossings > 0 && e.other_crossings > 0)
      c.error_per_crossing.add(e.t, e.error / e.crossings, e.other_error / e.other_crossings);
    c.error_over_A = std::max(c.error_over_A, e.error / A);
    c.other_error_over_A = std::max(c.other_error_over_A, e.other_error / other_A);
  }
  return c;
}

// "more at 0 of 6 times (6 within a factor 3, 0 fewer; t = 2.0e-4 to 1.2e-3; ours / Fig. 2's
// 1 to 1)"
std::string equal_time_text(const EqualTimeCount& n, const std::string& direction) {
  if (n.total() == 0) return "no time both runs record";
  const auto [lo, hi] = std::minmax_element(n.ratios.begin(), n.ratios.end(), TotalLess());
  std::ostringstream s;
  s << direction << " at " << n.in_direction(direction) << " of " << n.total() << " times ("
    << n.within << " within a factor " << agreement_factor() << ", "
    << (direction == "fewer" ? n.more : n.fewer) << (direction == "fewer" ? " more" : " fewer")
    << "; t = " << sci(n.times.front()) << " to " << sci(n.times.back()) << "; ours / theirs "
    << ratio(*lo) << " to " << ratio(*hi) << ")";
  return s.str();
}

// The verdict of a count: the paper's direction at each time both record, at none, or at some;
// not tested when those times span too little of the paper's run.
std::string count_verdict(const EqualTimeComparison& c, const EqualTimeCount& n,
                          const std::string& direction) {
  if (n.total() == 0) return kNoValue;
  if (!c.tests()) return "not tested: " + ratio(100 * c.share()) + "% of the paper's run";
  const int k = n.in_direction(direction);
  if (k == n.total()) return "agree";
  const std::string at =
      direction + " at " + std::to_string(k) + " of " + std::to_string(n.total()) + " times";
  return (k == 0 ? "differ: " : "partly: ") + at;
}

std::vector<Line> equal_time_lines(const Against& a, const EqualTimeComparison& c) {
  const std::string paper = a.direction + " grid-crossing errors than " + figure_title(a.other);
  const std::string other = figure_title(a.other);
  return {
      {"grid crossings by equal times, against " + other, paper,
       equal_time_text(c.crossings, a.direction), count_verdict(c, c.crossings, a.direction)},
      {"error in u per grid crossing by equal times, against " + other, paper,
       equal_time_text(c.error_per_crossing, a.direction),
       count_verdict(c, c.error_per_crossing, a.direction)},
  };
}

// The claims of one comparison between two figures: at each time both record, our run's
// crossings, and its error per crossing, more (or fewer) than the other run's by more than the
// agreement factor, as the paper's text has it; counted only where the times test it.
std::vector<Claim> equal_time_claims(const PaperFigure& f, const Against& a,
                                     const EqualTimeComparison& c, const Coverage& runs) {
  std::vector<Claim> out;
  const std::string relation = a.direction + " than " + agreement_factor() + " times";
  auto one = [&](const std::string& id, const std::string& statement, const EqualTimeCount& n) {
    Claim k = claim(f.name + "-" + id + "-vs-" + a.other, statement,
                    "{n} of {times} times counted; both runs record {all} times, {span}, where "
                    "the error in u of ours reaches {error} A and that of the other run "
                    "{other_error} A; ours / the other run's there {lo} to {hi}");
    k.value("fig", figure_title(f.name)).value("other", figure_title(a.other));
    k.value("relation", relation)
        .value("share", ratio(100 / kAgreementFactor) + "%")
        .value("paper", a.direction + " grid-crossing errors than " + figure_title(a.other));
    k.every("n", c.tests() ? n.in_direction(a.direction) : 0, "times", c.tests() ? n.total() : 0);
    k.count("all", n.total());
    const bool any = n.total() > 0;
    const auto [lo, hi] = std::minmax_element(n.ratios.begin(), n.ratios.end(), TotalLess());
    k.value("span", any ? "t = " + sci(c.times.front().t) + " to " + sci(c.times.back().t) + ", " +
                              ratio(100 * c.share()) +
                              "% of the paper's run (to t = " + sci(c.paper_end) + ")"
                        : kNoValue)
        .value("error", ratio(c.error_over_A))
        .value("other_error", ratio(c.other_error_over_A))
        .value("lo", any ? ratio(*lo) : kNoValue)
        .value("hi", any ? ratio(*hi) : kNoValue);
    out.push_back(k.on(runs));
  };
  one("crossings",
      "At each time both runs record, over at least {share} of the paper's run of {fig}, our run "
      "of {fig} has crossed cell boundaries {relation} as often as our run of {other} (the "
      "paper's text: {paper})",
      c.crossings);
  one("error-per-crossing",
      "At each time both runs record, over at least {share} of the paper's run of {fig}, our run "
      "of {fig} has an error in u per grid crossing {relation} that of our run of {other} (the "
      "paper's text: {paper})",
      c.error_per_crossing);
  return out;
}

// The times both runs record, in a table: crossings and errors of each, and the ratios.
void equal_time_table(std::ostream& md, const PaperFigure& f, const Against& a,
                      const EqualTimeComparison& c, const ojson& row, const ojson* other_row) {
  const std::string fig = figure_title(f.name), other = figure_title(a.other);
  md << "**" << fig << " against " << other << " at equal times.** The paper compares the bottom "
     << "plots of the two figures, each drawn against its own step number; ";
  const auto dt = number(row, "dt");
  const auto other_dt = other_row ? number(*other_row, "dt") : std::nullopt;
  if (dt && other_dt)
    md << "a step of " << fig << " is " << ratio(*dt / *other_dt) << " times one of " << other
       << ", so a count per step would set the runs side by side at different times. ";
  if (c.times.empty()) {
    md << "Our histories of the two runs share no recorded time, so they are not compared "
          "here.\n\n";
    return;
  }
  md << "This report compares the runs at the " << c.times.size()
     << " times both histories record, t = " << sci(c.times.front().t) << " to "
     << sci(c.times.back().t);
  if (const auto end = end_time(row))
    md << " (our run of " << fig << " ends at t = " << sci(*end) << ")";
  md << "; the verdicts of the two rows above count the times at which ours "
     << (a.direction == "fewer" ? "lies under " : "exceeds ") << other
     << "'s by more than a factor " << agreement_factor() << ". They span "
     << ratio(100 * c.share()) << "% of the paper's run of " << fig
     << " (to t = " << sci(c.paper_end) << "; " << fig << "'s error in u reaches "
     << ratio(c.error_over_A) << " A there, " << other << "'s " << ratio(c.other_error_over_A)
     << " A)"
     << (c.tests() ? "."
                   : ", less than the " + ratio(100 / kAgreementFactor) +
                         "% that tests the paper's text: the rows read *not tested*.")
     << "\n\n"
     << "| t | crossings " << fig << " | " << other << " | error in u " << fig << " | " << other
     << " | error per crossing, " << fig << " / " << other << " |\n|---|---|---|---|---|---|\n";
  for (const auto& e : c.times) {
    md << "| " << sci(e.t) << " | " << shortest(e.crossings) << " | " << shortest(e.other_crossings)
       << " | " << sci(e.error) << " | " << sci(e.other_error) << " | "
       << (e.crossings > 0 && e.other_crossings > 0 && e.other_error > 0
               ? ratio((e.error / e.crossings) / (e.other_error / e.other_crossings))
               : kNoValue)
       << " |\n";
  }
  md << "\n";
}

// ---- The figure's class and what explains it.

// The class Table 1's rules give the figure: the paper's run against ours.
struct FigureClass {
  std::string cls, why;
};

FigureClass figure_class(const PaperFigure& f, const ojson& row, const CourantEdges& edges) {
  const PaperObservable* o = f.find("outcome");
  const auto paper_steps = paper_number(f.find("steps"));
  const std::string ours = outcome(row);
  const std::int64_t steps = row.at("steps").get<std::int64_t>();
  if (!o || !o->stated()) return {"unreadable", "the paper's text does not say how the run ends"};
  const std::string paper_goes_on =
      paper_steps ? "the paper's run goes on to step " + count_text(*paper_steps)
                  : std::string("the paper's run goes on");
  if (o->value == "survived") {
    if (ours == "stable") return {"agree-stable", "both reach T"};
    if (ours == "meaningless")
      return {"ours-meaningless",
              "the paper's run reaches T; ours does too, but its error over time reached A"};
    return {failure_class(row, edges), paper_goes_on + " (T); ours fails at step " +
                                           std::to_string(steps) + " (" +
                                           RunRow(row).failure_reason.value_or("") + ")"};
  }
  if (ours == "meaningless")
    return {"ours-meaningless",
            "the paper's run fails; ours reaches T with an error over time that reached A"};
  if (ours == "stable")
    return {"paper-unstable-ours-stable", "the paper's run fails; ours reaches T"};
  if (paper_steps && !within_agreement_factor(double(steps), *paper_steps) &&
      steps < *paper_steps) {
    return {failure_class(row, edges),
            "both fail, but " + paper_goes_on + " and ours fails at step " + std::to_string(steps) +
                " (" + RunRow(row).failure_reason.value_or("") +
                "): the class of a failure where the paper's run lasts longer"};
  }
  return {"agree-unstable", "both fail"};
}

// What the courant scan says at the figure's Courant number (above-spectral-limit and
// above-our-edge).
std::string courant_context(const ojson& row, const StudyInputs& inputs) {
  const auto it = inputs.find("courant");
  if (it == inputs.end() || !it->second.present())
    return "The courant scan has not been run: `make reproduce` runs it.";
  const double c = scan_courant(row);
  const std::string method = RunRow(row).method;
  int n = 0, reached = 0;
  std::int64_t last_failure = 0;
  Coverage runs;
  for (const auto& r : it->second.doc.at("cases")) {
    const RunRow rr(r);
    if (scan_courant(r) != c || rr.method != method) continue;
    ++n;
    runs.add(rr);
    if (rr.survived()) {
      ++reached;
    } else {
      last_failure = std::max(last_failure, r["failure_step"].get<std::int64_t>());
    }
  }
  if (n == 0) return "The courant scan has no run of this method at c dt/h = " + shortest(c) + ".";
  std::string s = "In the courant scan ([courant.md](courant.md)), " + std::to_string(reached) +
                  " of the " + std::to_string(n) + " " + method +
                  " runs at c dt/h = " + shortest(c) + " (" + runs.text() + ") reach T";
  if (reached < n) s += "; the last of the failures comes at step " + std::to_string(last_failure);
  return s + ".";
}

// ---- The variant runs of a figure's case.

bool same_case(const ojson& a, const ojson& b) {
  for (const char* k : {"method", "E", "A", "dt", "T", "cells", "ppc", "bc", "scene"})
    if (!a.contains(k) || !b.contains(k) || a.at(k) != b.at(k)) return false;
  return true;
}

// "walls = ghost, position_update = particle": how a run differs from the figure's own.
std::string choice_label(const ojson& r, const ojson& base) {
  std::string s;
  for (const auto& k : kChoiceParams) {
    if (!r.contains(k) || !base.contains(k) || r.at(k) == base.at(k)) continue;
    const ojson& v = r.at(k);
    s += (s.empty() ? "" : ", ") + k + " = " +
         (v.is_string()   ? v.get<std::string>()
          : v.is_number() ? shortest(v.get<double>())
                          : "–");
  }
  return s.empty() ? "our default" : s;
}

// Whether a run reproduces the paper's run: how it ends and (if stated) when.
std::string reproduces(const PaperFigure& f, const ojson& r) {
  const PaperObservable* o = f.find("outcome");
  const auto paper_steps = paper_number(f.find("steps"));
  const std::string ours = outcome(r);
  const double steps = r.at("steps").get<double>();
  if (!o || !o->stated()) return kNoValue;
  if (o->value == "survived")
    return ours == "stable" ? "yes" : ours == "meaningless" ? "reaches T, meaningless" : "no";
  if (ours != "unstable") return "no: reaches T";
  if (!paper_steps || within_agreement_factor(steps, *paper_steps)) return "yes";
  return "no: " + ratio(steps / *paper_steps) + "x the paper's steps";
}

// The experiments that rerun a figure's case under each documented implementation choice: the
// comparison reads the one whose first case is the figure's.
const std::vector<std::string> kFigureVariants = {"fig2_variants", "fig3_variants"};

// The input holding the variant runs of this figure's case, if any has been run.
const StudyInput* variant_input(const ojson& row, const StudyInputs& inputs, std::string& name) {
  for (const auto& n : kFigureVariants) {
    const ojson* base = first_row(inputs, n);
    if (base && same_case(*base, row)) {
      name = n;
      return &inputs.at(n);
    }
  }
  return nullptr;
}

void variant_runs(std::ostream& md, const PaperFigure& f, const ojson& row,
                  const StudyInputs& inputs, std::map<std::string, std::string>& shown) {
  std::string name;
  const StudyInput* in = variant_input(row, inputs, name);
  if (!in) {
    md << "*No variant runs of this case have been run (";
    for (const auto& n : kFigureVariants)
      md << (n == kFigureVariants.front() ? "" : ", ") << "`experiments/" << n << ".json`";
    md << "): `make reproduce` runs them.*\n\n";
    return;
  }
  if (const auto it = shown.find(name); it != shown.end()) {
    md << "**Variant runs** ([" << name << ".md](" << name << ".md)): the same case as "
       << figure_title(it->second) << "; see [its section](#" << it->second << ").\n\n";
    return;
  }
  shown[name] = f.name;
  const ojson& cases = in->doc.at("cases");
  const ojson& base = cases.at(0);
  md << "**Variant runs** ([" << name << ".md](" << name
     << ".md)): the case under each documented implementation choice of the variants study "
        "([variants.md](variants.md)), changed alone from our default or in its pairs, and "
        "with periodic boundaries. "
        "Whether each reproduces the paper's run (how it ends and, where the paper says, when):\n\n"
        "| choice | run | steps | error over time / A | crossings | eq. (108) min | the paper's "
        "run |\n|---|---|---|---|---|---|---|\n";
  std::vector<std::string> yes, meaningless;
  const ojson* closest = nullptr;
  const auto paper_steps = paper_number(f.find("steps"));
  auto distance = [&](const ojson& r) {
    return std::abs(std::log(r.at("steps").get<double>() / *paper_steps));
  };
  for (const auto& r : cases) {
    const std::string label = choice_label(r, base);
    const std::string rep = reproduces(f, r);
    const auto e = row_error_over_A(r);
    md << "| " << label << " | " << verdict(r) << " | " << r.at("steps").dump() << " | "
       << (e ? ratio(*e) : kNoValue) << " | "
       << (number(r, "crossings") ? r.at("crossings").dump() : kNoValue) << " | "
       << opt_sci(r.contains("dt_stable_min") ? r.at("dt_stable_min") : ojson()) << " | " << rep
       << " |\n";
    if (rep == "yes") yes.push_back(label);
    if (rep == "reaches T, meaningless")
      meaningless.push_back(label + " (" + (e ? ratio(*e) : kNoValue) + " A)");
    if (paper_steps && (!closest || distance(r) < distance(*closest))) closest = &r;
  }
  md << "\n";
  md << yes.size() << " of " << cases.size() << " of these runs reproduce the paper's run"
     << (yes.empty() ? std::string(".") : ": " + semicolon_list(yes) + ".");
  if (!meaningless.empty()) {
    md << " Reaching T only as meaningless runs (error over time at least A): "
       << semicolon_list(meaningless) << ".";
    const PaperObservable* peak = f.find("peak_error");
    if (!peak || !peak->stated())
      md << " The paper's text does not state its run's error, so whether it too reached A "
            "cannot be told from it.";
  }
  if (yes.empty() && meaningless.empty() && closest) {
    md << " The closest in steps is " << choice_label(*closest, base) << ": "
       << closest->at("steps").dump() << " steps, "
       << ratio(closest->at("steps").get<double>() / *paper_steps) << "x the paper's "
       << count_text(*paper_steps) << ".";
  }
  md << "\n\n";
}

// ---- A figure's section.

// The Table 1 cell of the same method, E and dt whose amplitude is nearest to the figure's.
const QuotedCell* nearest_cell(const ojson& row, const std::vector<QuotedCell>& table1) {
  const QuotedCell* best = nullptr;
  const double A = row.at("A").get<double>();
  for (const auto& c : table1) {
    if (RunRow(row).method != c.method || row.at("E").get<double>() != c.E ||
        row.at("dt").get<double>() != c.dt) {
      continue;
    }
    if (!best || std::abs(c.A - A) < std::abs(best->A - A)) best = &c;
  }
  return best;
}

// The other figures whose run is the same case as this one's.
std::string same_case_figures(const PaperFigure& f, const ojson& row,
                              const std::vector<PaperFigure>& paper, const StudyInputs& inputs) {
  std::string s;
  for (const auto& g : paper) {
    const ojson* other = g.name == f.name ? nullptr : first_row(inputs, g.name);
    if (other && same_case(*other, row))
      s += (s.empty() ? "" : ", ") + std::string("[") + figure_title(g.name) + "](#" + g.name + ")";
  }
  return s;
}

// The passages the paper's values are read from, each once, by section.
void quoted_passages(std::ostream& md, const PaperFigure& f) {
  std::vector<std::pair<std::string, std::vector<std::string>>> quoted;
  for (const auto& o : f.observables) {
    if (!o.stated()) continue;
    auto sec = std::find_if(quoted.begin(), quoted.end(),
                            [&](const auto& q) { return q.first == o.section; });
    if (sec == quoted.end()) sec = quoted.insert(quoted.end(), {o.section, {}});
    add_unique(sec->second, o.evidence);
  }
  for (const auto& [section, passages] : quoted) {
    md << "The paper, " << section << ":";
    for (const auto& q : passages)
      md << "\n- " << q;
    md << "\n\n";
  }
}

void figure_section(std::ostream& md, const PaperFigure& f, const std::vector<PaperFigure>& paper,
                    const StudyInputs& inputs, const CourantEdges& edges,
                    const std::vector<QuotedCell>& table1, FigureSections& out,
                    std::map<std::string, std::string>& shown) {
  md << "<a id=\"" << f.name << "\"></a>\n### " << figure_title(f.name) << ": "
     << case_text(f.method, f.E, f.A, f.dt) << "\n\n";
  const auto it = inputs.find(f.name);
  const ojson* row = first_row(inputs, f.name);
  if (!row) {
    md << "*Our run of it (`experiments/" << f.name
       << ".json`) has not been run: `make reproduce` runs it.*\n\n";
    out.classes.emplace_back(f.name, "not run");
    return;
  }
  const ojson* history = history_of(it->second.doc);
  const OurRun run{row, trace_of(history)};
  const std::string ours_case = case_text(RunRow(*row).method, row->at("E").get<double>(),
                                          row->at("A").get<double>(), row->at("dt").get<double>());
  md << "Our run: [" << f.name << ".md](" << f.name << ".md)";
  if (ours_case != case_text(f.method, f.E, f.A, f.dt))
    md << " (**a different case: " << ours_case << "**)";
  const FigureClass k = figure_class(f, *row, edges);
  out.classes.emplace_back(f.name, k.cls);
  const ComparisonClass* c = find_class(k.cls);
  md << ". Class: [" << k.cls << "](#" << k.cls << ")"
     << (c ? std::string(", *") + c->title + "*" : std::string()) << ": " << k.why << ".";
  if (k.cls == "above-spectral-limit" || k.cls == "above-our-edge")
    md << " " << courant_context(*row, inputs);
  if (const QuotedCell* near = nearest_cell(*row, table1)) {
    md << " Table 1's nearest cell, " << case_text(near->method, near->E, near->A, near->dt)
       << ": the paper's "
       << "max error " << (near->paper == "*" ? std::string("\\* (unstable)") : near->paper)
       << ", ours " << near->ours << " ([" << near->cls << "](#" << near->cls << ")).";
  }
  if (const std::string same = same_case_figures(f, *row, paper, inputs); !same.empty())
    md << " Our run is the same case as that of " << same << ".";
  md << "\n\n| observable | paper | ours | verdict |\n|---|---|---|---|\n";
  std::vector<Line> lines = {outcome_line(f.find("outcome"), *row),
                             steps_line(f.find("steps"), *row),
                             peak_error_line(f.find("peak_error"), run),
                             bound_min_line(f.find("dt_stable_min"), run),
                             bound_min_step_line(f.find("bound_min_step"), f.find("steps"), run),
                             crossings_line(f.find("crossings"), run)};
  const std::optional<Against> vs = against(f.find("crossing_errors"));
  EqualTimeComparison at_equal_times;
  const ojson* other_row = vs ? first_row(inputs, vs->other) : nullptr;
  if (vs) {
    const auto o = inputs.find(vs->other);
    const ojson* other_history =
        o != inputs.end() && o->second.present() ? history_of(o->second.doc) : nullptr;
    const auto paper_steps = paper_number(f.find("steps"));
    const double A = row->at("A").get<double>(), T = row->at("T").get<double>();
    at_equal_times =
        compare_at_equal_times(history, other_history, paper_steps ? *paper_steps * f.dt : T, A,
                               other_row ? other_row->at("A").get<double>() : A);
    for (auto& l : equal_time_lines(*vs, at_equal_times))
      lines.push_back(std::move(l));
    // The runs the claims read, over the span of c t the times both record.
    Coverage runs = coverage_of(std::vector<const ojson*>{row});
    if (other_row) runs.add(*other_row);
    if (!at_equal_times.times.empty())
      runs.wave_passes = {
          std::stod(significant(*RunRow(*row).wave_passes * at_equal_times.times.back().t / T, 3))};
    for (auto& figure_claim : equal_time_claims(f, *vs, at_equal_times, runs))
      out.claims.push_back(std::move(figure_claim));
  }
  for (const auto& l : lines)
    md << "| " << l.label << " | " << l.paper << " | " << l.ours << " | " << l.verdict << " |\n";
  md << "\n";
  if (vs) equal_time_table(md, f, *vs, at_equal_times, *row, other_row);
  quoted_passages(md, f);
  variant_runs(md, f, *row, inputs, shown);
}

}  // namespace
}  // namespace studies::comparison_figures

const PaperObservable* PaperFigure::find(const std::string& quantity) const {
  for (const auto& o : observables)
    if (o.quantity == quantity) return &o;
  return nullptr;
}

std::vector<PaperFigure> read_paper_figures(const std::filesystem::path& csv) {
  using namespace studies::comparison_figures;
  std::vector<PaperFigure> figures;
  std::error_code ec;
  if (!std::filesystem::is_regular_file(csv, ec)) return figures;
  const CsvTable t = read_csv(csv);
  for (const char* col : {"figure", "method", "E", "A", "dt", "quantity", "value", "confidence",
                          "section", "evidence"}) {
    if (std::find(t.header.begin(), t.header.end(), col) == t.header.end())
      throw std::runtime_error(csv.string() + ": no column '" + col + "'");
  }
  for (const auto& row : t.rows) {
    const std::string& q = row.at("quantity");
    if (std::find(kQuantities.begin(), kQuantities.end(), q) == kQuantities.end())
      throw std::runtime_error(csv.string() + ": unknown quantity '" + q + "'");
    auto f = std::find_if(figures.begin(), figures.end(),
                          [&](const PaperFigure& x) { return x.name == row.at("figure"); });
    if (f == figures.end()) {
      PaperFigure fig;
      fig.name = row.at("figure");
      fig.method = row.at("method");
      std::transform(fig.method.begin(), fig.method.end(), fig.method.begin(), ::tolower);
      fig.E = std::stod(row.at("E"));
      fig.A = std::stod(row.at("A"));
      fig.dt = std::stod(row.at("dt"));
      figures.push_back(std::move(fig));
      f = std::prev(figures.end());
    }
    f->observables.push_back(
        {q, row.at("value"), row.at("confidence"), row.at("section"), row.at("evidence")});
  }
  return figures;
}

FigureSections figure_sections(const std::vector<PaperFigure>& paper,
                               const std::string& transcription, const StudyInputs& inputs,
                               const CourantEdges& edges, const std::vector<QuotedCell>& table1) {
  using namespace studies::comparison_figures;
  FigureSections out;
  std::ostringstream md;
  md << "## Figures 1-3: the paper's observables beside ours\n\n";
  if (paper.empty()) {
    md << "*No transcription of the paper's figures beside its Table 1 (" << transcription
       << ").*\n\n";
    out.markdown = md.str();
    return out;
  }
  md << "The paper's section 5.2 says in words what its Figs. 1-3 show; the plots themselves "
        "are not in its text, so an observable that only a plot would show is *not stated*. "
        "The transcription, with the passage each value is read from: ["
     << transcription << "](" << transcription
     << "). A number of ours (steps, errors, bounds, crossings) and the paper's are said to "
        "agree when within a factor "
     << agreement_factor()
     << " of each other (the rule of the max errors). A figure's class is the one Table 1's rules "
        "give its run; where both runs fail but ours more than a factor "
     << agreement_factor()
     << " sooner, the class of our failure where the paper's run lasts longer.\n\n";
  std::map<std::string, std::string> shown;  // variant input -> figure whose section shows it
  for (const auto& f : paper)
    figure_section(md, f, paper, inputs, edges, table1, out, shown);
  out.markdown = md.str();
  return out;
}

}  // namespace mpmstab
