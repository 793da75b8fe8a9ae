// The Courant scan's reading of its rows: per case, the largest C up to which every run survives,
// the run there, a case that fails at every C, and survival that comes back above a failure.
#include <gtest/gtest.h>

#include "study_rows.hpp"

namespace mpmstab {
namespace {

using ojson = nlohmann::ordered_json;

ojson scan_row(double E, double C, const char* outcome) {
  ojson r = study_row("gimp", E);
  r["courant"] = C;
  r["dt"] = C * 0.01 / std::sqrt(E);
  r["A_over_h"] = 1.5;
  r["cT"] = std::sqrt(E);
  if (std::string(outcome) == "unstable") test_support::fail_row(r, "nonpositive_F");
  if (std::string(outcome) == "meaningless") test_support::meaningless_row(r);
  return r;
}

TEST(CourantStudy, EachCaseSaysWhereSurvivalStopsAndWhereItComesBack) {
  const std::vector<ojson> rows = {
      scan_row(4, 0.25, "stable"),     scan_row(4, 0.5, "meaningless"),
      scan_row(4, 0.7, "unstable"),    scan_row(4, 0.8, "stable"),     // comes back at 0.8
      scan_row(64, 0.25, "unstable"),  scan_row(64, 0.5, "unstable"),  // fails at each C
      scan_row(256, 0.25, "unstable"), scan_row(256, 0.5, "stable"),   // fails first, then not
  };
  const auto report = test_support::study_report("courant", rows);
  const std::string& md = report.markdown;
  // A stable run is shown with its error over time per A and its accuracy class.
  EXPECT_NE(md.find("| gimp | 0.015 | 4 | 1.5 | 2 | 0.5 | **meaningless** (1 A) | not tested "
                    "for length | 0.25 | stable (0.00067 A, accurate) | 0.8 |"),
            std::string::npos)
      << md;
  EXPECT_NE(md.find("| gimp | 0.015 | 64 | 1.5 | 8 | below the scan: its smallest C, 0.25, fails "
                    "| – | – | below the scan: its smallest C is not stable | – | – |"),
            std::string::npos)
      << md;
  // Failing at the smallest C is not failing at each C: the counts tell them apart.
  EXPECT_NE(md.find("Of 3 cases, 2 fail at the smallest C of the scan (1 of them at each C of "
                    "the scan) and 2 reach T again above a failure"),
            std::string::npos)
      << md;
  int found = 0;
  for (const auto& c : report.claims) {
    if (c.id == "every-case-survives-somewhere" || c.id == "survival-monotone-in-courant") {
      ++found;
      EXPECT_FALSE(c.holds) << c.id;
    }
    if (c.id == "every-case-survives-somewhere") {
      EXPECT_EQ(render(c, c.evidence), "2 of 3 cases fail at the smallest C of the scan");
    }
  }
  EXPECT_EQ(found, 2);
}

// A run that ends stable with an error over time of at least a tenth of A is inaccurate.
TEST(CourantStudy, AStableRunCarriesItsAccuracyClass) {
  ojson r = scan_row(16, 0.25, "stable");
  r["max_error_over_time"] = 0.3 * r["A"].get<double>();
  const std::string md = test_support::study_report("courant", {r}).markdown;
  EXPECT_NE(md.find("| 0.25 (the largest C of the scan) | stable (0.3 A, inaccurate) |"),
            std::string::npos)
      << md;
}

}  // namespace
}  // namespace mpmstab
