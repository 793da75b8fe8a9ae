// A study: everything that is specific to one kind of experiment, declared in one place
// (experiments/studies/<name>.cpp) and registered under the name a spec gives as "report".
// The engine (spec, sweep, cache, reports) reads a study's declaration and calls its hooks;
// it never names a study.
#pragma once

#include <filesystem>
#include <functional>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "base/params.hpp"
#include "claims.hpp"
#include "files.hpp"
#include "run/edge.hpp"

namespace mpmstab {

struct Spec;
struct SweepOutcome;

// What one case of a study computes from its parameters.
enum class CaseWork {
  run,          // one run to T at the case's dt (or policy)
  edge_search,  // the largest fixed dt that survives to T: a scan and a bisection of runs
};

// An experiment whose results a study reads, by the name of its spec (resolved beside the
// study's spec). Where that spec exists, its results must be in the report folder before the
// study's report is written (read_inputs refuses otherwise): a report never depends on which
// experiments happen to have been run, or on what the cache holds. A required input's spec must
// exist too; another's may be absent (a spec copied alone), and the report says so.
struct InputDecl {
  std::string name;
  bool required = false;
};

// The results of an experiment a study reads: its spec and its <out>/<name>.json (null when it
// has not been run into that folder).
struct StudyInput {
  const Spec* spec = nullptr;
  nlohmann::ordered_json doc;
  bool present() const { return !doc.is_null(); }
};
using StudyInputs = std::map<std::string, StudyInput>;  // by InputDecl::name

// A required input whose results are not in the report folder.
class MissingInput : public InputError {
 public:
  using InputError::InputError;
};

// What a study's report is written from.
struct ReportContext {
  const Spec& spec;
  const std::vector<nlohmann::ordered_json>& rows;  // one flat row per case (report.hpp)
  const SweepOutcome& outcome;                      // the records, for history and final state
  const std::filesystem::path& out;                 // the report folder
  const std::string& csv_header;                    // '#' lines heading every CSV it writes
  const StudyInputs& inputs;                        // the declared inputs, by name
  // The follow-up runs the study asked for (Study::follow_up), as flat rows in the order it
  // asked: empty when it asks for none. Each row carries what it was asked for (kFollowUpOf,
  // kFollowUpRole): read them with follow_ups_of(), never by position.
  const std::vector<nlohmann::ordered_json>& follow_up;
};

// A run a study asks for after its cases, and what it is for: the case it serves (its index in
// FollowUpContext::rows, or kNoCase for one that serves the study as a whole) and its role, a
// few words ("ensemble member", "periodic twin", "corner", "verifying run"). The engine computes
// it like any case and hands its flat row to the report with both written into it.
struct FollowUp {
  static constexpr std::size_t kNoCase = static_cast<std::size_t>(-1);
  std::size_t of = kNoCase;
  std::string role;
  RunParams params;
};
// The keys of a follow-up row that say what it was asked for (they are not among the columns of
// <name>_follow_up.csv, which lists the runs in the order asked).
inline constexpr const char* kFollowUpOf = "follow_up_of";
inline constexpr const char* kFollowUpRole = "follow_up_role";
// The follow-up rows asked for case `of` in role `role`, in the order asked.
std::vector<const nlohmann::ordered_json*> follow_ups_of(
    const std::vector<nlohmann::ordered_json>& follow_up, std::size_t of, std::string_view role);

// What a study's follow-up runs are chosen from: its spec and the rows of its cases.
struct FollowUpContext {
  const Spec& spec;
  const std::vector<nlohmann::ordered_json>& rows;  // rows[i] is the record of spec.cases[i]
  const StudyInputs& inputs;                        // the declared inputs, by name
};

// What a study adds to the files every experiment writes.
struct StudyReport {
  std::string markdown;                   // <name>.md between the description and provenance
  std::optional<std::string> data_csv;    // <name>_data.csv, what its figure script draws
  nlohmann::ordered_json json = nullptr;  // stored as "study" in <name>.json when not null
  // Its conclusions (claims.hpp): printed in <name>.md before the body, stored as "claims" in
  // <name>.json and in <name>_claims.csv, which make check compares with the blessed truth values.
  std::vector<Claim> claims;
};

// A study that has no cases of its own reads only its inputs and writes its own files.
struct DerivedContext {
  const Spec& spec;
  const std::filesystem::path& out;
  const StudyInputs& inputs;
  const nlohmann::ordered_json& options;  // study options given on the command line
};

// A table a study writes whose rows `make check` compares with blessed expectations
// (reference/regression/<spec name>_verdicts.csv), beside the blessed run values.
struct BlessedOutput {
  std::string file;                        // in the results folder, e.g. "comparison.csv"
  std::vector<std::string> key_columns;    // identify a row
  std::vector<std::string> value_columns;  // must match exactly
  std::string what;                        // "comparison verdicts": how messages name it
};

struct Study {
  std::string name;     // the value of a spec's "report"
  std::string summary;  // one line: what the study shows

  // What a spec of this study must and may contain (checked by the spec parser).
  CaseWork work = CaseWork::run;
  EdgeOptions edge;              // the search of an edge_search study
  bool has_cases = true;         // false: a derived study, computed from its inputs only
  bool needs_reference = false;  // a paper table to compare with
  bool takes_variants = false;   // "variants" (and then requires them)
  bool one_case = false;         // exactly one case (a figure of one run)
  // What the study's report reads beyond each run's verdict and final error: a spec lists it
  // in "record" (a column it does not record reads "–"); mpmstab list --studies shows it.
  struct Records {
    bool error_over_time = false, dt_stable = false, crossings = false, history = false,
         final_state = false;
  } records;
  // Columns variant, paper_method and error_at in every row (else only where a case compares
  // another error than the one at T).
  bool study_columns = false;
  // Experiments whose results the study reads: they run before it (mpmstab list orders them),
  // and their <out>/<name>.json is handed to its report.
  std::vector<InputDecl> inputs;
  // The study draws a figure: experiments/<spec name>.gp on <out>/<name>_data.csv.
  bool figure = false;

  // Runs chosen from the rows of its cases (a confirming run of a recommendation, an ensemble of
  // perturbed layouts near an edge): computed after its cases, through the cache like any case
  // (always one run each), and handed to `report` as ReportContext::follow_up.
  std::function<std::vector<FollowUp>(const FollowUpContext&)> follow_up;
  // <name>.md's body and the figure data, from the rows of a sweep (studies with cases).
  std::function<StudyReport(const ReportContext&)> report;
  // The paragraph of results/README.md, after the spec's title and description: "What it
  // shows", from the rows of <name>.json and what its report published there under "study"
  // (null when it publishes nothing): a finding the report computed is read, not computed again.
  std::function<std::string(const Spec&, const std::vector<nlohmann::ordered_json>& rows,
                            const nlohmann::ordered_json& published)>
      index;
  // The figure's subtitle, from <name>.json (studies with a figure).
  std::function<std::string(const Spec&, const nlohmann::ordered_json& doc)> figure_subtitle;
  // The value gnuplot's `dt` takes (default "0").
  std::function<std::string(const nlohmann::ordered_json& doc)> figure_dt;
  // A derived study's files (has_cases false).
  std::function<void(const DerivedContext&)> write_derived;
  // Tables it writes that make check compares with blessed expectations.
  std::vector<BlessedOutput> blessed;
};

// The registry: every study linked into the program, by name.
const Study* find_study(std::string_view name);
std::vector<const Study*> all_studies();  // by name

// A study file registers its study with a static StudyRegistration.
struct StudyRegistration {
  explicit StudyRegistration(Study study);
};

}  // namespace mpmstab
