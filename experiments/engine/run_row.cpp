#include "run_row.hpp"

#include <algorithm>

#include "base/result.hpp"
#include "csv.hpp"
#include "report_util.hpp"

namespace mpmstab {

using ojson = nlohmann::ordered_json;

namespace {

std::optional<double> number_at(const ojson& row, const char* column) {
  const auto it = row.find(column);
  return it != row.end() && it->is_number() ? std::optional(it->get<double>()) : std::nullopt;
}

std::optional<std::int64_t> integer_at(const ojson& row, const char* column) {
  const auto it = row.find(column);
  return it != row.end() && it->is_number() ? std::optional(it->get<std::int64_t>()) : std::nullopt;
}

std::string label_of_method(const ojson& r) {
  std::string s = text(r, "method");
  const std::string transfer = text(r, "transfer"), update = text(r, "update");
  if (!transfer.empty() && transfer != "flip") {
    s += '/';
    s += transfer;
    for (const char* order : {"flip_fraction", "xpic_order", "fmpm_order"}) {
      const auto v = number_at(r, order);
      if (!v) continue;
      s += '(';
      s += shortest(*v);
      s += ')';
    }
  }
  if (!update.empty() && update != "usl") {
    s += '/';
    s += update;
  }
  return s;
}

std::string label_of_scheme(const ojson& r, std::string s) {
  if (has_number(r, "ppc") && r["ppc"].get<int>() != 2)
    s += " (ppc " + std::to_string(r["ppc"].get<int>()) + ")";
  for (const char* key : {"shift", "jitter"}) {
    const auto v = number_at(r, key);
    if (!v || *v == 0) continue;
    s += " (";
    s += key;
    s += ' ';
    s += shortest(*v);
    s += ')';
  }
  return s;
}

}  // namespace

RunRow::RunRow(const ojson& row)
    : outcome(text(row, "outcome")),
      failure_step(integer_at(row, "failure_step")),
      failure_time(number_at(row, "failure_time")),
      steps(integer_at(row, "steps")),
      particles(number_at(row, "particles")),
      error_over_time(number_at(row, "max_error_over_time")),
      A(number_at(row, "A")),
      wave_passes(number_at(row, "cT")),
      cells(number_at(row, "cells")),
      scene(text(row, "scene")),
      courant(number_at(row, "courant")),
      courant_spectral(number_at(row, "courant_spectral")),
      method(text(row, "method")),
      method_label(label_of_method(row)),
      scheme_label(label_of_scheme(row, method_label)) {
  if (const std::string reason = text(row, "failure_reason"); !reason.empty())
    failure_reason = reason;
}

namespace {

void insert_coverage_value(std::vector<double>& values, const std::optional<double>& v) {
  if (!v) return;
  const double x = std::stod(significant(*v, 3));
  const auto at = std::lower_bound(values.begin(), values.end(), x);
  if (at == values.end() || *at != x) values.insert(at, x);
}

// One value as itself, two or three listed, more as their range and count.
std::string coverage_values(const std::vector<double>& v) {
  if (v.size() <= 3) return mpmstab::listing(v);
  return span(v) + " (" + std::to_string(v.size()) + " values)";
}

}  // namespace

void Coverage::add(const RunRow& r) {
  insert_coverage_value(A, r.A);
  insert_coverage_value(wave_passes, r.wave_passes);
  insert_coverage_value(cells, r.cells);
  const std::string scene = r.scene.empty() ? "bar" : r.scene;
  if (std::find(scenes.begin(), scenes.end(), scene) == scenes.end()) scenes.push_back(scene);
}

std::string Coverage::text() const {
  if (empty()) return "";
  std::vector<std::string> parts;
  if (!A.empty()) parts.push_back("A = " + coverage_values(A));
  if (!wave_passes.empty()) parts.push_back("c T = " + coverage_values(wave_passes));
  if (!cells.empty()) parts.push_back(coverage_values(cells) + " cells");
  if (!scenes.empty()) parts.push_back(list_of(scenes));
  std::string s;
  for (std::size_t k = 0; k < parts.size(); ++k)
    s += (k ? "; " : "") + parts[k];
  return s;
}

Coverage coverage_of(const std::vector<ojson>& rows) {
  Coverage c;
  for (const auto& r : rows)
    c.add(r);
  return c;
}

Coverage coverage_of(const std::vector<const ojson*>& rows) {
  Coverage c;
  for (const auto* r : rows)
    c.add(*r);
  return c;
}

bool RunRow::under_a_wave_pass() const {
  return wave_passes && stable_under_a_wave_pass(outcome == "stable", *wave_passes);
}

Ending RunRow::ending() const {
  if (outcome == "unstable") return Ending::unstable;
  if (outcome == "meaningless") return Ending::meaningless;
  if (outcome == "too_short") return Ending::too_short;
  if (outcome != "stable") return Ending::unknown;
  return under_a_wave_pass() ? Ending::under_a_wave_pass : Ending::stable;
}

std::optional<double> RunRow::error_over_A() const {
  if (!error_over_time || !A || !(*A > 0)) return std::nullopt;
  return *error_over_time / *A;
}

std::optional<Accuracy> RunRow::accuracy() const {
  if (!error_over_time || !A || !(*A > 0)) return std::nullopt;
  return accuracy_class(*error_over_time, *A);
}

bool RunRow::accurate() const {
  return stable_over_a_wave_pass() && accuracy() == Accuracy::accurate;
}

std::optional<double> RunRow::stable_error_over_time() const {
  return stable_over_a_wave_pass() ? error_over_time : std::nullopt;
}

bool RunRow::above_spectral_limit() const {
  return courant && courant_spectral && *courant > *courant_spectral;
}

double RunRow::particle_steps() const {
  return particles && steps ? *particles * double(*steps) : 0.0;
}

void VerdictTally::add(const RunRow& r) {
  ++runs;
  switch (r.ending()) {
    case Ending::unstable:
      ++unstable;
      if (r.failure_reason) ++reasons[*r.failure_reason];
      return;
    case Ending::meaningless:
      ++meaningless;
      return;
    case Ending::too_short:
      ++too_short;
      return;
    case Ending::under_a_wave_pass:
      ++under_a_wave_pass;
      return;
    case Ending::unknown:
      ++unknown;
      return;
    case Ending::stable:
      break;
  }
  ++stable;
  const std::optional<Accuracy> a = r.accuracy();
  if (!a) {
    ++unmeasured;
  } else if (*a == Accuracy::accurate) {
    ++accurate;
  } else {
    ++inaccurate;
    inaccurate_errors.push_back(*r.error_over_A());
  }
}

VerdictTally verdict_tally(const std::vector<ojson>& rows) {
  VerdictTally t;
  for (const auto& r : rows)
    t.add(r);
  return t;
}

std::string outcome(const ojson& r) {
  return text(r, "outcome");
}

bool survived(const ojson& r) {
  return outcome(r) != "unstable";
}

bool under_a_wave_pass(const ojson& r) {
  return RunRow(r).under_a_wave_pass();
}

std::string under_a_wave_pass_word(double wave_passes) {
  return "survived, c T = " + param(wave_passes) + " < " + shortest(kMinWavePasses) +
         " wave pass: too short to count as stable";
}

// Our verdict, in the notation of the table: "*" for unstable, with the reason and step.
std::string verdict_word(const ojson& row) {
  const RunRow r(row);
  switch (r.ending()) {
    case Ending::too_short:
      return "too short to judge (reached T in " + row["steps"].dump() + " steps, fewer than " +
             std::to_string(kMinStepsToJudge) + ")";
    case Ending::meaningless:
      return "meaningless (survived; error over time reached A)";
    case Ending::under_a_wave_pass:
      return under_a_wave_pass_word(*r.wave_passes);
    case Ending::unstable:
      return "\\* " + r.failure_reason.value_or("") + " at step " +
             std::to_string(r.failure_step.value_or(0)) +
             " (t = " + sci(r.failure_time.value_or(0)) + ")";
    default:
      return "stable";
  }
}

std::string verdict(const ojson& r) {
  return verdict_with_error(r, RunRow(r).error_over_A());
}

std::string verdict_with_error(const ojson& r, std::optional<double> error_over_A) {
  const std::string word = verdict_word(r);
  if (outcome(r) != "stable") return word;
  if (!error_over_A) return word + " (error over time not recorded)";
  return word + ", " + std::string(to_string(accuracy_class(*error_over_A, 1.0))) + " (" +
         beside_thresholds(*error_over_A, {kAccurateFraction, 1.0}) + " A)";
}

std::string edge_run_verdict(const ojson& r) {
  return verdict_with_error(r, number_at(r, "error_at_edge_over_A"));
}

std::string method_label(const ojson& r) {
  return RunRow(r).method_label;
}

std::string scheme_label(const ojson& r) {
  return RunRow(r).scheme_label;
}

double particle_steps(const ojson& r) {
  return RunRow(r).particle_steps();
}

std::string work(const ojson& r) {
  return sci(particle_steps(r));
}

std::optional<Accuracy> row_accuracy(const ojson& r) {
  return RunRow(r).accuracy();
}

std::optional<double> row_error_over_A(const ojson& r) {
  return RunRow(r).error_over_A();
}

bool accurate_run(const ojson& r) {
  return RunRow(r).accurate();
}

std::optional<double> stable_error_over_time(const ojson& r) {
  return RunRow(r).stable_error_over_time();
}

bool above_spectral_limit(const ojson& r) {
  return RunRow(r).above_spectral_limit();
}

std::vector<double> values_of(const std::vector<ojson>& rows,
                              std::optional<double> RunRow::*field) {
  std::vector<double> v;
  for (const auto& r : rows)
    if (const auto x = RunRow(r).*field) v.push_back(*x);
  return v;
}

std::optional<double> compared_error(const ojson& row, ErrorAt error_at) {
  if (!survived(row)) return std::nullopt;
  return error_at == ErrorAt::T ? number_at(row, "max_error") : RunRow(row).error_over_time;
}

}  // namespace mpmstab
