// Experiment specs: JSON files under experiments/, read into plain structs and validated here,
// in one place. Every error names the file and the key path (for example `cases[3].dt`).
#pragma once

#include <filesystem>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "params.hpp"

namespace mpmstab {

// The layout of an experiment's report.
enum class ReportKind {
  table1,    // Table 1: E blocks, dt rows, MPM and GIMP, paper beside ours
  table2,    // Table 2: grid crossings per E and A, dt_sound
  figure,    // one case whose history or final state a gnuplot script draws
  cases,     // a plain table of every case (supporting experiments)
  edge,      // per case, the largest fixed dt that survives to T (its dt is searched, not given)
  tradeoff,  // error against cost across methods, time-step policies and their parameters
  extremes,  // verdicts over extreme parameters: where and why each method fails
  variants,  // Table 1's cells under documented implementation choices, against the paper
};

// Which of our errors is compared with the paper's "Max Error": the max error at T (the
// design's reading, `max_error`) or the largest over the run (`max_error_over_time`).
enum class ErrorAt { T, max_over_time };

struct CaseSpec {
  RunParams params;
  bool dt_inferred = false;  // the paper does not print this cell's dt; it is inferred
  ErrorAt error_at = ErrorAt::T;
  // Variants experiments: the variant this case belongs to ("" otherwise), and the method of
  // the paper's column it is compared with: the base case's, also when the variant changes the
  // method (gimp cells run with cpgimp still compare with the paper's GIMP column).
  std::string variant;
  Method paper_method = Method::gimp;
};

// One variant of a variants experiment: `set` applied to every base case whose method is listed.
struct VariantSpec {
  std::string name;
  std::string description;
  std::string change;  // the settings it changes, "walls = ghost, error_at = max_over_time"
  // How many implementation choices it changes: a key of `set` or error_at each count one;
  // flip_fraction qualifies transfer and does not count on its own.
  int changes = 0;
  bool baseline = false;        // changes nothing: the default, which the others are read against
  std::vector<Method> methods;  // the base cases' methods it applies to; empty: every case
  std::size_t first_case = 0;   // its cases are Spec::cases[first_case, first_case + cases)
  std::size_t cases = 0;
};

struct Spec {
  std::filesystem::path path;  // the spec file
  std::string name;            // outputs are <out>/<name>.{csv,json,md}
  std::string title;
  std::string description;
  ReportKind report = ReportKind::table1;
  std::filesystem::path reference;    // paper table to compare with (table kinds), resolved
  std::filesystem::path cases_from;   // the spec whose cases (and defaults) this one takes, if any
  std::vector<VariantSpec> variants;  // variants experiments: cases holds every variant's cases
  std::vector<CaseSpec> cases;        // each with params.observe set from "record"
};

// A spec that cannot be used: `path` is the key path inside the file ("" for the whole file).
class SpecError : public std::runtime_error {
 public:
  SpecError(const std::filesystem::path& file, const std::string& key_path,
            const std::string& message);
};

// Reads and validates a spec. Throws SpecError.
Spec load_spec(const std::filesystem::path& file);

// Validates the text of a spec; `file` names it in messages and anchors its relative paths.
// Throws SpecError, and nothing else, for any text (the fuzz target tests/fuzz/ checks that).
Spec parse_spec(std::string_view text, const std::filesystem::path& file);

std::string_view to_string(ReportKind k);
std::string_view to_string(ErrorAt e);
std::optional<ErrorAt> parse_error_at(std::string_view s);

}  // namespace mpmstab
