#include "report_util.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>

#include "compare.hpp"
#include "csv.hpp"

namespace mpmstab {

namespace fs = std::filesystem;
using ojson = nlohmann::ordered_json;

std::string fixed(double v, int decimals) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*f", decimals, v);
  return buf;
}

std::string seconds(double s) {
  if (s < 1) return fixed(s * 1e3, s < 0.01 ? 2 : 0) + " ms";
  return s < 10 ? fixed(s, 2) + " s" : fixed(s, 0) + " s";
}

// A ratio to two significant digits: "11", "7.6", "0.13", "1.2e+02".
std::string ratio(double r) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.2g", r);
  return buf;
}

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

// A parameter: its value to 3 significant digits without trailing zeros ("1e-5", "2.5e-3").
std::string param(double v) {
  std::string s = sci(v, 3);
  const auto e = s.find('e');
  std::string mantissa = s.substr(0, e), rest = e == std::string::npos ? "" : s.substr(e);
  if (mantissa.find('.') != std::string::npos) {
    mantissa.erase(mantissa.find_last_not_of('0') + 1);
    if (mantissa.back() == '.') mantissa.pop_back();
  }
  return mantissa + rest;
}

std::string opt_sci(const ojson& v) {
  return v.is_number() ? sci(v.get<double>()) : "–";
}

// Our verdict, in the notation of the table: "*" for unstable, with the reason and step.
std::string verdict(const ojson& r) {
  if (!r["stable"].get<bool>()) {
    return "\\* " + r["failure_reason"].get<std::string>() + " at step " +
           std::to_string(r["failure_step"].get<std::int64_t>()) +
           " (t = " + sci(r["failure_time"].get<double>()) + ")";
  }
  return r["meaningless"] == true ? "stable, meaningless (error reached A)" : "stable";
}

std::string cost(const ojson& r) {
  return seconds(r["wall_seconds"].get<double>()) + ", " +
         fixed(r["ns_per_particle_step"].get<double>(), 1) + " ns";
}

double quantile(std::vector<double> v, double q) {
  std::sort(v.begin(), v.end());
  const double pos = q * double(v.size() - 1);
  const std::size_t i = static_cast<std::size_t>(pos);
  return i + 1 < v.size() ? v[i] + (pos - double(i)) * (v[i + 1] - v[i]) : v.back();
}

std::string link(const fs::path& from_dir, const fs::path& target) {
  return fs::relative(target, from_dir).generic_string();
}

// ---------------------------------------------------------------------------------------------
// Table 1.

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

std::optional<double> compared_error(const ojson& row, ErrorAt error_at) {
  if (row["stable"] != true) return std::nullopt;
  const ojson& v = row[error_at == ErrorAt::T ? "max_error" : "max_error_over_time"];
  return v.is_number() ? std::optional<double>(v.get<double>()) : std::nullopt;
}

Table1Key paper_key(const CaseSpec& c) {
  const auto& p = c.params;
  return {p.A, p.E, p.dt, std::string(to_string(c.paper_method))};
}

bool within_factor_3(double ours, double paper) {
  static const ColumnRule factor3{"max_error", 0, 2.0 / 3.0, false};
  return cells_agree(CellValue{CellValue::Kind::number, ours, ""},
                     CellValue{CellValue::Kind::number, paper, ""}, factor3);
}

std::string sci(double v, int digits) {
  if (v == 0) return "0";
  if (!std::isfinite(v)) return std::isnan(v) ? "nan" : (v > 0 ? "inf" : "-inf");
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*e", digits - 1, v);
  // 5.1e-05 -> 5.1e-5, 1.0e+04 -> 1.0e4
  std::string s = buf;
  const auto e = s.find('e');
  std::string mantissa = s.substr(0, e);
  std::string exponent = s.substr(e + 1);
  const bool negative = exponent[0] == '-';
  exponent = exponent.substr(1);
  exponent.erase(0, std::min(exponent.find_first_not_of('0'), exponent.size() - 1));
  if (exponent == "0") return mantissa;
  return mantissa + "e" + (negative ? "-" : "") + exponent;
}

std::string read_file(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return "";
  std::stringstream buffer;
  buffer << in.rdbuf();
  return buffer.str();
}

}  // namespace mpmstab
