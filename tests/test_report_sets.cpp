// Whole report sets (experiments/engine/files.hpp, ReportBatch): a make reproduce killed at any
// instant leaves every experiment's reports either all old or all new once the folder is next
// locked (the journal of an interrupted publication is finished), never a mix.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <random>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "files.hpp"
#include "support.hpp"

namespace mpmstab {
namespace {

namespace fs = std::filesystem;
using Files = std::map<std::string, std::string>;  // name -> content

std::string read(const fs::path& p) {
  std::ifstream in(p);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// Three experiments of small cases; `T` changes every record, so every report changes.
void write_specs(const fs::path& dir, const std::string& T) {
  for (const char* name : {"a", "b", "c"}) {
    std::ofstream(dir / (std::string(name) + ".json"))
        << R"({"name": ")" << name << R"(", "report": "cases", "defaults": {"T": )" << T
        << R"(, "cells": 20}, "cases": [)"
        << R"({"method": "gimp", "E": 4, "A": 0.01, "dt": 1e-3},)"
        << R"({"method": "mpm", "E": 9, "A": 0.02, "dt": 1e-3},)"
        << R"({"method": "cpdi", "E": 16, "A": 0.01, "dt": 5e-4}]})";
  }
}

// The files of experiment `name` in `out` (its reports, not the cache).
Files set_of(const fs::path& out, const std::string& name) {
  Files files;
  for (const auto& e : fs::directory_iterator(out)) {
    const std::string f = e.path().filename().string();
    if (e.is_regular_file() && (f.rfind(name + ".", 0) == 0 || f.rfind(name + "_", 0) == 0))
      files[f] = read(e.path());
  }
  return files;
}

bool has_journal(const fs::path& out) {
  for (const auto& e : fs::directory_iterator(out))
    if (e.path().filename().string().ends_with(".journal")) return true;
  return false;
}

std::vector<std::string> reproduce_args(const fs::path& dir, const fs::path& out) {
  return {MPMSTAB_BIN,
          "reproduce",
          (dir / "a.json").string(),
          (dir / "b.json").string(),
          (dir / "c.json").string(),
          "--jobs",
          "1",
          "--out",
          out.string()};
}

// Starts build/mpmstab (no shell), its output discarded.
pid_t start(std::vector<std::string> args) {
  const pid_t pid = fork();
  if (pid == 0) {
    const int null = ::open("/dev/null", O_WRONLY);
    if (null >= 0) {
      dup2(null, STDOUT_FILENO);
      dup2(null, STDERR_FILENO);
    }
    std::vector<char*> argv;
    for (auto& a : args)
      argv.push_back(a.data());
    argv.push_back(nullptr);
    execv(MPMSTAB_BIN, argv.data());
    _exit(127);
  }
  return pid;
}

int wait_for(pid_t pid) {
  int raw = 0;
  while (waitpid(pid, &raw, 0) < 0 && errno == EINTR) {
  }
  return raw;
}

class ReportSets : public ::testing::Test {
 protected:
  fs::path dir = fs::temp_directory_path() / ("mpmstab_sets_" + std::to_string(::getpid()));
  fs::path old_out = dir / "old", new_out = dir / "new";
  std::map<std::string, Files> old_sets, new_sets;

  void SetUp() override {
    fs::create_directories(dir);
    write_specs(dir, "0.05");
    ASSERT_EQ(wait_for(start(reproduce_args(dir, old_out))), 0);
    write_specs(dir, "0.1");
    fs::copy(old_out, new_out, fs::copy_options::recursive);
    ASSERT_EQ(wait_for(start(reproduce_args(dir, new_out))), 0);
    for (const char* name : {"a", "b", "c"}) {
      old_sets[name] = set_of(old_out, name);
      new_sets[name] = set_of(new_out, name);
      ASSERT_GE(new_sets[name].size(), 3u) << name;
      for (const auto& [file, text] : new_sets[name])  // every file of the set changes
        ASSERT_NE(old_sets[name].at(file), text) << file;
    }
  }
  void TearDown() override { fs::remove_all(dir); }

  // A fresh copy of the old results, with the cache of the new run's cases (so that the
  // run to kill spends its time publishing, not computing, when asked).
  fs::path fresh(const std::string& label, bool warm) {
    const fs::path work = dir / label;
    fs::remove_all(work);
    fs::copy(old_out, work, fs::copy_options::recursive);
    if (warm)
      fs::copy(new_out / "cache", work / "cache",
               fs::copy_options::recursive | fs::copy_options::overwrite_existing);
    return work;
  }

  // Every experiment's set is all old or all new; returns how many are new.
  int expect_whole(const fs::path& work, const std::string& when) {
    int fresh_sets = 0;
    for (const char* name : {"a", "b", "c"}) {
      const Files now = set_of(work, name);
      const bool is_old = now == old_sets[name], is_new = now == new_sets[name];
      EXPECT_TRUE(is_old || is_new) << name << " is mixed after a kill " << when;
      fresh_sets += is_new;
    }
    EXPECT_FALSE(has_journal(work)) << when;
    return fresh_sets;
  }
};

// A kill right after each rename of the first publication: before recovery the folder holds a
// journal (and a mixed set); after it, every set is whole, the interrupted one new.
TEST_F(ReportSets, AKillBetweenAnyTwoRenamesIsFinishedFromTheJournal) {
  const std::size_t files = new_sets["a"].size();
  for (std::size_t n = 1; n < files; ++n) {
    const fs::path work = fresh("rename_" + std::to_string(n), true);
    ::setenv("MPMSTAB_TEST_KILL_AFTER_RENAMES", std::to_string(n).c_str(), 1);
    const int raw = wait_for(start(reproduce_args(dir, work)));
    ::unsetenv("MPMSTAB_TEST_KILL_AFTER_RENAMES");
    ASSERT_TRUE(WIFSIGNALED(raw) && WTERMSIG(raw) == SIGKILL) << n;
    EXPECT_TRUE(has_journal(work)) << n;
    int mixed = 0;
    for (const char* name : {"a", "b", "c"}) {
      const Files now = set_of(work, name);
      mixed += now != old_sets[name] && now != new_sets[name];
    }
    EXPECT_EQ(mixed, 1) << "the kill after rename " << n << " interrupts one set";
    EXPECT_GT(finish_interrupted_publications(work), 0u);
    EXPECT_GE(expect_whole(work, "after rename " + std::to_string(n)), 1);
  }
}

// make reproduce killed at random instants (fixed seed) over the length of a whole run, from a
// warm cache (the run is mostly publishing) and from a cold one: after the next process locks
// the folder, every set is whole.
TEST_F(ReportSets, AReproduceKilledAtRandomInstantsLeavesEverySetWhole) {
  for (const bool warm : {true, false}) {
    const fs::path timed = fresh(warm ? "timed_warm" : "timed_cold", warm);
    const auto t0 = std::chrono::steady_clock::now();
    ASSERT_EQ(wait_for(start(reproduce_args(dir, timed))), 0);
    const double length =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    std::mt19937 random(warm ? 20261125 : 5211626);
    std::uniform_real_distribution<double> instant(0.0, length);
    for (int k = 0; k < 6; ++k) {
      const double at = instant(random);
      const fs::path work = fresh("kill_" + std::to_string(k), warm);
      const pid_t pid = start(reproduce_args(dir, work));
      std::this_thread::sleep_for(std::chrono::duration<double>(at));
      ::kill(pid, SIGKILL);
      wait_for(pid);
      finish_publications_in(work);
      expect_whole(work, "at " + std::to_string(at) + " s of " + std::to_string(length) +
                             (warm ? " (warm cache)" : " (cold cache)"));
    }
  }
}

}  // namespace
}  // namespace mpmstab
