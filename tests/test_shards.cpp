// Sharded sweeps: a case always lands in the same shard, the shards cover every case once, and
// merging them gives the reports of a single sweep byte for byte, refusing what is missing or
// disagrees.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

#include "cache.hpp"
#include "merge.hpp"
#include "report.hpp"
#include "spec.hpp"
#include "support.hpp"
#include "sweep.hpp"

namespace mpmstab {
namespace {

namespace fs = std::filesystem;

constexpr const char* kCases = R"(
        {"E": 4, "A": 0.015, "method": "gimp"}, {"E": 4, "A": 0.015, "method": "mpm"},
        {"E": 16, "A": 0.015, "method": "gimp"}, {"E": 16, "A": 0.05, "method": "mpm"},
        {"E": 64, "A": 0.05, "method": "gimp"}, {"E": 64, "A": 0.05, "method": "mpm"},
        {"E": 256, "A": 0.015, "method": "gimp"}, {"E": 1e4, "A": 0.05, "method": "gimp"})";
constexpr const char* kCasesReversed = R"(
        {"E": 1e4, "A": 0.05, "method": "gimp"}, {"E": 256, "A": 0.015, "method": "gimp"},
        {"E": 64, "A": 0.05, "method": "mpm"}, {"E": 64, "A": 0.05, "method": "gimp"},
        {"E": 16, "A": 0.05, "method": "mpm"}, {"E": 16, "A": 0.015, "method": "gimp"},
        {"E": 4, "A": 0.015, "method": "mpm"}, {"E": 4, "A": 0.015, "method": "gimp"})";

class Shards : public ::testing::Test {
 protected:
  fs::path dir = fs::temp_directory_path() / ("mpmstab_shard_test_" + std::to_string(::getpid()));
  void SetUp() override {
    fs::remove_all(dir);
    fs::create_directories(dir);
  }
  void TearDown() override { fs::remove_all(dir); }

  Spec spec(const std::string& cases, const std::string& name = "small") {
    return parse_spec(R"({"name": ")" + name + R"(", "report": "cases",
        "record": ["crossings", "error_over_time"],
        "defaults": {"T": 0.05, "cells": 20, "dt": 1e-4}, "cases": [)" +
                          cases + "]}",
                      dir / (name + ".json"));
  }
  SweepOutcome sweep(const Spec& s, const fs::path& out, std::optional<Shard> shard = {}) {
    SweepOptions o;
    o.jobs = 2;
    o.quiet = true;
    o.cache = out / "cache";
    o.shard = shard;
    return run_sweep(s, o);
  }
  static std::string read(const fs::path& p) {
    std::ifstream in(p);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
  }
  // The keys of the cases a shard ran.
  static std::set<std::string> ran(const Spec& s, const SweepOutcome& o) {
    std::set<std::string> keys;
    for (std::size_t i = 0; i < s.cases.size(); ++i)
      if (!o.records[i].is_null()) keys.insert(case_key(s.cases[i].params));
    return keys;
  }
};

TEST(ShardOf, IsAFunctionOfTheKeyAndSpreadsKeys) {
  std::vector<int> count(4, 0);
  for (int i = 0; i < 4000; ++i) {
    RunParams p;
    p.E = 1 + i;
    const std::string key = case_key(p);
    const int s = shard_of(key, 4);
    ASSERT_GE(s, 0);
    ASSERT_LT(s, 4);
    EXPECT_EQ(s, shard_of(key, 4));
    ++count[s];
  }
  for (int c : count)
    EXPECT_GT(c, 800) << "a shard got far fewer than its quarter of 4000 keys";
  EXPECT_EQ(shard_of(case_key(RunParams{}), 1), 0);
}

TEST_F(Shards, CoverEveryCaseOnceWhateverTheOrderOfTheSpec) {
  const Spec forward = spec(kCases), reversed = spec(kCasesReversed);
  std::set<std::string> all;
  std::size_t total = 0;
  for (int i = 0; i < 3; ++i) {
    const auto a = sweep(forward, dir / ("f" + std::to_string(i)), Shard{i, 3});
    const auto b = sweep(reversed, dir / ("r" + std::to_string(i)), Shard{i, 3});
    EXPECT_FALSE(a.interrupted);
    EXPECT_EQ(ran(forward, a), ran(reversed, b)) << "shard " << i;
    EXPECT_EQ(a.computed + a.other_shards, static_cast<int>(forward.cases.size()));
    total += ran(forward, a).size();
    for (const auto& k : ran(forward, a))
      all.insert(k);
  }
  EXPECT_EQ(total, forward.cases.size());  // no case in two shards
  EXPECT_EQ(all.size(), forward.cases.size());
}

TEST_F(Shards, MergedReportsEqualASingleSweepByteForByte) {
  const Spec s = spec(kCases);
  SweepOutcome single = sweep(s, dir / "local");
  omit_machine_measurements(single);
  write_reports(s, single, dir / "local");

  std::vector<fs::path> parts;
  for (int i = 0; i < 4; ++i) {
    parts.push_back(dir / ("shard-" + std::to_string(i)));
    sweep(s, parts.back(), Shard{i, 4});
  }
  std::reverse(parts.begin(), parts.end());  // the order of the folders does not matter
  SweepOutcome merged = merge_shards(s, parts);
  omit_machine_measurements(merged);
  write_reports(s, merged, dir / "merged");
  for (const char* f : {"small.csv", "small.json", "small.md"}) {
    const std::string a = read(dir / "local" / f), b = read(dir / "merged" / f);
    EXPECT_FALSE(a.empty()) << f;
    EXPECT_EQ(a, b) << f;
  }
}

TEST_F(Shards, MergeNamesMissingCases) {
  const Spec s = spec(kCases);
  sweep(s, dir / "a", Shard{0, 2});  // shard 1 never ran
  try {
    merge_shards(s, {dir / "a"});
    FAIL() << "a merge with a shard missing succeeded";
  } catch (const MergeError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("are in none of the folders"), std::string::npos) << what;
    EXPECT_NE(what.find("cases["), std::string::npos) << what;
  }
}

TEST_F(Shards, MergeRefusesDuplicatesThatDisagreeAndAcceptsThoseThatAgree) {
  const Spec s = spec(kCases);
  sweep(s, dir / "a");
  sweep(s, dir / "b");
  EXPECT_NO_THROW(merge_shards(s, {dir / "a", dir / "b"}));  // timings differ: that is fine

  // One changed digit in one result of folder b.
  const ResultCache cache(dir / "b" / "cache");
  auto record = *cache.load(s.cases[2].params);
  record["result"]["max_error_over_time"] =
      record["result"]["max_error_over_time"].get<double>() * (1 + 1e-15);
  cache.store(s.cases[2].params, record);
  try {
    merge_shards(s, {dir / "a", dir / "b"});
    FAIL() << "disagreeing duplicates were merged";
  } catch (const MergeError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("cases[2]"), std::string::npos) << what;
    EXPECT_NE(what.find("disagree"), std::string::npos) << what;
  }
}

TEST_F(Shards, OmittingMachineMeasurementsKeepsEveryResult) {
  const Spec s = spec(kCases);
  const SweepOutcome kept = sweep(s, dir / "a");
  SweepOutcome omitted = kept;
  omit_machine_measurements(omitted);
  for (std::size_t i = 0; i < kept.records.size(); ++i) {
    EXPECT_EQ(deterministic_part(kept.records[i]), deterministic_part(omitted.records[i]));
    EXPECT_EQ(omitted.records[i]["timing"]["wall_seconds"], 0.0);
    EXPECT_FALSE(kept.records[i]["result"].contains("wall_seconds"));  // kept apart
    EXPECT_EQ(omitted.records[i]["provenance"]["date"], "omitted");
  }
}

using Outcome = test_support::CliOutcome;
using test_support::run_mpmstab;

TEST_F(Shards, CommandLineRefusesBadShardsAndWritesSlurmScripts) {
  const std::string spec_file = (dir / "small.json").string();
  std::ofstream(spec_file) << R"({"name": "small", "report": "cases",
      "defaults": {"T": 0.01, "cells": 10, "dt": 1e-3}, "cases": [)"
                           << kCases << "]}";
  const std::string out = " --out " + (dir / "out").string();
  for (const char* bad : {"4/4", "-1/4", "1/0", "a/4", "3", "1/4x"}) {
    const Outcome o = run_mpmstab("sweep " + spec_file + " --shard " + bad + out);
    EXPECT_EQ(o.status, 2) << bad << ": " << o.output;
    EXPECT_NE(o.output.find("--shard"), std::string::npos) << bad << ": " << o.output;
  }
  EXPECT_EQ(run_mpmstab("sweep " + spec_file + " --timing never" + out).status, 2);
  EXPECT_FALSE(fs::exists(dir / "out" / "small.csv"));

  // A shard writes its manifest and no report.
  const Outcome shard = run_mpmstab("sweep " + spec_file + " --shard 1/2" + out);
  ASSERT_EQ(shard.status, 0) << shard.output;
  EXPECT_TRUE(fs::exists(dir / "out" / "small.shard-1-of-2.json"));
  EXPECT_FALSE(fs::exists(dir / "out" / "small.csv"));
  // Merging only that shard names what is missing, writes nothing.
  const Outcome partial = run_mpmstab("merge " + spec_file + " " + (dir / "out").string() +
                                      " --out " + (dir / "merged").string());
  EXPECT_EQ(partial.status, 2) << partial.output;
  EXPECT_NE(partial.output.find("in none of the folders"), std::string::npos) << partial.output;
  EXPECT_FALSE(fs::exists(dir / "merged" / "small.csv"));
  EXPECT_EQ(run_mpmstab("merge " + spec_file + " " + (dir / "nowhere").string()).status, 2);

  const std::string work = (dir / "work").string();
  EXPECT_EQ(run_mpmstab("slurm " + spec_file + " --work " + work).status, 2);  // --shards missing
  EXPECT_EQ(
      run_mpmstab("slurm " + spec_file + " --shards 4 --time '1h; rm -rf /' --work " + work).status,
      2);
  const Outcome slurm =
      run_mpmstab("slurm " + spec_file + " --shards 4 --partition debug --time 00:10:00 --work " +
                  work + " --timing omit");
  ASSERT_EQ(slurm.status, 0) << slurm.output;
  const std::string sweep = read(dir / "work" / "small.sweep.sbatch");
  const std::string merge = read(dir / "work" / "small.merge.sbatch");
  const std::string submit = read(dir / "work" / "small.submit.sh");
  EXPECT_NE(sweep.find("#SBATCH --array=0-3\n"), std::string::npos) << sweep;
  EXPECT_NE(sweep.find("#SBATCH --partition=debug\n"), std::string::npos) << sweep;
  EXPECT_NE(sweep.find("#SBATCH --time=00:10:00\n"), std::string::npos) << sweep;
  EXPECT_NE(sweep.find("--shard \"${SLURM_ARRAY_TASK_ID}/4\""), std::string::npos) << sweep;
  EXPECT_NE(merge.find("/shard-3'"), std::string::npos) << merge;
  EXPECT_NE(merge.find("--timing omit"), std::string::npos) << merge;
  EXPECT_NE(submit.find("--dependency=afterok:"), std::string::npos) << submit;
}

// Several specs sharded in one queue (reproduce --shard), their records gathered (merge
// --records-only): a reproduce into that folder then computes nothing and writes the reports of
// an unsharded one, byte for byte.
TEST_F(Shards, ReproduceShardsAndMergedRecordsGiveTheUnshardedReports) {
  const std::string a = (dir / "small.json").string(), b = (dir / "other.json").string();
  std::ofstream(a) << R"({"name": "small", "report": "cases",
      "defaults": {"T": 0.01, "cells": 10, "dt": 1e-3}, "cases": [)"
                   << kCases << "]}";
  std::ofstream(b) << R"({"name": "other", "report": "cases",
      "defaults": {"T": 0.01, "cells": 12, "dt": 1e-3}, "cases": [)"
                   << kCasesReversed << "]}";
  const std::string specs = a + " " + b, d = dir.string();
  ASSERT_EQ(run_mpmstab("reproduce " + specs + " --jobs 1 --out " + d + "/local").status, 0);
  for (int i = 0; i < 3; ++i) {
    const Outcome o = run_mpmstab("reproduce " + specs + " --jobs 1 --shard " + std::to_string(i) +
                                  "/3 --out " + d + "/shard-" + std::to_string(i));
    ASSERT_EQ(o.status, 0) << o.output;
    EXPECT_TRUE(fs::exists(dir / ("shard-" + std::to_string(i)) /
                           ("other.shard-" + std::to_string(i) + "-of-3.json")));
    EXPECT_FALSE(fs::exists(dir / ("shard-" + std::to_string(i)) / "small.md"));
  }
  // Without one shard: refused, the missing cases named, nothing written.
  const Outcome partial = run_mpmstab("merge " + specs + " " + d + "/shard-0 " + d +
                                      "/shard-1 --records-only --out " + d + "/partial");
  EXPECT_EQ(partial.status, 2) << partial.output;
  EXPECT_NE(partial.output.find("in none of the folders"), std::string::npos) << partial.output;
  EXPECT_FALSE(fs::exists(dir / "partial" / "cache"));
  EXPECT_EQ(run_mpmstab("merge " + specs + " " + d + "/shard-0 --out " + d + "/x").status, 2);
  const Outcome merged = run_mpmstab("merge " + specs + " " + d + "/shard-0 " + d + "/shard-1 " +
                                     d + "/shard-2 --records-only --out " + d + "/merged");
  ASSERT_EQ(merged.status, 0) << merged.output;
  EXPECT_FALSE(fs::exists(dir / "merged" / "small.md"));
  const Outcome rendered = run_mpmstab("reproduce " + specs + " --jobs 1 --out " + d + "/merged");
  ASSERT_EQ(rendered.status, 0) << rendered.output;
  EXPECT_NE(rendered.output.find("(0 computed, 8 from the cache"), std::string::npos)
      << rendered.output;
  for (const char* f : {"small.csv", "small.json", "small.md", "other.csv", "other.md"})
    EXPECT_EQ(read(dir / "local" / f), read(dir / "merged" / f)) << f;

  // The tier's job array and render job, written in the checkout (its experiments/, Makefile).
  auto in_checkout = [](const std::string& args) {
    std::vector<std::string> argv = test_support::words(args);
    argv.insert(argv.begin(), MPMSTAB_BIN);
    return test_support::run_program(MPMSTAB_BIN, std::move(argv), MPMSTAB_SOURCE_DIR);
  };
  const Outcome slurm = in_checkout("slurm --tier studies --shards 4 --throttle 2 --work " + d +
                                    "/work --out " + d + "/tier");
  ASSERT_EQ(slurm.status, 0) << slurm.output;
  const std::string sweep = read(dir / "work" / "studies.sweep.sbatch");
  const std::string render = read(dir / "work" / "studies.render.sbatch");
  EXPECT_NE(sweep.find("#SBATCH --array=0-3%2\n"), std::string::npos) << sweep;
  EXPECT_NE(sweep.find(" reproduce 'experiments/"), std::string::npos) << sweep;
  const std::string follow = read(dir / "work" / "studies.follow.sbatch");
  EXPECT_NE(follow.find("#SBATCH --array=0-3%2\n"), std::string::npos) << follow;
  EXPECT_NE(follow.find("/shard-3' --follow-ups --shard \"${SLURM_ARRAY_TASK_ID}/4\""),
            std::string::npos)
      << follow;
  EXPECT_NE(render.find("/follow-3' --records-only --with-follow-ups --out"), std::string::npos)
      << render;
  EXPECT_NE(render.find("exec make --no-print-directory tier 'TIER=studies'"), std::string::npos)
      << render;
  // Each job after the one before it: cases, follow-up runs, render.
  const std::string submit = read(dir / "work" / "studies.submit.sh");
  EXPECT_NE(submit.find("follow=$(sbatch --parsable --dependency=afterok:\"$sweep\" "),
            std::string::npos)
      << submit;
  EXPECT_NE(submit.find("render=$(sbatch --parsable --dependency=afterok:\"$follow\" "),
            std::string::npos)
      << submit;
  EXPECT_EQ(in_checkout("slurm --tier everything --shards 4 --work " + d + "/w2").status, 2);
  EXPECT_EQ(in_checkout("slurm " + a + " --tier studies --shards 4 --work " + d + "/w2").status, 2);
  // Outside a checkout the render job could not run make: refused.
  EXPECT_EQ(run_mpmstab("slurm --tier studies --shards 4 --work " + d + "/w2").status, 2);
}

// The follow-up runs in an array of their own (reproduce --follow-ups --shard I/N): chosen from
// the cases' shards, computed in shards, gathered (merge --with-follow-ups); make reproduce then
// computes nothing more and writes the unsharded reports, byte for byte.
TEST_F(Shards, FollowUpShardsGiveTheUnshardedReportsAndLeaveNothingToCompute) {
  const std::string a = (dir / "tiny_edge.json").string(), d = dir.string();
  std::ofstream(a) << R"({"name": "tiny_edge", "report": "edge", "record": ["error_over_time"],
      "defaults": {"T": 0.25, "cells": 8, "ppc": 2, "bc": "dirichlet"},
      "cases": [{"method": "gimp", "A": 0.015, "E": 4}, {"method": "mpm", "A": 0.05, "E": 16}]})";
  ASSERT_EQ(run_mpmstab("reproduce " + a + " --jobs 1 --out " + d + "/local").status, 0);
  ASSERT_TRUE(fs::exists(dir / "local" / "tiny_edge_follow_up.csv"));
  std::string cases, follow;
  for (int i = 0; i < 3; ++i) {
    const std::string shard = " --shard " + std::to_string(i) + "/3 --jobs 1 --out " + d;
    ASSERT_EQ(run_mpmstab("reproduce " + a + shard + "/shard-" + std::to_string(i)).status, 0);
    cases += " " + d + "/shard-" + std::to_string(i);
  }
  // A case missing from every folder given: refused, nothing written.
  const Outcome missing = run_mpmstab("reproduce " + a + " " + d +
                                      "/shard-0 --follow-ups --shard 0/3 --out " + d + "/f");
  EXPECT_EQ(missing.status, 2) << missing.output;
  EXPECT_NE(missing.output.find("in none of the folders"), std::string::npos) << missing.output;
  EXPECT_FALSE(fs::exists(dir / "f"));
  EXPECT_EQ(run_mpmstab("reproduce " + a + cases + " --follow-ups --out " + d + "/f").status, 2);
  std::size_t manifests = 0;
  for (int i = 0; i < 3; ++i) {
    const std::string out = d + "/follow-" + std::to_string(i);
    const Outcome o = run_mpmstab("reproduce " + a + cases + " --follow-ups --shard " +
                                  std::to_string(i) + "/3 --jobs 1 --out " + out);
    ASSERT_EQ(o.status, 0) << o.output;
    manifests +=
        fs::exists(fs::path(out) / ("tiny_edge.shard-" + std::to_string(i) + "-of-3.json"));
    follow += " " + out;
  }
  EXPECT_EQ(manifests, 3u);
  // The follow-up runs must all be found once asked for.
  const Outcome without = run_mpmstab("merge " + a + cases +
                                      " --records-only --with-follow-ups --out " + d + "/merged");
  EXPECT_EQ(without.status, 2) << without.output;
  EXPECT_NE(without.output.find("its follow-up runs"), std::string::npos) << without.output;
  EXPECT_FALSE(fs::exists(dir / "merged"));
  const Outcome merged = run_mpmstab("merge " + a + cases + follow +
                                     " --records-only --with-follow-ups --out " + d + "/merged");
  ASSERT_EQ(merged.status, 0) << merged.output;
  auto records = [&] {
    std::size_t n = 0;
    for (const auto& e : fs::directory_iterator(dir / "merged" / "cache"))
      n += e.path().filename().string().size() == 21;  // <16 hex digits>.json
    return n;
  };
  const std::size_t before = records();
  ASSERT_EQ(run_mpmstab("reproduce " + a + " --jobs 1 --out " + d + "/merged").status, 0);
  EXPECT_EQ(records(), before) << "the render computed runs the arrays should have";
  for (const char* f : {"tiny_edge.csv", "tiny_edge.json", "tiny_edge.md",
                        "tiny_edge_follow_up.csv", "tiny_edge_claims.csv"})
    EXPECT_EQ(read(dir / "local" / f), read(dir / "merged" / f)) << f;
}

}  // namespace
}  // namespace mpmstab
