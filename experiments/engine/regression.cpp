#include "regression.hpp"

#include <cstdio>
#include <fstream>
#include <iostream>
#include <map>
#include <optional>
#include <sstream>

#include "claims.hpp"
#include "compare.hpp"
#include "csv.hpp"
#include "files.hpp"
#include "provenance.hpp"
#include "report.hpp"
#include "result_json.hpp"
#include "sweep.hpp"

namespace mpmstab {

namespace {

namespace fs = std::filesystem;
using ojson = nlohmann::ordered_json;

// A regression row is identified by every parameter that can change it, and in a variants
// experiment by its variant (two variants may run the same parameters).
const std::vector<std::string> kKeyColumns = [] {
  std::vector<std::string> keys = parameter_names();
  keys.push_back("variant");
  return keys;
}();

// Every deterministic result column and how it is compared. Verdicts, reasons and counts are
// exact; floating-point values use the relative tolerance of the options.
std::vector<ColumnRule> value_rules(double rtol) {
  return {{"outcome", 0, 0, true},
          {"failure_reason", 0, 0, true},
          {"failure_step", 0, 0, false},
          {"steps", 0, 0, false},
          {"dt_mean", 0, rtol, false},
          {"max_error", 0, rtol, false},
          {"max_error_over_time", 0, rtol, false},
          {"error_l2_time", 0, rtol, false},
          {"energy_error_max", 0, rtol, false},
          {"energy_exact_error_max", 0, rtol, false},
          {"energy_drift", 0, rtol, false},
          {"energy_warning_step", 0, 0, false},
          {"crossings", 0, 0, false},
          {"dt_stable_min", 0, rtol, false},
          {"courant_spectral", 0, rtol, false},
          {"dt_min", 0, rtol, false},
          {"dt_max", 0, rtol, false},
          // edge experiments: the bracket of the search and its warnings
          {"dt_edge", 0, rtol, false},
          {"dt_fail", 0, rtol, false},
          {"dt_reference", 0, rtol, false},
          {"max_error_reference", 0, rtol, false},
          {"dt_accurate", 0, rtol, false},
          {"dt_inaccurate", 0, rtol, false},
          {"max_error_at_accurate", 0, rtol, false},
          {"outcome_at_accurate", 0, 0, true},
          {"survival_flips", 0, 0, true},
          {"search_particle_steps", 0, 0, false},
          {"monotone", 0, 0, true},
          {"dt_survives_above", 0, rtol, false},
          {"accuracy_monotone", 0, 0, true},
          {"dt_accurate_above", 0, rtol, false},
          {"probes", 0, 0, false}};
}

const std::vector<std::string> kVerdictKeys = {"method", "E", "A", "dt"};
const std::vector<ColumnRule> kVerdictRules = {{"verdict", 0, 0, true}, {"class", 0, 0, true}};

Table table_from_csv(const fs::path& file) {
  Table t;
  for (auto& row : read_csv(file).rows)
    t.rows.push_back(Row{std::move(row)});
  return t;
}

// A blessed file written before a key column existed holds runs with that parameter at its
// default (a new parameter never changes what the old runs did): read the missing cells so. A
// missing variant column reads as "" (not a variant).
Table blessed_table(const fs::path& file) {
  Table t = table_from_csv(file);
  RunResult defaults;
  const ojson d = to_json(defaults);
  for (auto& row : t.rows) {
    for (const auto& k : kKeyColumns) {
      if (!row.cells.count(k)) row.cells[k] = d.contains(k) ? csv_cell(d[k]) : "";
    }
  }
  return t;
}

// The fast subset of a spec, run now (no cache), as a table of text cells.
Table run_subset(const Spec& subset, const RegressionOptions& o) {
  SweepOptions so;
  so.jobs = o.jobs;
  so.force = true;
  so.quiet = true;
  const SweepOutcome outcome = run_sweep(subset, so);
  Table t;
  std::vector<std::string> columns = kKeyColumns;
  for (const auto& r : value_rules(0))
    columns.push_back(r.column);
  for (std::size_t i = 0; i < subset.cases.size(); ++i) {
    const ojson flat = flat_row(subset.cases[i], outcome.records[i]);
    Row row;
    for (const auto& c : columns)
      row.cells[c] = flat.contains(c) ? csv_cell(flat[c]) : "";  // edge columns: edge only
    t.rows.push_back(std::move(row));
  }
  return t;
}

std::string to_csv(const Table& t, const std::vector<std::string>& columns,
                   const std::string& comment) {
  std::ostringstream s;
  s << comment;
  for (std::size_t i = 0; i < columns.size(); ++i)
    s << (i ? "," : "") << columns[i];
  s << "\n";
  for (const auto& row : t.rows) {
    for (std::size_t i = 0; i < columns.size(); ++i) {
      const auto it = row.cells.find(columns[i]);
      s << (i ? "," : "") << csv_field(it == row.cells.end() ? "" : it->second);
    }
    s << "\n";
  }
  return s.str();
}

std::string describe(const Mismatch& m) {
  std::ostringstream s;
  s << m.cell;
  if (m.column.empty()) {
    s << ": " << to_string(m.kind);
  } else {
    s << ": " << m.column << " expected '" << m.expected << "', obtained '" << m.obtained << "'";
    if (m.relative_difference) s << ", relative difference " << shortest(*m.relative_difference);
    s << ", tolerance " << m.tolerance << " (" << to_string(m.kind) << ")";
  }
  return s.str();
}

std::vector<std::string> value_columns() {
  std::vector<std::string> columns = kKeyColumns;
  for (const auto& r : value_rules(0))
    columns.push_back(r.column);
  return columns;
}

std::string blessed_comment(const Spec& spec, double budget) {
  return "# blessed values of " + spec.path.generic_string() + ": its cases needing at most " +
         shortest(budget) + " particle-steps; rewritten only by make bless (see BLESSED.md)\n";
}

// A cell of a row; "" when the row has no such column (a file written before it existed).
std::string cell(const Row& row, const std::string& column) {
  const auto it = row.cells.find(column);
  return it == row.cells.end() ? std::string() : it->second;
}

// The blessed expectations of a table a study writes: reference/<spec name>_verdicts.csv.
fs::path blessed_output_file(const Spec& spec, const RegressionOptions& o) {
  return o.reference / (spec.name + "_verdicts.csv");
}

std::vector<ColumnRule> exact_rules(const BlessedOutput& b) {
  std::vector<ColumnRule> rules;
  for (const auto& c : b.value_columns)
    rules.push_back({c, 0, 0, true});
  return rules;
}

// The fast subset of an experiment against its blessed values; returns the failures.
int check_values(const Spec& spec, const RegressionOptions& o, int& cells) {
  const fs::path file = o.reference / (spec.name + ".csv");
  if (!fs::exists(file)) {
    std::cerr << "FAIL " << spec.name << ": no blessed values in " << file.string()
              << " (run make bless REASON=\"...\")\n";
    return 1;
  }
  const Table obtained = run_subset(fast_subset(spec, budget_of(spec, o)), o);
  cells += static_cast<int>(obtained.rows.size());
  int failures = 0;
  for (const auto& m :
       compare_tables(blessed_table(file), obtained, kKeyColumns, value_rules(o.rtol))) {
    std::cerr << "FAIL " << spec.name << ": " << describe(m) << "\n";
    ++failures;
  }
  return failures;
}

// A table the study wrote into the results against its blessed expectations.
int check_table(const BlessedOutput& b, const fs::path& expected, const fs::path& current) {
  if (!fs::exists(expected) || !fs::exists(current)) {
    std::cerr << "FAIL " << b.what << ": " << expected.string() << " or " << current.string()
              << " is missing (make reproduce, then make bless)\n";
    return 1;
  }
  int failures = 0;
  for (const auto& m : compare_tables(table_from_csv(expected), table_from_csv(current),
                                      b.key_columns, exact_rules(b))) {
    std::cerr << "FAIL " << b.what << ": " << describe(m) << "\n";
    ++failures;
  }
  return failures;
}

int check_output(const Spec& spec, const BlessedOutput& b, const RegressionOptions& o) {
  return check_table(b, blessed_output_file(spec, o), o.results / b.file);
}

// Every report's conclusions (claims.hpp): <results>/<name>_claims.csv, whose truth values are
// blessed in <reference>/<name>_claims.csv. A report without claims has neither file.
BlessedOutput claims_output(const Spec& spec) {
  return {.file = claims_file_name(spec.name),
          .key_columns = {"claim"},
          .value_columns = {"holds"},
          .what = spec.name + " claims"};
}
fs::path blessed_claims_file(const Spec& spec, const RegressionOptions& o) {
  return o.reference / claims_file_name(spec.name);
}
bool has_claims(const Spec& spec, const RegressionOptions& o) {
  return fs::exists(o.results / claims_output(spec).file) ||
         fs::exists(blessed_claims_file(spec, o));
}

}  // namespace

double budget_of(const Spec& spec, const RegressionOptions& o) {
  return o.budget_given || !spec.check_budget ? o.budget : *spec.check_budget;
}

Spec fast_subset(const Spec& spec, double budget) {
  Spec subset = spec;
  subset.cases.clear();
  for (const auto& c : spec.cases) {
    const auto& p = c.params;
    if (case_cost(p, spec.study->work) <= budget) subset.cases.push_back(c);
  }
  return subset;
}

int run_check(const std::vector<Spec>& specs, const RegressionOptions& o) {
  int failures = 0, cells = 0, experiments = 0, claim_reports = 0;
  std::vector<std::string> outputs;
  for (const auto& spec : specs) {
    if (spec.study->has_cases) {
      failures += check_values(spec, o, cells);
      ++experiments;
    }
    for (const auto& b : spec.study->blessed) {
      failures += check_output(spec, b, o);
      outputs.push_back(b.what);
    }
    if (has_claims(spec, o)) {
      const BlessedOutput b = claims_output(spec);
      failures += check_table(b, blessed_claims_file(spec, o), o.results / b.file);
      ++claim_reports;
    }
  }
  if (failures) {
    std::cerr << failures
              << " cells differ from the blessed values. If the change is intended, "
                 "bless it: make bless REASON=\"...\"\n";
    return 1;
  }
  std::cout << "check: " << cells << " cases of " << experiments
            << " experiments match the blessed values";
  for (const auto& what : outputs)
    std::cout << "; " << what << " unchanged";
  std::cout << "; the conclusions of " << claim_reports << " reports hold as blessed\n";
  return 0;
}

namespace {

// What a bless changed in one blessed table: the rows of a table blessed for the first time, or
// how many differences of each kind it had with the blessed values it replaces.
struct TableChange {
  std::string name;                            // the table's name: spec, verdicts or claims
  std::optional<std::size_t> first_rows;       // set when the table had no blessed values
  std::map<MismatchKind, std::size_t> counts;  // otherwise: differences per kind
};

// How the log names each kind of difference, in the order it lists them: a row the blessed table
// lacked is added, a blessed row the new values lack is removed.
struct KindLabel {
  MismatchKind kind;
  const char* one;
  const char* many;
};
const std::vector<KindLabel> kKindLabels = {
    {MismatchKind::extra_row, "row added", "rows added"},
    {MismatchKind::missing_row, "row removed", "rows removed"},
    {MismatchKind::value, "value changed", "values changed"},
    {MismatchKind::verdict, "verdict changed", "verdicts changed"},
    {MismatchKind::missing_value, "value appeared or disappeared",
     "values appeared or disappeared"},
    {MismatchKind::duplicate_row, "duplicate row", "duplicate rows"}};

std::string counted(std::size_t n, const char* one, const char* many) {
  return std::to_string(n) + " " + (n == 1 ? one : many);
}

// One table's line of the log entry, e.g. "1 row added, 1 row removed, 3 values changed".
std::string summary(const TableChange& c) {
  if (c.first_rows) {
    return counted(*c.first_rows, "row", "rows") + " blessed for the first time";
  }
  std::string s;
  for (const auto& l : kKindLabels) {
    const auto it = c.counts.find(l.kind);
    if (it != c.counts.end()) s += (s.empty() ? "" : ", ") + counted(it->second, l.one, l.many);
  }
  return s;
}

// The changes of a bless: one per difference, one per table blessed for the first time.
std::size_t change_count(const std::vector<TableChange>& changes) {
  std::size_t n = 0;
  for (const auto& c : changes) {
    n += c.first_rows ? 1 : 0;
    for (const auto& [kind, count] : c.counts)
      n += count;
  }
  return n;
}

// Rewrites a blessed table where it differs from `obtained`, keeping the old text of every value
// that still agrees; appends what changed to `changes`.
void bless_table(const std::string& name, const fs::path& file, Table obtained,
                 const std::vector<std::string>& keys, const std::vector<ColumnRule>& rules,
                 const std::vector<std::string>& columns, const std::string& comment,
                 std::vector<TableChange>& changes) {
  if (fs::exists(file)) {
    const Table old = keys == kKeyColumns ? blessed_table(file) : table_from_csv(file);
    const auto diffs = compare_tables(old, obtained, keys, rules);
    // Nothing changed: the file stays as it is, also in the columns it was written with.
    if (diffs.empty()) return;
    std::map<std::string, const Row*> old_rows;
    for (const auto& row : old.rows) {
      std::string id;
      for (const auto& k : keys)
        id += cell(row, k) + "|";
      old_rows[id] = &row;
    }
    for (auto& row : obtained.rows) {
      std::string id;
      for (const auto& k : keys)
        id += cell(row, k) + "|";
      const auto it = old_rows.find(id);
      if (it == old_rows.end()) continue;
      for (const auto& rule : rules) {
        const std::string before = cell(*it->second, rule.column);
        if (cells_agree(parse_cell(before), parse_cell(row.cells[rule.column]), rule)) {
          row.cells[rule.column] = before;
        }
      }
    }
    TableChange change{.name = name, .first_rows = std::nullopt, .counts = {}};
    for (const auto& m : diffs)
      ++change.counts[m.kind];
    changes.push_back(std::move(change));
  } else {
    changes.push_back({.name = name, .first_rows = obtained.rows.size(), .counts = {}});
  }
  write_if_changed(file, to_csv(obtained, columns, comment));
}

void bless_file(const BlessedOutput& b, const fs::path& current, const fs::path& blessed,
                std::vector<TableChange>& changes) {
  if (!fs::exists(current)) {
    std::cerr << "bless: " << current.string() << " is missing: run make reproduce to bless the "
              << b.what << " too\n";
    return;
  }
  std::vector<std::string> columns = b.key_columns;
  columns.insert(columns.end(), b.value_columns.begin(), b.value_columns.end());
  bless_table(b.what, blessed, table_from_csv(current), b.key_columns, exact_rules(b), columns,
              "# blessed " + b.what + " (" + (fs::path("results") / b.file).generic_string() +
                  "); rewritten only by make bless\n",
              changes);
}

void bless_output(const Spec& spec, const BlessedOutput& b, const RegressionOptions& o,
                  std::vector<TableChange>& changes) {
  bless_file(b, o.results / b.file, blessed_output_file(spec, o), changes);
}

// Appends the blessing to BLESSED.md: when, at which commit, why, and how many rows and values of
// each blessed table changed. The values themselves are in the history of the committed tables.
void log_blessing(const std::vector<TableChange>& changes, const RegressionOptions& o,
                  const std::string& reason) {
  const Provenance prov = current_provenance(o.jobs);
  std::ostringstream entry;
  entry << "\n## " << prov.date << ", commit " << prov.commit.substr(0, 12)
        << (prov.dirty ? " with uncommitted changes" : "") << "\n\nReason: " << reason
        << "\n\nChanges per blessed table:\n\n";
  for (const auto& c : changes)
    entry << "- " << c.name << ": " << summary(c) << "\n";
  const fs::path log = o.reference / "BLESSED.md";
  std::string text = read_if_present(log).value_or("");
  if (text.empty()) {
    text =
        "# Blessed regression values\n\nEvery change of `reference/regression/` by `make "
        "bless`: when, at which commit, why, and how many rows and values of each blessed table "
        "changed. The changed values themselves are not listed here: the blessed tables beside "
        "this file are committed, so `git log -p reference/regression/` shows them.\n";
  }
  write_if_changed(log, text + entry.str());
  std::cout << "bless: " << change_count(changes) << " changes recorded in " << log.string()
            << "\n";
}

}  // namespace

int run_bless(const std::vector<Spec>& specs, const RegressionOptions& o,
              const std::string& reason) {
  fs::create_directories(o.reference);
  // The blessed tables and the log entry are published together, or none of them.
  ReportBatch batch;
  std::vector<TableChange> changes;
  for (const auto& spec : specs) {
    if (spec.study->has_cases) {
      bless_table(spec.name, o.reference / (spec.name + ".csv"),
                  run_subset(fast_subset(spec, budget_of(spec, o)), o), kKeyColumns,
                  value_rules(o.rtol), value_columns(), blessed_comment(spec, budget_of(spec, o)),
                  changes);
    }
    for (const auto& b : spec.study->blessed)
      bless_output(spec, b, o, changes);
    if (has_claims(spec, o)) {
      const BlessedOutput b = claims_output(spec);
      bless_file(b, o.results / b.file, blessed_claims_file(spec, o), changes);
    }
  }
  if (changes.empty()) {
    std::cout << "bless: nothing changed; BLESSED.md is left as it is\n";
    return 0;
  }
  log_blessing(changes, o, reason);
  batch.publish();
  return 0;
}

}  // namespace mpmstab
