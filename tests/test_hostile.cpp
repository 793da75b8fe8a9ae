// Hostile input: every bad input to every command gets a message naming the key, option or
// file, exit status 2, and leaves every existing result file byte for byte unchanged.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include "support.hpp"

namespace {

namespace fs = std::filesystem;

class Hostile : public ::testing::Test {
 protected:
  static inline fs::path dir;
  static inline std::map<std::string, std::string> before;  // every file under out/

  static std::string read(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
  }
  static std::map<std::string, std::string> snapshot() {
    std::map<std::string, std::string> files;
    for (const auto& e : fs::recursive_directory_iterator(dir / "out")) {
      if (e.is_regular_file()) files[e.path().string()] = read(e.path());
    }
    return files;
  }
  static void write(const std::string& name, const std::string& text) {
    std::ofstream(dir / name) << text;
  }

  // One good sweep fills out/ with results; every bad command must leave them as they are.
  static void SetUpTestSuite() {
    dir = fs::temp_directory_path() / ("mpmstab_hostile_" + std::to_string(::getpid()));
    fs::remove_all(dir);
    fs::create_directories(dir);
    write("good.json", R"({"name": "good", "title": "Good", "report": "cases",
      "record": ["crossings"], "defaults": {"T": 0.01, "cells": 10, "dt": 1e-3},
      "cases": [{"method": "gimp", "E": 4, "A": 0.01}, {"method": "mpm", "E": 4, "A": 0.01}]})");
    write("t1.json", R"({"name": "t1", "report": "table1", "reference": "ref.csv",
      "defaults": {"T": 0.01, "cells": 10}, "cases": [{"method": "gimp", "E": 4, "A": 0.01, "dt": 1e-3}]})");
    write("ref.csv", "A,E,dt,method,dt_stable,max_error,confidence,evidence\n");
    ASSERT_EQ(mpmstab::test_support::run_mpmstab("sweep " + (dir / "good.json").string() +
                                                 " --out " + (dir / "out").string())
                  .status,
              0);
    before = snapshot();
    ASSERT_GE(before.size(), 4u);
  }
  static void TearDownTestSuite() { fs::remove_all(dir); }
};

struct Bad {
  std::string args;   // after "mpmstab"; DIR stands for the test folder
  std::string named;  // what the message must name
};

std::string expand(std::string s, const fs::path& dir) {
  for (std::size_t at; (at = s.find("DIR")) != std::string::npos;) {
    s.replace(at, 3, dir.string());
  }
  return s;
}

TEST_F(Hostile, EveryBadInputExitsTwoNamesTheCulpritAndChangesNothing) {
  // Spec files with one defect each.
  write("malformed.json", R"({"name": "x", "report": "cases", "cases": [)");
  write("empty.json", "");
  write("blank.json", "\n  \n");
  write("array.json", "[]");
  write("string.json", "\"spec\"");
  write("nocases.json", R"({"name": "x", "report": "cases"})");
  write(
      "wrongtype.json",
      R"({"name": "x", "report": "cases", "cases": [{"method": "gimp", "E": "four", "A": 0.01, "dt": 1e-3}]})");
  write(
      "unknownkey.json",
      R"({"name": "x", "report": "cases", "cases": [{"method": "gimp", "E": 4, "A": 0.01, "dt": 1e-3, "cell": 10}]})");
  write(
      "unknowntop.json",
      R"({"name": "x", "report": "cases", "recrod": [], "cases": [{"method": "gimp", "E": 4, "A": 0.01, "dt": 1e-3}]})");
  write(
      "negative.json",
      R"({"name": "x", "report": "cases", "cases": [{"method": "gimp", "E": -4, "A": 0.01, "dt": 1e-3}]})");
  write(
      "zero_dt.json",
      R"({"name": "x", "report": "cases", "cases": [{"method": "gimp", "E": 4, "A": 0.01, "dt": 0}]})");
  write(
      "huge.json",
      R"({"name": "x", "report": "cases", "cases": [{"method": "gimp", "E": 1e999, "A": 0.01, "dt": 1e-3}]})");
  write(
      "dt_gt_T.json",
      R"({"name": "x", "report": "cases", "defaults": {"T": 0.5}, "cases": [{"method": "gimp", "E": 4, "A": 0.01, "dt": 1}]})");
  write(
      "cells.json",
      R"({"name": "x", "report": "cases", "cases": [{"method": "gimp", "E": 4, "A": 0.01, "dt": 1e-3, "cells": 1000000000}]})");
  write(
      "steps.json",
      R"({"name": "x", "report": "cases", "cases": [{"method": "gimp", "E": 4, "A": 0.01, "dt": 1e-9, "T": 1}]})");
  write(
      "method.json",
      R"({"name": "x", "report": "cases", "cases": [{"method": "sph", "E": 4, "A": 0.01, "dt": 1e-3}]})");
  write(
      "missing.json",
      R"({"name": "x", "report": "cases", "cases": [{"method": "gimp", "A": 0.01, "dt": 1e-3}]})");
  write(
      "defaults.json",
      R"({"name": "x", "report": "cases", "defaults": {"ppc": 0}, "cases": [{"method": "gimp", "E": 4, "A": 0.01, "dt": 1e-3}]})");
  write(
      "badname.json",
      R"({"name": "../escape", "report": "cases", "cases": [{"method": "gimp", "E": 4, "A": 0.01, "dt": 1e-3}]})");
  // Names that would overwrite a file another command (or another experiment) writes.
  for (const char* name : {"performance", "timings", "benchmark_step", "fig1_data", "comparison"}) {
    write(
        std::string("reserved_") + name + ".json",
        std::string(R"({"name": ")") + name +
            R"(", "report": "cases", "cases": [{"method": "gimp", "E": 4, "A": 0.01, "dt": 1e-3}]})");
  }
  write(
      "dup.json",
      R"({"name": "x", "report": "cases", "cases": [{"method": "gimp", "E": 4, "A": 0.01, "dt": 1e-3}, {"method": "gimp", "E": 4, "A": 0.01, "dt": 1e-3}]})");
  write(
      "edge_dt.json",
      R"({"name": "x", "report": "edge", "cases": [{"method": "gimp", "E": 4, "A": 0.01, "dt": 1e-3}]})");
  fs::create_directories(dir / "adir.json");
  write("afile", "x");

  const std::vector<Bad> cases = {
      // run
      {"run --method gimp --E -1 --A 0.01 --dt 1e-3", "--E"},
      {"run --method gimp --E 0 --A 0.01 --dt 1e-3", "--E"},
      {"run --method gimp --E nan --A 0.01 --dt 1e-3", "--E"},
      {"run --method gimp --E inf --A 0.01 --dt 1e-3", "--E"},
      {"run --method gimp --E 4 --A -1 --dt 1e-3", "--A"},
      {"run --method gimp --E 4 --A 0.01 --dt 0", "--dt"},
      {"run --method gimp --E 4 --A 0.01 --dt 2", "--dt"},
      {"run --method gimp --E 4 --A 0.01 --dt 1e-3 --cells 0", "--cells"},
      {"run --method gimp --E 4 --A 0.01 --dt 1e-3 --cells 100000000000", "--cells"},
      {"run --method gimp --E 4 --A 0.01 --dt 1e-3 --ppc 0", "--ppc"},
      {"run --method flip --E 4 --A 0.01 --dt 1e-3", "--method"},
      {"run --method gimp --E 4 --A 0.01 --dt 1e-3 --bc open", "--bc"},
      {"run --method gimp --E four --A 0.01 --dt 1e-3", "--E"},
      {"run --method gimp --E 4 --A 0.01 --dt 1e-3 --T 1e300", "--dt"},
      {"run --method gimp --E 4 --A 0.01 --dt 1e-3 --Young 4", "--Young"},
      {"run --method gimp --E 4 --A 0.01 --dt 1e-3 --history DIR/afile/h.csv", "--history"},
      // edge
      {"edge --method gimp --E -4 --A 0.01", "--E"},
      {"edge --method gimp --E 4 --A 0.01 --dt 1e-3", "--dt"},
      {"edge --method gimp --E 4 --A 0.01 --tolerance 0", "--tolerance"},
      // sweep
      {"sweep DIR/malformed.json --out DIR/out", "malformed JSON"},
      {"sweep DIR/empty.json --out DIR/out", "is empty"},
      {"sweep DIR/blank.json --out DIR/out", "is empty"},
      {"sweep DIR/array.json --out DIR/out", "must be a JSON object"},
      {"sweep DIR/string.json --out DIR/out", "must be a JSON object"},
      {"sweep DIR/nocases.json --out DIR/out", "cases: is required"},
      {"sweep DIR/wrongtype.json --out DIR/out", "cases[0].E: must be a number"},
      {"sweep DIR/unknownkey.json --out DIR/out", "did you mean 'cells'"},
      {"sweep DIR/unknowntop.json --out DIR/out", "did you mean 'record'"},
      {"sweep DIR/negative.json --out DIR/out", "cases[0].E"},
      {"sweep DIR/zero_dt.json --out DIR/out", "cases[0].dt"},
      {"sweep DIR/huge.json --out DIR/out", "number overflow"},
      {"sweep DIR/dt_gt_T.json --out DIR/out", "cases[0].dt"},
      {"sweep DIR/cells.json --out DIR/out", "cases[0].cells"},
      {"sweep DIR/steps.json --out DIR/out", "cases[0].dt"},
      {"sweep DIR/method.json --out DIR/out", "cases[0].method"},
      {"sweep DIR/missing.json --out DIR/out", "cases[0].E: is required"},
      {"sweep DIR/defaults.json --out DIR/out", "defaults.ppc"},
      {"sweep DIR/badname.json --out DIR/out", "name:"},
      {"sweep DIR/reserved_performance.json --out DIR/out", "'performance' is reserved"},
      {"sweep DIR/reserved_timings.json --out DIR/out", "'timings' is reserved"},
      {"sweep DIR/reserved_benchmark_step.json --out DIR/out", "'benchmark_step' is reserved"},
      {"sweep DIR/reserved_fig1_data.json --out DIR/out", "'fig1_data' is reserved"},
      {"sweep DIR/reserved_comparison.json --out DIR/out", "'comparison' is reserved"},
      {"sweep DIR/dup.json --out DIR/out", "cases[1]: repeats cases[0]"},
      {"sweep DIR/edge_dt.json --out DIR/out", "cases[0].dt"},
      {"sweep DIR/adir.json --out DIR/out", "is a directory"},
      {"sweep DIR/absent.json --out DIR/out", "absent.json"},
      {"sweep DIR/good.json --out DIR/afile", "--out"},
      {"sweep DIR/good.json --out /proc/none/out", "--out"},
      {"sweep DIR/good.json --out DIR/out --jobs 0", "--jobs"},
      {"sweep DIR/good.json --out DIR/out --jobs many", "--jobs"},
      {"sweep DIR/good.json DIR/good.json --out DIR/out", "one spec"},
      {"sweep --out DIR/out", "spec"},
      {"sweep DIR/good.json --out DIR/out --froce", "--froce"},
      // the other commands
      {"index DIR/malformed.json --out DIR/out", "malformed JSON"},
      {"index --out DIR/out", "spec"},
      {"plot DIR/good.json --out DIR/out", "has no figure"},
      {"plot DIR/empty.json --out DIR/out", "is empty"},
      {"compare DIR/good.json --out DIR/out", "table1"},
      {"compare DIR/t1.json --out DIR/out", "t1.json"},
      {"performance DIR/malformed.json --out DIR/out", "malformed JSON"},
      {"check DIR/malformed.json --reference DIR/out", "malformed JSON"},
      {"check DIR/good.json --rtol -1 --reference DIR/out", "--rtol"},
      {"bless DIR/good.json --reference DIR/out/ref", "--reason"},
      {"bless DIR/malformed.json --reason x --reference DIR/out/ref", "malformed JSON"},
      {"frobnicate", "frobnicate"},
  };
  ASSERT_GE(cases.size(), 40u);
  for (const auto& c : cases) {
    const auto [status, output] = mpmstab::test_support::run_mpmstab(expand(c.args, dir));
    EXPECT_EQ(status, 2) << c.args << "\n" << output;
    EXPECT_NE(output.find(expand(c.named, dir)), std::string::npos) << c.args << "\n" << output;
    EXPECT_EQ(output.find("internal error"), std::string::npos) << c.args << "\n" << output;
  }
  // Every existing result is byte for byte as it was, and nothing was added.
  EXPECT_EQ(snapshot(), before);
}

}  // namespace
