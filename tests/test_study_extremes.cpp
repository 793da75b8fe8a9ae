// The extremes study: every run has a verdict, counted in its Courant band, and a stable run
// whose output is not finite is counted as such.
#include <gtest/gtest.h>

#include "study_rows.hpp"

namespace mpmstab {
namespace {

using ojson = nlohmann::ordered_json;
using test_support::study_row;

TEST(ExtremesStudy, EveryRunHasAVerdictCountedInItsBand) {
  std::vector<ojson> rows;
  ojson stable = study_row("gimp", 4);  // Courant 0.02, A/h 1.5
  ojson meaningless = stable;
  test_support::meaningless_row(meaningless);
  ojson unstable = stable;
  unstable["courant"] = 3.0;
  test_support::fail_row(unstable, "left_domain");
  ojson nan_output = stable;  // a stable run whose output is not finite is counted
  nan_output["dt_stable_min"] = nullptr;
  rows = {stable, meaningless, unstable, nan_output};
  const auto report = test_support::study_report("extremes", rows);
  EXPECT_NE(report.markdown.find("4 cases, every one with a verdict: 2 stable, 1 meaningless "
                                 "(survived, but the error over time reached A), 1 unstable "
                                 "(left_domain 1). Stable outputs holding a NaN or an "
                                 "infinity: 1."),
            std::string::npos)
      << report.markdown;
  EXPECT_NE(report.markdown.find("| c dt/h < 0.5 | 3 | 2 | 1 | none |"), std::string::npos)
      << report.markdown;
  EXPECT_NE(report.markdown.find("| 1 <= c dt/h < 10 | 1 | 0 | 0 | left_domain 1 |"),
            std::string::npos)
      << report.markdown;
  // The figure's data: one row per spot and verdict code (0, 1 or 2), with its number of runs:
  // the two stable runs at one spot are drawn once, counted 2. The one method present is panel 0.
  EXPECT_NE(report.data_csv->find("0,2e-2,1.5,0,2,gimp\n0,2e-2,1.5,1,1,gimp\n0,3,1.5,2,1,gimp\n"),
            std::string::npos)
      << *report.data_csv;
}

}  // namespace
}  // namespace mpmstab
