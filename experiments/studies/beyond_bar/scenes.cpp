// Scenes: every scene whose body lies inside a larger grid, against its exact solution, per
// method (docs/theory.md, "Scenes"): the error over time and in L2 with its cost at three
// Courant numbers (the speed/accuracy trade), the dense spectral limit of the body with its free
// surfaces against the interior Bloch limit of the same scheme (the bar on a periodic grid,
// rows of this spec), the survival edge (read from the scene_edges experiment), the small-mass
// treatments and an extremes battery. The cases say which part they belong to by what they are:
// the bar rows are the interior limits, a small_mass other than none the treatments, c dt/h
// above the trade's or A or T other than the scene's reference the extremes.
#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <sstream>

#include "claims.hpp"
#include "csv.hpp"
#include "key.hpp"
#include "report_util.hpp"
#include "run_row.hpp"
#include "shared/by_scene.hpp"
#include "study.hpp"
#include "sweep.hpp"

namespace mpmstab::studies::scenes {
namespace {

using ojson = nlohmann::ordered_json;

// The reference setting of every scene: its trade's middle Courant number and its history.
constexpr double kReferenceCourant = 0.2;
// At most this many points of a history per series in the figure's data.
constexpr int kFigurePoints = 300;

double num(const ojson& r, const char* column) {
  return r[column].get<double>();
}
std::optional<double> opt(const ojson& r, const char* column) {
  return has_number(r, column) ? std::optional(r[column].get<double>()) : std::nullopt;
}

// Which part of the study a row belongs to.
enum class Part { interior, trade, treatment, extreme, peer };

// A dense limit more than this fraction below the interior one is lowered by the free surface
// (the limits are bisected to a relative 1e-4).
constexpr double kLimitDrop = 0.01;

// The peer comparison: Uintah's final particle error must be matched within this relative
// tolerance (its step is its CFL choice, within 2e-6 relative of the fixed step compared).
constexpr double kPeerTolerance = 0.05;
// The peer's grid: cells of its domain (the scenes' own grid has another count).
constexpr int kPeerCells = 52;
// A rigid translation is exact to round-off in both codes: the largest position error over the
// run, in the peer's length unit (its cell), must stay below this in each.
constexpr double kRoundOffCells = 1e-9;

// The scene's reference amplitude and run length: those of its trade rows.
struct Reference {
  double A = 0, T = 0;
};
std::map<std::string, Reference> references(const std::vector<ojson>& rows) {
  // The trade rows are the first rows of each scene (the spec lists them first); a scene's
  // reference is its first row's.
  std::map<std::string, Reference> out;
  for (const auto& r : rows) {
    const std::string scene = text(r, "scene");
    if (scene == "bar" || out.count(scene)) continue;
    out[scene] = {num(r, "A"), num(r, "T")};
  }
  return out;
}

Part part_of(const ojson& r, const std::map<std::string, Reference>& ref) {
  const std::string scene = text(r, "scene");
  if (scene == "bar") return Part::interior;
  if (num(r, "cells") == kPeerCells) return Part::peer;
  if (small_mass_of(r) != "none") return Part::treatment;
  const Reference& f = ref.at(scene);
  const bool cfl = text(r, "policy") == "cfl";
  if (!cfl || num(r, "A") != f.A || num(r, "T") != f.T ||
      num(r, "cfl_factor") > 2 * kReferenceCourant)
    return Part::extreme;
  return Part::trade;
}

// The error over time (or in L2) per A: the scenes' yardstick.
std::optional<double> relative(const ojson& r, const char* column) {
  const auto v = opt(r, column);
  if (!v || !has_number(r, "A") || num(r, "A") <= 0) return std::nullopt;
  return *v / num(r, "A");
}

bool at_reference(const ojson& r) {
  return has_number(r, "cfl_factor") && num(r, "cfl_factor") == kReferenceCourant;
}

// The scene_edges rows by (scene, method, small_mass).
using EdgeKey = std::tuple<std::string, std::string, std::string>;
std::map<EdgeKey, ojson> edges_of(const StudyInputs& inputs) {
  std::map<EdgeKey, ojson> out;
  const auto it = inputs.find("scene_edges");
  if (it == inputs.end() || !it->second.present()) return out;
  for (const auto& r : it->second.doc["cases"])
    out[{text(r, "scene"), RunRow(r).method, small_mass_of(r)}] = r;
  return out;
}
// The survival edge of a (scene, method, treatment) as the tables print it.
std::string edge_text(const std::map<EdgeKey, ojson>& edges, const EdgeKey& key) {
  const auto it = edges.find(key);
  return it == edges.end() ? "–" : mpmstab::edge_text(it->second);
}

std::vector<std::string> scenes_in_order(const std::vector<ojson>& rows) {
  std::vector<std::string> out;
  for (const auto& r : rows)
    if (text(r, "scene") != "bar") add_unique(out, text(r, "scene"));
  return out;
}

// A history row's value `key` per A, empty where the row has none.
std::string over_A(const ojson& row, const char* key, double A) {
  const auto it = row.find(key);
  return it != row.end() && it->is_number() ? sci(it->get<double>() / A, 6) : "";
}

// A peer row's error beside ours: our error `ours` in the peer's length unit (its cell: this grid's
// h), and the peer's final largest particle error in `problem` with the row's basis (linear for
// mpm, the peer's GIMP for cpgimp).
std::pair<std::optional<double>, std::optional<double>> beside_peer(const ojson& r,
                                                                    std::optional<double> ours,
                                                                    const CsvTable& peer,
                                                                    const std::string& problem) {
  const std::string basis = RunRow(r).method == "mpm" ? "linear" : "GIMP";
  std::optional<double> theirs;
  for (const auto& row : peer.rows)
    if (row.at("problem") == problem && row.at("basis") == basis &&
        row.at("quantity") == "final_max_abs_displacement_error")
      theirs = std::stod(row.at("peer_value"));
  return {ours ? std::optional(*ours * num(r, "cells")) : std::nullopt, theirs};
}

std::string scenes_data(const std::vector<ojson>& rows, const SweepOutcome& out,
                        const std::map<std::string, Reference>& ref, const std::string& header) {
  const auto scenes = scenes_in_order(rows);
  std::map<std::string, int> series;
  for (const auto& r : rows)
    if (part_of(r, ref) == Part::trade) series.emplace(RunRow(r).method, 0);
  int k = 0;
  for (auto& [m, s] : series)
    s = k++;
  std::ostringstream csv;
  csv << header << "panel,series,scene,method,t,error_over_A,tip_over_A,tip_exact_over_A\n";
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const ojson& r = rows[i];
    if (part_of(r, ref) != Part::trade || !at_reference(r)) continue;
    const ojson& record = out.records[i];
    if (!record.is_object() || !record.contains("history")) continue;
    const auto& h = record["history"];
    const int panel =
        int(std::find(scenes.begin(), scenes.end(), text(r, "scene")) - scenes.begin());
    const std::size_t stride = std::max<std::size_t>(1, h.size() / kFigurePoints);
    for (std::size_t j = 0; j < h.size(); j += stride) {
      if (!h[j]["error"].is_number()) continue;
      csv << panel << "," << series[RunRow(r).method] << "," << text(r, "scene") << ","
          << RunRow(r).method << "," << shortest(h[j]["time"].get<double>()) << ","
          << sci(h[j]["error"].get<double>() / num(r, "A"), 4) << ","
          << over_A(h[j], "tip_u", num(r, "A")) << "," << over_A(h[j], "tip_u_exact", num(r, "A"))
          << "\n";
    }
  }
  return csv.str();
}

// The runs at the reference Courant number with and without each small-mass treatment, by scene
// and method.
using Treated = std::map<std::pair<std::string, std::string>, std::map<std::string, ojson>>;

// Each small-mass treatment against no treatment, over the (scene, method) pairs that ran both:
// a run is good when it is stable over at least a wave pass (not unstable, not meaningless). A
// pair with a run too short for a verdict (under a wave pass, or too few steps) is left out.
struct TreatmentCount {
  int rescued = 0, rescued_accurate = 0, failing = 0, broken = 0, good = 0, short_pairs = 0;
  Coverage at;  // where the pairs counted lie (run_row.hpp)
};

// One treatment against none.
TreatmentCount treatment_count(const Treated& treated, const char* treatment) {
  auto has_verdict = [](const RunRow& r) {
    return r.ending() == Ending::stable || r.ending() == Ending::unstable ||
           r.ending() == Ending::meaningless;
  };
  TreatmentCount n;
  for (const auto& [key, by] : treated) {
    const auto none = by.find("none"), it = by.find(treatment);
    if (none == by.end() || it == by.end()) continue;
    const RunRow without(none->second), with(it->second);
    if (!has_verdict(without) || !has_verdict(with)) {
      ++n.short_pairs;
      continue;
    }
    const bool stable_with = with.ending() == Ending::stable;
    n.at.add(without);
    n.at.add(with);
    if (without.ending() != Ending::stable) {
      ++n.failing;
      n.rescued += stable_with;
      n.rescued_accurate += with.accurate();
    } else {
      ++n.good;
      n.broken += !stable_with;
    }
  }
  return n;
}

// What the study finds, from its rows and the peer's table: the scenes, each one's reference,
// the interior limits, the runs with and without each treatment; how many runs the figure draws
// and how many have a verdict; the dense limit against the interior one (lowered for the
// B-splines and for the others, the range of the ratio); the peers matched; each treatment
// against none; the trade (the pairs whose error does not fall by a factor 2 with the step);
// where the rows each claim reads lie (run_row.hpp): every run, the runs whose limits are
// compared, the peers' runs, the trade's pairs.
struct Findings {
  std::map<std::string, Reference> ref;
  std::vector<std::string> scenes;
  std::map<std::string, double> interior;
  Treated treated;
  int runs = 0, at_reference = 0, verdicts = 0;
  int spline_lowered = 0, splines = 0, other_lowered = 0, others = 0, limits_compared = 0;
  double ratio_lo = 1e300, ratio_hi = 0;
  int peer_compared = 0, peer_agree = 0, rigid_compared = 0, rigid_agree = 0;
  std::map<std::string, TreatmentCount> treatments;
  int trade_pairs = 0, trade_flat = 0;
  double trade_worst = 0;
  Coverage all_at, limits_at, peer_at, rigid_at, trade_at;
};

// The peers' rows matched: within kPeerTolerance on the impulsive bar, rigid to round-off on the
// block.
void find_peers(const ojson& r, const CsvTable& peer, Findings& f) {
  const RunRow rr(r);
  if (text(r, "scene") == "impulsive") {
    const auto [in_cells, theirs] = beside_peer(r, opt(r, "max_error"), peer, "impulsiveBar");
    ++f.peer_compared;
    f.peer_at.add(r);
    f.peer_agree +=
        rr.survived() && theirs && in_cells && std::abs(*in_cells / *theirs - 1) <= kPeerTolerance;
  } else if (text(r, "scene") == "block") {
    const auto [in_cells, theirs] = beside_peer(r, rr.error_over_time, peer, "advectBlock");
    ++f.rigid_compared;
    f.rigid_at.add(r);
    f.rigid_agree += rr.survived() && theirs && in_cells && *in_cells < kRoundOffCells &&
                     *theirs < kRoundOffCells;
  }
}

// The findings of the rows and the peer's table.
Findings find(const Spec& spec, const std::vector<ojson>& rows) {
  Findings f{.ref = references(rows), .scenes = scenes_in_order(rows)};
  for (const auto& r : rows)  // the interior (Bloch) limit of each method, from the bar rows
    if (const RunRow run(r); part_of(r, f.ref) == Part::interior && run.courant_spectral)
      f.interior[run.method] = *run.courant_spectral;
  const CsvTable peer = read_csv(spec.reference);
  // The trade's error per A and run, by scene, method and c dt/h.
  std::map<std::pair<std::string, std::string>, std::map<Key, std::pair<double, const ojson*>>> err;
  f.runs = int(rows.size());
  for (const auto& r : rows) {
    f.verdicts += !outcome(r).empty();
    f.all_at.add(r);
    const Part part = part_of(r, f.ref);
    const RunRow run(r);
    if (part == Part::peer) find_peers(r, peer, f);
    if (part == Part::treatment || (part == Part::trade && at_reference(r)))
      f.treated[{text(r, "scene"), run.method}][small_mass_of(r)] = r;
    if (part != Part::trade) continue;
    if (const auto e = run.error_over_A(); e && run.survived())
      err[{text(r, "scene"), run.method}][Key(num(r, "cfl_factor"), "cfl_factor")] = {*e, &r};
    if (!at_reference(r)) continue;
    ++f.at_reference;
    const auto it = f.interior.find(run.method);
    if (!run.courant_spectral || it == f.interior.end()) continue;
    const double x = *run.courant_spectral / it->second;
    ++f.limits_compared;
    f.limits_at.add(r);
    const bool spline = run.method.rfind("bspline", 0) == 0;
    (spline ? f.splines : f.others) += 1;
    (spline ? f.spline_lowered : f.other_lowered) += x < 1 - kLimitDrop;
    f.ratio_lo = std::min(f.ratio_lo, x);
    f.ratio_hi = std::max(f.ratio_hi, x);
  }
  for (const char* treatment : {"cutoff", "drop", "momentum"})
    f.treatments[treatment] = treatment_count(f.treated, treatment);
  for (const auto& [key, by] : err) {
    if (by.size() < 2) continue;
    ++f.trade_pairs;
    for (const auto& [courant, run] : by)
      f.trade_at.add(*run.second);
    const double gain = by.rbegin()->second.first / by.begin()->second.first;
    f.trade_worst = std::max(f.trade_worst, gain);
    f.trade_flat += gain < 2;
  }
  return f;
}

// 1. Per scene and method, at the reference Courant number.
std::string per_scene_section(const std::vector<ojson>& rows,
                              const std::map<std::string, Reference>& ref,
                              const std::map<std::string, double>& interior,
                              const std::map<EdgeKey, ojson>& edges) {
  std::ostringstream md;
  md << "## Per scene and method\n\nAt c dt/h = " << shortest(kReferenceCourant)
     << ", no small-mass treatment.\n\n"
        "| scene | method | verdict | error over time / A | L2 / A | cost | edge c dt/h | "
        "dense limit | interior limit | dense / interior |\n"
        "|---|---|---|---:|---:|---:|---:|---:|---:|---:|\n";
  for (const auto& r : rows) {
    if (part_of(r, ref) != Part::trade || !at_reference(r)) continue;
    const RunRow run(r);
    const std::string method = run.method;
    const auto dense = run.courant_spectral;
    const auto it = interior.find(method);
    const std::string q = dense && it != interior.end() ? fixed(*dense / it->second, 3) : "–";
    md << "| " << text(r, "scene") << " | " << method << " | " << verdict(r) << " | "
       << opt_sci(RunRow(r).error_over_A()) << " | " << opt_sci(relative(r, "error_l2_time"))
       << " | " << work(r) << " | " << edge_text(edges, {text(r, "scene"), method, "none"}) << " | "
       << opt_fixed(dense) << " | " << (it == interior.end() ? "–" : fixed(it->second, 3)) << " | "
       << q << " |\n";
  }
  return md.str();
}

// 2. The trade: every run of it.
std::string trade_section(const std::vector<ojson>& rows,
                          const std::map<std::string, Reference>& ref) {
  std::ostringstream md;
  md << "\n## The speed/accuracy trade\n\nError over time / A and cost at each c dt/h, no "
        "small-mass treatment.\n\n| scene | method | c dt/h | verdict | error over time / A | "
        "cost |\n|---|---|---:|---|---:|---:|\n";
  for (const auto& r : rows) {
    if (part_of(r, ref) != Part::trade) continue;
    md << "| " << text(r, "scene") << " | " << RunRow(r).method << " | "
       << shortest(num(r, "cfl_factor")) << " | " << verdict(r) << " | "
       << opt_sci(RunRow(r).error_over_A()) << " | " << work(r) << " |\n";
  }
  return md.str();
}

// 4. The extremes: every run of them, and how many runs of the study have a verdict.
std::string extremes_section(const std::vector<ojson>& rows,
                             const std::map<std::string, Reference>& ref) {
  std::ostringstream md;
  md << "\n## Extremes\n\nEvery scene far beyond its reference: above the limit in c dt/h, a "
        "large amplitude, a long run. Each run ends with a verdict.\n\n| scene | method | c dt/h "
        "| A/h | c T | verdict | error over time / A |\n|---|---|---:|---:|---:|---|---:|\n";
  for (const auto& r : rows) {
    if (part_of(r, ref) != Part::extreme) continue;
    md << "| " << text(r, "scene") << " | " << RunRow(r).method << " | "
       << shortest(num(r, "cfl_factor")) << " | " << significant(num(r, "A_over_h"), 3) << " | "
       << significant(*RunRow(r).wave_passes, 3) << " | " << verdict(r) << " | "
       << opt_sci(RunRow(r).error_over_A()) << " |\n";
  }
  return md.str();
}

// 3. Small-mass treatments.
std::string small_mass_section(const Treated& treated, const std::map<EdgeKey, ojson>& edges) {
  std::ostringstream md;
  md << "\n## Small-mass nodes\n\nAt c dt/h = " << shortest(kReferenceCourant)
     << " (docs/theory.md, \"Small-mass nodes\"): the verdict and error of each treatment, "
        "and its survival edge.\n\n| scene | method | treatment | verdict | error over time / A "
        "| edge c dt/h |\n|---|---|---|---|---:|---:|\n";
  for (const auto& [key, by] : treated) {
    if (by.size() < 2) continue;  // a method run without treatments
    for (const char* t : {"none", "cutoff", "drop", "momentum"}) {
      const auto it = by.find(t);
      if (it == by.end()) continue;
      md << "| " << key.first << " | " << key.second << " | " << t << " | " << verdict(it->second)
         << " | " << opt_sci(RunRow(it->second).error_over_A()) << " | "
         << edge_text(edges, {key.first, key.second, t}) << " |\n";
    }
  }
  return md.str();
}

// 5. and 6. Beside Uintah's impulsiveBar and advectBlock.
std::string peer_sections(const ReportContext& ctx, const std::map<std::string, Reference>& ref,
                          const CsvTable& peer) {
  const auto& rows = ctx.rows;
  std::ostringstream md;
  md << "\n## Beside Uintah's impulsiveBar\n\nUintah's 1D MPM code, AMRMPM.m, run on its "
        "impulsively loaded bar (["
     << ctx.spec.reference.filename().string() << "](../reference/peers/"
     << ctx.spec.reference.filename().string()
     << ") and its notes beside it): the same bar in this grid's units (lengths over the "
        "peer's domain), its effective tip traction and end time, its basis (linear, and the "
        "cpGIMP it runs as GIMP). Both errors are the largest |u_p - u(X_p, T)| over the "
        "particles at the peer's end time, in the peer's length unit; the tolerance is "
     << percent(kPeerTolerance)
     << ".\n\n| method | outcome | peer outcome | error | peer error | "
        "ratio |\n|---|---|---|---:|---:|---:|\n";
  for (const auto& r : rows) {
    if (part_of(r, ref) != Part::peer || text(r, "scene") != "impulsive") continue;
    const auto [in_cells, theirs] = beside_peer(r, opt(r, "max_error"), peer, "impulsiveBar");
    md << "| " << RunRow(r).method << " | " << outcome(r) << " | stable | " << opt_sci(in_cells)
       << " | " << opt_sci(theirs) << " | "
       << (in_cells && theirs ? fixed(*in_cells / *theirs, 5) : "–") << " |\n";
  }

  md << "\n## Beside Uintah's advectBlock\n\nThe same code's block at its own setting: a "
        "bar two cells shorter than its domain, moving at a constant speed (A c in this grid's "
        "units, the block's length and speed over the peer's domain) until the code stops it, "
        "at its fixed dt; here on a periodic grid, since the peer prescribes the block's "
        "velocity at its end nodes, which a periodic grid makes unnecessary. Both "
        "errors are the largest |u_p - u(X_p, t)| over the particles and the steps, in the "
        "peer's length unit; a rigid translation is exact but for round-off, so both must stay "
        "below "
     << sci(kRoundOffCells, 1)
     << " cells.\n\n| method | steps | outcome | peer outcome | error over time | peer error "
        "|\n|---|---:|---|---|---:|---:|\n";
  for (const auto& r : rows) {
    if (part_of(r, ref) != Part::peer || text(r, "scene") != "block") continue;
    const RunRow rr(r);
    const auto [in_cells, theirs] = beside_peer(r, rr.error_over_time, peer, "advectBlock");
    md << "| " << rr.method << " | " << shortest(num(r, "steps")) << " | " << rr.outcome
       << " | stable | " << opt_sci(in_cells) << " | " << opt_sci(theirs) << " |\n";
  }
  return md.str();
}

// The claims on the peers, the verdicts and the limits.
std::vector<Claim> survey_claims(const Findings& n) {
  Claim rigid = claim("rigid-like-uintah-advect-block",
                      "On Uintah's advectBlock at its own setting, every basis compared survives "
                      "and keeps the block rigid to round-off in both codes (position error over "
                      "the run below {tolerance} cells): {agree} of {compared}.");
  rigid.value("tolerance", sci(kRoundOffCells, 1))
      .every("agree", n.rigid_agree, "compared", n.rigid_compared)
      .on(n.rigid_at);
  Claim peer =
      claim("agrees-with-uintah-impulsive",
            "On Uintah's impulsiveBar at its own setting, every basis compared has the "
            "peer's outcome and its final error within {tolerance}: {agree} of {compared}.");
  peer.value("tolerance", percent(kPeerTolerance))
      .every("agree", n.peer_agree, "compared", n.peer_compared)
      .on(n.peer_at);
  Claim verdicts = claim("every-run-has-a-verdict",
                         "Every run ends with a verdict (unstable, meaningless or stable): {with} "
                         "of {runs}.");
  verdicts.every("with", n.verdicts, "runs", static_cast<long long>(n.runs)).on(n.all_at);
  Claim c = claim("free-surface-lowers-only-spline-limits",
                  "The free surface lowers the spectral limit (the dense limit of the body more "
                  "than {tolerance} below the interior one) for each B-spline pair (scene and "
                  "B-spline basis run here) and for no other method: {spline_lowered} of "
                  "{splines} B-spline pairs, {other_lowered} of {others} others (dense over "
                  "interior from {lo} to {hi}).");
  c.value("tolerance", percent(kLimitDrop));
  c.count("spline_lowered", n.spline_lowered).count("splines", n.splines);
  c.count("other_lowered", n.other_lowered).count("others", n.others);
  c.number("lo", n.limits_compared ? n.ratio_lo : 0, 3).number("hi", n.ratio_hi, 3);
  c.holds = n.splines > 0 && n.others > 0 && n.spline_lowered == n.splines && n.other_lowered == 0;
  return {rigid, peer, verdicts, c.on(n.limits_at)};
}

// Each treatment against no treatment, and whether a smaller step buys accuracy.
std::vector<Claim> treatment_and_trade_claims(const Findings& f) {
  std::vector<Claim> claims;
  for (const auto& [treatment, n] : f.treatments) {
    Claim c = claim(std::string("small-mass-") + treatment,
                    "The {treatment} treatment makes every run that is not stable without a "
                    "treatment stable, and no stable run worse: {rescued} of {failing} made "
                    "stable ({accurate} of them accurate), {broken} of {good} made unstable or "
                    "meaningless; {short} pairs with a run too short for a verdict (under a "
                    "wave pass, or too few steps) are not counted.");
    c.count("short", n.short_pairs);
    c.value("treatment", treatment).count("rescued", n.rescued).count("failing", n.failing);
    c.count("accurate", n.rescued_accurate);
    c.count("broken", n.broken).count("good", n.good);
    c.holds = n.failing > 0 && n.rescued == n.failing && n.broken == 0;
    claims.push_back(c.over(n.failing).on(n.at));  // a rescue of one run is not "every run"
  }
  Claim c = claim("space-error-dominates",
                  "At these settings the error does not move with the step: from the largest "
                  "to the smallest c dt/h of the trade the error falls by less than a factor "
                  "{factor} in {flat} of {pairs} scene and method pairs (the largest fall is "
                  "{worst}).");
  claims.push_back(c.number("factor", 2)
                       .every("flat", f.trade_flat, "pairs", f.trade_pairs)
                       .number("worst", f.trade_worst, 3)
                       .on(f.trade_at));
  return claims;
}

StudyReport scenes_report(const ReportContext& ctx) {
  const auto& rows = ctx.rows;
  const Findings f = find(ctx.spec, rows);
  const auto edges = edges_of(ctx.inputs);
  Coverage edges_at;  // where the edges' searches lie
  for (const auto& [key, r] : edges)
    edges_at.add(r);
  std::ostringstream md;
  md << "**The measures** (docs/theory.md, \"Scenes\"): *error over time / A*, the largest "
        "|u_p - u(X_p, t)| over the particles and the steps, per the scene's displacement scale "
        "A; *L2 / A*, the RMS over the body and the run; *cost*, particle-steps. *Dense limit*: "
        "the spectral limit, in c dt/h, of the whole body with its free surfaces; *interior*: "
        "the Bloch limit of the same scheme on a periodic lattice; *edge*: the survival edge "
        "in c dt/h from [scene_edges.md](scene_edges.md), searched at "
     << (edges_at.empty() ? std::string("–") : edges_at.text())
     << " (none where that experiment has not been run).\n\n"
     << cost_metric_text() << "\n\n";

  md << per_scene_section(rows, f.ref, f.interior, edges) << trade_section(rows, f.ref)
     << small_mass_section(f.treated, edges) << extremes_section(rows, f.ref)
     << peer_sections(ctx, f.ref, read_csv(ctx.spec.reference));
  std::vector<Claim> claims = survey_claims(f);
  for (auto& c : treatment_and_trade_claims(f))
    claims.push_back(std::move(c));
  return StudyReport{.markdown = md.str(),
                     .data_csv = scenes_data(rows, ctx.outcome, f.ref, ctx.csv_header),
                     .claims = std::move(claims)};
}

std::string scenes_subtitle(const Spec& spec, const ojson& doc) {
  const Findings f = find(spec, std::vector<ojson>(doc["cases"].begin(), doc["cases"].end()));
  return std::to_string(f.at_reference) + " runs at c dt/h = " + shortest(kReferenceCourant) +
         "; error over time per A";
}

std::string scenes_index(const Spec& spec, const std::vector<ojson>& rows, const ojson&) {
  const Findings f = find(spec, rows);
  std::ostringstream md;
  md << "![" << spec.title << "](" << spec.name << ".png)\n\n**What it shows.** " << f.scenes.size()
     << " scenes (" << list_of(f.scenes)
     << ") against their exact solutions, per method: the error over time, the free end's "
        "motion beside the exact one, and the cost at three Courant numbers, the dense spectral "
        "limit of each body with its free surfaces against the interior limit, the survival "
        "edge, the small-mass treatments and an extremes battery, in "
     << f.runs << " runs. [" << spec.name << ".md](" << spec.name << ".md)\n";
  return md.str();
}

const StudyRegistration kScenes{{
    .name = "scenes",
    .summary = "scenes with free surfaces, loads and impact: error, cost, limits, small mass",
    .needs_reference = true,
    .records = {.error_over_time = true, .history = true},
    .inputs = {{.name = "scene_edges"}},
    .figure = true,
    .report = scenes_report,
    .index = scenes_index,
    .figure_subtitle = scenes_subtitle,
}};

}  // namespace
}  // namespace mpmstab::studies::scenes
