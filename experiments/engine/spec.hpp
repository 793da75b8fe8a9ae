// Experiment specs: JSON files under experiments/, read into plain structs and validated here,
// in one place. Every error names the file and the key path (for example `cases[3].dt`).
#pragma once

#include <filesystem>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "base/params.hpp"
#include "study.hpp"

namespace mpmstab {

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
  // Only the base cases whose fixed dt is at least this (a variant too costly to run on the
  // smallest steps); none: every step.
  std::optional<double> dt_at_least;
  std::size_t first_case = 0;  // its cases are Spec::cases[first_case, first_case + cases)
  std::size_t cases = 0;
};

// Which `make` target regenerates an experiment (docs/engineering.md, "Two tiers"): `paper`, the
// paper's tables and figures and the comparison with the experiments it cites (make reproduce);
// `studies`, everything else (make studies). A paper experiment reads only paper experiments.
enum class Tier { paper, studies };
std::string_view to_string(Tier t);

struct Spec {
  std::filesystem::path path;  // the spec file
  std::string name;            // outputs are <out>/<name>.{csv,json,md}
  std::string title;
  std::string description;
  const Study* study = nullptr;       // the study named by "report" (never null once parsed)
  std::filesystem::path reference;    // paper table to compare with (table kinds), resolved
  std::filesystem::path cases_from;   // the spec whose cases (and defaults) this one takes, if any
  std::vector<VariantSpec> variants;  // variants experiments: cases holds every variant's cases
  std::vector<CaseSpec> cases;        // each with params.observe set from "record"
  // Where the experiment stands among the others (mpmstab list, the index of results): after
  // every experiment it reads, then by this number, then by name.
  double index_order = 0;
  Tier tier = Tier::studies;  // "tier"
  // make check reruns the cases needing at most this many particle-steps (unset: the default
  // budget of mpmstab check).
  std::optional<double> check_budget;
  // The experiments whose results the study reads (Study::inputs), as specs beside this one.
  struct Input {
    std::string name;  // the InputDecl's
    std::filesystem::path path;
  };
  std::vector<Input> inputs;
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

std::string_view to_string(ErrorAt e);
std::optional<ErrorAt> parse_error_at(std::string_view s);

}  // namespace mpmstab
