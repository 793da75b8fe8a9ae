// The methods study's wave column set against runs: one single-mode run per scheme (the walls'
// treatments sharing it) on the column's cells rounded up, none where the column is above its
// cap, the run's error printed beside the column, and the claim that the column's value gives a
// run within the tolerance counted over the schemes run, with where they were run.
#include <gtest/gtest.h>

#include <cmath>

#include "analysis/dispersion.hpp"
#include "scenes/validate.hpp"
#include "study_rows.hpp"

namespace mpmstab {
namespace {

using ojson = nlohmann::ordered_json;
using test_support::line_with;
using test_support::study_row;

// An edge search's row of the study: the bar at the tiny amplitude.
ojson method_row(const std::string& method, const std::string& transfer, const char* walls) {
  ojson r = study_row(method, 64);
  r["transfer"] = transfer;
  r["update"] = "usl";
  r["walls"] = walls;
  r["A"] = 1e-4;
  r["dt_edge_over_cfl"] = 1.0;
  return r;
}

// The cells the symbol asks for at the study's C, periods and tolerance, rounded up.
int column_cells(Method method, Transfer transfer) {
  RunParams p;
  p.method = method;
  p.transfer = transfer;
  return int(std::ceil(*cells_per_wavelength_amplitude(dispersion_scheme(p), 0.5, 10, 0.01)));
}

// A single-mode run of the row's scheme on `cells` cells with its error over time per A.
ojson mode_run(ojson r, int cells, double error_over_A) {
  r["scene"] = "mode";
  r["bc"] = "periodic";
  r["walls"] = "clip";
  r["E"] = 1.0;
  r["A"] = 1e-6;
  r["T"] = 10.0;
  r["cT"] = 10.0;
  r["cells"] = cells;
  r["dt"] = 0.5 / cells;
  r["steps"] = 20 * cells;
  r["particles"] = 2 * cells;
  r["max_error_over_time"] = error_over_A * 1e-6;
  return r;
}

const std::vector<ojson> kRows = {
    method_row("gimp", "flip", "clip"), method_row("bspline2", "flip", "clip"),
    method_row("bspline2", "flip", "modified"),  // shares the run of the line above
    method_row("gimp", "pic", "clip")};          // its column is thousands of cells: not run

TEST(MethodsStudy, AsksOneSingleModeRunPerSchemeOnTheColumnsCells) {
  Spec spec;
  spec.study = find_study("methods");
  for (const auto& r : kRows) {
    CaseSpec c;
    c.params.method = *parse_method(r["method"].get<std::string>());
    c.params.transfer = *parse_transfer(r["transfer"].get<std::string>());
    c.params.walls = *parse_walls(r["walls"].get<std::string>());
    spec.cases.push_back(c);
  }
  const StudyInputs inputs;
  const auto asked = spec.study->follow_up(FollowUpContext{spec, kRows, inputs});
  ASSERT_EQ(asked.size(), 2u);
  EXPECT_EQ(asked[0].of, 0u);
  EXPECT_EQ(asked[1].of, 1u);
  EXPECT_EQ(asked[0].params.cells, column_cells(Method::gimp, Transfer::flip));
  EXPECT_EQ(asked[1].params.cells, column_cells(Method::bspline2, Transfer::flip));
  for (const auto& f : asked) {
    EXPECT_EQ(f.params.scene, SceneKind::mode);
    EXPECT_EQ(f.params.bc, Boundary::periodic);
    EXPECT_EQ(f.params.walls, Walls::clip);
    EXPECT_DOUBLE_EQ(*courant_number(f.params), 0.5);
    EXPECT_DOUBLE_EQ(wave_passes(f.params), 10.0);
    EXPECT_TRUE(validate(f.params).empty());
  }
}

TEST(MethodsStudy, PrintsEachRunBesideTheColumnAndCountsTheSchemesWithin) {
  const int gimp = column_cells(Method::gimp, Transfer::flip);
  const int spline = column_cells(Method::bspline2, Transfer::flip);
  const std::vector<ojson> runs = {mode_run(kRows[0], gimp, 0.005),
                                   mode_run(kRows[1], spline, 0.03)};
  const auto report = test_support::study_report("methods", kRows, runs);
  EXPECT_NE(line_with(report.markdown, "| gimp | flip |").find("| 0.5% |"), std::string::npos);
  EXPECT_NE(line_with(report.markdown, "| bspline2 | flip |").find("| 3% |"), std::string::npos);
  EXPECT_NE(line_with(report.markdown, "| bspline2 (modified) | flip |").find("| 3% |"),
            std::string::npos);
  EXPECT_NE(line_with(report.markdown, "| gimp | pic |").find("| not run (column above its cap) |"),
            std::string::npos);
  ASSERT_EQ(report.claims.size(), 1u);
  const Claim& c = report.claims[0];
  EXPECT_EQ(c.id, "wave-column-within-tolerance-in-a-run");
  EXPECT_EQ(c.status(), Claim::Status::fails);  // 1 of 2 schemes within
  EXPECT_NE(c.measured_on.find("mode"), std::string::npos) << c.measured_on;
  EXPECT_NE(c.measured_on.find("A = 1e-6"), std::string::npos) << c.measured_on;
  EXPECT_NE(report.markdown.find("by transfer flip 1 of 2"), std::string::npos);
}

}  // namespace
}  // namespace mpmstab
