// The edges in dt: per case, the survival edge (the largest fixed dt that survives to T) and the
// accuracy edge (the largest that keeps the error over time of the smallest dt), against h/c and
// the eq. (108) bound, with the dts where survival flips; one section per scene, the figure drawing
// every scene.
#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <map>
#include <optional>
#include <sstream>
#include <string_view>
#include <tuple>

#include "base/accuracy.hpp"
#include "claims.hpp"
#include "csv.hpp"
#include "key.hpp"
#include "report.hpp"
#include "report_util.hpp"
#include "shared/by_scene.hpp"
#include "shared/edge_length.hpp"
#include "shared/ensemble.hpp"
#include "study.hpp"

namespace mpmstab::studies::edge {
namespace {

using ojson = nlohmann::ordered_json;

// A dt in units of h/c: "0.823".
std::string in_cfl(double v) {
  return fixed(v, 3);
}

// A row's wave passes c T: "8", "31.6".
std::string passes(const ojson& r) {
  return significant(*RunRow(r).wave_passes, 3);
}

// "monotone", or "**not monotone**: survives again at up to 1.58e-4 (fails from 1.12e-4,
// survives from 1.58e-4)": the column survival_flips, "fails 0.000112; survives 0.000158", gives
// each dt from which survival changes as dt grows, below the survival edge.
std::string monotone_text(const ojson& r) {
  if (survival_monotone(r)) return "monotone";
  std::string s = "**not monotone**", flips = text(r, "survival_flips"), word, from;
  if (has_number(r, "dt_survives_above"))
    s += ": survives again at up to " + sci(r["dt_survives_above"].get<double>(), 3);
  std::replace(flips.begin(), flips.end(), ';', ' ');
  std::istringstream in(flips);
  for (double dt = 0; in >> word >> dt;)
    from += (from.empty() ? "" : ", ") + word + " from " + sci(dt, 3);
  return from.empty() ? s : s + " (" + from + ")";
}

// Why a row has no survival edge: no dt of the scan survives, or the smallest dt tried fails
// (a larger one may survive: no dt below it does).
std::string no_edge_text(const ojson& r) {
  return has_number(r, "dt_fail") ? "none: the smallest dt tried fails" : "none in the scan";
}

// "0.91 to 1.2", or "1" where both ends print alike.
std::string from_to(const std::string& lo, const std::string& hi) {
  return lo == hi ? lo : lo + " to " + hi;
}

// The range of some values, each printed by `print`: some dts over h/c ("0.823 to 0.897") or
// some ratios ("0.91 to 1.2").
std::string range_of(const std::vector<double>& v, std::string (*print)(double) = in_cfl) {
  const auto [lo, hi] = std::minmax_element(v.begin(), v.end(), TotalLess());
  return from_to(print(*lo), print(*hi));
}

// ---------------------------------------------------------------------------------------------
// The edges under perturbation (ensemble.hpp): every survival edge the report quotes is rerun
// as an ensemble of kEnsembleMembers layouts perturbed far below the discretisation error, at
// dt_edge (where the search's run survived) and at dt_fail (the dt just above it, which failed).
// The edge is robust when every member survives at dt_edge and fails at dt_fail; otherwise it is
// *sensitive*, with the counts.

struct EdgeEnsemble {
  int at_edge = 0, survived = 0;  // members at dt_edge, and those that survived
  int at_fail = 0, failed = 0;    // members at dt_fail, and those that failed
  bool run() const { return at_edge > 0; }
  bool robust() const { return run() && survived == at_edge && failed == at_fail; }
};

RunParams at_dt(const RunParams& base, double dt) {
  RunParams p = base;
  p.dt = dt;
  return p;
}

// What each follow-up run of a case is for: a member of its ensemble at dt_edge or at dt_fail,
// a rerun of an edge for length (edge_length), the periodic twin at dt_accurate.
constexpr const char* kMemberAtEdge = "ensemble member at dt_edge";
constexpr const char* kMemberAtFail = "ensemble member at dt_fail";
constexpr const char* kTwin = "periodic twin at dt_accurate";

std::vector<FollowUp> edge_follow_up(const FollowUpContext& c) {
  std::vector<FollowUp> runs;
  for (std::size_t i = 0; i < c.rows.size(); ++i) {
    const ojson& r = c.rows[i];
    if (!has_number(r, "dt_edge")) continue;
    const RunParams& base = c.spec.cases.at(i).params;
    for (auto& p : ensemble_members(at_dt(base, r["dt_edge"].get<double>())))
      runs.push_back({.of = i, .role = kMemberAtEdge, .params = std::move(p)});
    if (!has_number(r, "dt_fail")) continue;
    for (auto& p : ensemble_members(at_dt(base, r["dt_fail"].get<double>())))
      runs.push_back({.of = i, .role = kMemberAtFail, .params = std::move(p)});
  }
  for (auto& f : all_length_runs(c.rows, c.spec.cases))
    runs.push_back(std::move(f));
  // What the walls cost at the accuracy edge: a case with Dirichlet walls and an accuracy edge is
  // rerun there with periodic boundaries (both scenes' exact solutions are periodic), whose error
  // at T is the interior's own.
  for (std::size_t i = 0; i < c.rows.size(); ++i) {
    if (text(c.rows[i], "bc") != "dirichlet" || !has_number(c.rows[i], "dt_accurate")) continue;
    RunParams p = at_dt(c.spec.cases.at(i).params, c.rows[i]["dt_accurate"].get<double>());
    p.bc = Boundary::periodic;
    runs.push_back({.of = i, .role = kTwin, .params = p});
  }
  return runs;
}

// What the follow-up runs found per row, keyed by the row's address: its ensemble (empty where
// it has no edge or the follow-up runs are absent) and its runs at the test lengths.
struct EdgeFollowUps {
  std::map<const ojson*, EdgeEnsemble> ensembles;
  LengthRuns long_runs;
  std::map<const ojson*, ojson> twins;  // the periodic twin at dt_accurate
};

EdgeFollowUps edge_follow_ups(const std::vector<ojson>& rows, const std::vector<ojson>& follow_up) {
  EdgeFollowUps out;
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const ojson& r = rows[i];
    const auto at_edge = follow_ups_of(follow_up, i, kMemberAtEdge);
    if (!has_number(r, "dt_edge") || at_edge.empty()) continue;
    EdgeEnsemble& e = out.ensembles[&r];
    for (const ojson* m : at_edge) {
      ++e.at_edge;
      e.survived += survived(*m);
    }
    for (const ojson* m : follow_ups_of(follow_up, i, kMemberAtFail)) {
      ++e.at_fail;
      e.failed += !survived(*m);
    }
  }
  out.long_runs = read_length_runs(rows, follow_up);
  for (std::size_t i = 0; i < rows.size(); ++i)
    for (const ojson* twin : follow_ups_of(follow_up, i, kTwin))
      out.twins[&rows[i]] = *twin;
  return out;
}

// The margin of an edge to the spectral limit and how long it holds: "0.97 x limit; holds to
// c T = 1000", "1.04 x limit; **transient**: fails at c T = 530".
std::string margin_text(const EdgeFollowUps& f, const ojson& r, const char* dt_col) {
  if (!has_number(r, dt_col)) return "";
  std::string s;
  if (const auto limit = RunRow(r).courant_spectral)
    s = fixed(r[dt_col].get<double>() / r["dt_cfl"].get<double>() / *limit, 3) + " x limit; ";
  return s + lasting_text(f.long_runs, r, dt_col);
}

// The table's cell: "robust: 8 of 8 survive, 8 of 8 fail above", "**sensitive**: 5 of 8
// survive, 8 of 8 fail above", "–".
std::string ensemble_cell(const std::map<const ojson*, EdgeEnsemble>& all, const ojson& r) {
  const auto it = all.find(&r);
  if (it == all.end() || !it->second.run()) return "–";
  const EdgeEnsemble& e = it->second;
  std::ostringstream s;
  s << (e.robust() ? "robust: " : "**sensitive**: ") << e.survived << " of " << e.at_edge
    << " survive";
  if (e.at_fail) s << ", " << e.failed << " of " << e.at_fail << " fail above";
  return s.str();
}

// The figure: one panel per scene, one series per method and amplitude.
const std::vector<std::string> kPanels = {"bar", "steffen"};
const std::vector<std::pair<std::string, double>> kSeries = {
    {"gimp", 0.015},     {"gimp", 0.05},    {"mpm", 0.015},      {"mpm", 0.05},
    {"cpdi", 0.015},     {"cpdi", 0.05},    {"bspline2", 0.015}, {"bspline2", 0.05},
    {"bspline3", 0.015}, {"bspline3", 0.05}};

int panel_of(const ojson& r) {
  const auto it = std::find(kPanels.begin(), kPanels.end(), r["scene"].get<std::string>());
  return it == kPanels.end() ? -1 : int(it - kPanels.begin());
}

int series_of(const ojson& r) {
  const RunRow rr(r);
  for (std::size_t i = 0; i < kSeries.size(); ++i)
    if (rr.method == kSeries[i].first && rr.A == kSeries[i].second) return int(i) + 1;
  return 0;
}

// Why a case is not drawn ("" when it is).
std::string not_drawn_reason(const ojson& r) {
  if (panel_of(r) < 0) return "a scene the figure has no panel for";
  if (series_of(r) == 0) return "no series in the figure";
  if (!has_number(r, "dt_edge")) return "no edge (" + no_edge_text(r) + ")";
  return "";
}

// What the figure draws: the cases drawn (sorted by panel, series and c T), how many with an
// accuracy edge, and those drawn without one; the cases not drawn, by reason.
struct FigureCount {
  std::size_t cases = 0, with_accuracy = 0;
  std::vector<const ojson*> drawn;
  std::map<std::string, std::vector<const ojson*>> not_drawn;  // by reason
  std::vector<const ojson*> no_accuracy;                       // drawn without accuracy edge
};

FigureCount figure_count(const std::vector<ojson>& rows) {
  FigureCount c;
  c.cases = rows.size();
  for (const auto& r : rows) {
    const std::string reason = not_drawn_reason(r);
    if (!reason.empty()) {
      c.not_drawn[reason].push_back(&r);
      continue;
    }
    c.drawn.push_back(&r);
    if (has_number(r, "dt_accurate"))
      ++c.with_accuracy;
    else
      c.no_accuracy.push_back(&r);
  }
  std::stable_sort(c.drawn.begin(), c.drawn.end(), [](const ojson* a, const ojson* b) {
    return std::tuple(panel_of(*a), series_of(*a), Key(*RunRow(*a).wave_passes, "c T")) <
           std::tuple(panel_of(*b), series_of(*b), Key(*RunRow(*b).wave_passes, "c T"));
  });
  return c;
}

// ---------------------------------------------------------------------------------------------
// Findings

// What some searches found (one method's at one amplitude in one scene, or every search): how
// many found a survival edge, how often the run there is meaningless, both edges over h/c, the
// accuracy edge against the survival edge (how often below it, and the lowest ratio), why some
// have none; the survival edge against eq. (108) at it and against the spectral limit at the
// layout, and the accuracy edge against that limit; and where the searches lie that decide each
// (Coverage, run_row.hpp): every one, those with a survival edge, without one, with an accuracy
// edge, with eq. (108) measured, with a limit, with a limit and an accuracy edge.
struct Edges {
  int cases = 0, with_edge = 0, meaningless = 0, below = 0, no_accuracy = 0, withheld = 0;
  std::vector<double> edge, accurate;
  double below_lo = 1e300;
  int bound_n = 0, bound_below = 0;  // edges with eq. (108) measured, and those it lies below
  double bound_lo = 1e300, bound_hi = 0;
  int limit_n = 0, limit_above = 0, accurate_limit_n = 0, accurate_limit_above = 0;
  double limit_hi = 0;
  Coverage all_at, edge_at, none_at, accurate_at, bound_at, limit_at, accurate_limit_at;
  // Counts one search in.
  void add(const ojson& r) {
    ++cases;
    all_at.add(r);
    if (!has_number(r, "dt_edge")) return none_at.add(r);
    ++with_edge;
    edge_at.add(r);
    const RunRow rr(r);
    edge.push_back(r["dt_edge_over_cfl"].get<double>());
    meaningless += rr.outcome == "meaningless";
    if (has_number(r, "dt_edge_over_stable")) {
      const double over = r["dt_edge_over_stable"].get<double>();
      ++bound_n;
      bound_at.add(r);
      bound_below += over > 1;
      bound_lo = std::min(bound_lo, over);
      bound_hi = std::max(bound_hi, over);
    }
    const auto limit = rr.courant_spectral;
    if (limit) {
      const double rel = r["dt_edge_over_cfl"].get<double>() / *limit;
      ++limit_n;
      limit_at.add(r);
      limit_above += rel > 1;
      limit_hi = std::max(limit_hi, rel);
    }
    if (has_number(r, "dt_accurate")) {
      accurate.push_back(r["dt_accurate_over_cfl"].get<double>());
      accurate_at.add(r);
      const double ratio = r["dt_accurate"].get<double>() / r["dt_edge"].get<double>();
      below_lo = std::min(below_lo, ratio);
      below += ratio < 1;
      accurate_limit_n += limit.has_value();
      if (limit) accurate_limit_at.add(r);
      accurate_limit_above +=
          limit && r["dt_accurate"].get<double>() / r["dt_cfl"].get<double>() > *limit;
    } else if (r.value("accuracy_edge_withheld", false)) {
      ++withheld;
    } else {
      ++no_accuracy;
    }
  }
};

// Against amplitude: for each method of a scene run at one c T with at least kAmplitudeSweep
// amplitudes, its searches in order of A / h.
constexpr std::size_t kAmplitudeSweep = 3;

// What one scene's searches found: per method and amplitude, its edges; the searches not monotone
// (with their flips); per method and amplitude, how many periodic twins were run and each one's
// error over time against the Dirichlet run's; the amplitude sweeps.
using Group = std::pair<std::string, Key>;  // a method and an amplitude
struct SceneFindings {
  std::string scene;
  std::vector<const ojson*> rows;
  std::map<Group, Edges> per;
  std::vector<std::string> non_monotone;
  std::map<Group, int> twins;
  std::map<Group, std::vector<double>> twin_ratios;
  std::vector<std::pair<std::string, std::vector<const ojson*>>> sweeps;  // method, rows
  int none = 0;  // searches without a survival edge
};

// The findings of one scene's searches.
SceneFindings scene_findings(std::string scene, std::vector<const ojson*> rows,
                             const EdgeFollowUps& f) {
  SceneFindings s{.scene = std::move(scene), .rows = std::move(rows)};
  std::map<std::pair<std::string, Key>, std::vector<const ojson*>> sweeps;
  for (const ojson* p : s.rows) {
    const ojson& r = *p;
    const RunRow rr(r);
    const Group group{rr.method, Key(*rr.A, "A")};
    s.per[group].add(r);
    s.none += !has_number(r, "dt_edge");
    sweeps[{rr.method, Key(*rr.wave_passes, "c T")}].push_back(p);
    // A search not monotone: "mpm, A = 0.05, E = 4 (c T = 2) (**not monotone**: ...)".
    if (has_number(r, "dt_edge") && !survival_monotone(r))
      s.non_monotone.push_back(rr.method + ", A = " + value_text(*rr.A) +
                               ", E = " + shortest(r["E"].get<double>()) + " (c T = " + passes(r) +
                               ") (" + monotone_text(r) + ")");
    const auto it = f.twins.find(p);
    if (it == f.twins.end()) continue;
    ++s.twins[group];
    const RunRow twin(it->second);
    if (twin.survived() && twin.error_over_time && has_number(r, "max_error_at_accurate"))
      s.twin_ratios[group].push_back(*twin.error_over_time /
                                     r["max_error_at_accurate"].get<double>());
  }
  for (auto& [key, list] : sweeps) {
    if (list.size() < kAmplitudeSweep) continue;
    std::sort(list.begin(), list.end(), [](const ojson* a, const ojson* b) {
      return TotalLess()((*a)["A_over_h"].get<double>(), (*b)["A_over_h"].get<double>());
    });
    s.sweeps.emplace_back(key.first, list);
  }
  return s;
}

// What the study finds, from its rows and their follow-up runs (none for the index and the
// subtitle, which print no finding of them): each scene's, every search's, how many edges were
// rerun on an ensemble and how many of those are robust, how many searches found survival
// monotone, the survival and the accuracy edges rerun for length (and where those searches lie),
// and what the figure draws. Its pointers are into the rows.
struct Findings {
  std::vector<SceneFindings> scenes;
  Edges all;
  int run = 0, robust = 0, monotone = 0;
  std::array<LengthTally, 2> lengths;  // dt_edge, dt_accurate
  std::array<Coverage, 2> lengths_at;
  FigureCount figure;
};

// The findings of every search: grouped by scene in the order the scenes first appear.
Findings find(const std::vector<ojson>& rows, const EdgeFollowUps& f) {
  Findings out{.figure = figure_count(rows)};
  std::vector<std::pair<std::string, std::vector<const ojson*>>> scenes;  // in order of first row
  for (const auto& r : rows) {
    const std::string scene = r["scene"].get<std::string>();
    auto it = std::find_if(scenes.begin(), scenes.end(), [&](auto& s) { return s.first == scene; });
    if (it == scenes.end()) it = scenes.insert(scenes.end(), {scene, {}});
    it->second.push_back(&r);
    out.all.add(r);
    out.monotone += survival_monotone(r);
    for (const std::size_t k : {0, 1}) {
      const Lasting l = lasting(f.long_runs, r, k ? "dt_accurate" : "dt_edge");
      out.lengths[k].add(l);
      if (l.tested) out.lengths_at[k].add(r);
    }
    const auto e = f.ensembles.find(&r);
    if (!has_number(r, "dt_edge") || e == f.ensembles.end() || !e->second.run()) continue;
    ++out.run;
    out.robust += e->second.robust();
  }
  for (auto& [scene, list] : scenes)
    out.scenes.push_back(scene_findings(scene, std::move(list), f));
  return out;
}

// ---------------------------------------------------------------------------------------------
// Claims

// The conclusions the rows and their follow-up runs decide.
std::vector<Claim> edge_claims(const Findings& f) {
  const Edges& e = f.all;
  std::vector<Claim> claims;
  Claim ens = claim("edges-robust",
                    "Every survival edge quoted here survives, and the dt above it fails, on "
                    "{members} layouts perturbed by {unit} of the particle spacing",
                    "{robust} of {run} edges rerun are robust; {with_edge} edges found");
  ens.count("members", kEnsembleMembers)
      .value("unit", sci(kEnsemblePerturbation, 1))
      .count("robust", f.robust)
      .count("run", f.run)
      .count("with_edge", e.with_edge);
  ens.holds = f.run == e.with_edge && f.robust == f.run;
  claims.push_back(ens.over(f.run).on(e.edge_at));

  Claim eq108 = claim("eq108-below-every-edge",
                      "Eq. (108) at the survival edge lies below the edge in every case where "
                      "both are measured",
                      "{below} of {n}; the edge is {lo} to {hi} times eq. (108)");
  claims.push_back(eq108.every("below", e.bound_below, "n", e.bound_n)
                       .value("lo", e.bound_n ? ratio(e.bound_lo) : "–")
                       .value("hi", e.bound_n ? ratio(e.bound_hi) : "–")
                       .on(e.bound_at));

  Claim limit = claim("edges-at-most-the-limit",
                      "No survival edge lies above its scheme's spectral limit at the layout",
                      "{above} of {n} lie above it, at most {hi} times it");
  limit.count("above", e.limit_above)
      .count("n", e.limit_n)
      .value("hi", e.limit_n ? fixed(e.limit_hi, 3) : "–");
  limit.holds = e.limit_above == 0;
  claims.push_back(limit.over(e.limit_n).on(e.limit_at));

  Claim below = claim("accurate-edges-at-most-the-limit",
                      "Every accuracy edge lies at or below its scheme's spectral limit (where no "
                      "mode of the linearised step grows; how long each holds is tested apart)",
                      "{above} of {n} lie above it");
  below.count("above", e.accurate_limit_above).count("n", e.accurate_limit_n);
  below.holds = e.accurate_limit_above == 0;
  claims.push_back(below.over(e.accurate_limit_n).on(e.accurate_limit_at));

  // Each kind of edge rerun for length: which hold to the longest test length.
  for (const bool survival : {true, false}) {
    const LengthTally& t = f.lengths[survival ? 0 : 1];
    Claim c = length_claim(
        survival ? "survival-edges-hold-for-length" : "accuracy-edges-hold-for-length",
        std::string("Every ") + (survival ? "survival" : "accuracy") +
            " edge holds when its run is {first}x and {second}x as long (at most {cap} wave "
            "passes)",
        std::string("{held} of {tested} hold; the others fail") +
            (survival ? "" : " or leave the accuracy class") + " at c T = {span}",
        t);
    claims.push_back(c.value("span", span(t.failed_at, 3)).on(f.lengths_at[survival ? 0 : 1]));
  }
  Claim mono = claim("survival-monotone", "Survival is monotone in dt in every search",
                     "{monotone} of {n} searches");
  mono.every("monotone", f.monotone, "n", static_cast<long long>(f.all.cases)).on(f.all.all_at);
  claims.push_back(mono);
  return claims;
}

// ---------------------------------------------------------------------------------------------
// Text

// Why a search found no survival edge, where the reading does not tell the two apart.
constexpr const char* kNoEdge = "no dt of the scan survives, or the smallest dt tried fails";

// Where some searches lie, their scene named apart (each section and panel names its own): "A =
// 0.015 and 0.05; c T = 1 to 100 (7 values); 100 cells", with `lengths_only` "c T = 1, 2 and 4";
// in `one_clause` (the figure's subtitle, which breaks its lines at "; ") its parts joined by ", ".
std::string where(Coverage c, bool lengths_only = false, bool one_clause = false) {
  c.scenes.clear();
  if (lengths_only) c.A = c.cells = {};
  std::string s = c.text();
  for (auto at = s.find("; "); one_clause && at != std::string::npos; at = s.find("; ", at))
    s.replace(at, 2, ", ");
  return s;
}

// One method's sentence of the summary at one amplitude: each range with the run lengths its
// searches span.
std::string method_summary(const Group& group, const Edges& m) {
  std::ostringstream md;
  md << group.first << " at A = " << value_text(group.second) << ": ";
  if (m.edge.empty())
    return md.str() + "no edge at " + where(m.none_at, true) + ": " + kNoEdge + ". ";
  md << "the survival edge is " << range_of(m.edge) << " h/c over " << where(m.edge_at, true)
     << ", and the run there is meaningless in " << m.meaningless << " of " << m.with_edge
     << " cases";
  if (m.with_edge < m.cases) md << "; none at " << where(m.none_at, true) << " (" << kNoEdge << ")";
  if (!m.accurate.empty())
    md << "; the accuracy edge is " << range_of(m.accurate) << " h/c over "
       << where(m.accurate_at, true) << ", below the survival edge in " << m.below << " of "
       << m.accurate.size() << " cases"
       << (m.below ? " (down to " + ratio(m.below_lo) + " times it)" : "");
  if (m.no_accuracy)
    md << "; " << m.no_accuracy << " ha" << (m.no_accuracy == 1 ? "s" : "ve")
       << " no accuracy edge (the run at the smallest surviving dt is meaningless)";
  if (m.withheld)
    md << "; " << m.withheld << " ha" << (m.withheld == 1 ? "s" : "ve")
       << " none that is accurate (the search's reference run or its run at the edge has an "
          "error over time of at least "
       << shortest(kAccurateFraction) << " A)";
  if (m.bound_n)
    md << "; eq. (108) at the survival edge is " << from_to(ratio(m.bound_lo), ratio(m.bound_hi))
       << " times below it";
  md << ". ";
  return md.str();
}

// The reading of one scene's searches and where they lie: per method and amplitude, the range of
// both edges over h/c with the run lengths they span, how often the run at the survival edge is
// meaningless and the accuracy edge lies below it; the searches without an edge; the
// non-monotone ones with their flips.
std::string edge_summary_text(const SceneFindings& s) {
  const std::size_t n = s.rows.size();
  std::ostringstream md;
  md << "Of " << n << " searches (" << where(coverage_of(s.rows)) << "), "
     << n - std::size_t(s.none) << " found a survival edge";
  if (s.none) md << " and " << s.none << " none (" << kNoEdge << ")";
  md << ". ";
  for (const auto& [group, m] : s.per)
    md << method_summary(group, m);
  md << s.non_monotone.size() << " of " << n
     << " searches found survival not monotone in dt (a dt above the lowest failure survives; "
        "the edge is below that failure)";
  if (!s.non_monotone.empty()) {
    md << ": ";
    for (std::size_t i = 0; i < s.non_monotone.size(); ++i)
      md << (i ? "; " : "") << s.non_monotone[i];
  }
  md << ".";
  return md.str();
}

// The search and both rules, stated once, with the numbers of the study's search options.
std::string search_rule(const EdgeOptions& o) {
  std::string search = edge_search_text(o);
  search[0] = static_cast<char>(std::toupper(static_cast<unsigned char>(search[0])));
  return "**The search.** " + search +
         ". The *survival edge* dt_edge is the largest dt up to which every dt tried survives to "
         "T; the run there is measured (its outcome, its error at T, the minimum of eq. (108) "
         "over it). The *accuracy edge* dt_accurate: the reference is the smallest dt tried that "
         "survives, and its error over time (max over steps and particles) the yardstick; walking "
         "up from it, dt_accurate is the last dt tried before the first that fails or has an "
         "error over time more than " +
         shortest(o.accuracy_factor) +
         " times the reference's, bisected against that one to the same tolerance and scanned "
         "below in the same way, and its run must be stable (its error over time stays below A), "
         "else the search goes on below it. An accuracy edge is one only where its reference run "
         "and its own run are accurate (their error over time below " +
         shortest(kAccurateFraction) +
         " A, docs/studies.md, \"Accuracy classes\"); elsewhere the table says why there is none. "
         "Every error over time is also given per A. The probes observe only their error over "
         "time; the outcome is measured for the reference and at both edges. Survival is *not "
         "monotone* when a dt above the lowest failure survives again: the edge stays below that "
         "failure, and the column gives the highest dt that survives above it and, in increasing "
         "dt, each dt from which the run fails or survives again (between it and the dt tried "
         "just below it). Every edge holds for the amplitude A and the run length c T of its row. "
         "The *spectral limit* is the Courant number at which the scheme, linearised about rest "
         "with the particles of the initial layout frozen, starts to amplify (docs/theory.md, "
         "\"The spectral limit\"): the edge of a tiny amplitude; where the edges at the paper's "
         "amplitudes lie against it is counted in the conclusions. The *ensemble* column: the "
         "case rerun on layouts perturbed far below the discretisation error (docs/studies.md, "
         "\"Ensembles\") at dt_edge and at the dt just above it that failed; *robust* when every "
         "member survives at dt_edge and fails above, *sensitive* otherwise. The survival edge's "
         "*bracket* is the dt just above it that failed: the edge lies between the two. The *edge "
         "/ limit* columns give each edge's margin to the spectral limit (below one: below the "
         "limit) and how long it holds: every edge, below the limit too, is rerun at its dt for " +
         shortest(kLengthFactors[0]) + " and " + shortest(kLengthFactors[1]) +
         " times its wave passes (at most " + shortest(kLongPasses) +
         "), and printed as holding to the longest it passed (a survival edge by surviving, an "
         "accuracy edge by staying stable and accurate) or as **transient** with the length at "
         "which it failed. No edge is claimed beyond the length it was rerun for. E only rescales "
         "time: a case at E run to T is the scheme run for c T = sqrt(E) T wave passes (column c "
         "T), so the edges against E at a fixed T are edges against run length.";
}

// An error over time with its size per A: "3.1e-4 (0.021 A)".
std::string per_A(const ojson& r, const char* error, const char* over_A) {
  if (!has_number(r, error)) return "–";
  return sci(r[error].get<double>(), 2) +
         (has_number(r, over_A) ? " (" + significant(r[over_A].get<double>(), 2) + " A)"
                                : std::string());
}

// The accuracy edge's two cells: the edge over h/c (with the dt first when `with_dt`) and its
// margin to the spectral limit, or why there is none: "1.2e-3 (0.61) | 0.95 x limit; ... |".
std::string accuracy_cells(const EdgeFollowUps& f, const ojson& r, bool with_dt) {
  if (!has_number(r, "dt_accurate"))
    return r.value("accuracy_edge_withheld", false) ? "none (not accurate) | – |"
                                                    : "none (reference meaningless) | – |";
  const std::string over = in_cfl(r["dt_accurate_over_cfl"].get<double>());
  return (with_dt ? sci(r["dt_accurate"].get<double>(), 3) + " (" + over + ")" : over) + " | " +
         margin_text(f, r, "dt_accurate") + " |";
}

// Per case: where it lies (A / h, c T), both edges against h/c with the bracket the bisection
// left and their margin to the spectral limit, the run at the survival edge, the errors at T,
// eq. (108), the flips and what the search cost.
std::string edge_table(const std::vector<const ojson*>& rows, const EdgeFollowUps& f) {
  std::ostringstream md;
  md << "| method | A | A/h | E | c T | h/c | spectral limit (h/c) | survival edge dt_edge "
        "(h/c; bracket) | survival edge / limit; length | run at dt_edge (error over time / A) "
        "| error at T there | accuracy edge dt_accurate (h/c) | accuracy edge / limit; length | "
        "error over time: reference → at dt_accurate (periodic twin) | eq. (108) at dt_edge "
        "(dt_edge / it) | survival in dt | ensemble | probes | particle-steps |\n"
        "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n";
  for (const ojson* p : rows) {
    const ojson& r = *p;
    const bool found = has_number(r, "dt_edge");
    const RunRow rr(r);
    md << "| " << rr.method << " | " << shortest(*rr.A) << " | "
       << significant(r["A_over_h"].get<double>(), 3) << " | " << shortest(r["E"].get<double>())
       << " | " << passes(r) << " | " << sci(r["dt_cfl"].get<double>(), 3) << " | "
       << opt_fixed(rr.courant_spectral) << " | ";
    if (!found) {
      md << no_edge_text(r) << " | – | – | – | – | – | – | – | ";
    } else {
      md << sci(r["dt_edge"].get<double>(), 3) << " ("
         << in_cfl(r["dt_edge_over_cfl"].get<double>());
      if (has_number(r, "dt_fail"))
        md << "; fails at " << in_cfl(r["dt_fail"].get<double>() / r["dt_cfl"].get<double>());
      md << ") | " << margin_text(f, r, "dt_edge") << " | " << edge_run_verdict(r) << " | "
         << opt_sci(r["max_error"]) << " | ";
      md << accuracy_cells(f, r, true) << " "
         << per_A(r, "max_error_reference", "error_reference_over_A") << " → "
         << per_A(r, "max_error_at_accurate", "error_at_accurate_over_A");
      if (const auto it = f.twins.find(&r); it != f.twins.end())
        md << " (periodic "
           << (survived(it->second) ? opt_sci(RunRow(it->second).error_over_time)
                                    : verdict(it->second))
           << ")";
      md << " | " << opt_sci(r["dt_stable_min_at_edge"]);
      if (has_number(r, "dt_edge_over_stable"))
        md << " (" << ratio(r["dt_edge_over_stable"].get<double>()) << ")";
      md << " | ";
    }
    md << monotone_text(r) << " | " << ensemble_cell(f.ensembles, r) << " | " << r["probes"].dump()
       << " | " << sci(r["search_particle_steps"].get<double>()) << " |\n";
  }
  return md.str();
}

// "bar: mpm, A = 0.05, c T = 4, 8; steffen: ...": by scene, method and A, each run length
// ascending.
std::string listed(const std::vector<const ojson*>& rows) {
  std::map<std::tuple<std::string, std::string, double>, std::vector<double>> groups;
  for (const ojson* r : rows) {
    const RunRow rr(*r);
    groups[{text(*r, "scene"), rr.method, *rr.A}].push_back(*rr.wave_passes);
  }
  std::string s;
  for (auto& [key, lengths] : groups) {
    std::sort(lengths.begin(), lengths.end());
    s += (s.empty() ? "" : "; ") + std::get<0>(key) + ": " + std::get<1>(key) +
         ", A = " + value_text(std::get<2>(key)) + ", c T =";
    for (std::size_t k = 0; k < lengths.size(); ++k)
      s += (k ? ", " : " ") + significant(lengths[k], 3);
  }
  return s;
}

// What the figure leaves out, and why.
std::string not_drawn_text(const FigureCount& c) {
  std::ostringstream md;
  md << "**Drawn.** " << c.drawn.size() << " of " << c.cases << " cases ("
     << where(coverage_of(c.drawn)) << "), " << c.with_accuracy
     << " of them with their accuracy edge.";
  for (const auto& [reason, rows] : c.not_drawn)
    md << " Not drawn, " << reason << " (" << rows.size() << "): " << listed(rows) << ".";
  if (!c.no_accuracy.empty())
    md << " Drawn without an accuracy edge, their reference run being meaningless or the edge "
          "not accurate ("
       << c.no_accuracy.size() << "): " << listed(c.no_accuracy) << ".";
  return md.str();
}

// Against amplitude: each amplitude sweep of the scene, its edges in order of A / h, with their
// margins to the spectral limit ("" when the scene has no such sweep).
std::string amplitude_table(const SceneFindings& s, const EdgeFollowUps& f) {
  if (s.sweeps.empty()) return "";
  std::ostringstream md;
  md << "\n**Against amplitude.** The same cases ordered by A / h at one run length: each "
        "edge, its margin to the spectral limit and the run there.\n\n"
        "| method | c T | A/h | survival edge (h/c) | survival edge / limit; length | run at "
        "it (error over time / A) | accuracy edge (h/c) | accuracy edge / limit; length |\n"
        "|---|---|---|---|---|---|---|---|\n";
  for (const auto& [method, list] : s.sweeps) {
    for (const ojson* r : list) {
      md << "| " << method << " | " << passes(*r) << " | "
         << significant((*r)["A_over_h"].get<double>(), 3) << " | ";
      if (!has_number(*r, "dt_edge")) {
        md << no_edge_text(*r) << " | – | – | – | – |\n";
        continue;
      }
      md << in_cfl((*r)["dt_edge_over_cfl"].get<double>()) << monotone_words(*r) << " | "
         << margin_text(f, *r, "dt_edge") << " | " << edge_run_verdict(*r) << " | ";
      md << accuracy_cells(f, *r, false) << "\n";
    }
  }
  return md.str();
}

// What the walls cost at the accuracy edge, per method and amplitude: the periodic twin's error
// over time against the Dirichlet run's ("" when no twin was run).
std::string walls_text(const SceneFindings& s) {
  if (s.twins.empty()) return "";
  std::ostringstream md;
  md << "**Walls.** Each case with Dirichlet walls is rerun at its accuracy edge with periodic "
        "boundaries (no wall: the interior's own error); the periodic error over time is, per "
        "method and amplitude, ";
  for (const auto& [m, n] : s.twins) {
    md << (m == s.twins.begin()->first ? "" : "; ") << m.first << " at A = " << value_text(m.second)
       << ": ";
    const auto it = s.twin_ratios.find(m);
    if (it == s.twin_ratios.end()) {
      md << "not compared (" << n << " twins, none reached T)";
      continue;
    }
    md << range_of(it->second, ratio) << " times the Dirichlet one (median "
       << ratio(quantile(it->second, 0.5)) << ", " << it->second.size() << " of " << n << " twins)";
  }
  md << ".\n\n";
  return md.str();
}

// One scene's section: the first has the figure and states the rules; each has its own reading
// and table.
std::string edge_markdown(const Spec& spec, const Findings& all, const SceneFindings& s, bool first,
                          const EdgeFollowUps& f) {
  std::ostringstream md;
  if (first) {
    md << "## Results\n\n"
       << search_rule(spec.study->edge) << "\n\n"
       << cost_metric_text() << "\n\n![" << spec.title << "](" << spec.name
       << ".png)\n\nThe figure draws both edges in units of h/c for every scene, on a log "
          "scale, beside each series' spectral limit (dotted) and eq. (108) at its survival edge "
          "(dash-dotted). "
       << not_drawn_text(all.figure) << " Vector version: [" << spec.name << ".svg](" << spec.name
       << ".svg); data: [" << spec.name << "_data.csv](" << spec.name << "_data.csv).\n\n## "
       << scene_title(s.scene) << "\n\n";
  } else {
    md << "\n## " << scene_title(s.scene) << "\n\n";
  }
  md << "**Reading.** " << edge_summary_text(s) << "\n\n"
     << walls_text(s) << edge_table(s.rows, f) << amplitude_table(s, f);
  return md.str();
}

// ---------------------------------------------------------------------------------------------
// Figure

std::string edge_subtitle_text(const FigureCount& c) {
  std::string s = std::to_string(c.drawn.size()) + " of " + std::to_string(c.cases) +
                  " cases drawn (" + where(coverage_of(c.drawn), false, true) + ", " +
                  std::to_string(c.with_accuracy) + " with an accuracy edge)";
  for (const auto& [reason, rows] : c.not_drawn)
    s += "; not drawn, " + reason + ": " + std::to_string(rows.size());
  return s;
}

// A row per drawn case, by panel, series and E; the cases not drawn in the header.
std::string edge_data_csv(const FigureCount& count, const std::string& header_lines) {
  std::ostringstream csv;
  csv << header_lines << "# " << edge_subtitle_text(count) << "\n";
  for (const auto& [reason, list] : count.not_drawn)
    csv << "# not drawn, " << reason << ": " << listed(list) << "\n";
  if (!count.no_accuracy.empty())
    csv << "# drawn without an accuracy edge (reference meaningless or not accurate): "
        << listed(count.no_accuracy) << "\n";
  csv << "# panel: " << codes(kPanels) << "; series:";
  for (std::size_t i = 0; i < kSeries.size(); ++i)
    csv << (i ? ", " : " ") << i + 1 << ' ' << kSeries[i].first
        << " A = " << shortest(kSeries[i].second);
  csv << "; cT: the wave passes c T = sqrt(E) T of the run; dt in units of h/c; "
         "meaningless_at_edge: whether the run at the survival edge is meaningless (a boolean); "
         "limit_over_cfl: the scheme's spectral limit at the layout; eq108_over_cfl: eq. (108) at "
         "the survival edge (its "
         "minimum over the run there), both in units of h/c (empty where not measured)\n"
         "panel,series,cT,dt_edge_over_cfl,dt_accurate_over_cfl,meaningless_at_edge,limit_over_cfl,"
         "eq108_over_cfl\n";
  for (const ojson* r : count.drawn) {
    const RunRow rr(*r);
    csv << panel_of(*r) << ',' << series_of(*r) << ',' << shortest(*rr.wave_passes) << ','
        << csv_cell((*r)["dt_edge_over_cfl"]) << ',' << csv_cell((*r)["dt_accurate_over_cfl"])
        << ',' << (rr.outcome == "meaningless" ? 1 : 0) << ','
        << (rr.courant_spectral ? shortest(*rr.courant_spectral) : std::string()) << ',';
    if (has_number(*r, "dt_stable_min_at_edge"))
      csv << shortest((*r)["dt_stable_min_at_edge"].get<double>() / (*r)["dt_cfl"].get<double>());
    csv << '\n';
  }
  return csv.str();
}

std::string edge_subtitle(const Spec& spec, const ojson& doc) {
  const std::vector<ojson> rows(doc["cases"].begin(), doc["cases"].end());
  const Findings f = find(rows, {});
  return edge_subtitle_text(f.figure) + "; " + std::to_string(f.all.cases - f.monotone) +
         " not monotone in dt (each edge drawn is the lowest failure found); each listed in " +
         spec.name + ".md";
}

StudyReport edge_report(const ReportContext& c) {
  const EdgeFollowUps follow_ups = edge_follow_ups(c.rows, c.follow_up);
  const Findings f = find(c.rows, follow_ups);
  StudyReport report;
  for (std::size_t i = 0; i < f.scenes.size(); ++i)
    report.markdown += edge_markdown(c.spec, f, f.scenes[i], i == 0, follow_ups);
  report.data_csv = edge_data_csv(f.figure, c.csv_header);
  report.claims = edge_claims(f);
  return report;
}

std::string edge_index(const Spec& spec, const std::vector<ojson>& rows, const ojson&) {
  std::ostringstream md;
  md << "![" << spec.title << "](" << spec.name << ".png)\n\n**What it shows.** ";
  const Findings f = find(rows, {});
  for (const SceneFindings& scene : f.scenes)
    md << "*" << scene_title(scene.scene) << ".* " << edge_summary_text(scene) << " ";
  md << "Details: [" << spec.name << ".md](" << spec.name << ".md).\n\n";
  return md.str();
}

const StudyRegistration kEdge{{
    .name = "edge",
    .summary = "per case, the largest fixed dt that survives to T and the largest that stays "
               "accurate (a search over dt)",
    .work = CaseWork::edge_search,
    .records = {.error_over_time = true},
    .figure = true,
    .follow_up = edge_follow_up,
    .report = edge_report,
    .index = edge_index,
    .figure_subtitle = edge_subtitle,
}};

}  // namespace
}  // namespace mpmstab::studies::edge
