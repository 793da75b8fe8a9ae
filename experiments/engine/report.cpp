#include "report.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <exception>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

#include "base/accuracy.hpp"
#include "base/version.hpp"
#include "cache.hpp"
#include "cached_run.hpp"
#include "claims.hpp"
#include "csv.hpp"
#include "files.hpp"
#include "key.hpp"
#include "parallel.hpp"
#include "report_util.hpp"
#include "result_json.hpp"
#include "run_row.hpp"
#include "scenes/validate.hpp"
#include "strict_json.hpp"
#include "study.hpp"

namespace mpmstab {

namespace {

using ojson = nlohmann::ordered_json;
namespace fs = std::filesystem;

// ---------------------------------------------------------------------------------------------
// Flat rows: the same columns in the CSV and in the JSON "cases" array.

// A report lists a coordinate's values up to this many, and gives their range beyond.
constexpr std::size_t kListedCoordinates = 6;

// The record's columns (result_json.hpp) with, after dt, whether the paper's dt was inferred,
// after body_force_time how the velocity starts,
// after courant (c dt / h) the amplitude in cells A / h and the wave passes c T, and, last, the
// case's cache key.
const std::vector<std::string> kColumns = [] {
  std::vector<std::string> cols;
  for (const auto& c : record_columns()) {
    cols.push_back(c);
    if (c == "dt") cols.push_back("dt_inferred");
    // How the velocity starts: from the case (the record, cached before it existed, lacks it).
    if (c == "body_force_time") cols.push_back("start");
    if (c == "courant") {  // the run's dimensionless coordinates beside its Courant number
      cols.push_back("A_over_h");
      cols.push_back("cT");
    }
  }
  cols.push_back("key");
  return cols;
}();
// Before those, in a variants experiment or where a case compares another error than the one at
// T: the variant, the paper's column and which error is compared with it.
const std::vector<std::string> kStudyColumns = {"variant", "paper_method", "error_at"};

// ---------------------------------------------------------------------------------------------
// Provenance of a set of cases: each field's distinct values, in spec order.

ojson aggregate_provenance(const std::vector<ojson>& records) {
  std::vector<std::string> fields = {"commit", "dirty", "compiler", "flags",
                                     "eigen",  "cpu",   "kernels",  "threads"};
  ojson out;
  for (const auto& f : fields) {
    std::vector<std::pair<std::string, int>> values;
    auto note = [&](const std::string& value) {
      auto it = std::find_if(values.begin(), values.end(),
                             [&](const auto& e) { return e.first == value; });
      if (it == values.end()) {
        values.emplace_back(value, 1);
      } else {
        ++it->second;
      }
    };
    for (const auto& rec : records) {
      // A field added after a record was cached ("kernels") is absent from it.
      const ojson& prov = rec["provenance"];
      if (!prov.contains(f)) {
        note("not recorded");
        continue;
      }
      const ojson& v = prov[f];
      note(v.is_string() ? v.get<std::string>() : v.dump());
    }
    std::string text;
    for (const auto& [value, count] : values) {
      if (!text.empty()) text += "; ";
      text += value;
      if (values.size() > 1) text += " (" + std::to_string(count) + " cases)";
    }
    out[f] = text;
  }
  std::string first, last;
  for (const auto& rec : records) {
    const std::string d = rec["provenance"]["date"].get<std::string>();
    if (first.empty() || d < first) first = d;
    if (last.empty() || d > last) last = d;
  }
  out["date"] = first == last ? first : first + " .. " + last;
  return out;
}

}  // namespace

std::string provenance_lines(const ojson& prov) {
  std::ostringstream s;
  s << "# solver version: " << kSolverVersion
    << "\n# compiler: " << prov["compiler"].get<std::string>()
    << "\n# flags: " << prov["flags"].get<std::string>()
    << "\n# eigen: " << prov["eigen"].get<std::string>()
    << "\n# the commit, CPU, date and threads of the runs: timings.json\n";
  return s.str();
}

std::string provenance_markdown(const ojson& prov) {
  std::ostringstream md;
  md << "## Provenance\n\n| | |\n|---|---|\n| solver version | " << kSolverVersion << " |\n";
  for (const auto& [k, v] : prov.items())
    md << "| " << k << " | " << v.get<std::string>() << " |\n";
  md << "\nWhat can differ between runs with the same results (the commit, CPU, date and thread "
        "count of the runs, and their wall times) is in [timings.json](timings.json), summarised "
        "in [performance.md](performance.md).\n";
  return md.str();
}

void add_accuracy_classes(ojson& row, double A) {
  auto over_A = [&](const char* col) {
    return row[col].is_number() ? ojson(row[col].get<double>() / A) : ojson(nullptr);
  };
  row["error_at_edge_over_A"] = over_A("max_error_over_time");
  row["error_reference_over_A"] = over_A("max_error_reference");
  row["error_at_accurate_over_A"] = over_A("max_error_at_accurate");
  bool withheld = false;
  if (row["dt_accurate"].is_number()) {
    for (const char* col : {"max_error_reference", "max_error_at_accurate"}) {
      if (row[col].is_number() && accuracy_class(row[col].get<double>(), A) != Accuracy::accurate)
        withheld = true;
    }
  }
  row["accuracy_edge_withheld"] = withheld;
  if (withheld) {
    row["dt_accurate"] = nullptr;
    row["dt_accurate_over_cfl"] = nullptr;
  }
}

ojson flat_row(const CaseSpec& c, const ojson& record) {
  const ojson& r = record["result"];
  ojson row;
  row["variant"] = c.variant;
  row["paper_method"] = to_string(c.paper_method);
  row["error_at"] = to_string(c.error_at);
  for (const auto& col : kColumns) {
    if (col == "dt_inferred") {
      row[col] = c.dt_inferred;
    } else if (col == "key") {
      row[col] = case_key(c.params);
    } else if (col == "A_over_h") {
      row[col] = amplitude_per_cell(c.params);
    } else if (col == "cT") {
      row[col] = wave_passes(c.params);
    } else if (col == "start") {  // from the case: records cached before it existed lack it
      row[col] = to_string(c.params.start);
    } else {
      row[col] = r.at(col);
    }
  }
  if (record.contains("edge")) {
    const ojson extra = edge_columns(record["edge"]);
    for (auto it = extra.begin(); it != extra.end(); ++it)
      row[it.key()] = it.value();
    add_accuracy_classes(row, c.params.A);
  }
  return row;
}

std::string csv_cell(const ojson& v) {
  if (v.is_null()) return "";
  if (v.is_boolean()) return v.get<bool>() ? "true" : "false";
  if (v.is_number_float()) return shortest(v.get<double>());
  if (v.is_number()) return v.dump();
  return csv_field(v.get<std::string>());
}

namespace {

bool has_study_columns(const Spec& spec) {
  if (spec.study->study_columns) return true;
  for (const auto& c : spec.cases) {
    if (c.error_at != ErrorAt::T) return true;
  }
  return false;
}

// The flat rows of every case, without the study columns where the spec has none.
std::vector<ojson> flat_rows(const Spec& spec, const SweepOutcome& outcome) {
  std::vector<ojson> rows;
  const bool study_columns = has_study_columns(spec);
  for (std::size_t i = 0; i < spec.cases.size(); ++i) {
    rows.push_back(flat_row(spec.cases[i], outcome.records[i]));
    if (!study_columns) {
      for (const auto& col : kStudyColumns)
        rows.back().erase(col);
    }
  }
  return rows;
}

// The machine's measurements of a sweep, for results/timings.json: each case's wall time (an
// edge case's whole search) and ns per particle-step, their sum, and the wall time of the sweep.
// A rerun served from the cache keeps the sweep wall time of the sweep that computed the cases.
ojson sweep_timing(const Spec& spec, const SweepOutcome& outcome, const ojson& when,
                   const ojson& previous) {
  ojson cases = ojson::array();
  double compute_seconds = 0, particle_steps = 0;
  for (std::size_t i = 0; i < spec.cases.size(); ++i) {
    const ojson& t = outcome.records[i]["timing"];
    compute_seconds += t["wall_seconds"].get<double>();
    particle_steps += record_particle_steps(outcome.records[i]);
    cases.push_back({{"key", case_key(spec.cases[i].params)},
                     {"wall_seconds", t["wall_seconds"]},
                     {"ns_per_particle_step", t["ns_per_particle_step"]}});
  }
  double sweep_wall = outcome.wall_seconds;
  if (outcome.computed == 0 && !outcome.merged && !outcome.timing_omitted &&
      previous.contains("sweep_wall_seconds") && previous["sweep_wall_seconds"].is_number()) {
    sweep_wall = previous["sweep_wall_seconds"].get<double>();
  }
  return {{"cases", spec.cases.size()},
          {"cache_records_rejected", outcome.rejected},
          {"commit", when["commit"]},
          {"dirty", when["dirty"]},
          {"cpu", when["cpu"]},
          {"kernels", when["kernels"]},
          {"date", when["date"]},
          {"threads", when["threads"]},
          {"particle_steps", particle_steps},
          {"compute_seconds", compute_seconds},
          {"sweep_wall_seconds", sweep_wall},
          {"per_case", cases}};
}

ojson read_timings(const fs::path& path) {
  ojson all = ojson::object();
  if (const auto text = read_if_present(path); text && !text->empty()) {
    try {
      all = parse_json_strict<ojson>(*text, path);
    } catch (const InputError&) {
      all = ojson::object();  // unreadable: rebuilt from the experiments swept from now on
    }
    if (!all.is_object()) all = ojson::object();
  }
  return all;
}

// The entries in name order, `name` replaced by `entry`.
// The cache folder is made here when it is missing: a fresh clone has no results/cache, and the
// first writer of the machine's timings may be `make` (mpmstab build-time) before any sweep.
void store_timing(const fs::path& path, ojson all, const std::string& name, ojson entry) {
  std::error_code ec;
  fs::create_directories(path.parent_path(), ec);
  if (ec)
    throw std::runtime_error("cannot create the folder " + path.parent_path().string() + ": " +
                             ec.message());
  std::map<std::string, ojson> sorted;
  for (auto& [k, v] : all.items())
    sorted[k] = v;
  sorted[name] = std::move(entry);
  ojson doc = ojson::object();
  for (auto& [k, v] : sorted)
    doc[k] = std::move(v);
  write_if_changed(path, doc.dump(1) + "\n");
}

// The machine's measurements, an entry per experiment, updated in place for the experiment just
// swept (experiments in name order), in the ignored cache folder: a clock that moved changes no
// file people browse (`mpmstab performance` publishes them, report.hpp).
void write_timings(const Spec& spec, const SweepOutcome& outcome, const ojson& when,
                   const RunAccount& report_runs, const fs::path& out) {
  const fs::path path = machine_timings(out);
  ojson all = read_timings(path);
  const ojson previous = all.contains(spec.name) ? all[spec.name] : ojson::object();
  ojson entry = sweep_timing(spec, outcome, when, previous);
  // The runs its report computed; a report rendered again from the cache keeps the count of the
  // render that computed them.
  if (report_runs.runs > 0) {
    entry["report_runs"] =
        report_runs_json(report_runs.runs, report_runs.particle_steps, report_runs.seconds);
  } else if (previous.contains("report_runs")) {
    entry["report_runs"] = previous["report_runs"];
  }
  store_timing(path, std::move(all), spec.name, std::move(entry));
}

}  // namespace

fs::path machine_timings(const fs::path& out) {
  return out / "cache" / "timings.json";
}

std::string reproduce_timing_key(const std::string& label) {
  return "(" + label + ")";
}

std::optional<std::string> timing_label(const std::string& key) {
  if (key.size() < 3 || key.front() != '(' || key.back() != ')') return std::nullopt;
  return key.substr(1, key.size() - 2);
}

void write_reproduce_timing(const fs::path& out, const std::string& label, const ojson& entry,
                            bool computed) {
  const fs::path path = machine_timings(out);
  ojson all = read_timings(path);
  const std::string key = reproduce_timing_key(label);
  if (!computed && all.contains(key)) return;  // keep the run that computed
  store_timing(path, std::move(all), key, entry);
}

namespace {

// <name>_follow_up.csv: the follow-up runs of the experiment <name>.
std::string follow_up_file_name(const std::string& name) {
  return name + "_follow_up.csv";
}

// <name>.csv: one row per case, under the header lines.
std::string rows_csv(const std::vector<ojson>& rows, const std::vector<std::string>& columns,
                     const std::string& header) {
  std::ostringstream csv;
  csv << header
      << "# every column is the same for the same spec whatever the machine and the number of "
         "jobs; columns are defined in docs/theory.md and docs/studies.md; wall times are in "
         "timings.json.\n";
  for (std::size_t c = 0; c < columns.size(); ++c)
    csv << (c ? "," : "") << columns[c];
  csv << "\n";
  for (const auto& row : rows) {
    for (std::size_t c = 0; c < columns.size(); ++c) {
      csv << (c ? "," : "") << csv_cell(row[columns[c]]);
    }
    csv << "\n";
  }
  return csv.str();
}

// The title, description and links that open every experiment's Markdown report.
// The document `name` in docs/ of the repository that holds the spec (experiments/<name>.json).
fs::path doc_of(const Spec& spec, const char* name) {
  return spec.path.parent_path().parent_path() / "docs" / name;
}

std::string report_head(const Spec& spec, const fs::path& out, bool follow_up) {
  const std::string spec_path = spec.path.generic_string();
  std::ostringstream md;
  md << "# " << spec.title << "\n\n"
     << spec.description << "\n\nSpec: [`" << spec_path << "`](" << link(out, spec.path)
     << ") · data: [" << spec.name << ".csv](" << spec.name << ".csv), [" << spec.name << ".json]("
     << spec.name << ".json)"
     << (follow_up ? ", its follow-up runs [" + follow_up_file_name(spec.name) + "](" +
                         follow_up_file_name(spec.name) + ")"
                   : std::string())
     << " · generated by `" << (spec.tier == Tier::paper ? "make reproduce" : "make studies")
     << "` · every quantity is defined in [docs/theory.md](" << link(out, doc_of(spec, "theory.md"))
     << ") and every outcome in [docs/studies.md](" << link(out, doc_of(spec, "studies.md"))
     << ").\n\n";
  return md.str();
}

// The distinct values of a coordinate to three significant digits: listed when a handful, else
// their range and count.
std::string coordinate_values(const std::vector<ojson>& rows, const char* column) {
  std::vector<double> v;
  for (double x : numbers(rows, column))
    v.push_back(std::stod(significant(x, 3)));
  std::sort(v.begin(), v.end(), TotalLess());
  v.erase(std::unique(v.begin(), v.end()), v.end());
  if (v.size() <= kListedCoordinates) return listing(v);
  return span(v) + " (" + std::to_string(v.size()) + " values)";
}

// Where the report's runs lie in the coordinates that fix a run (docs/theory.md, "Dimensionless
// coordinates").
std::string coordinates_markdown(const std::vector<ojson>& rows) {
  if (rows.empty()) return "";
  const bool adaptive = std::any_of(rows.begin(), rows.end(), [](const ojson& r) {
    const std::string policy = r.value("policy", std::string("fixed"));
    return policy != "fixed" && policy != "cfl";
  });
  std::ostringstream md;
  md << "**Dimensionless coordinates of these runs:** c dt / h "
     << coordinate_values(rows, "courant") << (adaptive ? " (an adaptive run's largest step)" : "")
     << "; A / h " << coordinate_values(rows, "A_over_h") << "; wave passes c T "
     << coordinate_values(rows, "cT")
     << ". These, the grid, the particles per cell and the method fix a run: E and T enter only "
        "through c T (columns `courant`, `A_over_h`, `cT`).\n\n";
  return md.str();
}

}  // namespace

std::vector<std::string> result_columns(const Spec& spec) {
  std::vector<std::string> columns;
  if (has_study_columns(spec)) columns = kStudyColumns;
  columns.insert(columns.end(), kColumns.begin(), kColumns.end());
  return columns;
}

ojson load_results(const Spec& spec, const fs::path& out) {
  const fs::path file = out / (spec.name + ".json");
  const std::optional<std::string> text = read_if_present(file);
  if (!text) return nullptr;
  return parse_results(*text, file, spec);
}

ojson parse_results(std::string_view text, const fs::path& file, const Spec& spec) {
  auto bad = [&](const std::string& what) {
    return BadResults(file.string() + ": " + what + " (not what `mpmstab sweep " +
                      spec.path.generic_string() + "` writes; rerun it)");
  };
  ojson doc;
  if (text.find_first_not_of(" \t\r\n") == std::string_view::npos) throw bad("is empty");
  try {
    doc = parse_json_strict<ojson>(text, file);
  } catch (const InputError& e) {
    throw bad(e.detail());
  }
  if (!doc.is_object()) throw bad("must be a JSON object");
  if (doc.contains("study") && !doc["study"].is_object()) throw bad("study: must be an object");
  if (!spec.study->has_cases) return doc;
  if (!doc.contains("cases") || !doc["cases"].is_array()) throw bad("cases: must be an array");
  if (doc["cases"].size() != spec.cases.size()) {
    throw bad("cases: " + std::to_string(doc["cases"].size()) + " rows for the spec's " +
              std::to_string(spec.cases.size()) + " cases");
  }
  for (std::size_t i = 0; i < doc["cases"].size(); ++i) {
    const std::string defect = record_defect(doc["cases"][i]);
    if (!defect.empty()) throw bad("cases[" + std::to_string(i) + "]" + defect);
  }
  return doc;
}

std::vector<Spec> load_inputs(const Spec& spec) {
  std::vector<Spec> specs;
  for (const auto& input : spec.inputs) {
    try {
      specs.push_back(load_spec(input.path));
    } catch (const SpecError& e) {
      throw InputError(spec.path, std::string("an input's spec is refused: ") + e.what());
    }
  }
  return specs;
}

StudyInputs read_inputs(const Study& study, const std::vector<std::string>& roles,
                        const std::vector<Spec>& specs, const fs::path& out) {
  StudyInputs inputs;
  for (const auto& decl : study.inputs)
    inputs[decl.name];  // declared but not given: no spec, no results
  for (std::size_t i = 0; i < specs.size() && i < roles.size(); ++i) {
    StudyInput& in = inputs[roles[i]];
    in.spec = &specs[i];
    in.doc = load_results(specs[i], out);
  }
  for (const auto& decl : study.inputs) {
    const StudyInput& in = inputs[decl.name];
    // An input whose spec is given must have been run: no report depends on what has run.
    if ((decl.required || in.spec) && !in.present()) {
      const std::string name = in.spec ? in.spec->name : decl.name;
      throw MissingInput((out / (name + ".json")).string() + " does not exist: run mpmstab sweep " +
                         (in.spec ? in.spec->path.string() : name + ".json") + " first");
    }
  }
  return inputs;
}

namespace {

std::vector<std::string> input_roles(const Spec& spec) {
  std::vector<std::string> roles;
  for (const auto& input : spec.inputs)
    roles.push_back(input.name);
  return roles;
}

}  // namespace

void check_inputs(const Spec& spec, const fs::path& out) {
  check_inputs(spec, out, {});
}

void check_inputs(const Spec& spec, const fs::path& out, const std::set<std::string>& produced) {
  if (!spec.reference.empty()) {
    if (read_csv(spec.reference).header.empty()) throw InputError(spec.reference, "has no columns");
  }
  std::vector<Spec> input_specs = load_inputs(spec);
  std::vector<std::string> roles = input_roles(spec);
  // What the run will produce is not read now (an earlier result there would be replaced), and
  // need not be there yet.
  Study study = *spec.study;
  for (std::size_t i = input_specs.size(); i-- > 0;) {
    if (!produced.count(input_specs[i].name)) continue;
    for (auto& decl : study.inputs)
      if (decl.name == roles[i]) decl.required = false;
    input_specs.erase(input_specs.begin() + std::ptrdiff_t(i));
    roles.erase(roles.begin() + std::ptrdiff_t(i));
  }
  read_inputs(study, roles, input_specs, out);
  std::error_code ec;
  const fs::path cache = out / "cache";
  if (fs::exists(fs::symlink_status(cache, ec)) && !fs::is_directory(cache, ec)) {
    throw InputError(cache, "is not a folder (the sweep keeps its finished cases there)");
  }
}

void write_derived_reports(const Spec& spec, const std::vector<std::string>& roles,
                           const std::vector<Spec>& input_specs, const fs::path& out,
                           const ojson& options) {
  fs::create_directories(out);
  const StudyInputs inputs = read_inputs(*spec.study, roles, input_specs, out);
  ReportBatch batch;  // the study's files are published together, or none of them
  spec.study->write_derived(DerivedContext{spec, out, inputs, options});
  batch.publish();
}

void write_derived_reports(const Spec& spec, const fs::path& out, const ojson& options) {
  const std::vector<Spec> input_specs = load_inputs(spec);
  write_derived_reports(spec, input_roles(spec), input_specs, out, options);
}

namespace {

// The follow-up runs a study asks for, from the rows of its cases and its inputs: null when none.
std::unique_ptr<FollowUps> make_follow_ups(const Spec& spec, const std::vector<ojson>& rows,
                                           const StudyInputs& inputs) {
  if (!spec.study->follow_up) return nullptr;
  const std::vector<FollowUp> asked = spec.study->follow_up(FollowUpContext{spec, rows, inputs});
  if (asked.empty()) return nullptr;
  // The same study, but every follow-up is one run (an edge study's too).
  auto f = std::make_unique<FollowUps>();
  f->study = *spec.study;
  f->study.work = CaseWork::run;
  Spec& follow = f->spec;
  follow = spec;
  follow.study = &f->study;
  follow.variants.clear();
  follow.cases.clear();
  for (const FollowUp& a : asked) {
    if (a.of != FollowUp::kNoCase && a.of >= rows.size())
      throw std::logic_error(spec.name + ": a follow-up run serves a case that is not there");
    f->asked.push_back({a.of, a.role});
    CaseSpec c;
    c.params = a.params;
    // A follow-up is read for its verdict, its errors and how long it ran, never for the
    // spectral limit of its layout: no dense analysis of it (Bloch's, where the layout is
    // uniform, costs nothing and stays). The perturbed layouts of an edge's ensemble each took
    // a dense analysis, one run after another: most of an empty-cache reproduce's wall time.
    c.params.observe.spectral = false;
    if (const auto issues = validate(c.params); !issues.empty())
      throw std::logic_error(spec.name + ": a follow-up run is not valid: " + issues.front().key +
                             ": " + issues.front().message);
    follow.cases.push_back(c);
  }
  return f;
}

// The follow-up runs a study asks for, as flat rows in its order.
std::vector<ojson> follow_up_rows(const Spec& spec, const std::vector<ojson>& rows,
                                  const StudyInputs& inputs, const FollowUpRunner& runner) {
  const std::unique_ptr<FollowUps> f = make_follow_ups(spec, rows, inputs);
  if (!f) return {};
  const Spec& follow = f->spec;
  SweepOutcome done;
  if (runner) {
    done = runner(follow);
  } else {
    SweepOptions options;
    options.quiet = true;
    done = run_sweep(follow, options);
  }
  if (done.records.size() != follow.cases.size())
    throw std::logic_error(spec.name + ": the follow-up runs given are not the ones asked for");
  std::vector<ojson> out;
  for (std::size_t i = 0; i < follow.cases.size(); ++i) {
    ojson row = flat_row(follow.cases[i], done.records.at(i));
    const auto& [of, role] = f->asked.at(i);
    row[kFollowUpOf] = of == FollowUp::kNoCase ? ojson(nullptr) : ojson(of);
    row[kFollowUpRole] = role;
    out.push_back(std::move(row));
  }
  return out;
}

}  // namespace

namespace {

// What an experiment's report set is made from, read before anything is rendered or written.
struct ReportSources {
  std::vector<ojson> rows;        // the flat rows of the cases, in spec order
  ojson prov;                     // what fixes the results: compiler, flags, Eigen
  ojson when;                     // when, where and on how many threads they ran (the timings')
  std::string header;             // the comment lines of every CSV of the set
  std::vector<Spec> input_specs;  // the specs of those experiments: `inputs` points into them
  StudyInputs inputs;             // the results of the experiments the study reads
  std::vector<ojson> follow_up;   // the rows of the runs the study asks for after the sweep
};

// 1. Load: the rows, the provenance, the inputs' results and the follow-up runs.
ReportSources load_sources(const Spec& spec, const SweepOutcome& outcome, const fs::path& out,
                           const FollowUpRunner& runner) {
  ReportSources src;
  src.rows = flat_rows(spec, outcome);
  // When and with how many threads the cases ran go with the timings: the reports hold only
  // what fixes the results (the build and the machine).
  src.prov = aggregate_provenance(outcome.records);
  for (const char* k : {"commit", "dirty", "cpu", "kernels", "date", "threads"}) {
    src.when[k] = src.prov[k];
    src.prov.erase(k);
  }
  src.header = "# experiment: " + spec.name + " (" + spec.path.generic_string() +
               ")\n# title: " + spec.title + "\n" + provenance_lines(src.prov);
  src.input_specs = load_inputs(spec);
  src.inputs = read_inputs(*spec.study, input_roles(spec), src.input_specs, out);
  src.follow_up = follow_up_rows(spec, src.rows, src.inputs, runner);
  return src;
}

// One file of the set and its whole text.
struct ReportFile {
  fs::path path;
  std::string text;
};

// 2. Render: every file of the set as text, from the sources alone; nothing is written.
std::vector<ReportFile> render_set(const Spec& spec, const SweepOutcome& outcome,
                                   const fs::path& out, const ReportSources& src) {
  const StudyReport study = spec.study->report(
      ReportContext{spec, src.rows, outcome, out, src.header, src.inputs, src.follow_up});
  ojson doc;
  doc["experiment"] = spec.name;
  doc["title"] = spec.title;
  doc["spec"] = spec.path.generic_string();
  doc["report"] = spec.study->name;
  doc["provenance"] = src.prov;
  doc["cases"] = src.rows;
  if (!study.json.is_null()) doc["study"] = study.json;
  if (!study.claims.empty()) doc["claims"] = claims_json(study.claims);
  std::vector<ReportFile> files;
  files.push_back(
      {out / (spec.name + ".csv"), rows_csv(src.rows, result_columns(spec), src.header)});
  files.push_back({out / (spec.name + ".json"), doc.dump(2) + "\n"});
  if (!study.claims.empty())
    files.push_back({out / claims_file_name(spec.name), claims_csv(study.claims, src.header)});
  if (study.data_csv) files.push_back({out / (spec.name + "_data.csv"), *study.data_csv});
  // The runs the study asked for after its cases (ensemble members, length reruns, verifying
  // runs), one row each, so that every number a report reads from them can be checked.
  if (!src.follow_up.empty())
    files.push_back(
        {out / follow_up_file_name(spec.name), rows_csv(src.follow_up, kColumns, src.header)});
  files.push_back({out / (spec.name + ".md"), report_head(spec, out, !src.follow_up.empty()) +
                                                  coordinates_markdown(src.rows) +
                                                  claims_markdown(study.claims) + study.markdown +
                                                  "\n" + provenance_markdown(src.prov)});
  return files;
}

// 3. Commit: the machine's timings (in the ignored cache folder) and every file of the set, as
// one publication (files.hpp): all of them or none.
void commit_set(const Spec& spec, const SweepOutcome& outcome, const ojson& when,
                const RunAccount& report_runs, const fs::path& out,
                const std::vector<ReportFile>& files) {
  ReportBatch batch;
  write_timings(spec, outcome, when, report_runs, out);
  for (const ReportFile& f : files)
    write_if_changed(f.path, f.text);
  batch.publish();
}

}  // namespace

std::unique_ptr<FollowUps> follow_ups(const Spec& spec, const SweepOutcome& outcome,
                                      const fs::path& out) {
  if (!spec.study->follow_up) return nullptr;
  const std::vector<ojson> rows = flat_rows(spec, outcome);
  const std::vector<Spec> input_specs = load_inputs(spec);
  const StudyInputs inputs = read_inputs(*spec.study, input_roles(spec), input_specs, out);
  return make_follow_ups(spec, rows, inputs);
}

std::vector<RunParams> expected_follow_ups(const Spec& spec, const fs::path& out) {
  if (!spec.study->follow_up) return {};
  try {
    const ojson doc = load_results(spec, out);
    if (doc.is_null() || !doc.contains("cases") || doc["cases"].size() != spec.cases.size())
      return {};
    const std::vector<ojson> rows(doc["cases"].begin(), doc["cases"].end());
    const std::vector<Spec> input_specs = load_inputs(spec);
    const StudyInputs inputs = read_inputs(*spec.study, input_roles(spec), input_specs, out);
    const std::unique_ptr<FollowUps> f = make_follow_ups(spec, rows, inputs);
    std::vector<RunParams> params;
    if (f)
      for (const CaseSpec& c : f->spec.cases)
        params.push_back(c.params);
    return params;
  } catch (const std::exception&) {
    return {};  // an estimate only: results that cannot be read give none
  }
}

std::map<std::string, double> published_work(const Spec& spec, const fs::path& out) {
  std::map<std::string, double> work;
  try {
    // Every row of the file, whatever its cases (a follow-up's spec shares its experiment's
    // name): only rows whose key a case has are used.
    const fs::path file = out / (spec.name + ".json");
    const std::optional<std::string> text = read_if_present(file);
    if (!text) return {};
    const ojson doc = parse_json_strict<ojson>(*text, file);
    if (!doc.is_object() || !doc.contains("cases") || !doc["cases"].is_array()) return {};
    for (const ojson& row : doc["cases"]) {
      const auto key = row.find("key");
      if (!row.is_object() || key == row.end() || !key->is_string()) continue;
      if (has_number(row, "search_particle_steps")) {
        work[key->get<std::string>()] = row["search_particle_steps"].get<double>();
      } else if (has_number(row, "steps") && has_number(row, "particles")) {
        work[key->get<std::string>()] = particle_steps(row);
      }
    }
  } catch (const std::exception&) {
    return {};  // an estimate only: results that cannot be read give none
  }
  return work;
}

std::map<std::string, double> published_report_work(const fs::path& out) {
  std::map<std::string, double> work;
  for (const fs::path& file : {machine_timings(out), out / "timings.json"}) {
    try {
      const std::optional<std::string> text = read_if_present(file);
      if (!text || text->empty()) continue;
      const ojson doc = parse_json_strict<ojson>(*text, file);
      if (!doc.is_object()) continue;
      for (const auto& [name, entry] : doc.items())
        if (const ReportRuns r = report_runs_of(entry); r.recorded)
          work.emplace(name, r.particle_steps);  // the machine's own first
    } catch (const std::exception&) {
      // an estimate only: timings that cannot be read give none
    }
  }
  return work;
}

void write_reports(const Spec& spec, const SweepOutcome& outcome, const fs::path& out,
                   const FollowUpRunner& runner) {
  fs::create_directories(out);
  const ReportSources sources = load_sources(spec, outcome, out, runner);
  // The runs the report makes itself, counted while it renders (cached_run.hpp).
  // An account open on this thread (the queue's, make reproduce) counts them too.
  RunAccount report_runs;
  std::vector<ReportFile> files;
  {
    const RunAccountScope counting(report_runs);
    files = render_set(spec, outcome, out, sources);
  }
  commit_set(spec, outcome, sources.when, report_runs, out, files);
}

namespace {

std::string index_intro() {
  return "# mpmstab results\n\n"
         "Regenerated from the specs in [`experiments/`](../experiments/) in two tiers: `make "
         "reproduce` the paper's tier (the experiments of M. Berzins, *Nonlinear stability and "
         "time step selection for the MPM method*, rerun with this project's solver and set "
         "beside the paper's values: its tables, its figures and the comparison with the "
         "experiments it cites), `make studies` every other study. Every number below is read "
         "from the files it links to.\n\n"
         "**Performance:** [performance.md](performance.md): the step kernel's benchmark, what "
         "each measured quantity costs, and the wall time of every experiment.\n\n";
}

std::string index_row(const Spec& spec, const ojson& doc) {
  const VerdictTally n =
      verdict_tally(std::vector<ojson>(doc["cases"].begin(), doc["cases"].end()));
  std::ostringstream md;
  md << "| " << spec.title << " | "
     << (spec.tier == Tier::paper ? "make reproduce" : "make studies") << " | [" << spec.name
     << ".md](" << spec.name << ".md) | [" << spec.name << ".csv](" << spec.name << ".csv), ["
     << spec.name << ".json](" << spec.name << ".json) | " << doc["cases"].size() << " | "
     << n.unstable << " | " << n.meaningless << " | " << n.too_short << " | " << n.under_a_wave_pass
     << " | " << n.stable << " | " << n.accurate << " | " << n.inaccurate << " |\n";
  return md.str();
}

std::string index_section(const Spec& spec, const ojson& doc) {
  std::ostringstream md;
  md << "## " << spec.title << "\n\n" << spec.description << "\n\n";
  const std::vector<ojson> rows(doc["cases"].begin(), doc["cases"].end());
  md << spec.study->index(spec, rows, doc.contains("study") ? doc["study"] : ojson());
  md << "Provenance: solver version " << kSolverVersion << ", "
     << doc["provenance"]["compiler"].get<std::string>() << ", Eigen "
     << doc["provenance"]["eigen"].get<std::string>()
     << " (the commit and machine of the runs: [timings.json](timings.json)).\n\n";
  return md.str();
}

}  // namespace

namespace {

// The index's paragraphs are independent (each reads its own spec and results file, up to a few
// megabytes, and some count their study's findings from the rows): they are written side by side.
constexpr unsigned kIndexThreads = 4;

}  // namespace

void write_index(const std::vector<Spec>& specs, const fs::path& out) {
  // Each spec's results, read once, side by side as the paragraphs are written (the first
  // failure in the specs' order is the one reported); a derived study (no cases of its own) is a
  // paragraph of the introduction, every other one a row and a section.
  std::vector<ojson> docs(specs.size());
  std::vector<std::string> sections(specs.size());
  const unsigned threads = std::clamp(available_cpus(), 1u, kIndexThreads);
  for_each_in_parallel(specs.size(), threads, [&](std::size_t i) {
    const Spec& spec = specs[i];
    if (!spec.study->has_cases) {
      sections[i] = spec.study->index(spec, {}, ojson());
      return;
    }
    docs[i] = load_results(spec, out);
    if (!docs[i].is_null()) sections[i] = index_section(spec, docs[i]);
  });
  std::ostringstream md;
  md << index_intro();
  for (std::size_t i = 0; i < specs.size(); ++i) {
    if (!specs[i].study->has_cases) md << sections[i];
  }
  md << "Outcomes and accuracy classes (docs/studies.md, \"Outcomes\"): *unstable*, the run "
        "stopped with a failure; *meaningless*, it reached T but its error over time reached the "
        "amplitude A; *too short*, it reached T in too few steps for a verdict; *under a wave "
        "pass*, it reached T below A but in fewer than "
     << shortest(kMinWavePasses)
     << " wave pass c T / L, too short to show an instability that crosses the body, and is "
        "not called stable; *stable*, it reached T with an error over time below A over at "
        "least "
     << shortest(kMinWavePasses) << " wave pass, and of those *accurate* below "
     << shortest(kAccurateFraction)
     << " A, *inaccurate* from there (a run whose error over time is not recorded is in "
        "neither). Wall times: [performance.md](performance.md).\n\n"
        "| experiment | made by | report | data | cases | unstable | meaningless | too short | "
        "under a wave pass | stable | of them accurate | of them inaccurate |\n"
        "|---|---|---|---|---|---|---|---|---|---|---|---|\n";
  for (std::size_t i = 0; i < specs.size(); ++i) {
    if (!specs[i].study->has_cases) continue;
    if (docs[i].is_null()) {
      md << "| " << specs[i].title << " | not generated | | | | | | | | | | |\n";
    } else {
      md << index_row(specs[i], docs[i]);
    }
  }
  md << "\n";
  for (std::size_t i = 0; i < specs.size(); ++i) {
    if (specs[i].study->has_cases) md << sections[i];
  }
  write_if_changed(out / "README.md", md.str());
}

}  // namespace mpmstab
