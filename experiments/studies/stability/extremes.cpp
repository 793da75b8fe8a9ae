// The extremes: verdicts over extreme parameters (Courant numbers from far below 1 to far above
// it, amplitudes from a tiny fraction of a cell to many cells), and per method where and why it
// fails.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <map>
#include <optional>
#include <sstream>
#include <tuple>

#include "base/accuracy.hpp"
#include "base/params.hpp"
#include "claims.hpp"
#include "csv.hpp"
#include "report_util.hpp"
#include "run_row.hpp"
#include "study.hpp"

namespace mpmstab::studies::extremes {
namespace {

using ojson = nlohmann::ordered_json;

// 0 stable, 1 stable but meaningless, 2 unstable, 3 too short to judge (reached T in fewer
// than kMinStepsToJudge steps: no verdict on its stability).
// The verdicts in the order of their codes in extremes_data.csv (the figure's colours).
const std::vector<std::string> kVerdicts = {"stable", "meaningless", "unstable", "too_short"};

int verdict_code(const RunRow& r) {
  const auto it = std::find(kVerdicts.begin(), kVerdicts.end(), r.outcome);
  return it == kVerdicts.end() ? 0 : int(it - kVerdicts.begin());
}

// The quantities a run that reached T reports, and which of them it measures. Eq. (108) is
// derived for MPM, GIMP and cpGIMP only (has_eq108): for the other bases dt_stable_min is null
// because it is not measured, not because it is not finite.
const std::vector<const char*> kSurvivorOutputs = {
    "max_error", "max_error_over_time", "dt_stable_min", "dt_min", "dt_max", "dt_mean", "courant",
    "crossings"};

// What a run that reached T reports: how many of its measured quantities are null or not finite
// (JSON has no NaN: a NaN or an infinity is written as null, so a measured quantity that is null
// is one), and how many are null because they are not measured.
struct OutputCheck {
  int non_finite = 0;
  int not_measured = 0;
};

OutputCheck check_outputs(const ojson& r) {
  OutputCheck c;
  const auto method = parse_method(RunRow(r).method);
  for (const char* key : kSurvivorOutputs) {
    const bool number = r.contains(key) && r[key].is_number();
    if (key == std::string_view("dt_stable_min") && !(method && has_eq108(*method))) {
      c.not_measured += !number;
    } else if (!number || !std::isfinite(r[key].get<double>())) {
      ++c.non_finite;
    }
  }
  return c;
}

// Failure reasons with their counts: "left_domain 1, nonpositive_F 73".
std::string reason_counts(const std::map<std::string, int>& reasons) {
  std::string s;
  for (const auto& [reason, n] : reasons)
    s += (s.empty() ? "" : ", ") + reason + " " + std::to_string(n);
  return s;
}

// The case with the most work (particle-steps, deterministic): its work and its parameters.
struct Slowest {
  double work = 0;
  std::string name;
};

Slowest slowest_case(const std::vector<ojson>& rows) {
  Slowest slowest;
  for (const auto& r : rows) {
    if (particle_steps(r) > slowest.work) {
      slowest.work = particle_steps(r);
      slowest.name = method_label(r) + " E=" + shortest(r["E"].get<double>()) +
                     " A=" + shortest(r["A"].get<double>()) +
                     " dt=" + param(r["dt"].get<double>()) + " cells=" + r["cells"].dump() +
                     " ppc=" + r["ppc"].dump();
    }
  }
  return slowest;
}

// What the opening and the conclusions count, from the rows.
struct Counts {
  int total = 0, with_verdict = 0;
  // How the runs ended (run_row.hpp): stable over at least kMinWavePasses wave passes, accurate
  // or inaccurate (an error over time that is not recorded is not accurate: inaccurate() counts
  // it), or over fewer (counted apart), meaningless, too short, unstable by reason.
  VerdictTally verdicts;
  std::vector<double> under_a_pass_cT;  // c T of those counted apart
  long long too_short_min = 0, too_short_max = 0;
  int reached = 0;            // runs that reached T (stable, meaningless or too short)
  int non_finite = 0;         // ... with a measured quantity null or not finite
  int not_measured = 0;       // ... with a quantity null because it is not measured
  int few_step_verdicts = 0;  // stable or meaningless verdicts on fewer than kMinStepsToJudge
  // Runs above their scheme's spectral limit (courant > courant_spectral).
  int above = 0, above_failed = 0, above_too_short = 0, above_survived = 0;
  long long above_survivor_steps = 0;   // the most steps an above-limit survivor took
  double above_survivor_ratio = 0;      // the largest c dt/h over the limit of a survivor
  int above_survivor_under_a_pass = 0;  // survivors of fewer than kMinWavePasses wave passes
  // Where the runs each claim counts lie (run_row.hpp): every case, those that reached T, those
  // above the limit long enough to judge, those counted stable.
  Coverage all_at, reached_at, above_judged_at, stable_at;
  // The runs the solver calls stable, over a wave pass or not.
  int solver_stable() const { return verdicts.stable + verdicts.under_a_wave_pass; }
  int inaccurate() const { return verdicts.inaccurate + verdicts.unmeasured; }
  int unstable() const { return total - reached; }
};

Counts count_rows(const std::vector<ojson>& rows) {
  Counts c;
  c.total = static_cast<int>(rows.size());
  for (const auto& row : rows) {
    const RunRow r(row);
    c.with_verdict += !r.outcome.empty();
    c.verdicts.add(r);
    c.all_at.add(r);
    if (r.ending() == Ending::stable) c.stable_at.add(r);
    const int v = verdict_code(r);
    const long long steps = r.steps.value_or(0);
    if (v != 2) {
      if (r.under_a_wave_pass()) c.under_a_pass_cT.push_back(*r.wave_passes);
      if (v == 3) {
        c.too_short_min = c.verdicts.too_short > 1 ? std::min(c.too_short_min, steps) : steps;
        c.too_short_max = std::max(c.too_short_max, steps);
      }
      if (v < 3 && steps < kMinStepsToJudge) ++c.few_step_verdicts;
      ++c.reached;
      c.reached_at.add(r);
      const OutputCheck out = check_outputs(row);
      c.non_finite += out.non_finite > 0;
      c.not_measured += out.not_measured > 0;
    }
    if (!r.above_spectral_limit()) continue;
    const double over = *r.courant / *r.courant_spectral;
    ++c.above;
    if (v != 3) c.above_judged_at.add(r);
    if (v == 2) {
      ++c.above_failed;
    } else if (v == 3) {
      ++c.above_too_short;
    } else {
      ++c.above_survived;
      c.above_survivor_under_a_pass += r.under_a_wave_pass();
      c.above_survivor_steps = std::max(c.above_survivor_steps, steps);
      c.above_survivor_ratio = std::max(c.above_survivor_ratio, over);
    }
  }
  return c;
}

// The opening: how many cases reached each verdict and why the unstable ones failed, the runs
// too short to judge, whether any output holds a NaN or an infinity, the slowest case, and the
// figure.
std::string extremes_summary(const Spec& spec, const Counts& c, const Slowest& slowest) {
  std::ostringstream md;
  md << "## Results\n\n**Summary.** " << c.total << " cases, " << c.with_verdict
     << " with a verdict. " << c.solver_stable() << " reached T in at least " << kMinStepsToJudge
     << " steps with an error over time below A (the solver's outcome stable); of these, "
     << c.verdicts.accurate + c.inaccurate() << " ran at least c T = " << shortest(kMinWavePasses)
     << " wave pass and are counted as stable here: " << c.verdicts.accurate
     << " accurate (error over "
     << "time below " << shortest(kAccurateFraction) << " A) and " << c.inaccurate()
     << " inaccurate";
  if (!c.verdicts.inaccurate_errors.empty())
    md << " (error over time " << span(c.verdicts.inaccurate_errors, 2) << " A)";
  md << "; the other " << c.verdicts.under_a_wave_pass << " ran fewer wave passes";
  if (!c.under_a_pass_cT.empty()) md << " (c T " << span(c.under_a_pass_cT, 2) << ")";
  md << ", too short to count as stable, and are counted apart. " << c.verdicts.meaningless
     << " meaningless (survived, but the error over time reached A), " << c.unstable()
     << " unstable (" << reason_counts(c.verdicts.reasons) << ")";
  if (c.verdicts.too_short) {
    md << ", " << c.verdicts.too_short << " too short to judge (they reached T in "
       << c.too_short_min << " to " << c.too_short_max << " steps, fewer than " << kMinStepsToJudge
       << ": no verdict on their stability)";
  }
  md << ". Runs that reached T with a measured quantity that is a NaN or an infinity: "
     << c.non_finite << " of " << c.reached;
  if (c.not_measured) {
    md << " (" << c.not_measured
       << " report dt_stable_min as not measured: eq. (108) is defined for MPM, GIMP and "
          "cpGIMP only)";
  }
  md << ". The largest case took " << sci(slowest.work) << " particle-steps (" << slowest.name
     << ").\n\n"
     << "![" << spec.title << "](" << spec.name << ".png)\n\nVector version: [" << spec.name
     << ".svg](" << spec.name << ".svg); data: [" << spec.name << "_data.csv](" << spec.name
     << "_data.csv).\n\n";
  return md.str();
}

// The conclusions, each decided by the counts.
std::vector<Claim> extremes_claims(const Counts& c) {
  std::vector<Claim> claims;
  Claim verdicts = claim("every-case-has-a-verdict", "Every case ends with a verdict",
                         "{with} of {total} cases have one");
  claims.push_back(verdicts.every("with", c.with_verdict, "total", c.total).on(c.all_at));

  Claim finite = claim("outputs-finite",
                       "No run that reached T reports a NaN or an infinity in a quantity it "
                       "measures",
                       "{bad} of {reached} do; {unmeasured} report dt_stable_min as not measured "
                       "(eq. (108) is not defined for their basis), which is not counted");
  finite.count("bad", c.non_finite).count("reached", c.reached).count("unmeasured", c.not_measured);
  finite.holds = c.non_finite == 0;
  claims.push_back(finite.over(c.reached).on(c.reached_at));

  Claim enough = claim("verdicts-rest-on-enough-steps",
                       "No stable or meaningless verdict rests on fewer than {min} steps",
                       "{few} do; {short} runs that reached T in fewer are reported as too short "
                       "to judge");
  enough.count("min", kMinStepsToJudge)
      .count("few", c.few_step_verdicts)
      .count("short", c.verdicts.too_short);
  enough.holds = c.few_step_verdicts == 0;
  claims.push_back(enough.on(c.reached_at));

  Claim above = claim("above-limit-fails",
                      "Every run above its scheme's spectral limit that is long enough to judge "
                      "fails",
                      "{failed} of {judged} fail; {survived} survive (the longest ran {steps} "
                      "steps, at most {ratio} times the limit; {survived_short} of them ran under "
                      "c T = {passes} wave pass); {short} more are too short to judge");
  above.count("failed", c.above_failed)
      .count("judged", c.above_failed + c.above_survived)
      .count("survived", c.above_survived)
      .count("steps", c.above_survivor_steps)
      .value("ratio", c.above_survived ? fixed(c.above_survivor_ratio, 5) : "–")
      .count("survived_short", c.above_survivor_under_a_pass)
      .value("passes", shortest(kMinWavePasses))
      .count("short", c.above_too_short)
      .over(c.above_failed + c.above_survived)
      .on(c.above_judged_at);
  above.holds = c.above_survived == 0;
  claims.push_back(above);

  Claim accurate = claim("stable-runs-accurate",
                         "Every run counted stable (it reached T over at least {passes} wave "
                         "pass) is accurate: its error over time stays below {fraction} A",
                         "{accurate} of {stable} are accurate, {inaccurate} inaccurate; {apart} "
                         "runs the solver calls stable ran fewer wave passes and are not counted");
  accurate.value("passes", shortest(kMinWavePasses))
      .value("fraction", shortest(kAccurateFraction))
      .every("accurate", c.verdicts.accurate, "stable", c.verdicts.accurate + c.inaccurate());
  accurate.count("inaccurate", c.inaccurate()).count("apart", c.verdicts.under_a_wave_pass);
  claims.push_back(accurate.on(c.stable_at));
  return claims;
}

// A band of Courant numbers c dt/h or of amplitudes in cells A/h: lo <= x < hi.
struct Band {
  double lo, hi;
  const char* note = "";
};
constexpr double kUnbounded = std::numeric_limits<double>::infinity();
const std::vector<Band> kCourantBands = {{0, 0.5}, {0.5, 1}, {1, 10}, {10, kUnbounded}};
// From one cell of displacement on, particles cross cells.
constexpr double kCrossingAmplitude = 1;
const std::vector<Band> kAmplitudeBands = {
    {0, 1e-3},
    {1e-3, 0.1},
    {0.1, kCrossingAmplitude},
    {kCrossingAmplitude, kUnbounded, " (particles cross cells)"}};

// "c dt/h < 0.5", "1e-3 <= A/h < 0.1", "c dt/h >= 10".
std::string band_name(const Band& b, const std::string& x) {
  const std::string name = b.lo == 0 ? x + " < " + value_text(b.hi)
                           : b.hi == kUnbounded
                               ? x + " >= " + value_text(b.lo)
                               : value_text(b.lo) + " <= " + x + " < " + value_text(b.hi);
  return name + b.note;
}

// One band of one method: how many runs fall in it, by verdict, and the reasons of the failures.
// A run the solver calls stable is counted as VerdictTally (run_row.hpp) counts it: stable over
// at least kMinWavePasses wave passes, accurate or not (an error over time that is not recorded
// is not accurate), or too short in wave passes to count as stable.
struct BandCount {
  int runs = 0, accurate = 0, inaccurate = 0, under = 0, meaningless = 0, too_short = 0;
  std::map<std::string, int> why;
};

// Where one method fails: per band of the Courant number (`by_courant`) or of the amplitude in
// cells, its runs there.
std::vector<BandCount> band_counts(const std::vector<ojson>& rows, const std::string& method,
                                   const std::vector<Band>& bands, bool by_courant) {
  std::vector<BandCount> out;
  for (const auto& b : bands) {
    BandCount n;
    for (const auto& row : rows) {
      const RunRow r(row);
      if (r.method_label != method) continue;
      const double x = by_courant ? *r.courant : *r.A * row["cells"].get<double>();
      if (x < b.lo || x >= b.hi) continue;
      ++n.runs;
      const int v = verdict_code(r);
      if (v == 0)
        ++(r.under_a_wave_pass()                ? n.under
           : r.accuracy() == Accuracy::accurate ? n.accurate
                                                : n.inaccurate);
      n.meaningless += v == 1;
      n.too_short += v == 3;
      if (v == 2) ++n.why[*r.failure_reason];
    }
    out.push_back(n);
  }
  return out;
}

// One method's findings: its band tables and, above its spectral limit at each run's layout
// (the range of that limit), its counts; below it, how many runs fail and how many of those have
// particles crossing cells.
struct MethodFindings {
  std::string name;
  std::vector<BandCount> by_courant, by_amplitude;
  Counts counts;
  double limit_lo = 1e300, limit_hi = 0;  // limit_hi 0: no spectral limit recorded
  int below_failed = 0, below_failed_crossing = 0;
};

// The findings of one method's runs.
MethodFindings method_findings(const std::vector<ojson>& rows, const std::string& method) {
  MethodFindings f{.name = method,
                   .by_courant = band_counts(rows, method, kCourantBands, true),
                   .by_amplitude = band_counts(rows, method, kAmplitudeBands, false)};
  std::vector<ojson> mine;
  for (const auto& row : rows) {
    const RunRow r(row);
    if (r.method_label != method) continue;
    mine.push_back(row);
    if (!r.courant_spectral) continue;
    const double limit = *r.courant_spectral;
    f.limit_lo = std::min(f.limit_lo, limit);
    f.limit_hi = std::max(f.limit_hi, limit);
    if (!r.above_spectral_limit() && r.outcome == "unstable") {
      ++f.below_failed;
      f.below_failed_crossing += *r.A * row["cells"].get<double>() >= kCrossingAmplitude;
    }
  }
  f.counts = count_rows(mine);
  return f;
}

// One of a method's band tables.
std::string band_table(const std::vector<BandCount>& counts, const std::vector<Band>& bands,
                       bool by_courant) {
  std::ostringstream md;
  md << "| " << (by_courant ? "Courant number" : "amplitude in cells")
     << " | runs | stable, c T >= " << shortest(kMinWavePasses)
     << ": accurate | stable, c T >= " << shortest(kMinWavePasses)
     << ": inaccurate | survived, c T < " << shortest(kMinWavePasses)
     << ": too short to count | meaningless | too short to judge | unstable: reasons "
        "|\n|---|---|---|---|---|---|---|---|\n";
  for (std::size_t i = 0; i < bands.size(); ++i) {
    const BandCount& n = counts[i];
    md << "| " << band_name(bands[i], by_courant ? "c dt/h" : "A/h") << " | " << n.runs << " | "
       << n.accurate << " | " << n.inaccurate << " | " << n.under << " | " << n.meaningless << " | "
       << n.too_short << " | " << (n.why.empty() ? std::string("–") : reason_counts(n.why))
       << " |\n";
  }
  md << "\n";
  return md.str();
}

// The reading for one method: above its limit, where the runs long enough to judge lie and how
// many fail, how many survive and how long and how far above the limit they ran, how many are too
// short to judge;
// below it, how many fail and how many of those have particles crossing cells.
std::string method_reading(const MethodFindings& f) {
  const Counts& c = f.counts;
  std::ostringstream md;
  md << f.name << ": ";
  if (f.limit_hi == 0) return md.str() + "no spectral limit recorded. ";
  md << "above its spectral limit (c dt/h " << fixed(f.limit_lo, 3);
  if (f.limit_hi > f.limit_lo) md << " to " << fixed(f.limit_hi, 3);
  md << " at these layouts; runs on " << c.above_judged_at.text() << ") " << c.above_failed
     << " of " << c.above_failed + c.above_survived << " runs long enough to judge fail";
  if (c.above_survived) {
    md << ", " << c.above_survived << " survive (the longest ran " << c.above_survivor_steps
       << " steps, at most " << fixed(c.above_survivor_ratio, 5) << " times the limit; "
       << c.above_survivor_under_a_pass << " of them ran under c T = " << shortest(kMinWavePasses)
       << " wave pass)";
  }
  md << " and " << c.above_too_short << " are too short to judge. Below it, " << f.below_failed
     << " runs fail, " << f.below_failed_crossing << " of them with "
     << band_name(kAmplitudeBands.back(), "A/h") << ". ";
  return md.str();
}

// Every case: its parameters, Courant number, wave passes, verdict, error over time (and per A
// with its accuracy class where the run reached T stable or meaningless) and cost.
std::string every_case_table(const std::vector<ojson>& rows) {
  std::ostringstream md;
  md << "### Each case\n\n| method | bc | E | A | dt | T | cells | ppc | c dt/h | c T | verdict | "
        "max error over time | error over time / A | accuracy | particle-steps "
        "|\n|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n";
  for (const auto& r : rows) {
    const RunRow run(r);
    // The error over time per A of a run that reached T stable or meaningless.
    const auto e =
        run.outcome == "stable" || run.outcome == "meaningless" ? run.error_over_A() : std::nullopt;
    md << "| " << run.method_label << " | " << r["bc"].get<std::string>() << " | "
       << shortest(r["E"].get<double>()) << " | " << shortest(r["A"].get<double>()) << " | "
       << param(r["dt"].get<double>()) << " | " << param(r["T"].get<double>()) << " | "
       << r["cells"].dump() << " | " << r["ppc"].dump() << " | " << opt_sci(run.courant) << " | "
       << opt_sci(run.wave_passes) << " | " << verdict_word(r) << " | "
       << opt_sci(run.error_over_time) << " | " << opt_sci(e) << " | "
       << (e ? std::string(to_string(accuracy_class(*e, 1.0))) : std::string("–")) << " | "
       << work(r) << " |\n";
  }
  return md.str();
}

// The methods of the rows (method_label: the basis, then a transfer other than FLIP), the
// paper's first, then the other bases in a fixed order, then the rest as they first appear.
std::vector<std::string> methods_of(const std::vector<ojson>& rows) {
  const std::vector<std::string> order = {"gimp", "mpm", "cpgimp", "cpdi", "bspline2", "bspline3"};
  std::vector<std::string> present;
  for (const auto& r : rows)
    add_unique(present, method_label(r));
  std::stable_sort(present.begin(), present.end(), [&](const std::string& a, const std::string& b) {
    return std::find(order.begin(), order.end(), a) < std::find(order.begin(), order.end(), b);
  });
  return present;
}

// The cases drawn at one spot of the figure: a method, a Courant number, an amplitude in cells
// and a verdict. Many cases share a spot (they differ in E, T, cells or ppc): they are drawn once,
// with their count.
using Spot = std::tuple<int, std::string, std::string, int>;

// What the study finds, from its rows: the counts over every case, the slowest case, per method
// its bands and reading, and the spots of the figure.
struct Findings {
  Counts counts;
  Slowest slowest;
  std::vector<std::string> methods;  // methods_of
  std::vector<MethodFindings> per_method;
  std::map<Spot, int> spots;
};

// The findings of every case.
Findings find(const std::vector<ojson>& rows) {
  Findings f{
      .counts = count_rows(rows), .slowest = slowest_case(rows), .methods = methods_of(rows)};
  for (const std::string& method : f.methods)
    f.per_method.push_back(method_findings(rows, method));
  for (const auto& row : rows) {
    const RunRow r(row);
    const auto m = std::find(f.methods.begin(), f.methods.end(), r.method_label);
    ++f.spots[{int(m - f.methods.begin()), param(*r.courant),
               param(*r.A * row["cells"].get<double>()), verdict_code(r)}];
  }
  return f;
}

// The report: the summary, per method its band tables, the reading and every case.
std::string extremes_markdown(const Spec& spec, const std::vector<ojson>& rows, const Findings& f) {
  std::ostringstream md;
  md << extremes_summary(spec, f.counts, f.slowest);
  md << "*Stable* here: the solver's outcome stable (the run reached T in at least "
     << kMinStepsToJudge
     << " steps with an error over time below A) over at least c T = " << shortest(kMinWavePasses)
     << " wave pass, beside its accuracy class (docs/studies.md, \"Accuracy classes\": "
        "accurate below "
     << shortest(kAccurateFraction)
     << " A, inaccurate from there up to A). A run the solver calls stable that ran fewer wave "
        "passes is *too short to count* as stable and is counted apart; *too short to judge*: "
        "fewer than "
     << kMinStepsToJudge << " steps, whatever its error.\n\n";
  for (const MethodFindings& m : f.per_method) {
    md << "### " << m.name << "\n\n"
       << band_table(m.by_courant, kCourantBands, true)
       << band_table(m.by_amplitude, kAmplitudeBands, false);
  }
  md << "Reading (computed from the rows): ";
  for (const MethodFindings& m : f.per_method)
    md << method_reading(m);
  md << "\n\n" << every_case_table(rows);
  return md.str();
}

std::string extremes_data_csv(const Findings& f, const std::string& header_lines) {
  std::ostringstream csv;
  csv << header_lines
      << "# one row per spot: method (its panel, counted from zero), Courant number, amplitude "
         "in cells, verdict ("
      << codes(kVerdicts)
      << "), the number of cases there and the method's name\n"
         "method,courant,A_over_h,verdict,cases,name\n";
  for (const auto& [spot, count] : f.spots) {
    const auto& [method, courant, a_over_h, verdict] = spot;
    csv << method << ',' << courant << ',' << a_over_h << ',' << verdict << ',' << count << ','
        << f.methods[static_cast<std::size_t>(method)] << '\n';
  }
  return csv.str();
}

// What the figure draws: every case, at fewer spots than cases.
std::string extremes_subtitle(const Spec&, const ojson& doc) {
  const Findings f = find(std::vector<ojson>(doc["cases"].begin(), doc["cases"].end()));
  return std::to_string(f.counts.total) + " cases at " + std::to_string(f.spots.size()) +
         " spots; the verdicts of one spot side by side, the marker growing with its number of "
         "cases (printed where it holds more than one); the stable marker is the solver's "
         "outcome: " +
         std::to_string(f.counts.verdicts.under_a_wave_pass) + " of its " +
         std::to_string(f.counts.solver_stable()) +
         " runs ran under c T = " + shortest(kMinWavePasses) + " wave pass";
}

std::string extremes_index(const Spec& spec, const std::vector<ojson>& rows, const ojson&) {
  const Counts c = find(rows).counts;
  std::ostringstream md;
  md << "![" << spec.title << "](" << spec.name << ".png)\n\n**What it shows.** " << c.total
     << " cases at the extremes, " << c.with_verdict << " with a verdict ("
     << c.verdicts.accurate + c.inaccurate()
     << " stable over at least c T = " << shortest(kMinWavePasses)
     << " wave pass: " << c.verdicts.accurate << " accurate, " << c.inaccurate() << " inaccurate; "
     << c.verdicts.under_a_wave_pass << " survived fewer wave passes; " << c.verdicts.meaningless
     << " meaningless; " << c.unstable() << " unstable); per method, where and why it fails: ["
     << spec.name << ".md](" << spec.name << ".md).\n\n";
  return md.str();
}

const StudyRegistration kExtremes{{
    .name = "extremes",
    .summary = "verdicts over extreme parameters: where and why each method fails",
    .records = {.error_over_time = true, .dt_stable = true, .crossings = true},
    .figure = true,
    .report =
        [](const ReportContext& c) {
          const Findings f = find(c.rows);
          return StudyReport{.markdown = extremes_markdown(c.spec, c.rows, f),
                             .data_csv = extremes_data_csv(f, c.csv_header),
                             .claims = extremes_claims(f.counts)};
        },
    .index = extremes_index,
    .figure_subtitle = extremes_subtitle,
}};

}  // namespace
}  // namespace mpmstab::studies::extremes
