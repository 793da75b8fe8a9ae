// The advice study's settings (experiments/studies/choice/advice_rule.hpp): the corners of a
// setting's region, how a failing corner shrinks the region, the data file `mpmstab advise` reads,
// and the command on a data file of its own (the verified search itself: test_advice_verify.cpp).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "choice/advice_rule.hpp"
#include "choice/advice_verify.hpp"
#include "files.hpp"
#include "run/run.hpp"
#include "support.hpp"

namespace mpmstab {
namespace {

using ojson = nlohmann::ordered_json;

RunParams base_run(int cells, double C) {
  RunParams p;
  p.method = Method::gimp;
  p.E = 4;  // c = 2
  p.A = kRegionRule.amplitudes[1];
  p.T = kRegionRule.lengths.front() / 2;
  p.cells = cells;
  p.stepping.policy = TimeStepPolicy::cfl;
  p.stepping.cfl_factor = C;
  return p;
}

TEST(Advice, CornersCoverEachAxisOfTheRegionAtTheSameCourantNumber) {
  const RunParams base = base_run(50, 0.25);
  const auto corners = region_corners(base);
  ASSERT_EQ(corners.size(), kRegionCorners);
  int finer = 0, other_scene = 0, periodic = 0, jittered = 0;
  for (const auto& c : corners) {
    const RunParams& p = c.params;
    EXPECT_DOUBLE_EQ(p.T * wave_speed(p), c.length);  // c T / L, whatever E
    EXPECT_EQ(p.stepping.cfl_factor, 0.25);
    EXPECT_EQ(p.method, base.method);
    if (c.kind == CornerKind::finer) {
      ++finer;
      EXPECT_EQ(p.cells, 50 * kRegionRule.refine);
      EXPECT_EQ(c.length, kRegionRule.lengths.front());
    } else {
      EXPECT_EQ(p.cells, 50);
    }
    if (c.kind == CornerKind::smallest_A) {
      EXPECT_EQ(p.A, kRegionRule.amplitudes[0]);
    }
    if (c.kind == CornerKind::largest_A || c.kind == CornerKind::periodic ||
        c.kind == CornerKind::other_scene || c.kind == CornerKind::jittered) {
      EXPECT_EQ(p.A, kRegionRule.amplitudes[2]);
    }
    other_scene += p.scene == SceneKind::steffen;
    periodic += p.bc == Boundary::periodic;
    jittered += p.layout.jitter > 0;
  }
  // Each of the scene and boundary corners once per length, the layout once per jitter and
  // length, the largest jitter the one `mpmstab advise` answers to; the finer grid once.
  EXPECT_EQ(finer, 1);
  EXPECT_EQ(other_scene, 2);
  EXPECT_EQ(periodic, 2);
  EXPECT_EQ(jittered, 2 * int(kRegionRule.jitters.size()));
  EXPECT_EQ(kRegionRule.jitters.back(), kAdviceDomain.jitter_max);
}

CornerRun corner(CornerKind kind, double length, double error_over_A,
                 const char* outcome = "stable") {
  CornerRun c;
  c.kind = kind;
  c.length = length;
  c.A = 0.015;
  c.cells = 50;
  c.outcome = outcome;
  c.error_over_A = error_over_A;
  return c;
}

// A setting whose every corner passes at `error`, to both lengths.
CheckedSetting passing(double courant, int cells, double error) {
  CheckedSetting s;
  s.method = "gimp";
  s.transfer = "flip";
  s.update = "usl";
  s.cells = cells;
  s.courant = courant;
  s.courant_spectral = 0.75;
  s.corners.push_back(corner(CornerKind::base, kRegionRule.lengths.front(), error));
  for (const auto& c : region_corners(base_run(cells, courant))) {
    s.corners.push_back(corner(c.kind, c.length, error));
    s.corners.back().jitter = c.jitter;
  }
  s.regions = regions_of(s);
  return s;
}

CornerRun* find(CheckedSetting& s, CornerKind kind, double length) {
  for (auto& c : s.corners)
    if (c.kind == kind && c.length == length) return &c;
  return nullptr;
}

TEST(Advice, AJitteredRegionStopsBelowTheFirstJitterThatFails) {
  CheckedSetting s = passing(0.25, 50, 0.01);
  const double long_ = kRegionRule.lengths.back();
  for (auto& c : s.corners)
    if (c.kind == CornerKind::jittered && c.length == long_ && c.jitter == kRegionRule.jitters[1])
      c.outcome = "unstable";
  s.regions = regions_of(s);
  ASSERT_EQ(s.regions.size(), 2u);
  EXPECT_EQ(s.regions[0].jitter, kRegionRule.jitters.back());
  EXPECT_EQ(s.regions[1].jitter, kRegionRule.jitters.front());
  ASSERT_EQ(s.regions[1].excluded.size(), 1u);  // the failing one; the larger one is beyond it
  EXPECT_EQ(s.regions[1].excluded.front().jitter, kRegionRule.jitters[1]);
  EXPECT_NE(region_text(s.regions[1]).find("jittered to 0.05"), std::string::npos);
}

TEST(Advice, AFailingCornerShrinksTheRegionAndIsNamed) {
  const double short_ = kRegionRule.lengths.front(), long_ = kRegionRule.lengths.back();
  CheckedSetting s = passing(0.25, 50, 0.01);
  ASSERT_EQ(s.regions.size(), 2u);
  EXPECT_EQ(s.regions[1].A_min, kRegionRule.amplitudes[0]);
  EXPECT_EQ(s.regions[1].A_max, kRegionRule.amplitudes[2]);
  EXPECT_TRUE(s.regions[1].periodic && s.regions[1].other_scene);
  EXPECT_EQ(s.regions[1].jitter, kRegionRule.jitters.back());
  EXPECT_EQ(s.regions[1].cells_max, 50 * kRegionRule.refine);

  // The largest amplitude fails to the longer length: the region stops at the middle one, and
  // the scene, boundary and layout corners (run at the largest) leave it though they pass.
  find(s, CornerKind::largest_A, long_)->outcome = "unstable";
  // An inaccurate neo-Hookean corner to the shorter length takes that scene out there.
  find(s, CornerKind::other_scene, short_)->error_over_A = 0.2;
  // The finer grid fails: the region keeps the setting's cells only.
  find(s, CornerKind::finer, short_)->outcome = "meaningless";
  s.regions = regions_of(s);
  ASSERT_EQ(s.regions.size(), 2u);
  const Region& shorter = s.regions[0];
  EXPECT_FALSE(shorter.other_scene);
  EXPECT_TRUE(shorter.periodic);
  EXPECT_EQ(shorter.cells_max, 50);
  const Region& longer = s.regions[1];
  EXPECT_EQ(longer.A_max, kRegionRule.amplitudes[1]);
  EXPECT_FALSE(longer.periodic || longer.other_scene || longer.jitter > 0);
  EXPECT_EQ(longer.excluded.size(), 2u);  // the largest amplitude and the finer grid
  EXPECT_NE(region_text(longer).find("no finer grid"), std::string::npos);

  // A base run that fails to the longer length leaves no region there.
  find(s, CornerKind::base, long_)->error_over_A = 0.5;
  s.regions = regions_of(s);
  ASSERT_EQ(s.regions.size(), 1u);
  EXPECT_EQ(s.regions[0].length, short_);

  // Beyond the spectral limit / limit_margin there is no region at all, however accurate.
  CheckedSetting fast = passing(0.7, 50, 0.01);
  EXPECT_TRUE(fast.regions.empty());
}

TEST(Advice, DataRoundTripsAndAMalformedSettingIsRefusedByKey) {
  const CheckedSetting s = passing(0.25, 50, 0.01);
  const CheckedSetting back = checked_setting_from_json(to_json(s));
  EXPECT_EQ(to_json(back), to_json(s));
  ojson bad = to_json(s);
  bad.erase("courant");
  try {
    checked_setting_from_json(bad);
    FAIL() << "a setting without courant was read";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("courant"), std::string::npos) << e.what();
  }
  bad = to_json(s);
  bad["regions"][0]["A_min"] = "small";
  EXPECT_THROW(checked_setting_from_json(bad), InputError);
  bad = to_json(s);
  bad["corners"][0]["kind"] = "sideways";
  EXPECT_THROW(checked_setting_from_json(bad), InputError);
}

// C from the balance: per method and grid, the smallest balancing C over the scenes, rounded
// down to two significant digits; curves of another transfer or start, and curves without a
// balancing C, give none; a malformed document is refused by key.
// The command: an answer as JSON from a data file, status 2 for a problem outside every region,
// a bad option value or a missing or malformed file, and nothing written.
TEST(Advice, TheCommandAnswersFromItsDataAndRefusesWithStatusTwo) {
  const auto dir = std::filesystem::temp_directory_path() / "mpmstab_advise_test";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  const auto data = dir / "advice.json";
  {
    ojson settings = ojson::array({to_json(passing(0.5, 50, 4e-3))});
    std::ofstream(data) << ojson{{"study", {{"settings", settings}}}}.dump();
  }
  const std::string file = data.string();
  auto ok = test_support::run_mpmstab("advise --A 0.015 --cT 2 --error 0.01 --json --data " + file);
  ASSERT_EQ(ok.status, 0) << ok.output;
  const ojson j = ojson::parse(ok.output);
  EXPECT_EQ(j["answer"]["method"], "gimp");
  EXPECT_EQ(j["answer"]["courant"], 0.5);
  for (const auto& r : j["verifying_runs"])
    EXPECT_TRUE(r["passes"].get<bool>()) << r.dump();
  auto outside = test_support::run_mpmstab("advise --A 0.5 --cT 2 --error 0.01 --data " + file);
  EXPECT_EQ(outside.status, 2);
  EXPECT_NE(outside.output.find("--A"), std::string::npos) << outside.output;
  EXPECT_EQ(test_support::run_mpmstab("advise --A 0.015 --cT 2 --error 0 --data " + file).status,
            2);
  EXPECT_EQ(test_support::run_mpmstab("advise --A 0.015 --cT 2 --error 0.01 --scene mode "
                                      "--data " +
                                      file)
                .status,
            2);
  EXPECT_EQ(test_support::run_mpmstab("advise --A 0.015 --cT 2 --error 0.01 --data " +
                                      (dir / "absent.json").string())
                .status,
            2);
  std::ofstream(dir / "bad.json") << "{\"study\": {\"settings\": [{\"method\": 3}]}}";
  const auto bad = test_support::run_mpmstab("advise --A 0.015 --cT 2 --error 0.01 --data " +
                                             (dir / "bad.json").string());
  EXPECT_EQ(bad.status, 2);
  EXPECT_NE(bad.output.find("method"), std::string::npos) << bad.output;
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace mpmstab

// The "run it with" line is a command that runs the setting: a transfer with a parameter
// ("fmpm(2)" in the data) is given as the transfer and its own option (--fmpm-order 2), and the
// line, typed as printed, is accepted by `mpmstab run`.
TEST(Advice, TheRunItWithLineOfATransferWithAParameterRuns) {
  const std::string data = std::string(MPMSTAB_SOURCE_DIR) + "/results/advice.json";
  const auto answer = mpmstab::test_support::run_mpmstab(
      "advise --A 0.01 --cT 2 --error 0.1 --methods gimp/fmpm(2) --data " + data);
  ASSERT_EQ(answer.status, 0) << answer.output;
  const std::string marker = "run it with             mpmstab ";
  const auto at = answer.output.find(marker);
  ASSERT_NE(at, std::string::npos) << answer.output;
  const auto start = at + marker.size();
  const std::string command = answer.output.substr(start, answer.output.find('\n', start) - start);
  EXPECT_NE(command.find("--transfer fmpm --fmpm-order 2"), std::string::npos) << command;
  EXPECT_EQ(command.find('('), std::string::npos) << command;
  const auto run = mpmstab::test_support::run_mpmstab(command);
  EXPECT_EQ(run.status, 0) << command << "\n" << run.output;
}
