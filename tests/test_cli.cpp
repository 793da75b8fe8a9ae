// The command line: every invalid input exits 2 naming the option; a valid run prints JSON.
#include <fmt/format.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

#include "args.hpp"
#include "result_json.hpp"
#include "run_summary.hpp"
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
  const auto j = nlohmann::ordered_json::parse(o.output);
  // Exactly the record's columns, in order, with A / h and c T after courant: the same shape as
  // a sweep's rows.
  std::vector<std::string> keys, expected;
  for (const auto& [k, v] : j.items())
    keys.push_back(k);
  for (const auto& c : mpmstab::record_columns()) {
    expected.push_back(c);
    if (c != "courant") continue;
    expected.push_back("A_over_h");
    expected.push_back("cT");
  }
  EXPECT_EQ(keys, expected);
  EXPECT_EQ(j["A_over_h"], 1.5);  // A = 0.015 on 100 cells
  EXPECT_EQ(j["outcome"], "stable");
  EXPECT_TRUE(j["failure_reason"].is_null());
  EXPECT_TRUE(j["failure_step"].is_null());
  EXPECT_EQ(j["steps"], 10);
  EXPECT_FALSE(j.contains("wall_seconds"));  // a machine measurement, not a result
}

// One name per quantity: every label the run's summary prints is the key of the record that
// holds the value (docs/theory.md, "Measured quantities"), or one of the few lines about the run
// itself; and no command calls the error over time the error at T (the edge search's probes
// measure the error over time only).
TEST(Cli, TheSummarysLabelsAreTheRecordsKeysAndNoErrorOverTimeIsCalledTheErrorAtT) {
  const auto out = run_mpmstab("run --method gimp --E 4 --A 0.015 --dt 1e-3");
  ASSERT_EQ(out.status, 0) << out.output;
  const auto& keys = mpmstab::record_columns();
  const std::vector<std::string> about_the_run = {
      "verdict", "steps", "particle-steps", "wall_seconds", "ns/particle-step", "A_over_h", "cT"};
  std::istringstream lines(out.output);
  int labels = 0;
  for (std::string line; std::getline(lines, line);) {
    if (line.rfind("  ", 0) != 0) continue;
    std::istringstream words(line);
    std::string label;
    words >> label;
    ++labels;
    const bool known =
        std::find(keys.begin(), keys.end(), label) != keys.end() ||
        std::find(about_the_run.begin(), about_the_run.end(), label) != about_the_run.end();
    EXPECT_TRUE(known) << "'" << label << "' in: " << line;
  }
  EXPECT_GT(labels, 8);
  for (const char* command : {"edge --help", "advise --help", "run --help"}) {
    const auto o = run_mpmstab(command);
    EXPECT_EQ(o.output.find("error at T stays"), std::string::npos) << command;
  }
  // The edge's "error over time there" is the error over time of a run at dt_edge, and its
  // "error at T there" that run's error at T.
  const std::string edge_case = "--method gimp --E 64 --A 0.015 --T 1";
  const auto text = run_mpmstab("edge " + edge_case);
  const auto json = run_mpmstab("edge " + edge_case + " --json");
  ASSERT_EQ(json.status, 0) << json.output;
  const double dt_edge = nlohmann::json::parse(json.output)["dt_edge"].get<double>();
  const auto at_edge =
      run_mpmstab("run " + edge_case + " --dt " + fmt::format("{:.17g}", dt_edge) + " --json");
  ASSERT_EQ(at_edge.status, 0) << at_edge.output;
  const auto r = nlohmann::json::parse(at_edge.output);
  EXPECT_NE(text.output.find("error over time there " +
                             mpmstab::fmt(r["max_error_over_time"].get<double>())),
            std::string::npos)
      << text.output;
  EXPECT_NE(text.output.find("error at T there      " + mpmstab::fmt(r["max_error"].get<double>())),
            std::string::npos)
      << text.output;
}

// README's example of a run is a doc test: the command of its "## Running one case" block is
// run and every line it prints is the README's, but the machine's wall time and ns per
// particle-step; and README's list of the record's keys is the --json record's, in order.
TEST(Cli, TheReadmesRunExampleIsWhatTheRunPrints) {
  std::ifstream in(std::filesystem::path(MPMSTAB_SOURCE_DIR) / "README.md");
  std::stringstream ss;
  ss << in.rdbuf();
  const std::string readme = ss.str();
  const auto section = readme.find("## Running one case");
  ASSERT_NE(section, std::string::npos);
  const auto open = readme.find("```\n$ build/mpmstab ", section);
  ASSERT_NE(open, std::string::npos);
  const auto close = readme.find("```", open + 3);
  std::istringstream block(readme.substr(open + 4, close - open - 4));
  std::string command;
  std::getline(block, command);
  const std::string prefix = "$ build/mpmstab ";
  const Outcome o = run_mpmstab(command.substr(prefix.size()));
  ASSERT_EQ(o.status, 0) << o.output;
  const auto machine = [](const std::string& line) {
    return line.rfind("  wall_seconds", 0) == 0 || line.rfind("  ns/particle-step", 0) == 0 ||
           line.rfind("  (then wall_seconds", 0) == 0;
  };
  std::vector<std::string> shown, printed;
  for (std::string line; std::getline(block, line);)
    if (!machine(line)) shown.push_back(line);
  std::istringstream out(o.output);
  for (std::string line; std::getline(out, line);)
    if (!machine(line)) printed.push_back(line);
  EXPECT_EQ(shown, printed);

  const auto keys_at = readme.find("(keys, in order: `", close);
  ASSERT_NE(keys_at, std::string::npos);
  const auto keys_end = readme.find('`', keys_at + 18);
  std::string list = readme.substr(keys_at + 18, keys_end - keys_at - 18);
  std::replace(list.begin(), list.end(), '\n', ' ');
  std::vector<std::string> listed;
  std::istringstream words(list);
  for (std::string w; words >> w;)
    listed.push_back(w.back() == ',' ? w.substr(0, w.size() - 1) : w);
  const Outcome j = run_mpmstab(command.substr(prefix.size()) + " --json");
  ASSERT_EQ(j.status, 0) << j.output;
  const auto record = nlohmann::ordered_json::parse(j.output);
  std::vector<std::string> keys;
  for (const auto& [k, v] : record.items())
    keys.push_back(k);
  EXPECT_EQ(listed, keys);
}

// The tokenizer (CLI11 under the program's refusals): both forms of a value, a value that
// starts with a dash, "--" before positional arguments that start with one; and each refusal
// in the program's words, naming the option.
TEST(Args, TokenizesBothFormsAndRefusesInTheProgramsWords) {
  using mpmstab::cli::Args;
  using mpmstab::cli::UsageError;
  const std::vector<mpmstab::cli::OptionSpec> known = {{"E"}, {"out"}, {"json", false}};
  const auto message = [&](std::vector<std::string_view> argv) {
    try {
      Args a(argv, known);
    } catch (const UsageError& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  const Args a({"spec.json", "--E", "-5", "--out=res", "--json", "--", "-x.json"}, known);
  EXPECT_EQ(a.value("E"), "-5");
  EXPECT_EQ(a.value("out"), "res");
  EXPECT_TRUE(a.flag("json"));
  EXPECT_EQ(a.positional(), (std::vector<std::string_view>{"spec.json", "-x.json"}));
  const Args none({}, known);
  EXPECT_FALSE(none.value("E").has_value());
  EXPECT_FALSE(none.flag("json"));
  EXPECT_EQ(message({"--jsn"}), "unknown option --jsn (did you mean --json?)");
  EXPECT_EQ(message({"--E", "1", "--E", "2"}), "option --E given twice");
  EXPECT_EQ(message({"--json", "--json"}), "option --json given twice");
  EXPECT_EQ(message({"--E"}), "option --E needs a value");
  EXPECT_EQ(message({"--json=yes"}), "option --json takes no value");
  EXPECT_EQ(message({"--json="}), "option --json takes no value");
}

TEST(Cli, UnstableRunIsAResultNotAnError) {
  const Outcome o = run_mpmstab("run --method gimp --E 1000 --A 0.015 --dt 1e-3 --json");
  ASSERT_EQ(o.status, 0) << o.output;
  const auto j = nlohmann::json::parse(o.output);
  EXPECT_EQ(j["outcome"], "unstable");
  EXPECT_FALSE(j["failure_reason"].get<std::string>().empty());
  EXPECT_TRUE(j["failure_step"].is_number());
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
      {with("transfer", "mls"), "--transfer"},
      {with("transfer", "xpic") + " --xpic-order 0", "--xpic-order"},
      {with("transfer", "fmpm") + " --fmpm-order 1.5", "--fmpm-order"},
      {with("fmpm-order", "2"), "--fmpm-order"},          // only with --transfer fmpm
      {with("walls", "modified"), "--walls"},             // B-splines only (the base case is gimp)
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

// The two front doors, a spec's case and `mpmstab run`, go through one validation: every
// combination below is refused by both with the same message (or accepted by both).
class OneValidation : public ::testing::Test {
 protected:
  void SetUp() override {
    dir = std::filesystem::temp_directory_path() /
          ("mpmstab_one_validation_" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir);
  }
  void TearDown() override { std::filesystem::remove_all(dir); }

  // The command line for the parameters of `c` (keys as in a spec, '_' spelt '-').
  static std::string command_line(const nlohmann::ordered_json& c) {
    std::string args = "run";
    for (const auto& [key, value] : c.items()) {
      std::string option = key;
      std::replace(option.begin(), option.end(), '_', '-');
      args += " --" + option + " " + (value.is_string() ? value.get<std::string>() : value.dump());
    }
    return args;
  }

  // The text after "<prefix>" up to the end of its line ("" if absent).
  static std::string after(const std::string& text, const std::string& prefix) {
    const auto at = text.find(prefix);
    if (at == std::string::npos) return "";
    const auto begin = at + prefix.size();
    return text.substr(begin, text.find('\n', begin) - begin);
  }

  std::filesystem::path dir;
};

TEST_F(OneValidation, TheCommandLineAndASpecRefuseTheSameCombinationsWithTheSameMessage) {
  using J = nlohmann::ordered_json;
  const J base = {{"method", "gimp"}, {"E", 4}, {"A", 0.01}, {"T", 0.01}};
  auto with = [&](J extra) {
    J c = base;
    for (auto& [k, v] : extra.items())
      c[k] = v;
    return c;
  };
  struct Case {
    J params;
    std::string refused_key;  // "" when both must accept
  };
  const std::vector<Case> cases = {
      {with({{"dt", 1e-3}, {"E", -1}}), "E"},
      {with({{"dt", 1e-3}, {"E", 0}}), "E"},
      {with({{"dt", 1e-3}, {"A", -0.1}}), "A"},
      {with({{"dt", 0}}), "dt"},
      {with({{"dt", -1e-3}}), "dt"},
      {with({{"dt", 0.5}}), "dt"},  // dt > T
      {with({{"dt", 1e-3}, {"cells", 0}}), "cells"},
      {with({{"dt", 1e-3}, {"ppc", 0}}), "ppc"},
      {with({{"dt", 1e-12}}), "dt"},  // over the step cap
      {with({{"policy", "cfl"}, {"dt", 1e-3}}), "dt"},
      {with({{"policy", "adaptive"}, {"dt", 1e-3}}), "dt"},
      {with({{"policy", "min"}, {"dt", 1e-3}}), "dt"},
      {with({{"dt", 1e-3}, {"cfl_factor", 0.2}}), "cfl_factor"},
      {with({{"policy", "adaptive"}, {"cfl_factor", 0.2}}), "cfl_factor"},
      {with({{"dt", 1e-3}, {"safety", 2}}), "safety"},
      {with({{"policy", "cfl"}, {"safety", 2}}), "safety"},
      {with({{"policy", "cfl"}, {"cfl_factor", 0}}), "cfl_factor"},
      {with({{"policy", "adaptive"}, {"safety", -1}}), "safety"},
      {with({{"dt", 1e-3}, {"flip_fraction", 0.5}}), "flip_fraction"},
      {with({{"dt", 1e-3}, {"transfer", "blend"}, {"flip_fraction", 1}}), "flip_fraction"},
      {with({{"dt", 1e-3}, {"bc", "periodic"}, {"walls", "ghost"}}), "walls"},
      {with({{"dt", 1e-3}, {"T", 0}}), "T"},
      // accepted by both
      {with({{"dt", 1e-3}}), ""},
      {with({{"policy", "cfl"}}), ""},
      {with({{"policy", "cfl"}, {"cfl_factor", 0.25}}), ""},
      {with({{"policy", "adaptive"}, {"safety", 0.5}}), ""},
      {with({{"policy", "min"}, {"safety", 0.5}, {"cfl_factor", 0.25}}), ""},
      {with({{"dt", 1e-3}, {"transfer", "blend"}, {"flip_fraction", 0.9}}), ""},
  };
  for (std::size_t i = 0; i < cases.size(); ++i) {
    const Case& c = cases[i];
    std::string name = "v";
    name += std::to_string(i);
    const J spec = {{"name", name}, {"report", "cases"}, {"cases", {c.params}}};
    const auto path = dir / (name + ".json");
    std::ofstream(path) << spec.dump();
    const Outcome cli = run_mpmstab(command_line(c.params));
    const Outcome swept =
        run_mpmstab("sweep " + path.string() + " --out " + (dir / "out").string());
    const std::string what = c.params.dump();
    if (c.refused_key.empty()) {
      EXPECT_EQ(cli.status, 0) << what << "\n" << cli.output;
      EXPECT_EQ(swept.status, 0) << what << "\n" << swept.output;
      continue;
    }
    std::string option = c.refused_key;
    std::replace(option.begin(), option.end(), '_', '-');
    std::string cli_prefix = "--";
    cli_prefix += option;
    cli_prefix += ": ";
    std::string spec_prefix = "cases[0].";
    spec_prefix += c.refused_key;
    spec_prefix += ": ";
    const std::string from_cli = after(cli.output, cli_prefix);
    const std::string from_spec = after(swept.output, spec_prefix);
    EXPECT_EQ(cli.status, 2) << what << "\n" << cli.output;
    EXPECT_EQ(swept.status, 2) << what << "\n" << swept.output;
    EXPECT_FALSE(from_cli.empty()) << what << "\n" << cli.output;
    EXPECT_EQ(from_cli, from_spec) << what << "\n" << cli.output << "\n" << swept.output;
  }
}

// `mpmstab run --json` and a sweep of the same case give the same record (the command line
// records every quantity by default; the spec lists them).
TEST_F(OneValidation, RunAndASpecGiveTheSameRecord) {
  std::ofstream(dir / "cfl.json") << R"({"name": "cfl", "report": "cases",
      "record": ["error_over_time", "dt_stable", "crossings"], "cases": [
      {"method": "gimp", "E": 64, "A": 0.015, "T": 0.1, "policy": "cfl"}]})";
  const Outcome one = run_mpmstab("run --method gimp --E 64 --A 0.015 --T 0.1 --policy cfl --json");
  ASSERT_EQ(one.status, 0) << one.output;
  ASSERT_EQ(run_mpmstab("sweep " + (dir / "cfl.json").string() + " --out " + (dir / "out").string())
                .status,
            0);
  const auto record = nlohmann::ordered_json::parse(one.output);
  std::ifstream in(dir / "out/cfl.json");
  const auto row = nlohmann::ordered_json::parse(in)["cases"][0];
  EXPECT_TRUE(record["dt"].is_null());  // the cfl policy chose its own step
  EXPECT_DOUBLE_EQ(record["dt_mean"].get<double>(),
                   record["T"].get<double>() / record["steps"].get<double>());
  for (const auto& [key, value] : record.items())
    EXPECT_EQ(row[key], value) << key;
}

}  // namespace
