#include "paper_table1.hpp"

#include <algorithm>
#include <cmath>

#include "compare.hpp"
#include "csv.hpp"
#include "report_util.hpp"

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

std::map<Table1Key, PaperCell> read_paper_table1(const Spec& spec) {
  std::map<Table1Key, PaperCell> cells;
  const CsvTable t = read_csv(spec.reference);
  // Cells without a printed dt are matched to the spec's case marked dt_inferred.
  for (const auto& row : t.rows) {
    PaperCell c{paper_value(row.at("dt_stable")), paper_value(row.at("max_error")),
                row.at("confidence"), row.at("evidence"), row.at("dt") != "?"};
    std::string method = row.at("method");
    std::transform(method.begin(), method.end(), method.begin(), ::tolower);
    const double A = std::stod(row.at("A")), E = std::stod(row.at("E"));
    double dt = std::nan("");
    if (c.dt_printed) {
      dt = std::stod(row.at("dt"));
    } else {
      for (const auto& cs : spec.cases) {
        const auto& p = cs.params;
        if (cs.dt_inferred && p.A == A && p.E == E && to_string(cs.paper_method) == method &&
            !cells.count({A, E, p.dt, method})) {
          dt = p.dt;
        }
      }
    }
    cells[{A, E, dt, method}] = c;
  }
  return cells;
}

Table1Key paper_key(const CaseSpec& c) {
  const auto& p = c.params;
  return {p.A, p.E, p.dt, std::string(to_string(c.paper_method))};
}

bool within_agreement_factor(double ours, double paper) {
  static const ColumnRule rule{"max_error", 0, (kAgreementFactor - 1) / kAgreementFactor, false};
  return cells_agree(CellValue{CellValue::Kind::number, ours, ""},
                     CellValue{CellValue::Kind::number, paper, ""}, rule);
}

std::string agreement_factor() {
  return param(kAgreementFactor);
}

}  // namespace mpmstab
