// Reports of an experiment: CSV and JSON (one row per case, with provenance) and a Markdown
// page whose body, and the data its figure plots, its study writes (study.hpp). Every file is
// written atomically, and only when its content changed.
#pragma once

#include <filesystem>
#include <functional>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "files.hpp"
#include "spec.hpp"
#include "sweep.hpp"

namespace mpmstab {

// A results file (<out>/<name>.json) that is not what a sweep of its spec writes: not JSON, not
// an object, or cases that are missing, of another count or without the record's columns.
class BadResults : public InputError {
 public:
  using InputError::InputError;
};

// Reads <out>/<name>.json and checks its shape against the spec before any study reads it: an
// object whose "cases" are the spec's cases, each an object with every record column (of the
// JSON type a record gives it) and whose "study", if present, is an object. Throws BadResults
// naming the file and the first defect; an absent file is null.
nlohmann::ordered_json load_results(const Spec& spec, const std::filesystem::path& out);
// The checks of load_results on text read from `file`.
nlohmann::ordered_json parse_results(std::string_view text, const std::filesystem::path& file,
                                     const Spec& spec);

// Everything a sweep or a derived study of `spec` will read, checked before any work: the
// reference table (a regular CSV file of bounded size with a header), the spec of every input
// and its results in `out` (present if required, of the right shape), and the cache folder (a
// folder if it exists). Throws InputError (exit status 2) naming the first defect.
void check_inputs(const Spec& spec, const std::filesystem::path& out);

// The machine's measurements of the sweeps into `out` (wall times, ns per particle-step, commit,
// CPU, date, threads): <out>/cache/timings.json, in the cache folder, which is not committed.
// Every other file a sweep writes is the same on any machine; <out>/timings.json, the committed
// copy that performance.md summarises, changes only when `mpmstab performance` (make timings)
// publishes this one.
std::filesystem::path machine_timings(const std::filesystem::path& out);

// The entry of the machine's timings for the last `mpmstab reproduce --label L` (its wall time,
// threads, cases, particle-steps), under the key "(L)" (make reproduce: "(make reproduce)", make
// studies: "(make studies)"): replaced by a run that computed cases, kept by one served entirely
// from the cache.
std::string reproduce_timing_key(const std::string& label);
// The label of such a key ("(make studies on X)" -> "make studies on X"); nothing for an
// experiment's entry.
std::optional<std::string> timing_label(const std::string& key);
void write_reproduce_timing(const std::filesystem::path& out, const std::string& label,
                            const nlohmann::ordered_json& entry, bool computed);
// The same, but an input named in `produced` (experiments a run will write before this one's
// reports) is not looked for in `out`.
void check_inputs(const Spec& spec, const std::filesystem::path& out,
                  const std::set<std::string>& produced);

// Computes a study's follow-up runs (Study::follow_up): the cases of `follow_up_spec`, a spec
// whose study does one run per case. The commands pass run_sweep with their cache and threads.
using FollowUpRunner = std::function<SweepOutcome(const Spec& follow_up_spec)>;

// The follow-up runs a study asks for (Study::follow_up), once its cases are done and the
// experiments it reads are written in `out`: a spec of one-run cases of the same study, which
// owns that study (the spec points to it). write_reports asks for the same runs again and takes
// their outcome from its runner; make reproduce computes them in its queue (SweepQueue::add).
struct FollowUps {
  Study study;
  Spec spec;
  // What each case of `spec` was asked for: the case it serves and its role (Study::follow_up).
  std::vector<std::pair<std::size_t, std::string>> asked;
};
// Null when the study asks for none.
std::unique_ptr<FollowUps> follow_ups(const Spec& spec, const SweepOutcome& outcome,
                                      const std::filesystem::path& out);
// The follow-up runs the spec's last published results in `out` (<name>.json and its inputs')
// ask for: what make reproduce expects to add to its queue before its cases are done, for the
// progress line's estimate only. Empty where those results are absent, or were written for
// other cases.
std::vector<RunParams> expected_follow_ups(const Spec& spec, const std::filesystem::path& out);
// The work of each case of `spec` as its last published results in `out` record it (key ->
// particle-steps: a run's steps times its particles, an edge case's whole search); empty when
// there are none or they cannot be read (an estimate only).
std::map<std::string, double> published_work(const Spec& spec, const std::filesystem::path& out);
// By experiment, the particle-steps of the runs its report made itself when it last computed some
// (timings.json's report_runs: the machine's own in out/cache, else the published one in out), an
// estimate of the work its next render will do in an empty cache; experiments neither file counts
// are absent. Each file is read once, for every experiment.
std::map<std::string, double> published_report_work(const std::filesystem::path& out);

// Writes <out>/<name>.csv, .json, .md, <name>_claims.csv for a study that draws conclusions and,
// for studies with a figure, <name>_data.csv; the sweep's wall times go to <out>/timings.json,
// the only file that changes between identical runs. Follow-up runs are computed by `runner`
// (none given: one thread, no cache).
void write_reports(const Spec& spec, const SweepOutcome& outcome, const std::filesystem::path& out,
                   const FollowUpRunner& runner = {});

// The specs of a spec's declared inputs (Study::inputs), in their order.
std::vector<Spec> load_inputs(const Spec& spec);
// The results of input specs in `out` (null where not run), each under its role: roles[i] is
// the InputDecl::name that specs[i] fills. Throws MissingInput for a required input, or one whose
// spec is given, that was not run.
StudyInputs read_inputs(const Study& study, const std::vector<std::string>& roles,
                        const std::vector<Spec>& specs, const std::filesystem::path& out);

// A study without cases of its own: its files from its declared inputs (or from `input_specs`
// in the given roles). `options` are study options from the command line. Throws MissingInput.
void write_derived_reports(
    const Spec& spec, const std::filesystem::path& out,
    const nlohmann::ordered_json& options = nlohmann::ordered_json::object());
void write_derived_reports(const Spec& spec, const std::vector<std::string>& roles,
                           const std::vector<Spec>& input_specs, const std::filesystem::path& out,
                           const nlohmann::ordered_json& options);

// The '#' lines of provenance that head every CSV, and the Markdown provenance section.
std::string provenance_lines(const nlohmann::ordered_json& prov);
std::string provenance_markdown(const nlohmann::ordered_json& prov);

// Writes <out>/README.md, the index a reader browses, from the <name>.json of each spec.
void write_index(const std::vector<Spec>& specs, const std::filesystem::path& out);

// An edge row's errors per A (error_at_edge_over_A, error_reference_over_A,
// error_at_accurate_over_A), and its accuracy edge only where it is one: the search's dt_accurate
// is kept only when neither its reference run nor its own run is known to be inaccurate
// (core/base/accuracy.hpp); else dt_accurate and dt_accurate_over_cfl are null and
// accuracy_edge_withheld is true. flat_row applies it to every edge row, so every report, CSV
// and check reads the one rule.
void add_accuracy_classes(nlohmann::ordered_json& row, double A);

// The CSV columns of a spec's result rows: in a variants experiment (or where a case compares
// another error than the one at T) the variant, the paper's column and the error compared, then
// the run's record columns (result_json.hpp), dt_inferred and the case key.
std::vector<std::string> result_columns(const Spec& spec);
// One case as a flat row: every column of result_columns(), for edge experiments also those of
// the search.
nlohmann::ordered_json flat_row(const CaseSpec& c, const nlohmann::ordered_json& record);
// A JSON value as a CSV field: "" for null, shortest round-trip text for numbers.
std::string csv_cell(const nlohmann::ordered_json& v);

}  // namespace mpmstab
