// Comparing two tables of results cell by cell: rows matched by their parameters (never by
// order), a tolerance rule per column, and explicit rules for unstable ("*"), NaN and missing
// values. No I/O: tables are passed in as text, as they are written in CSV files.
#pragma once

#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace mpmstab {

// One cell's value as written: a number, "*" (the run was unstable), "nan", or empty (missing).
struct CellValue {
  enum class Kind { number, unstable, nan, missing };
  Kind kind = Kind::missing;
  double number = 0;
  std::string text;
};

// Parses "*", "nan"/"NaN", "" and numbers; other text ("4.?e-6") is kept as text with kind
// missing. Columns whose rule is `text` compare the text exactly instead.
CellValue parse_cell(std::string_view text);

// Pass when |a - b| <= atol + rtol * max(|a|, |b|): continuous in a and b, also near zero.
struct ColumnRule {
  std::string column;
  double atol = 0;
  double rtol = 0;
  bool text = false;  // compare the text exactly (verdicts, failure reasons, booleans)
};

struct Row {
  std::map<std::string, std::string> cells;  // column -> text
};

struct Table {
  std::vector<Row> rows;
};

enum class MismatchKind {
  value,          // both numbers, outside the tolerance
  verdict,        // "*" against a number, or a differing text cell
  missing_value,  // one side empty or NaN, the other not
  missing_row,    // expected row absent from the obtained table
  extra_row,      // obtained row not in the expected table
  duplicate_row,  // two rows with the same parameters in one table
};

std::string_view to_string(MismatchKind k);

struct Mismatch {
  MismatchKind kind;
  std::string cell;    // the row's parameters, e.g. "method=gimp E=4 A=0.015 dt=0.001"
  std::string column;  // empty for row-level mismatches
  std::string expected;
  std::string obtained;
  std::optional<double> relative_difference;  // |a - b| / max(|a|, |b|) for numbers
  std::string tolerance;                      // the rule, e.g. "atol 0 + rtol 1e-12"
};

// True when two cell values agree under `rule`.
bool cells_agree(const CellValue& a, const CellValue& b, const ColumnRule& rule);

// Compares `obtained` with `expected`. Rows are matched by `key_columns`; numeric keys are
// compared as numbers ("1e-4" matches "0.0001") and text keys without regard to case.
std::vector<Mismatch> compare_tables(const Table& expected, const Table& obtained,
                                     const std::vector<std::string>& key_columns,
                                     const std::vector<ColumnRule>& rules);

}  // namespace mpmstab
