// The peers study: its comparator passes a faithful row and fails when one peer value moves by 1%.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "agreement/peers.hpp"
#include "study_rows.hpp"

namespace mpmstab {
namespace {

using ojson = nlohmann::ordered_json;

class PeersStudyTest : public ::testing::Test {
 protected:
  std::filesystem::path dir =
      std::filesystem::temp_directory_path() / ("mpmstab_peers_" + std::to_string(::getpid()));
  void SetUp() override { std::filesystem::create_directories(dir); }
  void TearDown() override { std::filesystem::remove_all(dir); }

  // The peer's file with one stable linear case and one failing GIMP case; `scale` multiplies
  // the linear case's error at T, `step` is the GIMP failure step.
  Spec spec(double scale, int step) {
    std::ofstream out(dir / "peer.csv");
    out.precision(17);
    out << "# a peer\npeer_basis,E,A,dt,T,outcome,peer_failure,fail_step,max_error_T,"
           "max_error_over_time,mpmstab_options\n"
        << "linear,4,0.015,0.001,1,stable,,," << 0.004463756254370124 * scale
        << ",0.007879317648918865,--method mpm\n"
        << "GIMP,256,0.015,0.001,1,unstable,partition_of_unity," << step
        << ",,0.5,--method cpgimp\n";
    Spec s;
    s.name = std::string("peers");
    s.reference = dir / "peer.csv";
    return s;
  }
  std::vector<ojson> rows() {
    ojson linear = test_support::study_row("mpm", 4);
    linear["dt"] = 0.001;
    linear["max_error"] = 0.004463756254370124;
    linear["max_error_over_time"] = 0.007879317648918865;
    ojson gimp = test_support::study_row("cpgimp", 256);
    gimp["dt"] = 0.001;
    test_support::fail_row(gimp, "nonpositive_F");
    gimp["failure_step"] = 12;
    return {linear, gimp};
  }
};

TEST_F(PeersStudyTest, AFaithfulSolverAgreesOnEveryCase) {
  const auto r = rows();
  const PeersStudy s = study_peers(spec(1.0, 12), r);
  ASSERT_EQ(s.cases.size(), 2u);
  EXPECT_TRUE(s.cases[0].agrees);
  EXPECT_TRUE(s.cases[0].errors_judged);
  EXPECT_TRUE(s.cases[1].agrees);  // partition_of_unity at the step where ours finds F <= 0
  EXPECT_FALSE(s.cases[1].errors_judged);
  const std::string md = peers_markdown(spec(1.0, 12), s, dir);
  EXPECT_NE(md.find("reproduces Uintah's 1D MPM code on 2 of 2 cases"), std::string::npos) << md;
  EXPECT_NE(md.find("`partition_of_unity`"), std::string::npos) << md;
}

TEST_F(PeersStudyTest, APeerValueMovedByOnePercentIsADisagreement) {
  const auto r = rows();
  const PeersStudy error_moved = study_peers(spec(1.01, 12), r);
  EXPECT_FALSE(error_moved.cases[0].agrees);
  EXPECT_EQ(peers_json(error_moved)["agree"], 1);
  EXPECT_NE(peers_verdicts_csv(error_moved, "").find("mpm,4,0.015,0.001,1,yes,yes,no,no"),
            std::string::npos);
  // 1% of a failure step of 12 is within the step tolerance (one step); two steps are not.
  EXPECT_TRUE(study_peers(spec(1.0, 13), r).cases[1].agrees);
  EXPECT_FALSE(study_peers(spec(1.0, 14), r).cases[1].agrees);
}

}  // namespace
}  // namespace mpmstab
