// The command line: every invalid input exits 2 naming the option; a valid run prints JSON.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <nlohmann/json.hpp>
#include <string>

#include "support.hpp"

namespace {

using Outcome = mpmstab::test_support::CliOutcome;
using mpmstab::test_support::run_mpmstab;

const std::string kValid = "--method gimp --E 4 --A 0.015 --dt 1e-3 --T 0.01";

std::string with(const std::string& option, const std::string& value) {
  // Replace (or add) one option in the valid command line.
  std::string args = kValid;
  const std::string key = "--" + option + " ";
  if (const auto at = args.find(key); at != std::string::npos) {
    const auto end = args.find(' ', at + key.size());
    args.erase(at, (end == std::string::npos ? args.size() : end) - at);
  }
  return args + " " + key + value;
}

TEST(Cli, ValidRunPrintsJsonWithEveryKey) {
  const Outcome o = run_mpmstab("run " + kValid + " --json");
  ASSERT_EQ(o.status, 0) << o.output;
  const auto j = nlohmann::json::parse(o.output);
  for (const char* key : {"method", "E", "A", "dt", "T", "cells", "ppc", "bc", "stable", "failure",
                          "steps", "max_error", "max_error_over_time", "crossings", "dt_stable_min",
                          "dt_cfl", "courant", "wall_seconds", "ns_per_particle_step"}) {
    EXPECT_TRUE(j.contains(key)) << key;
  }
  EXPECT_EQ(j["stable"], true);
  EXPECT_TRUE(j["failure"].is_null());
  EXPECT_EQ(j["steps"], 10);
}

TEST(Cli, UnstableRunIsAResultNotAnError) {
  const Outcome o = run_mpmstab("run --method gimp --E 1000 --A 0.015 --dt 1e-3 --json");
  ASSERT_EQ(o.status, 0) << o.output;
  const auto j = nlohmann::json::parse(o.output);
  EXPECT_EQ(j["stable"], false);
  EXPECT_FALSE(j["failure"]["reason"].get<std::string>().empty());
  EXPECT_TRUE(j["max_error"].is_null());
}

TEST(Cli, InvalidInputExitsTwoAndNamesTheOption) {
  struct Case {
    std::string args;
    std::string named;
  };
  const std::vector<Case> cases = {
      {with("E", "-1"), "--E"},
      {with("E", "0"), "--E"},
      {with("E", "abc"), "--E"},
      {with("E", "nan"), "--E"},
      {with("E", "inf"), "--E"},
      {with("E", "1e999"), "--E"},
      {with("A", "-0.1"), "--A"},
      {with("A", "0.1x"), "--A"},
      {with("dt", "0"), "--dt"},
      {with("dt", "-1e-3"), "--dt"},
      {with("dt", "1e-3x"), "--dt"},
      {with("dt", "5"), "--dt"},  // dt > T
      {with("T", "0"), "--T"},
      {with("T", "-1"), "--T"},
      {with("cells", "0"), "--cells"},
      {with("cells", "-4"), "--cells"},
      {with("cells", "2.5"), "--cells"},
      {with("cells", "99999999999999999999"), "--cells"},
      {with("ppc", "0"), "--ppc"},
      {with("ppc", "two"), "--ppc"},
      {with("method", "flip"), "--method"},
      {with("method", "GIMP"), "--method"},
      {with("bc", "neumann"), "--bc"},
      {with("position-update", "nodes"), "--position-update"},
      {with("dt-stable-sigma", "half"), "--dt-stable-sigma"},
      {with("dt-stable-vnorm", "l1"), "--dt-stable-vnorm"},
      {with("max-steps", "0"), "--max-steps"},
      {with("scene", "beam"), "--scene"},
      {with("walls", "mirror"), "--walls"},
      {with("walls", "ghost") + " --bc periodic", "--walls"},  // a periodic grid has no walls
      {with("transfer", "apic"), "--transfer"},
      {with("flip-fraction", "0.5"), "--flip-fraction"},  // only with --transfer blend
      {with("transfer", "blend") + " --flip-fraction 1", "--flip-fraction"},
      {with("transfer", "blend") + " --flip-fraction nan", "--flip-fraction"},
      {with("update", "usf2"), "--update"},
      {with("body-force-time", "middle"), "--body-force-time"},
      {"--method gimp --A 0.015 --dt 1e-3", "--E"},  // missing required option
      {"--E 4 --A 0.015 --dt 1e-3", "--method"},
      {kValid + " --Young 4", "--Young"},                         // unknown option
      {kValid + " --dt", "--dt"},                                 // given twice / no value
      {"--method gimp --E 4 --A 0.015 --dt 1e-9 --T 1", "--dt"},  // over the step cap
  };
  for (const auto& c : cases) {
    const Outcome o = run_mpmstab("run " + c.args);
    EXPECT_EQ(o.status, 2) << c.args << "\n" << o.output;
    EXPECT_NE(o.output.find(c.named), std::string::npos) << c.args << "\n" << o.output;
    EXPECT_EQ(o.output.find("internal error"), std::string::npos) << c.args;
  }
}

TEST(Cli, UnknownOptionSuggestsTheNearestOne) {
  const Outcome o = run_mpmstab("run " + kValid + " --cell 10");
  EXPECT_EQ(o.status, 2);
  EXPECT_NE(o.output.find("did you mean --cells"), std::string::npos) << o.output;
}

TEST(Cli, UnknownCommandAndBareInvocationExitTwo) {
  EXPECT_EQ(run_mpmstab("rnu").status, 2);
  EXPECT_NE(run_mpmstab("rnu").output.find("did you mean 'run'"), std::string::npos);
  EXPECT_EQ(run_mpmstab("").status, 2);
}

TEST(Cli, HelpExitsZero) {
  const Outcome o = run_mpmstab("run --help");
  EXPECT_EQ(o.status, 0);
  EXPECT_NE(o.output.find("--dt-stable-sigma"), std::string::npos);
}

// The version names the build a result would come from: solver version, commit, compiler, flags.
TEST(Cli, VersionNamesTheBuild) {
  const Outcome o = run_mpmstab("--version");
  EXPECT_EQ(o.status, 0);
  for (const char* field : {"mpmstab ", "solver version ", "commit: ", "compiler: ", "flags: "})
    EXPECT_NE(o.output.find(field), std::string::npos) << field << "\n" << o.output;
  EXPECT_NE(o.output.find("-ffp-contract=off"), std::string::npos) << o.output;
  EXPECT_EQ(run_mpmstab("--version extra").status, 2);
}

TEST(Cli, BadInputWritesNothing) {
  const auto path = std::filesystem::temp_directory_path() / "mpmstab_cli_history_test.csv";
  std::filesystem::remove(path);
  EXPECT_EQ(run_mpmstab("run " + with("E", "-4") + " --history " + path.string()).status, 2);
  EXPECT_FALSE(std::filesystem::exists(path));
  EXPECT_EQ(run_mpmstab("run " + kValid + " --history " + path.string()).status, 0);
  EXPECT_TRUE(std::filesystem::exists(path));
  std::filesystem::remove(path);
}

TEST(Cli, UnwritableHistoryIsAUsageError) {
  const Outcome o = run_mpmstab("run " + kValid + " --history /nonexistent-dir/h.csv");
  EXPECT_EQ(o.status, 2) << o.output;
  EXPECT_NE(o.output.find("--history"), std::string::npos) << o.output;
}

}  // namespace

namespace {

TEST(Cli, PoliciesTakeDtOnlyWhenFixed) {
  EXPECT_EQ(run_mpmstab("run --method gimp --E 4 --A 0.01 --T 0.01 --policy cfl").status, 0);
  const Outcome both =
      run_mpmstab("run --method gimp --E 4 --A 0.01 --T 0.01 --policy cfl --dt 1e-3");
  EXPECT_EQ(both.status, 2);
  EXPECT_NE(both.output.find("--dt"), std::string::npos);
  const Outcome bad = run_mpmstab("run --method gimp --E 4 --A 0.01 --policy adaptive --safety 0");
  EXPECT_EQ(bad.status, 2);
  EXPECT_NE(bad.output.find("--safety"), std::string::npos);
  EXPECT_EQ(run_mpmstab("run --method gimp --E 4 --A 0.01 --policy cfl --cfl-factor -1").status, 2);
  EXPECT_EQ(run_mpmstab("run --method gimp --E 4 --A 0.01 --policy sometimes").status, 2);
  const Outcome json =
      run_mpmstab("run --method mpm --E 4 --A 0.01 --T 0.05 --policy adaptive --safety 3 --json");
  ASSERT_EQ(json.status, 0) << json.output;
  const auto j = nlohmann::json::parse(json.output);
  EXPECT_EQ(j["policy"], "adaptive");
  EXPECT_LT(j["dt_min"].get<double>(), j["dt_max"].get<double>());
}

// The spec and the command line refuse a dt given with a policy that chooses its own, with the
// same message after the name of the option or key.
TEST(Cli, SpecsRefuseDtWithAPolicyAsTheCommandLineDoes) {
  const auto dir = std::filesystem::temp_directory_path() /
                   ("mpmstab_cli_dt_policy_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  std::ofstream(dir / "case.json") << R"({"name": "c", "report": "cases", "cases": [
      {"method": "gimp", "E": 4, "A": 0.01, "T": 0.01, "policy": "cfl", "dt": 1e-3}]})";
  std::ofstream(dir / "defaults.json") << R"({"name": "d", "report": "cases",
      "defaults": {"dt": 1e-3}, "cases": [{"method": "gimp", "E": 4, "A": 0.01, "T": 0.01},
      {"method": "gimp", "E": 4, "A": 0.01, "T": 0.01, "policy": "adaptive"}]})";
  const Outcome cli =
      run_mpmstab("run --method gimp --E 4 --A 0.01 --T 0.01 --policy cfl --dt 1e-3");
  const Outcome spec =
      run_mpmstab("sweep " + (dir / "case.json").string() + " --out " + (dir / "out").string());
  const Outcome defaults =
      run_mpmstab("sweep " + (dir / "defaults.json").string() + " --out " + (dir / "out").string());
  const std::string message = "only with policy fixed (the cfl policy chooses dt itself)";
  EXPECT_EQ(cli.status, 2);
  EXPECT_NE(cli.output.find("--dt: " + message), std::string::npos) << cli.output;
  EXPECT_EQ(spec.status, 2);
  EXPECT_NE(spec.output.find("cases[0].dt: " + message), std::string::npos) << spec.output;
  EXPECT_EQ(defaults.status, 2);
  EXPECT_NE(defaults.output.find("defaults.dt: only with policy fixed (the adaptive policy"),
            std::string::npos)
      << defaults.output;
  EXPECT_FALSE(std::filesystem::exists(dir / "out/c.md"));
  std::filesystem::remove_all(dir);
}

}  // namespace
