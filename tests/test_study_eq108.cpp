// The eq108 study sets each reading of eq. (108) against the paper's dt stable column, cell by
// cell, and claims a reading reproduces the column only when it does in every compared cell.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "study_rows.hpp"

namespace mpmstab {
namespace {

using ojson = nlohmann::ordered_json;

TEST(Eq108Study, EachReadingIsSetAgainstThePapersDtStable) {
  // The paper's GIMP cell at E = 1000, A = 0.015, dt = 1e-4 prints dt stable 3.9e-5.
  Spec spec;
  spec.name = std::string("eq108");
  spec.study = find_study("eq108");
  spec.reference = std::filesystem::path(MPMSTAB_SOURCE_DIR) / "reference" / "paper" / "table1.csv";
  std::vector<ojson> rows;
  for (const char* sigma : {"scaled", "raw"}) {
    CaseSpec c;
    c.params.method = Method::gimp;
    c.params.E = 1000;
    c.params.A = 0.015;
    c.params.dt = 1e-4;
    spec.cases.push_back(c);
    ojson r = test_support::study_row("gimp", 1000);
    r["dt_stable_sigma"] = sigma;
    r["dt_stable_vnorm"] = "l2";
    r["dt_stable_min"] = std::string(sigma) == "scaled" ? 3.9e-6 : 2e-5;  // 0.1 and 0.51 x
    rows.push_back(r);
  }
  const SweepOutcome outcome;
  const std::filesystem::path out = std::filesystem::temp_directory_path();
  const std::string header = "# header\n";
  const StudyInputs inputs;
  const std::vector<ojson> none;
  const StudyReport report =
      spec.study->report(ReportContext{spec, rows, outcome, out, header, inputs, none});
  EXPECT_NE(report.markdown.find("| 3.9e-5 | 3.9e-6 | 0.1 | 2.0e-5 | 0.51 |"), std::string::npos)
      << report.markdown;
  ASSERT_EQ(report.claims.size(), 1u);
  EXPECT_TRUE(report.claims[0].holds);  // raw, l2 is within a factor 3 in its one cell
  EXPECT_EQ(render(report.claims[0], report.claims[0].evidence),
            "the best reading (raw, l2) is within it in 1 of 1 cells; its ratios 0.51");
  // A reading whose bound is 0.1 times the paper's everywhere does not reproduce it.
  rows[1]["dt_stable_min"] = 3.9e-6;
  const StudyReport worse =
      spec.study->report(ReportContext{spec, rows, outcome, out, header, inputs, none});
  EXPECT_FALSE(worse.claims[0].holds);
}

}  // namespace
}  // namespace mpmstab
