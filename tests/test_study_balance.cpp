// The balance study's reading of its rows: the plateau, the time part, the balancing Courant
// number interpolated between the two C that bracket it, the time order, and the claims that
// compare the orders with first and second order.
#include <gtest/gtest.h>

#include <cmath>

#include "study_rows.hpp"

namespace mpmstab {
namespace {

using ojson = nlohmann::ordered_json;

// A run of the balance study's scan: error = plateau + k C^p (no particle crosses a cell).
ojson scan_row(const std::string& method, int cells, double C, double error) {
  ojson r = study_row(method, 64);
  r["transfer"] = "flip";
  r["update"] = "usl";
  r["A"] = 2.5e-4;
  r["A_over_h"] = 2.5e-4 * cells;
  r["cells"] = cells;
  r["policy"] = "cfl";
  r["cfl_factor"] = C;
  r["max_error_over_time"] = error;
  r["crossings"] = 0;
  return r;
}

std::vector<ojson> scan(const std::string& method, int cells, double plateau, double k, double p) {
  std::vector<ojson> rows;
  for (const double C : {0.8, 0.4, 0.2, 0.1, 0.05, 0.025})
    rows.push_back(scan_row(method, cells, C, plateau + k * std::pow(C, p)));
  return rows;
}

TEST(BalanceStudy, TheBalancingCourantNumberAndTheTimeOrderComeFromTheRows) {
  // First order, time part = plateau at C = 0.2 on 100 cells, at C = 0.1 on 200 cells (the
  // time part measured from the plateau at C = 0.025, which holds a little time error too).
  std::vector<ojson> rows = scan("gimp", 100, 1e-6, 5e-6, 1);
  for (const auto& r : scan("gimp", 200, 1e-6, 1e-5, 1))
    rows.push_back(r);
  const auto report = test_support::study_report("balance", rows);
  const std::string& md = report.markdown;
  // 100 cells: plateau 1e-6 + 5e-6 x 0.025 = 1.125e-6; time part 5e-6 (C - 0.025), 1.875e-6 at
  // C = 0.4 and 8.75e-7 at 0.2: on log axes the plateau lies 0.330 of the way from 0.2 to 0.4,
  // C = 0.2 x 2^0.330 = 0.251. 200 cells: plateau 1.25e-6, time part 1e-5 (C - 0.025): 0.152.
  // The time order, fitted over C = 0.8 to 0.1 (the time part at 0.05 is below the plateau /
  // 4), is the slope of log(C - 0.025) against log(C) there: 1.12.
  const std::string line = test_support::line_with(md, "| bar | gimp |");
  EXPECT_NE(line.find("| bar | gimp | 0.251 (1.12) | 0.152 (1.12) |"), std::string::npos) << md;
  bool first = false;
  for (const auto& c : report.claims) {
    if (c.id == "flip-time-error-first-order") {
      first = true;
      EXPECT_TRUE(c.holds) << render(c, c.evidence);
    }
    if (c.id == "balance-falls-with-h") {
      EXPECT_TRUE(c.holds) << render(c, c.evidence);
    }
  }
  EXPECT_TRUE(first);
}

TEST(BalanceStudy, ASecondOrderTimePartIsNotCalledFirstOrderAndAGapIsMarked) {
  std::vector<ojson> rows = scan("gimp", 100, 1e-7, 1e-5, 2);
  // A run left out below a C that entered: a gap in the curve, marked.
  rows[3]["outcome"] = "unstable";
  const auto report = test_support::study_report("balance", rows);
  EXPECT_NE(report.markdown.find("‡"), std::string::npos);
  for (const auto& c : report.claims)
    if (c.id == "flip-time-error-first-order") {
      EXPECT_FALSE(c.holds) << render(c, c.evidence);
    }
}

}  // namespace
}  // namespace mpmstab
