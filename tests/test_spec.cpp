// Experiment specs: every malformed spec is refused with the file and the key path; the shipped
// specs hold exactly the paper's cells.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <set>

#include "csv.hpp"
#include "spec.hpp"

namespace mpmstab {
namespace {

namespace fs = std::filesystem;

class SpecFiles : public ::testing::Test {
 protected:
  fs::path dir = fs::temp_directory_path() / ("mpmstab_spec_test_" + std::to_string(::getpid()));
  void SetUp() override { fs::create_directories(dir); }
  void TearDown() override { fs::remove_all(dir); }

  fs::path write(const std::string& text) {
    const fs::path p = dir / "spec.json";
    std::ofstream(p) << text;
    return p;
  }
  // The error message of loading `text`, or "" if it loads.
  std::string error_of(const std::string& text) {
    try {
      load_spec(write(text));
      return "";
    } catch (const SpecError& e) {
      return e.what();
    }
  }
};

const char* kGood = R"({
  "name": "demo", "title": "Demo", "report": "figure", "record": ["history", "crossings"],
  "history_stride": 5,
  "defaults": {"T": 0.1, "cells": 20},
  "cases": [{"method": "gimp", "E": 4, "A": 0.01, "dt": 1e-3}]
})";

TEST_F(SpecFiles, AGoodSpecLoadsWithDefaultsAndRecordFlags) {
  const Spec s = load_spec(write(kGood));
  EXPECT_EQ(s.name, "demo");
  ASSERT_EQ(s.cases.size(), 1u);
  const RunParams& p = s.cases[0].params;
  EXPECT_EQ(p.method, Method::gimp);
  EXPECT_EQ(p.T, 0.1);
  EXPECT_EQ(p.cells, 20);
  EXPECT_EQ(p.ppc, 2);  // not in the spec: the solver's default
  EXPECT_TRUE(p.observe.history);
  EXPECT_TRUE(p.observe.crossings);
  EXPECT_FALSE(p.observe.dt_stable);  // not asked for: not computed
  EXPECT_FALSE(p.observe.error_over_time);
  EXPECT_EQ(p.observe.history_stride, 5);
}

TEST_F(SpecFiles, ErrorsNameTheKeyPath) {
  struct Case {
    std::string text;
    std::string expected;  // a fragment of the message
  };
  auto with_case = [](const std::string& c) {
    return R"({"name": "t", "report": "figure", "cases": [)" + c + "]}";
  };
  auto with_cases = [](const std::string& c) {
    return R"({"name": "t", "report": "table1", "reference": "x.csv", "cases": [)" + c + "]}";
  };
  const std::string ok = R"({"method": "gimp", "E": 4, "A": 0.01, "dt": 1e-3})";
  const std::vector<Case> cases = {
      {"", "is empty"},
      {"   \n", "is empty"},
      {"{\"name\": \"t\",\n \"cases\": [1, 2,]}", "malformed JSON at line 2"},
      {"[1, 2]", "must be a JSON object"},
      {R"({"report": "figure", "cases": [{}]})", "name: is required"},
      {R"({"name": "t", "report": "figure"})", "cases: is required"},
      {R"({"name": "T 1", "report": "figure", "cases": [{}]})", "name: must be a non-empty"},
      {R"({"name": "t", "report": "table3", "cases": [{}]})", "report: unknown value 'table3'"},
      {R"({"name": "t", "report": "table1", "cases": [{}]})", "reference: is required"},
      {R"({"name": "t", "report": "figure", "cses": []})",
       "cses: unknown key 'cses' (did you mean 'cases'?)"},
      {R"({"name": "t", "report": "figure", "cases": []})", "cases: must be a non-empty array"},
      {R"({"name": "t", "report": "figure", "cases": {}})", "cases: must be a non-empty array"},
      {with_case("3"), "cases[0]: must be an object"},
      {with_case(R"({"method": "gimp", "E": 4, "A": 0.01})"), "cases[0].dt: is required"},
      {with_case(R"({"method": "gimp", "E": "4", "A": 0.01, "dt": 1e-3})"),
       "cases[0].E: must be a number, got string"},
      {with_case(R"({"method": "gimp", "E": -4, "A": 0.01, "dt": 1e-3})"), "cases[0].E: must be"},
      {with_case(R"({"method": "gimp", "E": 1e999, "A": 0.01, "dt": 1e-3})"),
       "malformed JSON: number overflow parsing '1e999'"},
      {with_case(R"({"method": "gimp", "E": 4, "A": -0.01, "dt": 1e-3})"), "cases[0].A"},
      {with_case(R"({"method": "gimp", "E": 4, "A": 0.01, "dt": 0})"), "cases[0].dt"},
      {with_case(R"({"method": "gimp", "E": 4, "A": 0.01, "dt": 2})"),
       "cases[0].dt: must not exceed T"},
      {with_case(R"({"method": "gimp", "E": 4, "A": 0.01, "dt": 1e-3, "cells": 2.5})"),
       "cases[0].cells: must be an integer"},
      {with_case(R"({"method": "gimp", "E": 4, "A": 0.01, "dt": 1e-3, "cells": 0})"),
       "cases[0].cells"},
      {with_case(R"({"method": "gimp", "E": 4, "A": 0.01, "dt": 1e-3, "ppc": 0})"), "cases[0].ppc"},
      {with_case(R"({"method": "flip", "E": 4, "A": 0.01, "dt": 1e-3})"),
       "cases[0].method: unknown value 'flip'"},
      {with_case(R"({"method": "gimp", "E": 4, "A": 0.01, "dt": 1e-3, "bc": "open"})"),
       "cases[0].bc: unknown value 'open'"},
      {with_case(R"({"method": "gimp", "E": 4, "A": 0.01, "dt": 1e-3, "dtt": 1})"),
       "cases[0].dtt: unknown key 'dtt' (did you mean 'dt'?)"},
      {with_case(R"({"method": "gimp", "E": 4, "A": 0.01, "dt": 1e-3, "dt_inferred": 1})"),
       "cases[0].dt_inferred: must be true or false"},
      {with_cases(ok + "," + ok), "cases[1]: repeats cases[0]"},
      {with_cases(ok + ", {\"method\": \"mpm\", \"E\": 4, \"A\": 0.01, \"dt\": 0}"), "cases[1].dt"},
      {R"({"name": "t", "report": "figure", "defaults": {"E": -1}, "cases": [{"method": "gimp", "A": 0.01, "dt": 1e-3}]})",
       "defaults.E: must be"},
      {R"({"name": "t", "report": "figure", "record": ["histroy"], "cases": [{}]})",
       "record[0]: unknown value 'histroy' (did you mean 'history'?)"},
      {R"({"name": "t", "report": "figure", "history_stride": 0, "cases": [{"method": "gimp", "E": 4, "A": 0.01, "dt": 1e-3}]})",
       "history_stride"},
      {R"({"name": "t", "report": "figure", "cases": [)" + ok + "," +
           R"({"method": "mpm", "E": 4, "A": 0.01, "dt": 1e-3}]})",
       "cases: a figure experiment has exactly one case"},
  };
  for (const auto& c : cases) {
    const std::string message = error_of(c.text);
    EXPECT_NE(message.find(c.expected), std::string::npos)
        << "spec: " << c.text << "\nmessage: " << message;
    EXPECT_NE(message.find("spec.json"), std::string::npos) << message;  // names the file
  }
}

TEST_F(SpecFiles, ADirectoryOrAMissingFileIsRefused) {
  EXPECT_THROW(load_spec(dir), SpecError);
  EXPECT_THROW(load_spec(dir / "absent.json"), SpecError);
}

// experiments/table1.json lists exactly the (A, E, dt, method) cells of the transcription; the
// cells without a printed dt are the ones marked dt_inferred.
TEST(ShippedSpecs, Table1HoldsExactlyThePapersCells) {
  const fs::path root = MPMSTAB_SOURCE_DIR;
  const Spec spec = load_spec(root / "experiments/table1.json");
  const CsvTable paper = read_csv(root / "reference/paper/table1.csv");
  ASSERT_EQ(spec.cases.size(), paper.rows.size());
  std::multiset<std::tuple<double, double, double, std::string>> ours, theirs;
  for (const auto& c : spec.cases) {
    const auto& p = c.params;
    ours.insert({p.A, p.E, c.dt_inferred ? -1.0 : p.dt, std::string(to_string(p.method))});
  }
  for (const auto& row : paper.rows) {
    std::string m = row.at("method");
    for (auto& ch : m)
      ch = static_cast<char>(std::tolower(ch));
    const bool printed =
        row.at("dt") != "?" && row.at("evidence").find("inferred") == std::string::npos;
    theirs.insert({std::stod(row.at("A")), std::stod(row.at("E")),
                   printed ? std::stod(row.at("dt")) : -1.0, m});
  }
  EXPECT_EQ(ours, theirs);
}

TEST(ShippedSpecs, EverySpecLoads) {
  const fs::path root = MPMSTAB_SOURCE_DIR;
  for (const char* name : {"table1", "table2", "fig1", "fig2", "fig3"}) {
    EXPECT_NO_THROW(load_spec(root / "experiments" / (std::string(name) + ".json"))) << name;
  }
  const Spec fig2 = load_spec(root / "experiments/fig2.json");
  EXPECT_TRUE(fig2.cases[0].params.observe.history);
  const Spec table1 = load_spec(root / "experiments/table1.json");
  EXPECT_FALSE(table1.cases[0].params.observe.history);  // no history where no figure needs it
}

}  // namespace
}  // namespace mpmstab
