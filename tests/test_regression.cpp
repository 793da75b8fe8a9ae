// The regression gate: check passes on blessed values, fails naming the cell on any change,
// bless rewrites only what changed and logs it, and refuses to run without a reason.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>

#include "provenance.hpp"
#include "regression.hpp"
#include "spec.hpp"
#include "support.hpp"

namespace mpmstab {
namespace {

namespace fs = std::filesystem;

class Regression : public ::testing::Test {
 protected:
  fs::path dir = fs::temp_directory_path() / ("mpmstab_regression_" + std::to_string(::getpid()));
  RegressionOptions options;

  void SetUp() override {
    fs::remove_all(dir);
    fs::create_directories(dir / "results");
    write_spec(0.015);
    // The comparison study (no cases of its own) declares its verdicts as a blessed output; it
    // requires the spec of the table it compares, which is not run here.
    std::ofstream(dir / "table1.json") << R"({"name": "table1", "report": "table1",
      "reference": "paper.csv", "cases": [{"E": 4, "A": 0.015, "method": "gimp", "dt": 1e-3}]})";
    std::ofstream(dir / "comparison.json") << R"({"name": "comparison", "report": "comparison"})";
    std::ofstream(dir / "results/comparison.csv")
        << "# verdicts\nmethod,E,A,dt,verdict,class,confidence\n"
           "gimp,4,0.015,0.001,agree,agree-stable,high\n";
    options.reference = dir / "reference";
    options.results = dir / "results";
    options.jobs = 2;
    options.budget = 5e5;  // the T = 2 case below (8e5 particle-steps) is left out
  }
  void TearDown() override { fs::remove_all(dir); }

  void write_spec(double A) {
    std::ofstream(dir / "small.json") << R"({"name": "small", "report": "cases",
      "record": ["error_over_time", "crossings", "dt_stable"],
      "defaults": {"T": 0.05, "cells": 20, "dt": 1e-4},
      "cases": [{"E": 4, "A": )" << A << R"(, "method": "gimp"},
                {"E": 64, "A": 0.05, "method": "mpm"},
                {"E": 1e4, "A": 0.05, "method": "gimp", "dt": 1e-3},
                {"E": 4, "A": 0.01, "method": "gimp", "T": 2}]})";
  }
  std::vector<Spec> specs() {
    return {load_spec(dir / "small.json"), load_spec(dir / "comparison.json")};
  }
  std::string read(const fs::path& p) {
    std::ifstream in(p);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
  }
  // A blessed table with the last digit of its first max_error_over_time value (column found by
  // name) changed; "" when it has no such value.
  static std::string with_one_value_changed(const std::string& csv) {
    auto split = [](const std::string& l) {
      std::vector<std::string> f;
      std::stringstream ss(l);
      for (std::string x; std::getline(ss, x, ',');)
        f.push_back(x);
      if (!l.empty() && l.back() == ',') f.push_back("");
      return f;
    };
    std::istringstream lines(csv);
    std::string out, line;
    bool changed = false;
    std::size_t column = 0;
    while (std::getline(lines, line)) {
      if (line.rfind("method,", 0) == 0) {
        const auto header = split(line);
        column = std::find(header.begin(), header.end(), "max_error_over_time") - header.begin();
      } else if (!changed && line.rfind("gimp,4,", 0) == 0) {
        auto f = split(line);
        if (column >= f.size() || f[column].empty()) return "";
        std::string& v = f[column];
        char& last = v[v.find('e') == std::string::npos ? v.size() - 1 : v.find('e') - 1];
        last = last == '9' ? '8' : static_cast<char>(last + 1);
        line.clear();
        for (std::size_t i = 0; i < f.size(); ++i)
          line += (i ? "," : "") + f[i];
        changed = true;
      }
      out += line + "\n";
    }
    return changed ? out : "";
  }
  // Runs check and returns (status, what it printed on stderr).
  std::pair<int, std::string> check() {
    testing::internal::CaptureStderr();
    const int status = run_check(specs(), options);
    return {status, testing::internal::GetCapturedStderr()};
  }
};

TEST_F(Regression, CheckFailsWithoutBlessedValuesAndPassesAfterBless) {
  EXPECT_EQ(check().first, 1);
  testing::internal::CaptureStdout();
  ASSERT_EQ(run_bless(specs(), options, "first blessing"), 0);
  testing::internal::GetCapturedStdout();
  const std::string blessed = read(options.reference / "small.csv");
  EXPECT_NE(blessed.find("gimp,4,0.015,1e-04,0.05"), std::string::npos) << blessed;
  EXPECT_EQ(blessed.find(",2,20,"), std::string::npos);  // the costly case is not in the subset
  testing::internal::CaptureStdout();
  EXPECT_EQ(check().first, 0);
  testing::internal::GetCapturedStdout();
}

TEST_F(Regression, ALastDigitChangeFailsNamingTheCellAndRestoringPasses) {
  testing::internal::CaptureStdout();
  run_bless(specs(), options, "first blessing");
  const fs::path file = options.reference / "small.csv";
  const std::string original = read(file);
  const std::string changed = with_one_value_changed(original);
  ASSERT_FALSE(changed.empty());
  std::ofstream(file) << changed;
  const auto [status, message] = check();
  testing::internal::GetCapturedStdout();
  EXPECT_EQ(status, 1);
  EXPECT_NE(message.find("method=gimp E=4 A=0.015 dt=1e-04"), std::string::npos) << message;
  EXPECT_NE(message.find("max_error_over_time expected"), std::string::npos) << message;
  EXPECT_NE(message.find("relative difference"), std::string::npos) << message;
  EXPECT_NE(message.find("tolerance atol 0 + rtol 0"), std::string::npos) << message;
  std::ofstream(file) << original;
  testing::internal::CaptureStdout();
  EXPECT_EQ(check().first, 0);
  testing::internal::GetCapturedStdout();
}

TEST_F(Regression, AChangedVerdictFailsCheckUntilBlessed) {
  testing::internal::CaptureStdout();
  run_bless(specs(), options, "first blessing");
  testing::internal::GetCapturedStdout();
  std::ofstream(dir / "results/comparison.csv")
      << "method,E,A,dt,verdict,class,confidence\n"
         "gimp,4,0.015,0.001,paper stable ours unstable,above-spectral-limit,high\n";
  const auto [status, message] = check();
  EXPECT_EQ(status, 1);
  EXPECT_NE(message.find("comparison verdict"), std::string::npos) << message;
  testing::internal::CaptureStdout();
  run_bless(specs(), options, "verdict moved");
  EXPECT_EQ(check().first, 0);
  testing::internal::GetCapturedStdout();
}

TEST_F(Regression, BlessRewritesOnlyWhatChangedAndLogsIt) {
  testing::internal::CaptureStdout();
  run_bless(specs(), options, "first blessing");
  const std::string before = read(options.reference / "small.csv");
  // Nothing changed: nothing is rewritten and nothing is logged.
  const std::string log_before = read(options.reference / "BLESSED.md");
  run_bless(specs(), options, "no change");
  EXPECT_EQ(read(options.reference / "BLESSED.md"), log_before);
  // One case changes: its row is replaced, the others keep their text, the log names it.
  write_spec(0.02);
  run_bless(specs(), options, "amplitude of the first case raised");
  testing::internal::GetCapturedStdout();
  const std::string after = read(options.reference / "small.csv");
  EXPECT_NE(after, before);
  EXPECT_NE(after.find("mpm,64,0.05,1e-04"), std::string::npos);
  auto line_of = [](const std::string& text, const std::string& prefix) {
    const auto at = text.find(prefix);
    return at == std::string::npos ? "" : text.substr(at, text.find('\n', at) - at);
  };
  EXPECT_EQ(line_of(after, "mpm,64,0.05,"), line_of(before, "mpm,64,0.05,"));
  // The log counts the new row and the old one; it does not list them.
  const std::string log = read(options.reference / "BLESSED.md");
  EXPECT_NE(log.find("Reason: amplitude of the first case raised\n\nChanges per blessed table:\n\n"
                     "- small: 1 row added, 1 row removed\n"),
            std::string::npos)
      << log;
  EXPECT_EQ(log.find("A=0.02"), std::string::npos) << log;
  EXPECT_NE(log.find("commit"), std::string::npos);
}

// Each blessing is logged with its date, commit and reason and, per blessed table, the count of
// each kind of change; the changed values themselves are left to the history of the tables.
TEST_F(Regression, BlessLogsTheCountsOfChangesPerTableAndNoValues) {
  testing::internal::CaptureStdout();
  ASSERT_EQ(run_bless(specs(), options, "first blessing"), 0);
  const fs::path file = options.reference / "small.csv";
  const std::string changed = with_one_value_changed(read(file));
  ASSERT_FALSE(changed.empty());
  std::ofstream(file) << changed;
  ASSERT_EQ(run_bless(specs(), options, "one value restored"), 0);
  testing::internal::GetCapturedStdout();
  const std::string log = read(options.reference / "BLESSED.md");
  const Provenance prov = current_provenance(1);
  const std::string heading = ", commit " + prov.commit.substr(0, 12) +
                              (prov.dirty ? " with uncommitted changes" : "") + "\n\n";
  const std::regex expected(
      "# Blessed regression values\n\n[^\n]*not listed[^\n]*\n"
      "\n## [0-9]{4}-[0-9]{2}-[0-9]{2}T[0-9]{2}:[0-9]{2}:[0-9]{2}Z" +
      heading +
      "Reason: first blessing\n\nChanges per blessed table:\n\n"
      "- small: 3 rows blessed for the first time\n"
      "- comparison verdicts: 1 row blessed for the first time\n"
      "\n## [0-9]{4}-[0-9]{2}-[0-9]{2}T[0-9]{2}:[0-9]{2}:[0-9]{2}Z" +
      heading +
      "Reason: one value restored\n\nChanges per blessed table:\n\n"
      "- small: 1 value changed\n");
  EXPECT_TRUE(std::regex_match(log, expected)) << log;
  EXPECT_EQ(log.find("max_error_over_time"), std::string::npos) << log;
  EXPECT_EQ(log.find("method="), std::string::npos) << log;
}

// In a variants experiment two variants may run the same parameters (one differs only in the
// error it compares): the variant is part of a row's key, so both rows are kept and checked.
TEST_F(Regression, VariantRowsAreKeyedByTheirVariant) {
  std::ofstream(dir / "base.json") << R"({"name": "base", "report": "table1",
      "reference": "paper.csv", "record": ["error_over_time"],
      "defaults": {"T": 0.05, "cells": 20, "dt": 1e-4},
      "cases": [{"E": 4, "A": 0.015, "method": "gimp"}, {"E": 64, "A": 0.05, "method": "mpm"}]})";
  std::ofstream(dir / "v.json") << R"({"name": "v", "report": "variants", "cases_from": "base.json",
      "variants": [{"name": "default"}, {"name": "over-time", "error_at": "max_over_time"}]})";
  const std::vector<Spec> v = {load_spec(dir / "v.json")};
  testing::internal::CaptureStdout();
  ASSERT_EQ(run_bless(v, options, "variants"), 0);
  testing::internal::GetCapturedStdout();
  const std::string blessed = read(options.reference / "v.csv");
  EXPECT_NE(blessed.find(",variant,"), std::string::npos) << blessed;
  EXPECT_NE(blessed.find(",over-time,"), std::string::npos) << blessed;
  EXPECT_NE(blessed.find(",default,"), std::string::npos) << blessed;
  testing::internal::CaptureStderr();
  testing::internal::CaptureStdout();
  const int status = run_check(v, options);
  testing::internal::GetCapturedStdout();
  const std::string message = testing::internal::GetCapturedStderr();
  EXPECT_EQ(status, 0) << message;
}

// A blessed file written before the variant column existed reads as rows of no variant.
TEST_F(Regression, ABlessedFileWithoutTheVariantColumnStillMatches) {
  testing::internal::CaptureStdout();
  ASSERT_EQ(run_bless(specs(), options, "first blessing"), 0);
  testing::internal::GetCapturedStdout();
  const fs::path file = options.reference / "small.csv";
  std::istringstream lines(read(file));
  std::string out, line;
  std::size_t column = std::string::npos;
  while (std::getline(lines, line)) {
    if (line.rfind("method,", 0) == 0) {
      // Drop the variant column: its index among the comma-separated header fields.
      std::size_t index = 0;
      for (std::size_t at = 0, next; at != std::string::npos; at = next, ++index) {
        next = line.find(',', at);
        const std::string name = line.substr(at, next == std::string::npos ? next : next - at);
        if (next != std::string::npos) ++next;
        if (name == "variant") column = index;
      }
      ASSERT_NE(column, std::string::npos) << line;
    }
    if (line[0] != '#') {
      std::vector<std::string> f;
      std::stringstream ss(line);
      for (std::string x; std::getline(ss, x, ',');)
        f.push_back(x);
      if (line.back() == ',') f.push_back("");
      f.erase(f.begin() + static_cast<std::ptrdiff_t>(column));
      line.clear();
      for (std::size_t i = 0; i < f.size(); ++i)
        line += (i ? "," : "") + f[i];
    }
    out += line + "\n";
  }
  std::ofstream(file) << out;
  ASSERT_EQ(read(file).find("variant"), std::string::npos);
  testing::internal::CaptureStdout();
  const auto [status, message] = check();
  testing::internal::GetCapturedStdout();
  EXPECT_EQ(status, 0) << message;
}

TEST_F(Regression, BlessRefusesWithoutAReason) {
  const auto blank =
      test_support::run_mpmstab("bless " + (dir / "small.json").string() + " --reference " +
                                options.reference.string() + " --reason '  '");
  EXPECT_EQ(blank.status, 2) << blank.output;
  EXPECT_FALSE(fs::exists(options.reference / "BLESSED.md"));
  const auto none = test_support::run_mpmstab("bless " + (dir / "small.json").string());
  EXPECT_EQ(none.status, 2) << none.output;
}

}  // namespace
}  // namespace mpmstab
