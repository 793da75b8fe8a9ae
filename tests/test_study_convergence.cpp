// The convergence study: the orders it fits are the slopes of the errors it tabulates, and a run
// that did not end stable leaves its point out of the fit.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>

#include "study_rows.hpp"
#include "support.hpp"

namespace {

namespace fs = std::filesystem;

std::string read(const fs::path& p) {
  std::ifstream in(p);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

TEST(ConvergenceStudy, TheFittedOrderIsTheSlopeOfTheTabulatedErrors) {
  const fs::path dir = fs::temp_directory_path() / ("mpmstab_conv_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  const std::string baseline =
      (fs::path(MPMSTAB_SOURCE_DIR) / "reference/peers/uintah_oofa_mms_baseline.csv").string();
  std::ofstream(dir / "conv.json") << R"({"name": "conv", "report": "convergence",
    "reference": ")" + baseline + R"(",
    "record": ["error_over_time", "error_l2"], "defaults": {"A": 0.001, "T": 0.3, "E": 64, "dt": 2e-5},
    "cases": [{"method": "bspline2", "cells": 25}, {"method": "bspline2", "cells": 50},
              {"method": "bspline2", "cells": 100},
              {"method": "mpm", "cells": 25, "dt": 0.2, "T": 0.5},
              {"method": "mpm", "cells": 50}, {"method": "mpm", "cells": 100},
              {"method": "bspline2", "cells": 25, "A": 2e-4},
              {"method": "bspline2", "cells": 50, "A": 2e-4},
              {"method": "bspline2", "cells": 100, "A": 2e-4}]})";
  const auto r = mpmstab::test_support::run_mpmstab("sweep " + (dir / "conv.json").string() +
                                                    " --out " + (dir / "out").string());
  ASSERT_EQ(r.status, 0) << r.output;
  const std::string md = read(dir / "out" / "conv.md");
  // | 64 | bspline2 | e25 | e50 (ratio, order) | e100 (ratio, order) | fitted | limit | at T |
  // in the first table: the error over time.
  const std::regex row(
      R"(\| 64 \| bspline2 \| ([0-9.e-]+) \| ([0-9.e-]+) \(([0-9.]+), ([0-9.-]+)\) \| )"
      R"(([0-9.e-]+) \(([0-9.]+), ([0-9.-]+)\) \| ([0-9.-]+) \|)");
  std::smatch m;
  ASSERT_TRUE(std::regex_search(md, m, row)) << md;
  const double e25 = std::stod(m[1]), e50 = std::stod(m[2]), e100 = std::stod(m[5]);
  const double ratio50 = std::stod(m[3]), order50 = std::stod(m[4]), order = std::stod(m[8]);
  // The bracket of a cell is the ratio to the grid before it and its order (h halves).
  EXPECT_NEAR(ratio50, e25 / e50, 0.01 * e25 / e50) << md;
  EXPECT_NEAR(order50, std::log2(e25 / e50), 0.01) << md;
  // Three points, equally spaced in log h: the least-squares slope is that of the end points
  // (to the two digits the table prints).
  EXPECT_NEAR(order, std::log(e25 / e100) / std::log(4.0), 0.1) << md;
  EXPECT_GT(order, 1.0) << md;
  // MPM's coarsest run steps past T at once (dt = 0.2 > h/c): unstable, so only two points
  // remain and no order is fitted.
  const std::regex mpm_row(
      R"(\| 64 \| mpm \| unstable \| [0-9.e-]+ \| [0-9.e-]+ \([^)]*\) \| – \|)");
  EXPECT_TRUE(std::regex_search(md, mpm_row)) << md;
  // The L2 table is there, and every order is fitted to a norm over time, never to the error
  // at T alone.
  EXPECT_NE(md.find("The L2 error over time"), std::string::npos) << md;
  EXPECT_TRUE(fs::exists(dir / "out" / "conv_data.csv"));
  // The refinement at another amplitude has a table of its own and is not drawn: the figure's
  // data holds the three bspline2 and the two stable mpm runs at the study's amplitude.
  EXPECT_NE(md.find("### The bases with a published order on finer grids"), std::string::npos);
  EXPECT_EQ(mpmstab::test_support::data_lines(read(dir / "out" / "conv_data.csv")).size(), 5u);
  // The published order is set against each refinement's last observed order (the first
  // table's, at the study's amplitude, and the one at the smaller amplitude), and the claim
  // says over which runs.
  const auto doc = nlohmann::json::parse(read(dir / "out" / "conv.json"));
  for (const auto& c : doc["claims"]) {
    if (c["id"] != "published-spatial-orders") continue;
    const std::string evidence = c["evidence"];
    EXPECT_NE(evidence.find(" of 2 refinements within it"), std::string::npos) << evidence;
    EXPECT_NE(evidence.find(m[7].str()), std::string::npos) << evidence;  // the range's end
    // A refinement beyond the tolerance is named with both orders, none otherwise.
    const bool all = evidence.rfind("2 of 2", 0) == 0;
    EXPECT_EQ(evidence.find("beyond it: none") != std::string::npos, all) << evidence;
    EXPECT_EQ(c["measured_on"], "A = 2e-4 and 1e-3; c T = 2.4; 25, 50 and 100 cells; bar");
    EXPECT_EQ(c["status"], "too-few");  // two refinements
  }
  fs::remove_all(dir);
}

}  // namespace
