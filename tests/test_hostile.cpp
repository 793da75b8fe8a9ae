// Hostile input: every bad input to every command gets a message naming the key, option or
// file, exit status 2, and leaves every existing result file byte for byte unchanged.
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <tuple>

#include <nlohmann/json.hpp>

#include "base/params.hpp"
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
  for (const char* name : {"performance", "timings", "benchmark_step", "fig1_data",
                           "table1_follow_up", "comparison"}) {
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

  // Loose JSON: duplicate keys, a byte-order mark, control characters in any string.
  const std::string gcase = R"({"method": "gimp", "E": 4, "A": 0.01, "dt": 1e-3})";
  auto spec_with = [&](const std::string& name, const std::string& members) {
    write(name, R"({"name": "x", "report": "cases", )" + members + "}");
  };
  spec_with("dup_top.json", R"("name": "y", "cases": [)" + gcase + "]");
  spec_with("dup_case.json",
            R"("cases": [{"method": "gimp", "E": 4, "E": 8, "A": 0.01, "dt": 1e-3}])");
  spec_with("dup_defaults.json", R"("defaults": {"T": 0.5, "T": 0.01}, "cases": [)" + gcase + "]");
  write("bom.json", "\xEF\xBB\xBF" + std::string(R"({"name": "x", "report": "cases", "cases": [)") +
                        gcase + "]}");
  spec_with("title_nl.json", R"("title": "two\nlines", "cases": [)" + gcase + "]");
  spec_with("title_cr.json", R"("title": "a\rb", "cases": [)" + gcase + "]");
  spec_with("desc_tab.json", R"("description": "a\tb", "cases": [)" + gcase + "]");
  spec_with("title_esc.json", R"("title": "a\u001b[31mred", "cases": [)" + gcase + "]");
  spec_with("title_nul.json", R"("title": "a\u0000b", "cases": [)" + gcase + "]");
  spec_with("title_del.json", "\"title\": \"a\x7f b\", \"cases\": [" + gcase + "]");
  spec_with("key_nl.json",
            R"("cases": [{"method": "gimp", "E": 4, "A": 0.01, "dt": 1e-3, "c\nells": 10}])");
  spec_with("scene_nl.json",
            R"("cases": [{"method": "gimp", "E": 4, "A": 0.01, "dt": 1e-3, "scene": "sine\n"}])");
  spec_with("nan_string.json",
            R"("cases": [{"method": "gimp", "E": "NaN", "A": 0.01, "dt": 1e-3}])");
  spec_with("inf_string.json",
            R"("cases": [{"method": "gimp", "E": "Infinity", "A": 0.01, "dt": 1e-3}])");
  spec_with("neg_zero_E.json",
            R"("cases": [{"method": "gimp", "E": -0.0, "A": 0.01, "dt": 1e-3}])");
  spec_with("nan_literal.json",
            R"("cases": [{"method": "gimp", "E": NaN, "A": 0.01, "dt": 1e-3}])");
  spec_with("trailing.json", R"("cases": [)" + gcase + "]} {");
  spec_with("comment.json", R"(/* c */ "cases": [)" + gcase + "]");
  // Bounded resources.
  spec_with(
      "memory.json",
      R"("cases": [{"method": "gimp", "E": 4, "A": 0.01, "dt": 1e-3, "cells": 10000000, "ppc": 4}])");
  write(
      "history_rows.json",
      R"({"name": "x", "report": "cases", "record": ["history"], "cases": [{"method": "gimp", "E": 4, "A": 0.01, "dt": 1e-8, "T": 1}]})");
  write(
      "history_adaptive.json",
      R"({"name": "x", "report": "cases", "record": ["history"], "cases": [{"method": "gimp", "E": 4, "A": 0.01, "policy": "adaptive"}]})");
  {
    std::ofstream big(dir / "big.json");
    big << R"({"name": "x", "report": "cases", "description": ")" << std::string(5u << 20, 'a')
        << R"(", "cases": [)" << gcase << "]}";
  }
  {
    std::ofstream(dir / "huge_ref.csv") << "A,E\n";
    fs::resize_file(dir / "huge_ref.csv", (std::uintmax_t{64} << 20) + 1);  // sparse
  }
  // Inputs that are not regular files: reading must not block or eat memory.
  ASSERT_EQ(::mkfifo((dir / "fifo.json").c_str(), 0644), 0);
  ASSERT_EQ(::mkfifo((dir / "fifo.csv").c_str(), 0644), 0);
  fs::create_symlink("/dev/zero", dir / "zero.json");
  auto t1_with_reference = [&](const std::string& name, const std::string& reference) {
    write(
        name,
        R"({"name": "t1", "report": "table1", "reference": ")" + reference +
            R"(", "defaults": {"T": 0.01, "cells": 10}, "cases": [{"method": "gimp", "E": 4, "A": 0.01, "dt": 1e-3}]})");
  };
  t1_with_reference("ref_fifo.json", "fifo.csv");
  t1_with_reference("ref_zero.json", "/dev/zero");
  t1_with_reference("ref_absent.json", "absent.csv");
  t1_with_reference("ref_dir.json", "adir.json");
  t1_with_reference("ref_huge.json", "huge_ref.csv");
  write("ref_unterminated.csv", "A,E,dt\n\"0.01,4,1e-3\n");
  t1_with_reference("ref_unterminated.json", "ref_unterminated.csv");
  write("ref_fields.csv", "A,E,dt\n0.01,4\n");
  t1_with_reference("ref_fields.json", "ref_fields.csv");
  write("ref_empty.csv", "");
  t1_with_reference("ref_empty.json", "ref_empty.csv");
  // Results files that are not what a sweep writes, each in a folder of its own.
  const std::vector<std::pair<std::string, std::string>> bad_results = {
      {"empty", ""},
      {"cases_empty", R"({"cases": []})"},
      {"case_empty", R"({"cases": [{}, {}]})"},
      {"truncated", R"({"cases": [{"method": "gimp")"},
      {"array", "[]"},
      {"dup", R"({"cases": [], "cases": []})"},
      {"bom", "\xEF\xBB\xBF{}"},
      {"cases_string", R"({"cases": "none"})"},
  };
  for (const auto& [name, text] : bad_results) {
    fs::create_directories(dir / ("res_" + name));
    std::ofstream(dir / ("res_" + name) / "good.json") << text;
  }
  // A blessed table that is not a table; a figure's results that are not results.
  fs::create_directories(dir / "reg_bad");
  std::ofstream(dir / "reg_bad" / "good.csv") << "method,E\n\"gimp,4\n";
  fs::create_directories(dir / "reg_fifo");
  ASSERT_EQ(::mkfifo((dir / "reg_fifo" / "good.csv").c_str(), 0644), 0);
  fs::create_directories(dir / "plot_bad");
  std::ofstream(dir / "plot_bad" / "fig3_data.csv") << "x\n1\n";
  std::ofstream(dir / "plot_bad" / "fig3.json") << R"({"cases": [{}]})";
  fs::create_directories(dir / "t1_bad");
  std::ofstream(dir / "t1_bad" / "t1.json") << R"({"cases": [{"method": 1}]})";
  // A shard folder whose cache holds garbage under the right keys is no source of results.
  fs::create_directories(dir / "shard_bad" / "cache");
  for (const auto& e : fs::directory_iterator(dir / "out" / "cache")) {
    std::ofstream(dir / "shard_bad" / "cache" / e.path().filename()) << R"({"result": 1})";
  }

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
      {"spectral --method gimpp --E 4", "--method"},
      {"run --method gimp --E 4 --A 0.01 --policy spectral --cells 1000", "--policy"},
      {"run --method gimp --E 4 --A 0.01 --policy spectral --cfl-factor 0.5", "--cfl-factor"},
      {"run --method gimp --E 4 --A 0.01 --policy spectral --dt 1e-3", "--dt"},
      {"spectral --method gimp --E -4", "--E"},
      {"spectral --method gimp --E 4 --dt 1e-3", "--dt"},
      {"spectral --method gimp --E 4 --cells 100000 --analysis dense", "--cells"},
      {"spectral --method gimp --E 4 --analysis fourier", "--analysis"},
      {"run --method gimp --E 4 --A 0.01 --dt 1e-3 --jitter 1", "--jitter"},
      {"run --method gimp --E 4 --A 0.01 --dt 1e-3 --shift 0.5", "--shift"},
      {"run --method gimp --E 4 --A 0.01 --dt 1e-3 --shift nan", "--shift"},
      {"spectral --method gimp --E 4 --jitter 0.5 --cells 1000", "--cells"},
      {"spectral --method gimp --E 4 --scene steffen --A 0.1 --analysis bloch", "--analysis"},
      {"spectral --method gimp --E 4 --transfer xpic --xpic-order 0", "--xpic-order"},
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
      {"sweep DIR/reserved_table1_follow_up.json --out DIR/out", "'table1_follow_up' is reserved"},
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
      {"build-time --out DIR/out", "--seconds is required"},
      {"build-time --seconds 0 --out DIR/out", "--seconds"},
      {"build-time --seconds -3 --out DIR/out", "--seconds"},
      {"build-time --seconds nan --out DIR/out", "--seconds"},
      {"build-time --seconds inf --out DIR/out", "--seconds"},
      {"build-time --seconds 1e400 --out DIR/out", "--seconds"},
      {"build-time --seconds fast --out DIR/out", "--seconds"},
      {"build-time --seconds 100 --jobs 0 --out DIR/out", "--jobs"},
      {"build-time --seconds 100 DIR/good.json --out DIR/out", "no positional argument"},
      {"build-time --seconds 100 --out DIR/afile", "--out"},
      // strict JSON, each refusal naming the key's path
      {"sweep DIR/dup_top.json --out DIR/out", "name: is given twice"},
      {"sweep DIR/dup_case.json --out DIR/out", "cases[0].E: is given twice"},
      {"sweep DIR/dup_defaults.json --out DIR/out", "defaults.T: is given twice"},
      {"sweep DIR/bom.json --out DIR/out", "byte-order mark"},
      {"sweep DIR/title_nl.json --out DIR/out", "title: contains the control character U+000A"},
      {"sweep DIR/title_cr.json --out DIR/out", "title: contains the control character U+000D"},
      {"sweep DIR/desc_tab.json --out DIR/out", "description: contains the control character"},
      {"sweep DIR/title_esc.json --out DIR/out", "title: contains the control character U+001B"},
      {"sweep DIR/title_nul.json --out DIR/out", "title: contains the control character U+0000"},
      {"sweep DIR/title_del.json --out DIR/out", "title: contains the control character U+007F"},
      {"sweep DIR/key_nl.json --out DIR/out", "a key contains the control character"},
      {"sweep DIR/scene_nl.json --out DIR/out", "cases[0].scene: contains the control character"},
      {"sweep DIR/nan_string.json --out DIR/out", "cases[0].E: must be a number"},
      {"sweep DIR/inf_string.json --out DIR/out", "cases[0].E: must be a number"},
      {"sweep DIR/neg_zero_E.json --out DIR/out", "cases[0].E"},
      {"sweep DIR/nan_literal.json --out DIR/out", "malformed JSON"},
      {"sweep DIR/trailing.json --out DIR/out", "malformed JSON"},
      {"sweep DIR/comment.json --out DIR/out", "malformed JSON"},
      // bounded resources
      {"sweep DIR/memory.json --out DIR/out", "the limit is 2048 MiB"},
      {"run --method gimp --E 4 --A 0.01 --dt 1e-3 --cells 10000000 --ppc 2", "2048 MiB"},
      {"sweep DIR/history_rows.json --out DIR/out", "history rows in memory; the limit is"},
      {"sweep DIR/history_adaptive.json --out DIR/out", "or lower max_steps"},
      {"sweep DIR/big.json --out DIR/out", "larger than the limit of 4 MiB"},
      {"sweep DIR/ref_huge.json --out DIR/out", "larger than the limit of 64 MiB"},
      // inputs that are not regular files: refused at once, never read
      {"sweep DIR/fifo.json --out DIR/out", "fifo.json: is not a regular file"},
      {"sweep DIR/zero.json --out DIR/out", "zero.json: is not a regular file"},
      {"sweep /dev/zero --out DIR/out", "/dev/zero: is not a regular file"},
      {"index DIR/fifo.json --out DIR/out", "fifo.json: is not a regular file"},
      {"plot DIR/fifo.json --out DIR/out", "fifo.json: is not a regular file"},
      {"check DIR/zero.json --reference DIR/out", "zero.json: is not a regular file"},
      // a reference that cannot be read is refused before any case runs
      {"sweep DIR/ref_fifo.json --out DIR/out", "fifo.csv: is not a regular file"},
      {"sweep DIR/ref_zero.json --out DIR/out", "/dev/zero: is not a regular file"},
      {"sweep DIR/ref_absent.json --out DIR/out", "absent.csv: does not exist"},
      {"sweep DIR/ref_dir.json --out DIR/out", "adir.json: is a directory"},
      {"sweep DIR/ref_unterminated.json --out DIR/out", "unterminated quoted field"},
      {"sweep DIR/ref_fields.json --out DIR/out", "2 fields, header has 3"},
      {"sweep DIR/ref_empty.json --out DIR/out", "no header line"},
      {"compare DIR/fifo.json --out DIR/out", "fifo.json: is not a regular file"},
      // results files that are not what a sweep writes
      {"index DIR/good.json --out DIR/res_empty", "res_empty/good.json: is empty"},
      {"index DIR/good.json --out DIR/res_cases_empty", "0 rows for the spec's 2 cases"},
      {"index DIR/good.json --out DIR/res_case_empty", "cases[0].method: is missing"},
      {"index DIR/good.json --out DIR/res_truncated", "malformed JSON"},
      {"index DIR/good.json --out DIR/res_array", "must be a JSON object"},
      {"index DIR/good.json --out DIR/res_dup", "cases: is given twice"},
      {"index DIR/good.json --out DIR/res_bom", "byte-order mark"},
      {"index DIR/good.json --out DIR/res_cases_string", "cases: must be an array"},
      {"merge DIR/good.json DIR/shard_bad --out DIR/out", "are in none of the folders"},
      {"check DIR/good.json --reference DIR/reg_bad", "reg_bad/good.csv: line 2: unterminated"},
      {"check DIR/good.json --reference DIR/reg_fifo", "reg_fifo/good.csv: is not a regular"},
      {"plot " MPMSTAB_SOURCE_DIR "/experiments/fig3.json --out DIR/plot_bad",
       "plot_bad/fig3.json: cases[0].method: is missing"},
      {"compare DIR/t1.json --out DIR/t1_bad", "t1_bad/t1.json: cases[0].method: has the wrong"},
      {"merge DIR/good.json DIR/absent_shard --out DIR/out", "not a folder"},
      {"merge DIR/good.json DIR/shard_bad --with-follow-ups --out DIR/out", "--with-follow-ups"},
      {"reproduce DIR/good.json DIR/shard_bad --follow-ups --out DIR/out", "--follow-ups"},
      // the history file: never anything but a regular file
      {"run --method gimp --E 4 --A 0.01 --dt 1e-3 --history /dev/null", "a device"},
      {"run --method gimp --E 4 --A 0.01 --dt 1e-3 --history DIR/fifo.csv", "a FIFO"},
      {"run --method gimp --E 4 --A 0.01 --dt 1e-3 --history DIR/zero.json", "a symbolic link"},
      {"run --method gimp --E 4 --A 0.01 --dt 1e-3 --history DIR/adir.json", "a directory"},
      // a reason is one line of the audit log
      {"bless DIR/good.json --reference DIR/out/ref --reason 'a\n## forged'", "--reason"},
      {"bless DIR/good.json --reference DIR/out/ref --reason 'a\x1b[2Jb'", "--reason"},
      {"bless DIR/good.json --reference DIR/out/ref --reason 'a\rb'", "--reason"},
      // job scripts: no control character in any value
      {"slurm DIR/good.json --shards 2 --partition 'p\n#SBATCH --x' --out DIR/out", "--partition"},
      {"slurm DIR/good.json --shards 2 --account 'a\tb' --out DIR/out", "--account"},
  };
  ASSERT_GE(cases.size(), 120u);
  for (const auto& c : cases) {
    const auto [status, output] = mpmstab::test_support::run_mpmstab(expand(c.args, dir));
    EXPECT_EQ(status, 2) << c.args << "\n" << output;
    EXPECT_NE(output.find(expand(c.named, dir)), std::string::npos) << c.args << "\n" << output;
    EXPECT_EQ(output.find("internal error"), std::string::npos) << c.args << "\n" << output;
  }
  // Every existing result is byte for byte as it was, and nothing was added.
  EXPECT_EQ(snapshot(), before);
}

// A symbolic link (to a file outside the folder, or to a device), a FIFO or a folder planted at
// each name a sweep writes: the sweep exits 2 naming it, the trap is still there and what it
// points to is unchanged. Each trap gets a results folder of its own.
TEST_F(Hostile, TrapsAtEveryOutputNameAreRefusedAndLeftAsTheyAre) {
  const fs::path outside = dir / "outside.txt";
  std::ofstream(outside) << "precious\n";
  int n = 0;
  for (const char* name :
       {"good.csv", "good.json", "good.md", "cache/timings.json", ".mpmstab.lock"}) {
    for (const char* kind : {"symlink", "device", "fifo", "folder"}) {
      const fs::path folder = dir / ("trap_" + std::to_string(n++));
      const fs::path trap = folder / name;
      fs::create_directories(trap.parent_path());
      if (std::string(kind) == "symlink") fs::create_symlink(outside, trap);
      if (std::string(kind) == "device") fs::create_symlink("/dev/null", trap);
      if (std::string(kind) == "fifo") {
        ASSERT_EQ(::mkfifo(trap.c_str(), 0644), 0);
      }
      if (std::string(kind) == "folder") fs::create_directories(trap);
      const auto [status, output] = mpmstab::test_support::run_mpmstab(
          "sweep " + (dir / "good.json").string() + " --out " + folder.string());
      EXPECT_EQ(status, 2) << name << " as " << kind << "\n" << output;
      EXPECT_NE(output.find(trap.string()), std::string::npos) << output;
      EXPECT_EQ(output.find("internal error"), std::string::npos) << output;
      const auto st = fs::symlink_status(trap);
      EXPECT_TRUE(fs::is_symlink(st) || fs::is_fifo(st) || fs::is_directory(st)) << trap;
      // No report of the set was published beside the trap.
      for (const char* other : {"good.csv", "good.json", "good.md"}) {
        if (std::string(other) != name) {
          EXPECT_FALSE(fs::exists(folder / other)) << trap;
        }
      }
    }
  }
  EXPECT_EQ(read(outside), "precious\n");
  EXPECT_EQ(snapshot(), before);
}

// Temporaries cannot be planted: their names are random and created with O_EXCL | O_NOFOLLOW,
// so a link at any name the old scheme used (<file>.tmp.<pid>) leads nowhere.
TEST_F(Hostile, LinksAtGuessableTemporaryNamesAreNotFollowed) {
  const fs::path folder = dir / "guess";
  fs::create_directories(folder);
  const fs::path outside = dir / "outside_tmp.txt";
  std::ofstream(outside) << "precious\n";
  // The next pids the program may get, for every file it writes.
  const long pid = static_cast<long>(::getpid());
  fs::create_directories(folder / "cache");
  for (const char* name : {"good.csv", "good.json", "good.md", "cache/timings.json"}) {
    const fs::path target = folder / name;
    const std::string file = target.filename().string();
    for (long p = pid; p < pid + 64; ++p)
      fs::create_symlink(outside, target.parent_path() / (file + ".tmp." + std::to_string(p)));
    fs::create_symlink(outside, target.parent_path() / ("." + file + ".tmp"));
  }
  const auto [status, output] = mpmstab::test_support::run_mpmstab(
      "sweep " + (dir / "good.json").string() + " --out " + folder.string());
  EXPECT_EQ(status, 0) << output;
  EXPECT_EQ(read(outside), "precious\n");
  EXPECT_TRUE(fs::is_regular_file(fs::symlink_status(folder / "good.md")));
}

}  // namespace

// Every number an option takes is finite, and every name an option takes is one the code knows:
// "inf" and "nan" are refused as not finite (not as out of a range), and an unknown name is
// named with every name the option accepts, from the table that parses it.
TEST(HostileOptions, NonFiniteNumbersAndUnknownNamesAreRefusedByName) {
  using namespace mpmstab;
  using test_support::run_mpmstab;
  const std::string table2 = std::string(MPMSTAB_SOURCE_DIR) + "/experiments/table2.json";
  const auto refused = [](const std::string& args, const std::vector<std::string>& named) {
    const auto [status, output] = run_mpmstab(args);
    EXPECT_EQ(status, 2) << args << "\n" << output;
    for (const auto& n : named)
      EXPECT_NE(output.find(n), std::string::npos) << args << ": no '" << n << "' in\n" << output;
    EXPECT_EQ(output.find("internal error"), std::string::npos) << args << "\n" << output;
  };
  // Each command with its required options; the option under test replaces its own entry.
  using Options = std::vector<std::pair<std::string, std::string>>;
  const std::vector<std::pair<std::string, Options>> commands = {
      {"run", {{"method", "gimp"}, {"E", "4"}, {"A", "0.01"}, {"dt", "1e-3"}, {"T", "1e-3"}}},
      {"edge", {{"method", "gimp"}, {"E", "4"}, {"A", "0.01"}, {"T", "1e-3"}}},
      {"spectral", {{"method", "gimp"}, {"E", "4"}, {"cells", "10"}}}};
  const auto with = [](std::string command, Options options, const std::string& option,
                       const std::string& value) {
    bool replaced = false;
    for (auto& [o, v] : options)
      if (o == option) v = value, replaced = true;
    if (!replaced) options.emplace_back(option, value);
    for (const auto& [o, v] : options)
      command += " --" + o + " " + v;
    return command;
  };
  const std::vector<std::string> real_options = {
      "E",          "A",           "flip-fraction",       "shift",   "jitter",
      "body-start", "body-length", "small-mass-fraction", "tip-load"};
  const std::vector<std::string> integer_options = {"cells", "ppc", "xpic-order", "fmpm-order"};
  for (const auto& [command, base] : commands) {
    for (const auto& o : real_options)
      for (const char* v : {"inf", "-inf", "nan"})
        refused(with(command, base, o, v),
                {"--" + o + ": '" + std::string(v) + "' is not a finite number"});
    for (const auto& o : integer_options)
      refused(with(command, base, o, "inf"), {"--" + o + ": 'inf' is not an integer"});
  }
  for (const char* o : {"dt", "T", "safety"})
    refused(with("run", commands[0].second, o, "nan"),
            {std::string("--") + o + ": 'nan' is not a finite number"});
  refused("run --method gimp --E 4 --A 0.01 --T 1e-3 --policy cfl --cfl-factor inf",
          {"--cfl-factor: 'inf' is not a finite number"});
  refused("edge --method gimp --E 4 --A 0.01 --T 1e-3 --tolerance inf",
          {"--tolerance: 'inf' is not a finite number"});
  for (const char* o : {"A", "cT", "error", "budget", "jitter"})
    for (const char* v : {"inf", "nan"})
      refused(with("advise", {{"A", "0.01"}, {"cT", "1"}, {"error", "0.1"}}, o, v),
              {std::string("--") + o + ": '" + v + "' is not a finite number"});
  // advise: values out of range name their option and bound; --no-verify runs nothing, so a
  // budget beside it is refused.
  const std::string advise_base = "advise --A 0.01 --cT 1 --error 0.1 ";
  refused(advise_base + "--budget 0", {"--budget", "> 0"});
  refused(advise_base + "--jitter -0.1", {"--jitter", ">= 0"});
  refused(advise_base + "--jitter 0.9", {"--jitter", "domain"});
  refused("advise --A 0.3 --cT 1e6 --error 1e-9", {"--A", "domain"});
  refused("advise --A 0.01 --cT 1e6 --error 0.1", {"--cT", "domain"});
  refused("advise --A 0.01 --cT 10 --error 1e-9", {"--error", "domain"});
  refused(advise_base + "--no-verify --budget 5", {"--no-verify"});
  refused("check " + table2 + " --rtol inf", {"--rtol: 'inf' is not a finite number"});
  refused("check " + table2 + " --budget nan", {"--budget: 'nan' is not a finite number"});

  // Names: each choice of the run options, with every name its table knows.
  const auto listed = [](std::string option, std::vector<std::string_view> names) {
    std::vector<std::string> out = {"--" + option + ": unknown value 'foo'"};
    for (const auto n : names)
      out.emplace_back(n);
    return out;
  };
  const std::string run = "run --method gimp --E 4 --A 0.01 --dt 1e-3 --T 0.1 --";
  refused("run --method foo --E 4 --A 0.01 --dt 1e-3", listed("method", names_of<Method>()));
  const std::vector<std::pair<std::string, std::vector<std::string_view>>> choices = {
      {"bc", names_of<Boundary>()},
      {"position-update", names_of<PositionUpdate>()},
      {"scene", names_of<SceneKind>()},
      {"walls", names_of<Walls>()},
      {"transfer", names_of<Transfer>()},
      {"update", names_of<UpdateOrder>()},
      {"small-mass", names_of<SmallMass>()},
      {"body-force-time", names_of<BodyForceTime>()},
      {"start", names_of<VelocityStart>()},
      {"dt-stable-sigma", names_of<StressScaling>()},
      {"dt-stable-vnorm", names_of<VelocityNorm>()},
      {"policy", names_of<TimeStepPolicy>()}};
  for (const auto& [option, names] : choices)
    refused(run + option + " foo", listed(option, names));
  refused("edge --method foo --E 4 --A 0.01", listed("method", names_of<Method>()));
  refused("spectral --method foo --E 4", listed("method", names_of<Method>()));
  // advise: an unknown method, transfer or update is named, with the names it could have been.
  const std::string advise = "advise --A 0.01 --cT 1 --error 0.1 --methods ";
  std::vector<std::string> bases = {"unknown method 'foo'"};
  for (const auto n : names_of<Method>())
    bases.emplace_back(n);
  refused(advise + "foo", bases);
  refused(advise + "gimp,foo/flip", bases);
  std::vector<std::string> transfers = {"unknown transfer or update 'foo'"};
  for (const auto n : names_of<Transfer>())
    transfers.emplace_back(n);
  for (const auto n : names_of<UpdateOrder>())
    transfers.emplace_back(n);
  refused(advise + "gimp/foo", transfers);
  refused(advise + "gimp/flip/foo", {"unknown update 'foo'", "usl", "musl"});
  refused(advise + "gimp/foo/usl", {"unknown transfer 'foo'", "apic"});
  refused(advise + "gimp/flip/usl/x", {"too many parts"});
  refused(advise + "gimp/", {"unknown transfer or update ''"});
  refused("advise --A 0.01 --cT 1 --error 0.1 --scene foo", {"--scene", "bar", "steffen"});
  refused("advise --A 0.01 --cT 1 --error 0.1 --bc foo", {"--bc", "dirichlet", "periodic"});
  refused("list --tier foo", {"--tier", "'foo'", "paper", "studies"});
}

// `make` records its build time in a fresh clone, whose results/ has no cache folder yet; where
// the record cannot be written, build-time says so in one plain line, exit status 1 (the
// Makefile goes on), and changes nothing.
TEST(BuildTime, RecordsInAFreshResultsFolderAndSaysPlainlyWhenItCannot) {
  using mpmstab::test_support::run_mpmstab;
  const fs::path dir =
      fs::temp_directory_path() / ("mpmstab_build_time_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir / "results");
  const auto fresh =
      run_mpmstab("build-time --seconds 90 --jobs 2 --out " + (dir / "results").string());
  EXPECT_EQ(fresh.status, 0) << fresh.output;
  EXPECT_TRUE(fs::is_regular_file(dir / "results" / "cache" / "timings.json"));
  // A cache that is a file: the record cannot be written.
  fs::create_directories(dir / "blocked");
  std::ofstream(dir / "blocked" / "cache") << "not a folder\n";
  const auto blocked = run_mpmstab("build-time --seconds 90 --out " + (dir / "blocked").string());
  EXPECT_EQ(blocked.status, 1) << blocked.output;
  EXPECT_NE(blocked.output.find("the build time was not recorded"), std::string::npos)
      << blocked.output;
  EXPECT_EQ(blocked.output.find("internal error"), std::string::npos) << blocked.output;
  std::ifstream in(dir / "blocked" / "cache");
  std::string line;
  std::getline(in, line);
  EXPECT_EQ(line, "not a folder");
  fs::remove_all(dir);
}

// advise --data: a setting whose method, transfer or update the solver does not know is refused
// when the file is read (exit 2, the key named), never run.
TEST(HostileOptions, AdviceDataWithUnknownNamesIsRefused) {
  using mpmstab::test_support::run_mpmstab;
  const fs::path dir =
      fs::temp_directory_path() / ("mpmstab_advice_data_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  std::ifstream in(fs::path(MPMSTAB_SOURCE_DIR) / "results" / "advice.json");
  const auto good = nlohmann::ordered_json::parse(in);
  ASSERT_FALSE(good["study"]["settings"].empty());
  const std::vector<std::tuple<std::string, std::string, std::string>> bad = {
      {"method", "foo", "setting.method: unknown method 'foo'"},
      {"transfer", "foo", "setting.transfer: unknown transfer 'foo'"},
      {"transfer", "fmpm(2", "setting.transfer: unknown transfer 'fmpm(2'"},
      {"transfer", "fmpm(two)", "has no number in parentheses"},
      {"transfer", "fmpm()", "has no number in parentheses"},
      {"update", "foo", "setting.update: unknown update 'foo'"}};
  for (const auto& [key, value, named] : bad) {
    auto doc = good;
    doc["study"]["settings"][0][key] = value;
    const fs::path file = dir / "advice.json";
    std::ofstream(file) << doc.dump(1);
    const auto out = run_mpmstab("advise --A 0.015 --cT 8 --error 0.01 --data " + file.string());
    EXPECT_EQ(out.status, 2) << key << " = " << value << "\n" << out.output;
    EXPECT_NE(out.output.find(named), std::string::npos) << out.output;
    EXPECT_EQ(out.output.find("internal error"), std::string::npos) << out.output;
  }
  fs::remove_all(dir);
}
