// Experiment specs: every malformed spec is refused with the file and the key path; the shipped
// specs hold exactly the paper's cells.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <set>

#include "cache.hpp"
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
  EXPECT_FALSE(p.observe.dt_stable);       // not asked for: not computed
  EXPECT_TRUE(p.observe.error_over_time);  // always: every record's outcome reads it
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
      {with_case(R"({"method": "gimp", "E": 4, "A": 0.01, "dt": 1e-3, "jitter": -0.1})"),
       "cases[0].jitter: must be a number in [0, 1)"},
      {with_case(R"({"method": "gimp", "E": 4, "A": 0.01, "dt": 1e-3, "shift": "x"})"),
       "cases[0].shift: must be a number"},
      {with_case(R"({"method": "gimp", "E": 4, "A": 0.01, "dt": 1e-3, "shift": 0.4,
                     "jitter": 0.5})"),
       "cases[0].jitter: |shift| + jitter / 2 must stay below 0.5"},
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

// A base spec of three Table 1 style cells and a variants spec that takes its cases.
const char* kBase = R"({
  "name": "base", "report": "table1", "reference": "paper.csv",
  "record": ["error_over_time", "dt_stable"],
  "defaults": {"T": 0.05, "cells": 20, "dt": 1e-4},
  "cases": [{"method": "gimp", "E": 4, "A": 0.015},
            {"method": "mpm", "E": 4, "A": 0.015},
            {"method": "gimp", "E": 64, "A": 0.05, "dt_inferred": true}]
})";

class VariantSpecs : public SpecFiles {
 protected:
  void SetUp() override {
    SpecFiles::SetUp();
    std::ofstream(dir / "base.json") << kBase;
  }
  // A variants spec taking base.json's cases, with these variants (JSON array text).
  std::string variants(const std::string& list, const std::string& extra = "") {
    return R"({"name": "v", "report": "variants", "cases_from": "base.json", )" + extra +
           R"("variants": )" + list + "}";
  }
};

TEST_F(VariantSpecs, EveryVariantAppliesItsSettingsToTheCasesItConcerns) {
  const Spec s = load_spec(write(variants(R"([
      {"name": "default", "description": "as is"},
      {"name": "cp+ghost", "set": {"method": "cpgimp", "walls": "ghost"}, "methods": ["gimp"]},
      {"name": "over-time", "error_at": "max_over_time"},
      {"name": "blend", "set": {"transfer": "blend", "flip_fraction": 0.9}}])")));
  EXPECT_EQ(s.study, find_study("variants"));
  EXPECT_EQ(s.cases_from.filename(), "base.json");
  EXPECT_EQ(s.reference, dir / "paper.csv");  // the base spec's, resolved next to it
  ASSERT_EQ(s.variants.size(), 4u);
  ASSERT_EQ(s.cases.size(), 3u + 2u + 3u + 3u);
  EXPECT_TRUE(s.variants[0].baseline);
  EXPECT_EQ(s.variants[0].change, "none");
  EXPECT_EQ(s.variants[0].description, "as is");
  EXPECT_EQ(s.variants[1].changes, 2);
  EXPECT_EQ(s.variants[1].first_case, 3u);
  EXPECT_EQ(s.variants[1].cases, 2u);
  EXPECT_EQ(s.variants[2].change, "error_at = max_over_time");
  EXPECT_EQ(s.variants[3].changes, 1);  // flip_fraction qualifies transfer
  // The gimp cells run with cpGIMP and ghost nodes, still compared with the paper's GIMP column.
  const CaseSpec& cp = s.cases[3];
  EXPECT_EQ(cp.variant, "cp+ghost");
  EXPECT_EQ(cp.params.method, Method::cpgimp);
  EXPECT_EQ(cp.paper_method, Method::gimp);
  EXPECT_EQ(cp.params.walls, Walls::ghost);
  EXPECT_EQ(cp.params.T, 0.05);                    // the base spec's defaults
  EXPECT_TRUE(cp.params.observe.error_over_time);  // and its record
  EXPECT_TRUE(s.cases[4].dt_inferred);
  EXPECT_EQ(s.cases[5].error_at, ErrorAt::max_over_time);
  EXPECT_EQ(s.cases[0].error_at, ErrorAt::T);
  EXPECT_EQ(s.cases[9].params.flip_fraction, 0.9);
  // The default's runs are the base spec's runs: same parameters, so the same cache entries.
  const Spec base = load_spec(dir / "base.json");
  EXPECT_EQ(canonical_parameters(s.cases[1].params), canonical_parameters(base.cases[1].params));
}

// dt_at_least keeps the base cases whose fixed dt is at least its value, and says so.
TEST_F(VariantSpecs, DtAtLeastRunsOnlyTheCellsWithLargerSteps) {
  std::ofstream(dir / "steps.json") << R"({"name": "steps", "report": "table1",
      "reference": "paper.csv", "defaults": {"T": 0.01, "E": 4, "A": 0.015},
      "cases": [{"method": "gimp", "dt": 1e-3}, {"method": "gimp", "dt": 1e-5},
                {"method": "mpm", "dt": 1e-4}, {"method": "mpm", "dt": 1e-6}]})";
  const Spec s = load_spec(write(R"({"name": "v", "report": "variants", "cases_from": "steps.json",
      "variants": [{"name": "default"},
                   {"name": "pic", "set": {"transfer": "pic"}, "dt_at_least": 1e-4}]})"));
  ASSERT_EQ(s.cases.size(), 4u + 2u);
  EXPECT_EQ(s.variants[1].cases, 2u);
  EXPECT_EQ(s.cases[4].params.dt, 1e-3);
  EXPECT_EQ(s.cases[5].params.dt, 1e-4);
  EXPECT_EQ(s.variants[1].change, "transfer = pic; only the cells with dt >= 0.0001");
  EXPECT_EQ(s.variants[1].changes, 1);
}

TEST_F(VariantSpecs, ErrorAtIsACaseKeyOfAnyTableSpec) {
  const Spec s = load_spec(write(R"({"name": "t", "report": "table1", "reference": "x.csv",
      "record": ["error_over_time"], "defaults": {"T": 0.05, "dt": 1e-3, "error_at": "max_over_time"},
      "cases": [{"method": "gimp", "E": 4, "A": 0.01},
                {"method": "mpm", "E": 4, "A": 0.01, "error_at": "T"}]})"));
  EXPECT_EQ(s.cases[0].error_at, ErrorAt::max_over_time);
  EXPECT_EQ(s.cases[1].error_at, ErrorAt::T);
}

TEST_F(VariantSpecs, ErrorsNameTheKeyPath) {
  const std::string def = R"({"name": "default"})";
  std::ofstream(dir / "nested.json")
      << R"({"name": "n", "report": "variants", "cases_from": "base.json", "variants": [{"name": "d"}]})";
  std::ofstream(dir / "broken.json") << R"({"name": "b", "report": "table1", "reference": "p.csv",
      "cases": [{"method": "gimp", "E": -4, "A": 0.01, "dt": 1e-3}]})";
  struct Case {
    std::string text;
    std::string expected;
  };
  const std::vector<Case> cases = {
      {R"({"name": "v", "report": "variants", "cases_from": "absent.json", "variants": [{"name": "d"}]})",
       "cases_from: " + (dir / "absent.json").string() + ": does not exist"},
      {R"({"name": "v", "report": "variants", "cases_from": ".", "variants": [{"name": "d"}]})",
       "cases_from: " + (dir / ".").string() + ": is a directory"},
      {R"({"name": "v", "report": "variants", "cases_from": "spec.json", "variants": [{"name": "d"}]})",
       "cases_from: names this spec itself"},
      {R"({"name": "v", "report": "variants", "cases_from": "nested.json", "variants": [{"name": "d"}]})",
       "cases_from: " + (dir / "nested.json").string() +
           ": cases_from: a spec named by cases_from must list its own cases"},
      {R"({"name": "v", "report": "variants", "cases_from": "broken.json", "variants": [{"name": "d"}]})",
       "cases_from: " + (dir / "broken.json").string() + ": cases[0].E: must be"},
      {R"({"name": "v", "report": "variants", "cases_from": 3, "variants": [{"name": "d"}]})",
       "cases_from: must be a string"},
      {variants("[" + def + "]",
                R"("cases": [{"method": "gimp", "E": 4, "A": 0.01, "dt": 1e-3}], )"),
       "cases: cases and cases_from exclude each other"},
      {variants("[" + def + "]", R"("defaults": {"T": 1}, )"),
       "defaults: cases_from takes the cases"},
      {R"({"name": "v", "report": "variants", "cases_from": "base.json"})",
       "variants: is required for a variants report"},
      {R"({"name": "v", "report": "table1", "cases_from": "base.json", "variants": []})",
       "variants: only a variants report takes variants"},
      {variants("[]"), "variants: must be a non-empty array"},
      {variants("[3]"), "variants[0]: must be an object"},
      {variants(R"([{"description": "x"}])"), "variants[0].name: is required"},
      {variants(R"([{"name": "A b"}])"), "variants[0].name: must be a non-empty name"},
      {variants("[" + def + "," + def + "]"), "variants[1].name: repeats 'default'"},
      {variants("[" + def + R"(, {"name": "w", "sett": {}}])"),
       "variants[1].sett: unknown key 'sett' (did you mean 'set'?)"},
      {variants("[" + def + R"(, {"name": "w", "set": []}])"),
       "variants[1].set: must be an object"},
      {variants("[" + def + R"(, {"name": "w", "set": {"wals": "ghost"}}])"),
       "variants[1].set.wals: unknown key 'wals' (did you mean 'walls'?)"},
      {variants("[" + def + R"(, {"name": "w", "set": {"walls": "open"}}])"),
       "variants[1].set.walls: unknown value 'open'"},
      {variants("[" + def + R"(, {"name": "w", "set": {"dt": 1e-5}}])"),
       "variants[1].set.dt: a variant keeps each cell's E, A and dt"},
      {variants("[" + def + R"(, {"name": "w", "set": {"error_at": "T"}}])"),
       "variants[1].set.error_at: is a key of the variant itself"},
      {variants("[" + def + R"(, {"name": "w", "set": {"dt_inferred": true}}])"),
       "variants[1].set.dt_inferred"},
      {variants("[" + def +
                R"(, {"name": "w", "set": {"transfer": "blend", "flip_fraction": 2}}])"),
       "variants[1].set.flip_fraction: with base case 0: flip_fraction must be a number in (0, 1)"},
      {variants("[" + def + R"(, {"name": "w", "set": {"bc": "periodic", "walls": "ghost"}}])"),
       "variants[1].set.walls: with base case 0"},
      {variants("[" + def + R"(, {"name": "w", "set": {"method": "mpm"}}])"),
       "variants[1]: makes base cases 0 and 1 the same run"},
      {variants("[" + def + R"(, {"name": "w", "methods": "gimp"}])"),
       "variants[1].methods: must be a non-empty array"},
      {variants("[" + def + R"(, {"name": "w", "methods": ["gimpp"]}])"),
       "variants[1].methods[0]: unknown value 'gimpp'"},
      {variants("[" + def + R"(, {"name": "w", "methods": ["mpm", "mpm"]}])"),
       "variants[1].methods[1]: repeats 'mpm'"},
      {variants("[" + def + R"(, {"name": "w", "methods": ["cpgimp"]}])"),
       "variants[1].methods: matches none of the base cases"},
      {variants("[" + def + R"(, {"name": "w", "set": {"transfer": "pic"}, "dt_at_least": 0}])"),
       "variants[1].dt_at_least: must be a positive number"},
      {variants("[" + def + R"(, {"name": "w", "set": {"transfer": "pic"}, "dt_at_least": "1"}])"),
       "variants[1].dt_at_least: must be a number"},
      {variants("[" + def + R"(, {"name": "w", "set": {"transfer": "pic"}, "dt_at_least": 1}])"),
       "variants[1].dt_at_least: matches none of the base cases"},
      {variants(R"([{"name": "d", "dt_at_least": 1e-5}])"),
       "variants[0].dt_at_least: the default variant runs every cell"},
      {variants("[" + def + R"(, {"name": "w", "error_at": "end"}])"),
       "variants[1].error_at: unknown value 'end' (expected T or max_over_time)"},
      {variants(R"([{"name": "w", "set": {"walls": "ghost"}}])"),
       "variants: needs one variant that changes nothing"},
      {R"({"name": "t", "report": "table1", "reference": "x.csv", "cases": [
          {"method": "gimp", "E": 4, "A": 0.01, "dt": 1e-3, "error_at": "t"}]})",
       "cases[0].error_at: unknown value 't'"},
  };
  for (const auto& c : cases) {
    const std::string message = error_of(c.text);
    EXPECT_NE(message.find(c.expected), std::string::npos)
        << "spec: " << c.text << "\nmessage: " << message;
    EXPECT_EQ(message.rfind((dir / "spec.json").string(), 0), 0u) << message;  // names the file
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
  for (const char* name : {"table1", "table2", "fig1", "fig2", "fig3", "variants"}) {
    EXPECT_NO_THROW(load_spec(root / "experiments" / (std::string(name) + ".json"))) << name;
  }
  const Spec fig2 = load_spec(root / "experiments/fig2.json");
  EXPECT_TRUE(fig2.cases[0].params.observe.history);
  const Spec table1 = load_spec(root / "experiments/table1.json");
  EXPECT_FALSE(table1.cases[0].params.observe.history);  // no history where no figure needs it
}

// The variants study: every Table 1 cell under the default, whose runs are table1.json's.
TEST(ShippedSpecs, TheVariantsStudyStartsFromTable1sRuns) {
  const fs::path root = MPMSTAB_SOURCE_DIR;
  const Spec table1 = load_spec(root / "experiments/table1.json");
  const Spec v = load_spec(root / "experiments/variants.json");
  ASSERT_FALSE(v.variants.empty());
  EXPECT_TRUE(v.variants.front().baseline);
  ASSERT_EQ(v.variants.front().cases, table1.cases.size());
  for (std::size_t i = 0; i < table1.cases.size(); ++i) {
    EXPECT_EQ(canonical_parameters(v.cases[i].params),
              canonical_parameters(table1.cases[i].params));
  }
  for (const auto& vs : v.variants)
    EXPECT_FALSE(vs.description.empty()) << vs.name;
}

}  // namespace
}  // namespace mpmstab
