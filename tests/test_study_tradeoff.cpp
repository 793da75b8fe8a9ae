// The trade study's reading of its rows: the Pareto front of (wall time, error), the cheapest
// setting for each accuracy, a run that failed or whose error reached A reaching no accuracy,
// and the largest safety factor that survived at every E.
#include <gtest/gtest.h>

#include "study_rows.hpp"

namespace mpmstab {
namespace {

using ojson = nlohmann::ordered_json;
using test_support::line_with;
using test_support::study_row;

ojson fixed_run(double dt, double error, double wall) {
  ojson r = study_row("gimp", 4);
  r["dt"] = dt;
  r["max_error_over_time"] = error;
  r["wall_seconds"] = wall;
  return r;
}

ojson adaptive_run(const std::string& method, double E, double s, bool stable) {
  ojson r = study_row(method, E);
  r["policy"] = "adaptive";
  r["safety"] = s;
  if (!stable) test_support::fail_row(r, "nonpositive_F");
  return r;
}

TEST(TradeoffStudy, ParetoFrontAndCheapestSettingPerAccuracy) {
  std::vector<ojson> rows = {
      fixed_run(1e-3, 2e-4, 1.0),   // cheapest, reaches 1e-3 only
      fixed_run(1e-4, 5e-6, 4.0),   // the only one to reach 1e-5
      fixed_run(2e-4, 5e-4, 6.0),   // dominated: dearer and less accurate than 1e-3
      fixed_run(5e-5, 9e-5, 2.0),   // reaches 1e-4 more cheaply than 1e-4
      fixed_run(1e-5, 1e-7, 0.5)};  // cheapest and best, but meaningless: reaches nothing
  rows[4]["meaningless"] = true;
  const std::string md = test_support::study_report("tradeoff", rows).markdown;

  const std::string cheapest = line_with(md, "| 4 |");
  EXPECT_NE(cheapest.find("| gimp fixed dt=1e-3: 2.0e-4 in 1.00 s"), std::string::npos) << cheapest;
  EXPECT_NE(cheapest.find("| gimp fixed dt=5e-5: 9.0e-5 in 2.00 s"), std::string::npos) << cheapest;
  EXPECT_NE(cheapest.find("| gimp fixed dt=1e-4: 5.0e-6 in 4.00 s"), std::string::npos) << cheapest;

  EXPECT_NE(line_with(md, "| gimp fixed dt=1e-3 |").find("**yes**"), std::string::npos);
  EXPECT_NE(line_with(md, "| gimp fixed dt=5e-5 |").find("**yes**"), std::string::npos);
  EXPECT_NE(line_with(md, "| gimp fixed dt=1e-4 |").find("**yes**"), std::string::npos);
  EXPECT_EQ(line_with(md, "| gimp fixed dt=2e-4 |").find("**yes**"), std::string::npos);
  EXPECT_EQ(line_with(md, "| gimp fixed dt=1e-5 |").find("**yes**"), std::string::npos);
  EXPECT_NE(md.find("The cheapest setting for a target accuracy is gimp fixed in 3 of the 3"),
            std::string::npos)
      << md;

  // The figure's data: an empty error where the run reaches no accuracy.
  const std::string data = *test_support::study_report("tradeoff", rows).data_csv;
  EXPECT_NE(data.find("4,1,0,10000,0.5,\n"), std::string::npos) << data;
}

TEST(TradeoffStudy, LargestSafetyFactorIsTheOneThatSurvivedAtEveryE) {
  std::vector<ojson> rows;
  for (double E : {4.0, 1e4}) {
    for (double s : {1.0, 2.0, 4.0, 8.0, 16.0}) {
      // GIMP fails from s = 8 at E = 1e4 only; MPM from s = 2 everywhere.
      rows.push_back(adaptive_run("gimp", E, s, !(E == 1e4 && s >= 8)));
      rows.push_back(adaptive_run("mpm", E, s, s < 2));
    }
  }
  const std::string md = test_support::study_report("tradeoff", rows).markdown;
  EXPECT_NE(md.find("The adaptive step survives at every E up to s = 4 for gimp."),
            std::string::npos)
      << md;
  EXPECT_NE(md.find("The adaptive step survives at every E up to s = 1 for mpm."),
            std::string::npos)
      << md;
}

}  // namespace
}  // namespace mpmstab
