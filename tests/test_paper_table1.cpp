// The transcribed Table 1 as the studies read it (experiments/studies/shared/paper_table1.hpp):
// every cell a spec runs is found, a cell whose dt the paper does not print is placed by the case
// marked dt_inferred and never keyed by a NaN, and a transcription or spec that cannot be read
// exactly is refused with the file and the row or case named.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>
#include <map>
#include <string>

#include <unistd.h>

#include "files.hpp"
#include "key.hpp"
#include "shared/paper_table1.hpp"
#include "spec.hpp"
#include "study_rows.hpp"

namespace mpmstab {
namespace {

namespace fs = std::filesystem;

const fs::path kExperiments = fs::path(MPMSTAB_SOURCE_DIR) / "experiments";

// The specs whose studies compare their cases with Table 1 cell by cell.
const char* const kTable1Readers[] = {"table1.json", "eq108.json", "variants.json"};

TEST(PaperTable1, EveryCaseOfEverySpecThatReadsTable1FindsItsCell) {
  for (const char* name : kTable1Readers) {
    const Spec spec = load_spec(kExperiments / name);
    const auto paper = read_paper_table1(spec);
    for (const CaseSpec& c : spec.cases) {
      EXPECT_TRUE(paper.count(paper_key(c)))
          << name << ": A = " << c.params.A << ", E = " << c.params.E << ", dt = " << c.params.dt
          << ", " << to_string(c.paper_method);
    }
  }
  // Table 1's own spec runs every cell: every row of the transcription is read, none lost.
  const Spec table1 = load_spec(kExperiments / "table1.json");
  EXPECT_EQ(read_paper_table1(table1).size(), read_paper_rows(table1.reference).size());
}

TEST(PaperTable1, ACellWithoutAPrintedDtIsReadWhereItsCaseIsAndOverwritesNoOther) {
  // Table 1 prints no dt for its last pair (A = 0.05, E = 4); the specs infer 1e-4. Keyed by a
  // NaN dt, the GIMP row overwrote the cell at dt = 1e-3 and the MPM row was lost.
  for (const char* name : {"table1.json", "eq108.json"}) {
    const auto paper = read_paper_table1(load_spec(kExperiments / name));
    const auto cell = [&](double dt, const char* method) {
      const auto it = paper.find({Key(0.05), Key(4.0), Key(dt), method});
      EXPECT_NE(it, paper.end()) << name << ", dt = " << dt << ", " << method;
      return it == paper.end() ? PaperCell{} : it->second;
    };
    EXPECT_EQ(cell(1e-4, "mpm").dt_stable.text, "4.8e-3") << name;
    EXPECT_FALSE(cell(1e-4, "mpm").dt_printed) << name;
    EXPECT_EQ(cell(1e-3, "gimp").dt_stable.text, "1.2e-3") << name;
    EXPECT_EQ(cell(1e-3, "gimp").max_error.text, "8.4e-5") << name;
    EXPECT_TRUE(cell(1e-3, "gimp").dt_printed) << name;
  }
}

// A temporary folder of the running test's own (tests run in parallel, each in its process).
fs::path test_dir() {
  const fs::path dir = fs::temp_directory_path() /
                       ("mpmstab_paper_table1_" +
                        std::string(testing::UnitTest::GetInstance()->current_test_info()->name()) +
                        "_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  return dir;
}

// A spec with one case, in the test's temporary folder, that reads the transcription `reference`.
Spec one_case_spec(const std::string& kase, const fs::path& reference) {
  const fs::path dir = test_dir();
  std::ofstream(dir / "spec.json") << R"({"name": "eq108", "report": "eq108", "reference": ")"
                                   << reference.string() << R"(", "record": ["dt_stable"],
  "defaults": {"T": 1, "cells": 100, "ppc": 2, "bc": "dirichlet"}, "cases": [)"
                                   << kase << "]}";
  return load_spec(dir / "spec.json");
}

const fs::path kTable1 = fs::path(MPMSTAB_SOURCE_DIR) / "reference" / "paper" / "table1.csv";

TEST(PaperTable1, ACaseAtAnUnprintedDtMustBeMarkedInferred) {
  const Spec unmarked =
      one_case_spec(R"({"A": 0.05, "E": 4.0, "method": "mpm", "dt": 0.0001})", kTable1);
  try {
    read_paper_table1(unmarked);
    ADD_FAILURE() << "an unprinted dt placed without dt_inferred";
  } catch (const SpecError& e) {
    EXPECT_NE(std::string(e.what()).find("cases[0]"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("dt_inferred"), std::string::npos) << e.what();
  }
  const Spec marked = one_case_spec(
      R"({"A": 0.05, "E": 4.0, "method": "mpm", "dt": 0.0001, "dt_inferred": true})", kTable1);
  // Every printed row, and the unprinted one this case places (the GIMP one stays unread).
  const auto rows = read_paper_rows(kTable1);
  const auto printed =
      std::count_if(rows.begin(), rows.end(), [](const PaperRow& r) { return r.dt.has_value(); });
  EXPECT_EQ(read_paper_table1(marked).size(), std::size_t(printed) + 1);
  fs::remove_all(test_dir());
}

TEST(PaperTable1, ATranscriptionWhoseKeyIsNotAFiniteNumberIsRefusedNamingTheRow) {
  const fs::path dir = test_dir();
  for (const char* bad : {"nan", "inf", "-nan", "0.05x"}) {
    const fs::path csv = dir / "table1.csv";
    std::ofstream(csv) << "A,E,dt,method,dt_stable,max_error,confidence,evidence\n"
                       << "0.015,4,1e-3,MPM,5.7e-3,4.7e-5,high,\n"
                       << bad << ",4,1e-3,GIMP,2.2e-3,6.8e-6,high,\n";
    const Spec spec = one_case_spec(R"({"A": 0.015, "E": 4.0, "method": "mpm", "dt": 0.001})", csv);
    try {
      read_paper_table1(spec);
      ADD_FAILURE() << bad << " read as a key";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find("row 3, column A"), std::string::npos) << e.what();
    }
  }
  fs::remove_all(dir);
}

// The table1 study's report for rows of experiments/table1.json's cases: every case stable with
// an error over time of 0.01 A, except those `change` alters (it is given the case and its row).
StudyReport table1_report(
    const std::function<void(const CaseSpec&, nlohmann::ordered_json&)>& change) {
  const Spec spec = load_spec(kExperiments / "table1.json");
  std::vector<nlohmann::ordered_json> rows;
  for (const CaseSpec& c : spec.cases) {
    auto r = test_support::study_row(std::string(to_string(c.params.method)), c.params.E);
    r["A"] = c.params.A;
    r["dt"] = c.params.dt;
    r["max_error_over_time"] = 0.01 * c.params.A;
    change(c, r);
    rows.push_back(r);
  }
  const SweepOutcome outcome;
  const fs::path out = fs::temp_directory_path();
  const std::string header = "# header\n";
  const StudyInputs inputs;
  const std::vector<nlohmann::ordered_json> follow_up;
  return spec.study->report(ReportContext{spec, rows, outcome, out, header, inputs, follow_up});
}

bool table1_claim_holds(const StudyReport& report, const std::string& id) {
  for (const auto& c : report.claims)
    if (c.id == id) return c.holds;
  ADD_FAILURE() << "no claim " << id;
  return false;
}

// A stable cell is given with its error over time / A and its accuracy class, and the count of
// stable cells is split by class: a stable MPM cell at 0.89 A is stable but inaccurate.
TEST(Table1Study, EveryStableCellStandsBesideItsErrorOverTimeAndAccuracyClass) {
  const auto is = [](const CaseSpec& c, double E, double A, double dt, Method m) {
    return c.params.E == E && c.params.A == A && c.params.dt == dt && c.params.method == m;
  };
  int cases = 0;
  const StudyReport report = table1_report([&](const CaseSpec& c, nlohmann::ordered_json& r) {
    ++cases;
    if (is(c, 64, 0.015, 1e-5, Method::mpm)) r["max_error_over_time"] = 0.89 * c.params.A;
    if (is(c, 64, 0.015, 1e-6, Method::mpm)) test_support::meaningless_row(r);
    if (is(c, 1e4, 0.015, 1e-4, Method::mpm)) test_support::fail_row(r, "nonpositive_F");
  });
  const std::string& md = report.markdown;
  const std::string inaccurate = test_support::line_with(md, "| 0.89 | inaccurate |");
  EXPECT_EQ(inaccurate.rfind("| 1e-5 | mpm |", 0), 0u) << inaccurate;
  EXPECT_NE(inaccurate.find("| stable | 0.89 | inaccurate |"), std::string::npos) << inaccurate;
  EXPECT_NE(md.find("| stable | 0.01 | accurate |"), std::string::npos) << md;
  EXPECT_NE(md.find("error over time reached A) | 1 | meaningless |"), std::string::npos) << md;
  EXPECT_NE(md.find("(t = 1.0e-3) | – | – |"), std::string::npos) << md;
  const int stable = cases - 2;
  EXPECT_NE(
      md.find("Ours: " + std::to_string(stable) +
              " stable (survived to T with an error over time below A): " +
              std::to_string(stable - 1) + " accurate and 1 inaccurate (error over time 0.89 A)"),
      std::string::npos)
      << md;
  EXPECT_FALSE(table1_claim_holds(report, "stable-cells-accurate"));
  // With every stable cell below 0.1 A, the claim holds.
  const StudyReport accurate = table1_report([&](const CaseSpec&, nlohmann::ordered_json&) {});
  EXPECT_TRUE(table1_claim_holds(accurate, "stable-cells-accurate"));
  EXPECT_NE(accurate.markdown.find(std::to_string(cases) + " accurate and 0 inaccurate"),
            std::string::npos);
}

TEST(Key, HoldsOnlyFiniteNumbersAndOrdersThemTotally) {
  EXPECT_THROW(Key(std::numeric_limits<double>::quiet_NaN(), "dt"), std::invalid_argument);
  EXPECT_THROW(Key(std::numeric_limits<double>::infinity(), "dt"), std::invalid_argument);
  EXPECT_EQ(Key(-0.0), Key(0.0));
  std::map<Key, int> m;
  for (int i = 0; i < 100; ++i)
    m[Key(1.0 / (i + 1))] = i;
  EXPECT_EQ(m.size(), 100u);
  EXPECT_EQ(m.begin()->second, 99);
  // TotalLess sorts a NaN last instead of breaking the sort.
  std::vector<double> v{3, std::numeric_limits<double>::quiet_NaN(), -1, 2};
  std::sort(v.begin(), v.end(), TotalLess{});
  EXPECT_EQ(v[0], -1);
  EXPECT_EQ(v[2], 3);
  EXPECT_TRUE(std::isnan(v[3]));
}

}  // namespace
}  // namespace mpmstab
