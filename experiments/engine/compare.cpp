#include "compare.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <sstream>

namespace mpmstab {

namespace {

std::optional<double> as_number(std::string_view s) {
  if (s.empty()) return std::nullopt;
  const char* first = s.data();
  const char* last = s.data() + s.size();
  if (*first == '+') ++first;
  double v = 0;
  const auto [ptr, ec] = std::from_chars(first, last, v);
  if (ec != std::errc() || ptr != last) return std::nullopt;
  return v;
}

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return std::tolower(c); });
  return s;
}

// The identity of a row: its key cells, numbers normalized to their shortest form.
std::string row_key(const Row& row, const std::vector<std::string>& keys) {
  std::string id;
  for (const auto& k : keys) {
    const auto it = row.cells.find(k);
    const std::string text = it == row.cells.end() ? "" : it->second;
    std::string norm;
    if (const auto v = as_number(text)) {
      char buf[64];
      const auto [end, ec] = std::to_chars(buf, buf + sizeof buf, *v);
      norm.assign(buf, end);
    } else {
      norm = lower(text);
    }
    id += (id.empty() ? "" : " ") + k + "=" + norm;
  }
  return id;
}

std::string rule_text(const ColumnRule& r) {
  if (r.text) return "exact text";
  std::ostringstream s;
  s << "atol " << r.atol << " + rtol " << r.rtol;
  return s.str();
}

}  // namespace

std::string_view to_string(MismatchKind k) {
  switch (k) {
    case MismatchKind::value:
      return "value";
    case MismatchKind::verdict:
      return "verdict";
    case MismatchKind::missing_value:
      return "missing value";
    case MismatchKind::missing_row:
      return "missing row";
    case MismatchKind::extra_row:
      return "extra row";
    case MismatchKind::duplicate_row:
      return "duplicate row";
  }
  return "?";
}

CellValue parse_cell(std::string_view text) {
  CellValue v;
  v.text = std::string(text);
  if (text.empty()) {
    v.kind = CellValue::Kind::missing;
  } else if (text == "*") {
    v.kind = CellValue::Kind::unstable;
  } else if (lower(std::string(text)) == "nan") {
    v.kind = CellValue::Kind::nan;
  } else if (const auto n = as_number(text)) {
    v.kind = std::isnan(*n) ? CellValue::Kind::nan : CellValue::Kind::number;
    v.number = *n;
  } else {
    v.kind = CellValue::Kind::missing;  // unreadable text: treated as absent unless rule.text
  }
  return v;
}

bool cells_agree(const CellValue& a, const CellValue& b, const ColumnRule& rule) {
  using K = CellValue::Kind;
  if (rule.text) return a.text == b.text;
  // Explicit rules for the special values: equal kinds agree, different kinds never do.
  if (a.kind != b.kind) return false;
  if (a.kind != K::number) return a.kind != K::missing || a.text == b.text;
  if (std::isinf(a.number) || std::isinf(b.number)) return a.number == b.number;
  const double scale = std::max(std::abs(a.number), std::abs(b.number));
  return std::abs(a.number - b.number) <= rule.atol + rule.rtol * scale;
}

std::vector<Mismatch> compare_tables(const Table& expected, const Table& obtained,
                                     const std::vector<std::string>& key_columns,
                                     const std::vector<ColumnRule>& rules) {
  std::vector<Mismatch> out;
  auto index = [&](const Table& t, MismatchKind dup_kind, std::vector<std::string>& order) {
    std::map<std::string, const Row*> rows;
    for (const auto& row : t.rows) {
      const std::string id = row_key(row, key_columns);
      if (!rows.emplace(id, &row).second) {
        out.push_back({dup_kind, id, "", "", "", std::nullopt, ""});
      } else {
        order.push_back(id);
      }
    }
    return rows;
  };
  std::vector<std::string> expected_order, obtained_order;
  const auto exp_rows = index(expected, MismatchKind::duplicate_row, expected_order);
  const auto obt_rows = index(obtained, MismatchKind::duplicate_row, obtained_order);

  for (const auto& id : expected_order) {
    const auto it = obt_rows.find(id);
    if (it == obt_rows.end()) {
      out.push_back({MismatchKind::missing_row, id, "", "present", "absent", std::nullopt, ""});
      continue;
    }
    const Row& e = *exp_rows.at(id);
    const Row& o = *it->second;
    for (const auto& rule : rules) {
      const auto ei = e.cells.find(rule.column);
      const auto oi = o.cells.find(rule.column);
      const CellValue a = parse_cell(ei == e.cells.end() ? "" : ei->second);
      const CellValue b = parse_cell(oi == o.cells.end() ? "" : oi->second);
      if (cells_agree(a, b, rule)) continue;
      Mismatch m{MismatchKind::value, id, rule.column, a.text, b.text, std::nullopt,
                 rule_text(rule)};
      using K = CellValue::Kind;
      if (rule.text || a.kind == K::unstable || b.kind == K::unstable) {
        m.kind = MismatchKind::verdict;
      } else if (a.kind != K::number || b.kind != K::number) {
        m.kind = MismatchKind::missing_value;
      } else {
        const double scale = std::max(std::abs(a.number), std::abs(b.number));
        m.relative_difference = scale > 0 ? std::abs(a.number - b.number) / scale : 0.0;
      }
      out.push_back(std::move(m));
    }
  }
  for (const auto& id : obtained_order) {
    if (!exp_rows.count(id)) {
      out.push_back({MismatchKind::extra_row, id, "", "absent", "present", std::nullopt, ""});
    }
  }
  return out;
}

}  // namespace mpmstab
