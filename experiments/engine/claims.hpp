// Claims: the conclusions a report draws, as data. A claim is a sentence whose every number
// comes from the records (named values substituted into a template), the predicate over the
// records that decides it, and whether it holds. A report prints every claim it declares with
// the numbers that decide it and its truth value; one that does not hold is printed as not
// holding, never dropped. The truth values go to <name>_claims.csv, which `make check` compares
// with reference/regression/<name>_claims.csv: a claim that flips fails CI until blessed.
#pragma once

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace mpmstab {

struct Coverage;  // run_row.hpp

struct Claim {
  std::string id;  // stable within the report: the key make check compares by
  // The sentence, with {name} for each value. It holds no number of its own: thresholds,
  // margins and counts are values too (tests/test_claims.cpp checks every committed report).
  std::string statement;
  std::vector<std::pair<std::string, std::string>> values;  // name -> formatted value
  bool holds = false;
  // What decides it, in words with placeholders like the statement ("" when the statement
  // says it): "{failing} of {above} runs above the limit fail".
  std::string evidence;

  // Where the runs that decide it lie (Coverage::text of those rows: amplitudes, run lengths,
  // grids, scenes), printed beside it: a conclusion measured at one amplitude, one length or
  // one grid says so. A claim that no run decides names what does (a transcription, a formula,
  // an independent code's records). Every committed claim says one or the other
  // (tests/test_claims.cpp).
  std::string measured_on;
  Claim& on(const Coverage& runs);
  Claim& on(std::string what);

  // For a claim about every one of a set of cases (cells, runs, settings): how many there are.
  // -1 (the default) for a claim of another form. A claim over no case is vacuous, and one that
  // would hold over fewer than kMinimumSupport generalises over too few to say "every": neither
  // is printed or counted as holding. A counterexample refutes at any size.
  long long support = -1;
  static constexpr long long kMinimumSupport = 3;
  Claim& over(long long cases);
  enum class Status { holds, fails, vacuous, too_few };
  Status status() const;

  // Fluent helpers for studies: the value's text as the report prints it.
  Claim& value(std::string name, std::string text);
  Claim& count(std::string name, long long n);
  Claim& number(std::string name, double v, int digits = 2);  // sci() or plain for 0.01..1e4
  // A claim about each of `total` cases, `n` of which satisfy it: counts both (in that order,
  // as the evidence "{n} of {total}" reads them), declares the support and decides the claim:
  // it holds when every case does (over no case it is vacuous, status()).
  Claim& every(std::string n_name, long long n, std::string total_name, long long total);
};

// Starts a claim: `holds` is set last, once the predicate is computed.
Claim claim(std::string id, std::string statement, std::string evidence = "");

// The statement (or evidence) with its values substituted. Throws std::logic_error for a
// placeholder without a value: a claim that cannot print its numbers is a defect of the study.
std::string render(const Claim& c, std::string_view text);
std::string render_statement(const Claim& c);

// How a claim's status is printed: in the report ("**holds**", "**vacuous (0 cases)**", ...)
// and in the claims CSV's holds column ("yes", "no", "vacuous", "too-few").
std::string status_markdown(const Claim& c);
std::string status_csv(const Claim& c);

// The "## Conclusions" section: one row per claim, its numbers and whether it holds.
std::string claims_markdown(const std::vector<Claim>& claims);
// The claims as stored in <name>.json ("claims"): id, template, values, rendered text, holds.
nlohmann::ordered_json claims_json(const std::vector<Claim>& claims);
// The claims table make check compares: claim,holds,statement (one row per claim).
std::string claims_csv(const std::vector<Claim>& claims, const std::string& header);
// The file of an experiment's claims, "<name>_claims.csv", in its results and, blessed, in the
// reference folder.
std::string claims_file_name(const std::string& name);
// <out>/<name>_claims.csv when its content changed (inside the open report batch, if any);
// nothing for a report without claims.
void write_claims(const std::filesystem::path& out, const std::string& name,
                  const std::vector<Claim>& claims, const std::string& header);

// Words that name things and carry digits (an equation's number, a table's, an order written
// as part of a method's name) and the notation of definitions and formulas ("1/c", "F = 1" at
// rest): the only digits a claim's template or a report's prose may hold.
const std::vector<std::string>& claim_name_tokens();
// The digits in `text` that are not inside a {placeholder} or one of claim_name_tokens():
// empty for a template that types no number by hand.
std::string hand_typed_digits(std::string_view text);

}  // namespace mpmstab
