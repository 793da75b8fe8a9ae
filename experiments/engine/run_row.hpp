// The row vocabulary: a flat result row (report.cpp flat_row) read once into a typed RunRow, and
// the one tally of how runs ended (VerdictTally). How a run ended, its failure, its error over
// time / A and accuracy class, its wave passes and whether it is stable over at least one, whether
// it ran above its scheme's spectral limit, its method and scheme labels and its cost are defined
// here and nowhere else: a study reads them from a RunRow, never by a row's column name.
#pragma once

#include <cstdint>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "base/accuracy.hpp"
#include "base/result.hpp"
#include "spec.hpp"

namespace mpmstab {

// kMinWavePasses (base/result.hpp): a run that reached T in fewer wave passes c T / L is too
// short to show an instability that takes a wave across the body: whatever its outcome says, no
// report, fit, tally, edge or command calls it stable (docs/studies.md, "Outcomes").

// How a run ended, as every report counts it: unstable (it stopped with a failure), meaningless
// (it reached T with an error over time of at least A), too short (too few steps for a verdict),
// under a wave pass (stable by its outcome, but over fewer than kMinWavePasses wave passes),
// stable (over at least kMinWavePasses wave passes); unknown where the row has no outcome.
// The one rule: a run whose outcome is stable but that covered fewer than kMinWavePasses wave
// passes is not called stable (a row, `mpmstab run` and `advise`'s verifying runs alike).
inline bool stable_under_a_wave_pass(bool outcome_stable, double wave_passes) {
  return outcome_stable && wave_passes < kMinWavePasses;
}

enum class Ending { unstable, meaningless, too_short, under_a_wave_pass, stable, unknown };

// A flat result row, read once.
struct RunRow {
  // "unstable", "meaningless", "stable", "too_short" as the solver says ("" where not measured).
  std::string outcome;
  std::optional<std::string> failure_reason;  // of a run that failed
  std::optional<std::int64_t> failure_step;
  std::optional<double> failure_time;
  std::optional<std::int64_t> steps;
  std::optional<double> particles;
  std::optional<double> error_over_time;  // max_error_over_time, where recorded
  std::optional<double> A;
  std::optional<double> wave_passes;  // c T / L
  std::optional<double> cells;
  std::string scene;  // "" where the row names none (the paper's bar)
  std::optional<double> courant, courant_spectral;
  std::string method;        // the basis ("" where the row names none)
  std::string method_label;  // "gimp/xpic(2)", "bspline3/usf"
  std::string scheme_label;  // method_label with ppc and layout: "gimp/usf (ppc 4)"

  explicit RunRow(const nlohmann::ordered_json& row);

  // It reached T: its outcome is anything but unstable (meaningless, stable or too short).
  bool survived() const { return outcome != "unstable"; }
  // The solver says stable, but it covered fewer than kMinWavePasses wave passes.
  bool under_a_wave_pass() const;
  // Stable, over at least kMinWavePasses wave passes: what every report calls stable.
  bool stable_over_a_wave_pass() const { return outcome == "stable" && !under_a_wave_pass(); }
  Ending ending() const;
  // The error over time per A, where both are recorded and A is positive.
  std::optional<double> error_over_A() const;
  // The accuracy class (core/base/accuracy.hpp) of the error over time against A, whatever the
  // outcome; none where either is not recorded or A is not positive.
  std::optional<Accuracy> accuracy() const;
  // Stable over at least a wave pass and accurate: the regime orders are fitted in.
  bool accurate() const;
  // The error over time of a run stable over at least a wave pass: the accuracy it reaches. A run
  // that failed, whose error reached A or that is too short for a verdict reaches none.
  std::optional<double> stable_error_over_time() const;
  // Run at a Courant number c dt / h above its scheme's spectral limit (where one is recorded).
  bool above_spectral_limit() const;
  // The deterministic cost: particles x steps (0 where either is not recorded).
  double particle_steps() const;
};

// How a set of runs ended: the one tally of the index and of every study.
struct VerdictTally {
  int runs = 0, unstable = 0, meaningless = 0, too_short = 0, under_a_wave_pass = 0, unknown = 0;
  // Stable over at least a wave pass, and of those accurate, inaccurate or without a recorded
  // error over time (unmeasured).
  int stable = 0, accurate = 0, inaccurate = 0, unmeasured = 0;
  std::vector<double> inaccurate_errors;  // error over time / A of the stable inaccurate runs
  std::map<std::string, int> reasons;     // the unstable runs by failure reason
  void add(const RunRow& r);
  void add(const nlohmann::ordered_json& row) { add(RunRow(row)); }
  // Reached T: meaningless, too short, under a wave pass or stable.
  int survived() const { return meaningless + too_short + under_a_wave_pass + stable; }
};
VerdictTally verdict_tally(const std::vector<nlohmann::ordered_json>& rows);

// Where a set of runs lies in what a conclusion drawn from them could be read across: the
// amplitudes A, the run lengths in wave passes c T, the grids (cells) and the scenes. A claim
// states it beside itself (Claim::on), so that a conclusion measured at one amplitude, one run
// length or one grid says so, computed from the rows that decide it.
struct Coverage {
  std::vector<double> A, wave_passes, cells;  // distinct values, increasing
  std::vector<std::string> scenes;            // distinct, in the order met ("bar" for none)
  void add(const RunRow& r);
  void add(const nlohmann::ordered_json& row) { add(RunRow(row)); }
  bool empty() const { return A.empty() && wave_passes.empty() && cells.empty(); }
  // "A = 0.015; c T = 2 to 31.6; 100 cells; bar": one value as itself, two or three listed,
  // more as their range; "" when empty.
  std::string text() const;
};
Coverage coverage_of(const std::vector<nlohmann::ordered_json>& rows);
Coverage coverage_of(const std::vector<const nlohmann::ordered_json*>& rows);

// The outcome of a flat record: "unstable", "meaningless", "stable", "too_short" ("" where not
// measured).
std::string outcome(const nlohmann::ordered_json& row);
// The run of a flat record survived to T: its outcome is meaningless, stable or too short.
bool survived(const nlohmann::ordered_json& row);
// The run's outcome is stable, but it covered fewer than kMinWavePasses wave passes (column cT).
bool under_a_wave_pass(const nlohmann::ordered_json& row);
// What a run that ended stable over fewer than kMinWavePasses wave passes is called, in every
// report, by `mpmstab run` and by `advise`: "survived, c T = 0.5 < 1 wave pass: too short to
// count as stable".
std::string under_a_wave_pass_word(double wave_passes);
// Our verdict word for a flat record: "stable", "survived, c T = 0.5 < 1 wave pass: too short to
// count as stable", "meaningless (...)", "too short to judge (...)", "\\* reason at step n (t =
// ..)". For a table that gives the error over time / A and the accuracy class in columns of its
// own.
std::string verdict_word(const nlohmann::ordered_json& row);
// verdict_word with, for a run that reached T below A, its accuracy class and error over time / A
// beside it: "stable, inaccurate (0.43 A)", "stable (error over time not recorded)".
std::string verdict(const nlohmann::ordered_json& row);
// verdict() with the error over time / A given, for a record whose error of the run it names is
// in another column (an edge search's run at its edge).
std::string verdict_with_error(const nlohmann::ordered_json& row,
                               std::optional<double> error_over_A);
// The verdict of an edge search's run at its edge: verdict_with_error() with the row's
// error_at_edge_over_A.
std::string edge_run_verdict(const nlohmann::ordered_json& row);
// The method of a flat record as the trade study names it: the basis, then the transfer (with
// its order or FLIP share) where it is not FLIP and the update order where it is not USL: "gimp",
// "gimp/xpic(2)", "bspline3/usf". Rows without those columns are named by their basis.
std::string method_label(const nlohmann::ordered_json& row);
// method_label with the particles per cell where not 2 and the layout where not uniform:
// "gimp/usf (ppc 4)", "mpm (shift 0.45)", "gimp (jitter 0.5)".
std::string scheme_label(const nlohmann::ordered_json& row);
// The deterministic cost of a run: particles x steps (an edge case: of its run at dt_edge).
double particle_steps(const nlohmann::ordered_json& row);
// particle_steps() in sci(): "2.4e5".
std::string work(const nlohmann::ordered_json& row);
// RunRow(row).accurate(): stable over at least a wave pass with an error over time below
// kAccurateFraction A.
bool accurate_run(const nlohmann::ordered_json& row);
// RunRow(row).accuracy().
std::optional<Accuracy> row_accuracy(const nlohmann::ordered_json& row);
// RunRow(row).error_over_A().
std::optional<double> row_error_over_A(const nlohmann::ordered_json& row);
// RunRow(row).stable_error_over_time().
std::optional<double> stable_error_over_time(const nlohmann::ordered_json& row);
// RunRow(row).above_spectral_limit().
bool above_spectral_limit(const nlohmann::ordered_json& row);
// A field of the rows' RunRows, in row order, where recorded: values_of(rows, &RunRow::courant).
std::vector<double> values_of(const std::vector<nlohmann::ordered_json>& rows,
                              std::optional<double> RunRow::*field);
// Our error compared with the paper's "Max Error" in a flat result row: max_error (at T) or
// max_error_over_time; null when the run failed or the value was not recorded.
std::optional<double> compared_error(const nlohmann::ordered_json& row, ErrorAt error_at);

}  // namespace mpmstab
