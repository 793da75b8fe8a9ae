#include "shared/paper_table1.hpp"

#include <algorithm>
#include <cmath>

#include "compare.hpp"
#include "csv.hpp"
#include "files.hpp"
#include "report_util.hpp"
#include "run_row.hpp"

namespace mpmstab {

PaperValue paper_value(const std::string& text) {
  PaperValue p;
  p.text = text;
  if (text == "*") {
    p.kind = PaperValue::unstable;
    return p;
  }
  try {
    std::size_t used = 0;
    p.value = std::stod(text, &used);
    if (used == text.size()) p.kind = PaperValue::number;
  } catch (const std::exception&) {
  }
  return p;
}

std::string show(const PaperValue& p) {
  if (p.kind == PaperValue::number) return sci(p.value);
  if (p.kind == PaperValue::unstable) return "*";
  return p.text.empty() ? "?" : "`" + p.text + "`";
}

namespace studies::paper_table1 {
namespace {

// A finite number of the transcription, or InputError naming the file, row and column.
double finite_cell(const std::filesystem::path& file, const CsvTable& t, std::size_t row,
                   const char* column) {
  const std::string& text = t.rows[row].at(column);
  const PaperValue v = paper_value(text);
  if (v.kind != PaperValue::number || !std::isfinite(v.value))
    throw InputError(file, "row " + std::to_string(row + 2) + ", column " + column +
                               ": not a finite number: '" + text + "'");
  return v.value;
}

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char ch) { return std::tolower(ch); });
  return s;
}

}  // namespace
}  // namespace studies::paper_table1

std::vector<PaperRow> read_paper_rows(const std::filesystem::path& reference) {
  using namespace studies::paper_table1;
  const CsvTable t = read_csv(reference);
  std::vector<PaperRow> rows;
  for (std::size_t i = 0; i < t.rows.size(); ++i) {
    const auto& r = t.rows[i];
    PaperRow row{finite_cell(reference, t, i, "A"), finite_cell(reference, t, i, "E"), std::nullopt,
                 lower(r.at("method")),
                 PaperCell{paper_value(r.at("dt_stable")), paper_value(r.at("max_error")),
                           r.at("confidence"), r.at("evidence"), r.at("dt") != "?"}};
    if (row.cell.dt_printed) row.dt = finite_cell(reference, t, i, "dt");
    rows.push_back(std::move(row));
  }
  return rows;
}

std::map<Table1Key, PaperCell> read_paper_table1(const Spec& spec) {
  const std::vector<PaperRow> rows = read_paper_rows(spec.reference);
  const auto printed = [&](double A, double E, const std::string& method, double dt) {
    return std::any_of(rows.begin(), rows.end(), [&](const PaperRow& r) {
      return r.dt && r.A == A && r.E == E && r.method == method && *r.dt == dt;
    });
  };
  std::map<Table1Key, PaperCell> cells;
  for (const PaperRow& row : rows) {
    std::optional<double> dt = row.dt;
    if (!dt) {
      // The spec's cases at this row's A, E and method whose dt no printed row has.
      for (std::size_t i = 0; i < spec.cases.size(); ++i) {
        const CaseSpec& cs = spec.cases[i];
        const RunParams& p = cs.params;
        if (p.A != row.A || p.E != row.E || to_string(cs.paper_method) != row.method ||
            printed(row.A, row.E, row.method, p.dt))
          continue;
        const std::string at = "cases[" + std::to_string(i) + "]";
        const std::string cell =
            "A = " + shortest(row.A) + ", E = " + shortest(row.E) + ", " + row.method;
        if (!cs.dt_inferred)
          throw SpecError(spec.path, at,
                          "Table 1 prints no dt for " + cell +
                              "; a case compared with that cell must be marked dt_inferred");
        if (dt && *dt != p.dt)
          throw SpecError(spec.path, at, "a second dt inferred for the Table 1 cell " + cell);
        dt = p.dt;
      }
      if (!dt) continue;  // no case of the spec runs this cell
    }
    const bool fresh = cells
                           .try_emplace({Key(row.A, "Table 1's A"), Key(row.E, "Table 1's E"),
                                         Key(*dt, "Table 1's dt"), row.method},
                                        row.cell)
                           .second;
    if (!fresh)
      throw InputError(spec.reference, "two rows for the cell A = " + shortest(row.A) +
                                           ", E = " + shortest(row.E) + ", dt = " + param(*dt) +
                                           ", " + row.method);
  }
  return cells;
}

Table1Key paper_key(const CaseSpec& c) {
  const auto& p = c.params;
  return {Key(p.A, "A"), Key(p.E, "E"), Key(p.dt, "dt"), std::string(to_string(c.paper_method))};
}

bool within_agreement_factor(double ours, double paper) {
  static const ColumnRule rule{"max_error", 0, (kAgreementFactor - 1) / kAgreementFactor, false};
  return cells_agree(CellValue{CellValue::Kind::number, ours, ""},
                     CellValue{CellValue::Kind::number, paper, ""}, rule);
}

bool paper_says_stable(const PaperCell& paper) {
  return paper.max_error.kind == PaperValue::number;
}

CellAgreement cell_agreement(const RunRow& row, const PaperCell* paper) {
  using enum CellAgreement;
  if (!paper || paper->max_error.kind == PaperValue::unreadable) return unreadable;
  const bool stable_in_paper = paper_says_stable(*paper);
  switch (row.ending()) {
    case Ending::meaningless:
      return ours_meaningless;
    case Ending::stable:
      return stable_in_paper ? both_stable : paper_unstable_ours_stable;
    case Ending::unstable:
      return stable_in_paper ? paper_stable_ours_unstable : both_unstable;
    default:  // too few steps, under a wave pass, no outcome: no verdict
      return ours_too_short;
  }
}

std::string agreement_factor() {
  return param(kAgreementFactor);
}

}  // namespace mpmstab
