// Nothing lost: a real SIGINT or SIGTERM sent to a real sweep stops it promptly, keeps every
// finished case, leaves no partial file, and a rerun resumes from the cache.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <thread>

#include "support.hpp"

namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

class Signals : public ::testing::TestWithParam<int> {
 protected:
  fs::path dir = fs::temp_directory_path() / ("mpmstab_signal_" + std::to_string(::getpid()));
  void SetUp() override {
    fs::remove_all(dir);
    fs::create_directories(dir);
    // 24 cases of about 0.1-0.2 s each: long enough to interrupt in the middle.
    std::ofstream spec(dir / "long.json");
    spec << R"({"name": "long", "report": "cases", "record": ["error_over_time"],
      "defaults": {"T": 1, "cells": 100, "dt": 1e-5, "A": 0.01}, "cases": [)";
    for (int i = 0; i < 24; ++i) {
      spec << (i ? "," : "") << R"({"method": ")" << (i % 2 ? "mpm" : "gimp") << R"(", "E": )"
           << 1 + i << "}";
    }
    spec << "]}";
  }
  void TearDown() override { fs::remove_all(dir); }

  std::size_t files_in(const fs::path& p, const std::string& with = "") {
    std::size_t n = 0;
    if (!fs::exists(p)) return 0;
    for (const auto& e : fs::directory_iterator(p)) {
      n += e.path().filename().string().find(with) != std::string::npos;
    }
    return n;
  }
};

TEST_P(Signals, StopsPromptlyKeepsFinishedCasesAndResumes) {
  const int sig = GetParam();
  const fs::path out = dir / "out";
  const std::string spec = (dir / "long.json").string();
  const std::string out_s = out.string();
  const pid_t pid = fork();
  ASSERT_GE(pid, 0);
  if (pid == 0) {
    const int null = ::open("/dev/null", O_WRONLY);
    dup2(null, 2);
    execl(MPMSTAB_BIN, MPMSTAB_BIN, "sweep", spec.c_str(), "--jobs", "2", "--out", out_s.c_str(),
          static_cast<char*>(nullptr));
    _exit(127);
  }
  // Wait until some cases are finished, then signal.
  const auto start = Clock::now();
  while (files_in(out / "cache", ".json") < 3 && Clock::now() - start < std::chrono::seconds(30)) {
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  ASSERT_GE(files_in(out / "cache", ".json"), 3u) << "the sweep did not get going";
  ASSERT_EQ(kill(pid, sig), 0);
  const auto signalled = Clock::now();
  int status = 0;
  ASSERT_EQ(waitpid(pid, &status, 0), pid);
  const double seconds = std::chrono::duration<double>(Clock::now() - signalled).count();
  EXPECT_LT(seconds, 2.0) << "the sweep did not stop promptly";
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 128 + sig);

  const std::size_t kept = files_in(out / "cache", ".json");
  EXPECT_GE(kept, 3u);
  EXPECT_LT(kept, 24u) << "the sweep finished before the signal: make its cases longer";
  EXPECT_EQ(files_in(out / "cache", ".tmp"), 0u);  // no partial file
  EXPECT_FALSE(fs::exists(out / "long.csv"));      // no report of an unfinished sweep
  EXPECT_FALSE(fs::exists(out / "long.md"));

  // The rerun computes only what is missing.
  const auto rerun =
      mpmstab::test_support::run_mpmstab("sweep " + spec + " --jobs 2 --out " + out_s);
  EXPECT_EQ(rerun.status, 0);
  const std::string& output = rerun.output;
  std::ostringstream expected;
  expected << "(" << 24 - kept << " computed, " << kept << " from the cache";
  EXPECT_NE(output.find(expected.str()), std::string::npos) << output;
  EXPECT_TRUE(fs::exists(out / "long.csv"));
}

INSTANTIATE_TEST_SUITE_P(SigintAndSigterm, Signals, ::testing::Values(SIGINT, SIGTERM));

}  // namespace
