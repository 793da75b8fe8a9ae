#include "regression.hpp"

#include <cstdio>
#include <fstream>
#include <iostream>
#include <sstream>

#include "atomic_file.hpp"
#include "compare.hpp"
#include "csv.hpp"
#include "provenance.hpp"
#include "report.hpp"
#include "report_util.hpp"
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
  return {{"stable", 0, 0, true},
          {"failure_reason", 0, 0, true},
          {"failure_step", 0, 0, false},
          {"meaningless", 0, 0, true},
          {"steps", 0, 0, false},
          {"max_error", 0, rtol, false},
          {"max_error_over_time", 0, rtol, false},
          {"crossings", 0, 0, false},
          {"dt_stable_min", 0, rtol, false},
          {"dt_min", 0, rtol, false},
          {"dt_max", 0, rtol, false},
          // edge experiments: the bracket of the search and its warnings
          {"dt_edge", 0, rtol, false},
          {"dt_fail", 0, rtol, false},
          {"monotone", 0, 0, true},
          {"failed_below_edge", 0, 0, false},
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

fs::path verdicts_file(const RegressionOptions& o) {
  return o.reference / "comparison_verdicts.csv";
}

}  // namespace

Spec fast_subset(const Spec& spec, double budget) {
  Spec subset = spec;
  subset.cases.clear();
  for (const auto& c : spec.cases) {
    const auto& p = c.params;
    if (case_cost(p, spec.report) <= budget) subset.cases.push_back(c);
  }
  return subset;
}

int run_check(const std::vector<Spec>& specs, const RegressionOptions& o) {
  int failures = 0, cells = 0;
  for (const auto& spec : specs) {
    const fs::path file = o.reference / (spec.name + ".csv");
    if (!fs::exists(file)) {
      std::cerr << "FAIL " << spec.name << ": no blessed values in " << file.string()
                << " (run make bless REASON=\"...\")\n";
      ++failures;
      continue;
    }
    const Spec subset = fast_subset(spec, o.budget);
    const Table obtained = run_subset(subset, o);
    cells += static_cast<int>(obtained.rows.size());
    for (const auto& m :
         compare_tables(blessed_table(file), obtained, kKeyColumns, value_rules(o.rtol))) {
      std::cerr << "FAIL " << spec.name << ": " << describe(m) << "\n";
      ++failures;
    }
  }
  // The paper-comparison verdicts against their expectations.
  const fs::path current = o.results / "comparison.csv";
  if (fs::exists(verdicts_file(o)) && fs::exists(current)) {
    for (const auto& m : compare_tables(table_from_csv(verdicts_file(o)), table_from_csv(current),
                                        kVerdictKeys, kVerdictRules)) {
      std::cerr << "FAIL comparison verdict: " << describe(m) << "\n";
      ++failures;
    }
  } else {
    std::cerr << "FAIL comparison verdicts: " << verdicts_file(o).string() << " or "
              << current.string() << " is missing (make reproduce, then make bless)\n";
    ++failures;
  }
  if (failures) {
    std::cerr << failures
              << " cells differ from the blessed values. If the change is intended, "
                 "bless it: make bless REASON=\"...\"\n";
    return 1;
  }
  std::cout << "check: " << cells << " cases of " << specs.size()
            << " experiments match the blessed values; comparison verdicts unchanged\n";
  return 0;
}

int run_bless(const std::vector<Spec>& specs, const RegressionOptions& o,
              const std::string& reason) {
  fs::create_directories(o.reference);
  std::vector<std::string> changes;
  auto bless_table = [&](const std::string& name, const fs::path& file, Table obtained,
                         const std::vector<std::string>& keys, const std::vector<ColumnRule>& rules,
                         const std::vector<std::string>& columns, const std::string& comment) {
    if (fs::exists(file)) {
      const Table old = keys == kKeyColumns ? blessed_table(file) : table_from_csv(file);
      const auto diffs = compare_tables(old, obtained, keys, rules);
      // Nothing changed: the file stays as it is, also in the columns it was written with.
      if (diffs.empty()) return;
      // Keep the old text of every value that still agrees: only changed values are rewritten.
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
      for (const auto& m : diffs)
        changes.push_back(name + ": " + describe(m));
    } else {
      changes.push_back(name + ": " + std::to_string(obtained.rows.size()) +
                        " rows blessed for the first time");
    }
    write_if_changed(file, to_csv(obtained, columns, comment));
  };

  for (const auto& spec : specs) {
    const Spec subset = fast_subset(spec, o.budget);
    bless_table(spec.name, o.reference / (spec.name + ".csv"), run_subset(subset, o), kKeyColumns,
                value_rules(o.rtol), value_columns(), blessed_comment(spec, o.budget));
  }
  const fs::path current = o.results / "comparison.csv";
  if (fs::exists(current)) {
    std::vector<std::string> columns = kVerdictKeys;
    columns.push_back("verdict");
    columns.push_back("class");
    bless_table("comparison verdicts", verdicts_file(o), table_from_csv(current), kVerdictKeys,
                kVerdictRules, columns,
                "# blessed verdict of every Table 1 cell against the paper (results/"
                "comparison.csv); rewritten only by make bless\n");
  } else {
    std::cerr << "bless: " << current.string()
              << " is missing: run make reproduce to bless the comparison verdicts too\n";
  }

  if (changes.empty()) {
    std::cout << "bless: nothing changed; BLESSED.md is left as it is\n";
    return 0;
  }
  const Provenance prov = current_provenance(o.jobs);
  std::ostringstream entry;
  entry << "\n## " << prov.date << ", commit " << prov.commit.substr(0, 12)
        << (prov.dirty ? " with uncommitted changes" : "") << "\n\nReason: " << reason
        << "\n\nCells changed (" << changes.size() << "):\n\n";
  for (const auto& c : changes)
    entry << "- " << c << "\n";
  const fs::path log = o.reference / "BLESSED.md";
  std::string text = read_file(log);
  if (text.empty()) {
    text =
        "# Blessed regression values\n\nEvery change of `reference/regression/` by `make "
        "bless`: when, at which commit, why, and which cells changed.\n";
  }
  write_file_atomically(log, text + entry.str());
  std::cout << "bless: " << changes.size() << " changes recorded in " << log.string() << "\n";
  return 0;
}

}  // namespace mpmstab
