// Experiment specs: JSON files under experiments/, read into plain structs and validated here,
// in one place. Every error names the file and the key path (for example `cases[3].dt`).
#pragma once

#include <filesystem>
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
};

struct CaseSpec {
  RunParams params;
  bool dt_inferred = false;  // the paper does not print this cell's dt; it is inferred
};

struct Spec {
  std::filesystem::path path;  // the spec file
  std::string name;            // outputs are <out>/<name>.{csv,json,md}
  std::string title;
  std::string description;
  ReportKind report = ReportKind::table1;
  std::filesystem::path reference;  // paper table to compare with (table kinds), resolved
  std::vector<CaseSpec> cases;      // each with params.observe set from "record"
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

}  // namespace mpmstab
