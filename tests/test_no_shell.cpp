// No shell, anywhere: programs are started with an argument vector, so no text from a spec, a
// result or a path can be read as shell (or gnuplot) syntax.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "support.hpp"

namespace mpmstab {
namespace {

namespace fs = std::filesystem;
using test_support::run_mpmstab;

std::string read(const fs::path& p) {
  std::ifstream in(p);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// No source (the solver, the engine, the studies, the commands and the tests) starts a shell.
TEST(NoShell, NoSourceCallsSystemOrPopen) {
  const std::string system_call = std::string("system") + "(";
  const std::string popen_call = std::string("popen") + "(";
  int files = 0;
  for (const char* dir : {"core", "experiments", "tests"}) {
    for (const auto& e : fs::recursive_directory_iterator(fs::path(MPMSTAB_SOURCE_DIR) / dir)) {
      const auto ext = e.path().extension();
      if (ext != ".cpp" && ext != ".hpp") continue;
      ++files;
      if (e.path().string().find("/fuzz/corpus/") != std::string::npos) continue;
      const std::string text = read(e.path());
      EXPECT_EQ(text.find(system_call), std::string::npos) << e.path();
      EXPECT_EQ(text.find(popen_call), std::string::npos) << e.path();
    }
  }
  EXPECT_GT(files, 40);
}

class PlotInjection : public ::testing::Test {
 protected:
  fs::path dir = fs::temp_directory_path() / ("mpmstab_no_shell_" + std::to_string(::getpid()));
  fs::path witness = dir / "PWNED";
  void SetUp() override {
    fs::create_directories(dir / "experiments");
    std::ofstream(dir / "experiments/f.json") << R"({"name": "f", "report": "figure",
        "record": ["error_over_time", "history", "dt_stable", "crossings"], "cases": [{"method": "gimp", "E": 1e4, "A": 0.06,
        "dt": 1e-3, "T": 0.01, "cells": 20}], "history_stride": 1})";
    fs::copy_file(fs::path(MPMSTAB_SOURCE_DIR) / "experiments/fig3.gp", dir / "experiments/f.gp");
    fs::copy_file(fs::path(MPMSTAB_SOURCE_DIR) / "experiments/history.gp",
                  dir / "experiments/history.gp");
  }
  void TearDown() override { fs::remove_all(dir); }
};

// A quote, a command substitution and a call of gnuplot's system function (spelt in two parts
// here, so that this file passes the test above) in the output folder's name and in a results
// file: the figure is drawn, nothing is run.
TEST_F(PlotInjection, HostileTextInPathsAndResultsRunsNothing) {
  const std::string hostile = "o'$(touch " + witness.string() + ")'\"; " + std::string("sys") +
                              "tem(\"touch " + witness.string() + "\"); a='";
  const fs::path out = dir / hostile;
  const std::string spec = (dir / "experiments/f.json").string();
  // The folder name is passed as one argument vector element (no shell in between).
  const std::vector<std::string> args = {"sweep", spec, "--out", out.string()};
  pid_t pid = fork();
  if (pid == 0) {
    std::vector<char*> argv = {const_cast<char*>(MPMSTAB_BIN)};
    for (const auto& a : args)
      argv.push_back(const_cast<char*>(a.c_str()));
    argv.push_back(nullptr);
    execv(MPMSTAB_BIN, argv.data());
    _exit(127);
  }
  int status = 0;
  waitpid(pid, &status, 0);
  ASSERT_EQ(WEXITSTATUS(status), 0);
  // A failure reason in the results JSON that would end gnuplot's string and run a command.
  std::string json = read(out / "f.json");
  const std::string from = "\"nonpositive_F\"";
  int replaced = 0;
  for (auto at = json.find(from); at != std::string::npos; at = json.find(from, at + 1)) {
    json.replace(at, from.size(), nlohmann::json(hostile).dump());
    ++replaced;
  }
  ASSERT_GT(replaced, 0) << json;  // the run failed: its reason is in the figure's title
  std::ofstream(out / "f.json") << json;
  pid = fork();
  if (pid == 0) {
    const std::string o = out.string();
    execl(MPMSTAB_BIN, MPMSTAB_BIN, "plot", spec.c_str(), "--out", o.c_str(),
          static_cast<char*>(nullptr));
    _exit(127);
  }
  waitpid(pid, &status, 0);
  EXPECT_EQ(WEXITSTATUS(status), 0);
  EXPECT_TRUE(fs::exists(out / "f.png"));
  EXPECT_FALSE(fs::exists(witness));
  EXPECT_FALSE(fs::exists(fs::path("PWNED")));
}

}  // namespace
}  // namespace mpmstab
