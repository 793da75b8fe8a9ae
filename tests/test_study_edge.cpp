// The edge study's summary of its searches: the range of the edge against h/c and eq. (108),
// and the searches that found stability not monotone in dt or no surviving dt at all.
#include <gtest/gtest.h>

#include "study_rows.hpp"

namespace mpmstab {
namespace {

using ojson = nlohmann::ordered_json;
using test_support::study_row;

TEST(EdgeStudy, SummaryRangesAndNonMonotoneSearches) {
  std::vector<ojson> rows;
  for (double over_cfl : {0.5, 0.8}) {
    ojson r = study_row("gimp", 4);
    r["dt_edge"] = over_cfl * 0.005;
    r["dt_fail"] = over_cfl * 0.0051;
    r["dt_edge_over_cfl"] = over_cfl;
    r["dt_stable_min_at_edge"] = 1e-5;
    r["dt_edge_over_stable"] = over_cfl * 500;
    r["monotone"] = over_cfl < 0.6;
    r["failed_below_edge"] = over_cfl < 0.6 ? 0 : 2;
    r["probes"] = 12;
    r["search_seconds"] = 1.0;
    rows.push_back(r);
  }
  ojson none = rows.front();
  none["dt_edge"] = none["dt_edge_over_cfl"] = none["dt_edge_over_stable"] = nullptr;
  rows.push_back(none);
  const std::string md = test_support::study_report("edge", rows).markdown;
  EXPECT_NE(md.find("gimp: the largest surviving fixed dt is 0.5 to 0.8 times h/c and 2.5e+02 "
                    "to 4e+02 times the eq. (108) bound of that run."),
            std::string::npos)
      << md;
  EXPECT_NE(md.find("1 of 3 searches found stability not monotone in dt"), std::string::npos) << md;
  EXPECT_NE(md.find("1 found no surviving dt in the scan"), std::string::npos) << md;
  EXPECT_NE(md.find("**no** (2 smaller dt failed)"), std::string::npos) << md;
}

}  // namespace
}  // namespace mpmstab
