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
            "the best reading (raw, l2: the most cells within it, ties broken by the smallest mean "
            "absolute natural log of ours / paper, here 0.668) is within it in 1 of 1 cells; its "
            "ratios 0.51");
  // A reading whose bound is 0.1 times the paper's everywhere does not reproduce it.
  rows[1]["dt_stable_min"] = 3.9e-6;
  const StudyReport worse =
      spec.study->report(ReportContext{spec, rows, outcome, out, header, inputs, none});
  EXPECT_FALSE(worse.claims[0].holds);
}

// The same cells on a coarser grid: each is set against the paper's dt stable beside the same
// cell on the paper's grid, and the claim for that grid holds only when every compared cell is
// within the agreement factor; those runs never enter the readings of the paper's grid.
TEST(Eq108Study, ACoarserGridIsSetAgainstThePaperBesideThePapersGrid) {
  // The paper's MPM cells at A = 0.015, dt = 1e-4 print dt stable 9.1e-4 (E = 256), 1.8e-3
  // (E = 64) and 3.4e-3 (E = 16).
  struct Cell {
    double E, paper;
  };
  const std::vector<Cell> cells = {{256, 9.1e-4}, {64, 1.8e-3}, {16, 3.4e-3}};
  Spec spec;
  spec.name = std::string("eq108");
  spec.study = find_study("eq108");
  spec.reference = std::filesystem::path(MPMSTAB_SOURCE_DIR) / "reference" / "paper" / "table1.csv";
  std::vector<ojson> rows;
  for (const int grid : {100, 10}) {
    for (const Cell& cell : cells) {
      CaseSpec c;
      c.params.method = Method::mpm;
      c.paper_method = Method::mpm;
      c.params.E = cell.E;
      c.params.A = 0.015;
      c.params.dt = 1e-4;
      c.params.cells = grid;
      spec.cases.push_back(c);
      ojson r = test_support::study_row("mpm", cell.E);
      r["cells"] = grid;
      r["dt_stable_sigma"] = "scaled";
      r["dt_stable_vnorm"] = "l2";
      // 0.08 times the paper on 100 cells, 1.2 times on 10.
      r["dt_stable_min"] = (grid == 100 ? 0.08 : 1.2) * cell.paper;
      rows.push_back(r);
    }
  }
  const SweepOutcome outcome;
  const std::filesystem::path out = std::filesystem::temp_directory_path();
  const std::string header = "# header\n";
  const StudyInputs inputs;
  const std::vector<ojson> none;
  auto report = [&] {
    return spec.study->report(ReportContext{spec, rows, outcome, out, header, inputs, none});
  };
  const StudyReport r = report();
  ASSERT_EQ(r.claims.size(), 2u);
  // The paper's grid: its one reading is 0.08 times the paper in each of its 3 cells.
  EXPECT_FALSE(r.claims[0].holds);
  EXPECT_EQ(render(r.claims[0], r.claims[0].evidence),
            "the best reading (scaled, l2: the most cells within it, ties broken by the smallest "
            "mean absolute natural log of ours / paper, here 2.53) is within it in 0 of 3 cells; "
            "its ratios 0.08");
  // The coarser grid: 1.2 times the paper in each, beside 0.08 on the paper's grid; measured on
  // that grid's runs.
  EXPECT_EQ(r.claims[1].id, "grid-10-scaled-l2-gives-the-paper");
  EXPECT_TRUE(r.claims[1].holds);
  EXPECT_EQ(r.claims[1].support, 3);
  EXPECT_EQ(render_statement(r.claims[1]),
            "On 10 cells (h = 0.1) instead of the paper's 100, eq. (108) (scaled, l2) gives the "
            "paper's dt stable column within a factor 3 in every cell where both are measured");
  EXPECT_EQ(render(r.claims[1], r.claims[1].evidence),
            "3 of 3 cells, ratios 1.2, in those within it 1.2 (on 100 cells 0.08 in 3 cells)");
  EXPECT_EQ(r.claims[1].measured_on, "A = 0.015; c T = 4, 8 and 16; 10 cells; bar");
  EXPECT_EQ(r.claims[0].measured_on, "A = 0.015; c T = 4, 8 and 16; 100 cells; bar");
  EXPECT_NE(r.markdown.find("## On 10 cells"), std::string::npos) << r.markdown;
  // The row: the paper, the paper's grid's bound and ratio, then this grid's bound, its ratio,
  // its error over time / A (1e-5 / 0.015) and accuracy class.
  EXPECT_NE(r.markdown.find("| 9.1e-4 | scaled, l2 | 7.3e-5 | 0.08 | 1.1e-3 | 1.2 | 6.7e-4 | "
                            "accurate |"),
            std::string::npos)
      << r.markdown;
  // One cell four times below the paper on the coarser grid refutes it.
  rows[4]["dt_stable_min"] = 0.25 * cells[1].paper;
  const StudyReport worse = report();
  EXPECT_FALSE(worse.claims[1].holds);
  EXPECT_EQ(render(worse.claims[1], worse.claims[1].evidence),
            "2 of 3 cells, ratios 0.25 to 1.2, in those within it 1.2 (on 100 cells 0.08 in 3 "
            "cells); beyond it: mpm E = 64, A = 0.015, dt = 1e-4 (0.25 times the paper's 1.8e-3, "
            "transcribed with high confidence)");
  // A meaningless run on the coarser grid is shown but not compared.
  test_support::meaningless_row(rows[4]);
  const StudyReport fewer = report();
  EXPECT_EQ(fewer.claims[1].support, 2);
  EXPECT_NE(fewer.markdown.find("4.5e-4 (meaningless) | – | 1.0 | meaningless |"),
            std::string::npos)
      << fewer.markdown;
}

}  // namespace
}  // namespace mpmstab
