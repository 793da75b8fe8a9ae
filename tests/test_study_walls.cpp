// The walls study pairs each cell's Dirichlet run with its periodic twin and reads what the walls
// do from the pairs: the verdicts that change, the ratio of the errors over time, and a claim per
// method that holds only where the walls leave every error within the tolerance.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "study_rows.hpp"

namespace mpmstab {
namespace {

using ojson = nlohmann::ordered_json;
using test_support::study_row;

ojson with_bc(ojson r, const char* bc, double error) {
  r["bc"] = bc;
  r["max_error_over_time"] = error;
  return r;
}

TEST(WallsStudy, PairsEachCellWithItsPeriodicTwinAndReadsWhatTheWallsCost) {
  // gimp: the walls raise the error 10 times; mpm: the same error; one mpm cell whose Dirichlet
  // run fails while its periodic twin survives.
  ojson failed = with_bc(study_row("mpm", 64), "dirichlet", 1e-3);
  test_support::fail_row(failed, "nonpositive_F");
  failed["max_error_over_time"] = 1e-3;
  const std::vector<ojson> rows = {with_bc(study_row("gimp", 4), "periodic", 1e-5),
                                   with_bc(study_row("gimp", 4), "dirichlet", 1e-4),
                                   with_bc(study_row("mpm", 4), "periodic", 2e-5),
                                   with_bc(study_row("mpm", 4), "dirichlet", 2e-5),
                                   with_bc(study_row("mpm", 64), "periodic", 3e-5),
                                   failed};
  const auto report = test_support::study_report("walls", rows);
  const std::string& md = report.markdown;
  // Each run called stable with its accuracy class and error over time per A.
  EXPECT_NE(md.find("| gimp | 4 | 0.015 | 1e-4 | 2.0e-2 | 1.5 | 2 | stable, accurate (0.0067 A) | "
                    "1.0e-4 | stable, accurate (0.00067 A) | 1.0e-5 | 0.1 |"),
            std::string::npos)
      << md;
  // The one-sided survivor is stable, not meaningless: counted as both.
  EXPECT_NE(md.find("mpm: of 2 cells, 1 end with the same outcome under both boundaries; 1 "
                    "survive only without walls (0 of them meaningless there) and 0 only with "
                    "them (0 meaningless); 1 are stable only without walls and 0 only with them."),
            std::string::npos)
      << md;
  EXPECT_NE(md.find("the walls raise the error by more than 1% in 1 cells, lower it in 0 and "
                    "leave it within 1% in 0"),
            std::string::npos)
      << md;
  ASSERT_EQ(report.claims.size(), 2u);
  EXPECT_EQ(report.claims[0].id, "walls-leave-error-gimp");
  EXPECT_FALSE(report.claims[0].holds);
  EXPECT_EQ(report.claims[1].id, "walls-leave-error-mpm");
  EXPECT_TRUE(report.claims[1].holds);
  EXPECT_EQ(render(report.claims[1], report.claims[1].evidence),
            "1 of 1 within; periodic / Dirichlet 1 to 1");
}

}  // namespace
}  // namespace mpmstab
