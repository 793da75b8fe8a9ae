// The comparison study: which of our errors is set beside the paper's Max Error, from its own
// spec or from the specs of its inputs, and the options it refuses.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <nlohmann/json.hpp>
#include <string>

#include "support.hpp"

using Outcome = mpmstab::test_support::CliOutcome;
using mpmstab::test_support::run_mpmstab;

namespace {

// mpmstab compare --error-at: which of our errors is set beside the paper's Max Error.
class CompareErrorAt : public ::testing::Test {
 protected:
  std::filesystem::path dir =
      std::filesystem::temp_directory_path() / ("mpmstab_compare_" + std::to_string(::getpid()));
  void SetUp() override {
    std::filesystem::remove_all(dir);
    std::filesystem::create_directories(dir);
    std::ofstream(dir / "paper.csv") << "A,E,dt,method,dt_stable,max_error,confidence,evidence\n"
                                        "0.015,4,1e-3,GIMP,2e-3,1e-5,high,\n"
                                        "0.015,4,1e-3,MPM,5e-3,5e-5,high,\n";
    std::ofstream(dir / "t.json") << R"({"name": "t", "report": "table1",
        "reference": "paper.csv", "record": ["error_over_time", "dt_stable"],
        "defaults": {"E": 4, "A": 0.015, "T": 1, "dt": 1e-3},
        "cases": [{"method": "gimp"}, {"method": "mpm"}]})";
    std::ofstream(dir / "bare.json") << R"({"name": "t", "report": "table1",
        "reference": "paper.csv", "defaults": {"E": 4, "A": 0.015, "T": 1, "dt": 1e-3},
        "cases": [{"method": "gimp"}, {"method": "mpm"}]})";
  }
  void TearDown() override { std::filesystem::remove_all(dir); }
  std::string read(const std::filesystem::path& p) {
    std::ifstream in(p);
    return std::string(std::istreambuf_iterator<char>(in), {});
  }
};

TEST_F(CompareErrorAt, ChoosesTheErrorComparedWithThePapers) {
  const std::string out = " --out " + (dir / "out").string();
  ASSERT_EQ(run_mpmstab("sweep " + (dir / "t.json").string() + out).status, 0);
  const auto rows = nlohmann::json::parse(read(dir / "out/t.json"))["cases"];
  const double at_T = rows[0]["max_error"].get<double>();
  const double over_time = rows[0]["max_error_over_time"].get<double>();
  ASSERT_NE(at_T, over_time);
  auto shown = [](double v) {  // as the report prints it
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.1e", v);
    std::string s = buf;
    const auto e = s.find("e-0");
    return e == std::string::npos ? s : s.erase(e + 2, 1);
  };

  Outcome o = run_mpmstab("compare " + (dir / "t.json").string() + out);
  ASSERT_EQ(o.status, 0) << o.output;
  std::string md = read(dir / "out/comparison.md");
  EXPECT_NE(md.find("max error at T (`max_error`)"), std::string::npos);
  EXPECT_NE(md.find("| " + shown(at_T) + " |"), std::string::npos) << shown(at_T);
  EXPECT_NE(md.find("Variants study not run"), std::string::npos);

  o = run_mpmstab("compare " + (dir / "t.json").string() + out + " --error-at max_over_time");
  ASSERT_EQ(o.status, 0) << o.output;
  md = read(dir / "out/comparison.md");
  EXPECT_NE(md.find("max error over the run (`max_error_over_time`"), std::string::npos);
  EXPECT_NE(md.find("| " + shown(over_time) + " |"), std::string::npos) << shown(over_time);

  // Bad values and a spec that does not record the error over time are refused, naming the option.
  o = run_mpmstab("compare " + (dir / "t.json").string() + out + " --error-at end");
  EXPECT_EQ(o.status, 2);
  EXPECT_NE(o.output.find("--error-at: unknown value 'end' (expected T or max_over_time)"),
            std::string::npos)
      << o.output;
  o = run_mpmstab("compare " + (dir / "bare.json").string() + out + " --error-at max_over_time");
  EXPECT_EQ(o.status, 2);
  EXPECT_NE(o.output.find("does not record error_over_time"), std::string::npos) << o.output;
  o = run_mpmstab("compare --help");
  EXPECT_EQ(o.status, 0);
  EXPECT_NE(o.output.find("--error-at"), std::string::npos);
}

// The same through the comparison's own spec, which finds table1.json beside it.
TEST_F(CompareErrorAt, TheComparisonSpecReadsTheTableBesideIt) {
  std::ofstream(dir / "table1.json") << R"({"name": "table1", "report": "table1",
      "reference": "paper.csv", "record": ["error_over_time", "dt_stable"],
      "defaults": {"E": 4, "A": 0.015, "T": 1, "dt": 1e-3},
      "cases": [{"method": "gimp"}, {"method": "mpm"}]})";
  std::ofstream(dir / "comparison.json") << R"({"name": "comparison", "report": "comparison"})";
  const std::string out = " --out " + (dir / "out").string();
  Outcome o = run_mpmstab("compare " + (dir / "comparison.json").string() + out);
  EXPECT_EQ(o.status, 2) << o.output;  // table1 has not been run into out/
  EXPECT_NE(o.output.find("table1.json does not exist"), std::string::npos) << o.output;
  ASSERT_EQ(run_mpmstab("sweep " + (dir / "table1.json").string() + out).status, 0);
  o = run_mpmstab("compare " + (dir / "comparison.json").string() + out +
                  " --error-at max_over_time");
  ASSERT_EQ(o.status, 0) << o.output;
  EXPECT_NE(read(dir / "out/comparison.md").find("max error over the run (`max_error_over_time`"),
            std::string::npos);
  // sweep writes the same report as compare does without options.
  ASSERT_EQ(run_mpmstab("compare " + (dir / "comparison.json").string() + out).status, 0);
  const std::string by_compare = read(dir / "out/comparison.md");
  std::filesystem::remove(dir / "out/comparison.md");
  ASSERT_EQ(run_mpmstab("sweep " + (dir / "comparison.json").string() + out).status, 0);
  EXPECT_EQ(read(dir / "out/comparison.md"), by_compare);
}

}  // namespace
