#include "claims.hpp"

#include "run_row.hpp"

#include <fmt/args.h>
#include <fmt/format.h>

#include <cmath>
#include <sstream>
#include <stdexcept>

#include "csv.hpp"
#include "files.hpp"
#include "report_util.hpp"

namespace mpmstab {

using ojson = nlohmann::ordered_json;

Claim& Claim::value(std::string name, std::string text) {
  values.emplace_back(std::move(name), std::move(text));
  return *this;
}

Claim& Claim::on(const Coverage& runs) {
  measured_on = runs.text();
  return *this;
}

Claim& Claim::on(std::string what) {
  measured_on = std::move(what);
  return *this;
}

Claim& Claim::over(long long cases) {
  support = cases;
  return *this;
}

Claim& Claim::every(std::string n_name, long long n, std::string total_name, long long total) {
  count(std::move(n_name), n).count(std::move(total_name), total).over(total);
  holds = total > 0 && n == total;
  return *this;
}

Claim::Status Claim::status() const {
  if (support == 0) return Status::vacuous;
  if (!holds) return Status::fails;
  if (support > 0 && support < kMinimumSupport) return Status::too_few;
  return Status::holds;
}

std::string status_markdown(const Claim& c) {
  switch (c.status()) {
    case Claim::Status::holds:
      return "**holds**";
    case Claim::Status::fails:
      return "**does not hold**";
    case Claim::Status::vacuous:
      return "**vacuous (0 cases)**";
    case Claim::Status::too_few:
      return "**too few cases (" + std::to_string(c.support) + "; at least " +
             std::to_string(Claim::kMinimumSupport) + " to say every)**";
  }
  return "";
}

std::string status_csv(const Claim& c) {
  switch (c.status()) {
    case Claim::Status::holds:
      return "yes";
    case Claim::Status::fails:
      return "no";
    case Claim::Status::vacuous:
      return "vacuous";
    case Claim::Status::too_few:
      return "too-few";
  }
  return "";
}

Claim& Claim::count(std::string name, long long n) {
  return value(std::move(name), std::to_string(n));
}

Claim& Claim::number(std::string name, double v, int digits) {
  const double a = std::fabs(v);
  std::string text;
  if (std::isfinite(v) && a >= 0.01 && a < 1e4) {
    std::ostringstream s;
    s.precision(digits < 3 ? 3 : digits);
    s << v;
    text = s.str();
  } else {
    text = sci(v, digits);
  }
  return value(std::move(name), text);
}

Claim claim(std::string id, std::string statement, std::string evidence) {
  Claim c;
  c.id = std::move(id);
  c.statement = std::move(statement);
  c.evidence = std::move(evidence);
  return c;
}

// fmt's named arguments: "{failing} of {above}" with the claim's values.
std::string render(const Claim& c, std::string_view text) {
  fmt::dynamic_format_arg_store<fmt::format_context> args;
  for (const auto& [name, value] : c.values)
    args.push_back(fmt::arg(name.c_str(), value));  // names by reference: c outlives args
  try {
    return fmt::vformat(text, args);
  } catch (const fmt::format_error& e) {
    throw std::logic_error("claim " + c.id + ": " + e.what() + " in \"" + std::string(text) + "\"");
  }
}

std::string render_statement(const Claim& c) {
  return render(c, c.statement);
}

std::string claims_markdown(const std::vector<Claim>& claims) {
  if (claims.empty()) return "";
  int holding = 0;
  for (const auto& c : claims)
    holding += c.status() == Claim::Status::holds;
  std::ostringstream md;
  md << "## Conclusions\n\n"
     << "Each conclusion of this report is a claim computed from its records: the sentence's "
        "numbers come from the rows, a predicate decides it, and it is printed whether it holds or "
        "not. "
     << holding << " of " << claims.size()
     << " hold. Their truth values are in the CSV `_claims` file beside this report and `make "
        "check` compares them with the blessed ones.\n\n"
     << "| claim | what decides it | measured on | holds |\n|---|---|---|---|\n";
  for (const auto& c : claims) {
    md << "| " << render_statement(c) << " | "
       << (c.evidence.empty() ? std::string("–") : render(c, c.evidence)) << " | "
       << (c.measured_on.empty() ? std::string("–") : c.measured_on) << " | " << status_markdown(c)
       << " |\n";
  }
  md << "\n";
  return md.str();
}

ojson claims_json(const std::vector<Claim>& claims) {
  ojson a = ojson::array();
  for (const auto& c : claims) {
    ojson values = ojson::object();
    for (const auto& [n, v] : c.values)
      values[n] = v;
    a.push_back({{"id", c.id},
                 {"template", c.statement},
                 {"evidence_template", c.evidence},
                 {"values", values},
                 {"statement", render_statement(c)},
                 {"evidence", c.evidence.empty() ? std::string() : render(c, c.evidence)},
                 {"measured_on", c.measured_on},
                 {"holds", c.status() == Claim::Status::holds},
                 {"status", status_csv(c)}});
  }
  return a;
}

std::string claims_csv(const std::vector<Claim>& claims, const std::string& header) {
  std::ostringstream csv;
  csv << header << "claim,holds,statement\n";
  for (const auto& c : claims)
    csv << csv_field(c.id) << ',' << status_csv(c) << ',' << csv_field(render_statement(c)) << '\n';
  return csv.str();
}

std::string claims_file_name(const std::string& name) {
  return name + "_claims.csv";
}

void write_claims(const std::filesystem::path& out, const std::string& name,
                  const std::vector<Claim>& claims, const std::string& header) {
  if (claims.empty()) return;
  write_if_changed(out / claims_file_name(name), claims_csv(claims, header));
}

const std::vector<std::string>& claim_name_tokens() {
  static const std::vector<std::string> tokens = {
      "eq. (108)", "Eq. (108)", "eqs. (105)-(108)", "Table 1", "Table 2", "Fig. 1", "Fig. 2",
      "Fig. 3", "Figs. 1-3", "1D", "l2", "xpic(2)", "fmpm(2)", "bspline2", "bspline3", "XPIC(2)",
      "FMPM(2)", "section 5.2", "Figures 1-3",
      // Notation, not results: the definitions and formulas the prose quotes.
      "1/c", "h = 1/", "1/sqrt(", "F = 1", "F_max = 1", "(4 m", "sin(2 pi X)", "(2008)", "(2010)",
      "sum to 1", "(±1)", "(k − 1) / k", "CFL number is 1", "F_p <= 0"};
  return tokens;
}

std::string hand_typed_digits(std::string_view text) {
  std::string digits;
  for (std::size_t i = 0; i < text.size();) {
    if (text[i] == '{') {
      const std::size_t close = text.find('}', i);
      i = close == std::string_view::npos ? text.size() : close + 1;
      continue;
    }
    bool token = false;
    for (const auto& t : claim_name_tokens()) {
      if (text.substr(i, t.size()) == t) {
        i += t.size();
        token = true;
        break;
      }
    }
    if (token) continue;
    if (text[i] >= '0' && text[i] <= '9') digits += text[i];
    ++i;
  }
  return digits;
}

}  // namespace mpmstab
