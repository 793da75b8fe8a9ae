// Generated blocks of the documents (experiments/studies/publish/documents.hpp): written from the
// results, and `mpmstab documents --check` (make check) fails where a block was edited by hand
// or its result changed; a malformed marker is refused and leaves the file untouched.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>

#include "base/instruction_set.hpp"
#include "cache.hpp"
#include "cached_run.hpp"
#include "files.hpp"
#include "parallel.hpp"
#include "performance.hpp"
#include "publish/documents.hpp"
#include "publish/verdicts.hpp"
#include "report.hpp"
#include "report_util.hpp"
#include "spec.hpp"
#include "support.hpp"

namespace mpmstab {
namespace {

std::string slurp(const std::filesystem::path& p) {
  std::ifstream in(p);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

const std::string kStart =
    "<!-- generated: readme-tier-times (mpmstab documents writes this block from results/; do "
    "not edit) -->\n";
const std::string kEnd = "<!-- end generated: readme-tier-times -->";

TEST(Documents, FillReplacesOnlyTheBlockAndRefusesUnknownOrUnclosedMarkers) {
  const std::map<std::string, std::string> blocks = {{"readme-tier-times", "rendered\n"}};
  std::vector<std::string> found;
  const std::string text = "before\n" + kStart + "old\n" + kEnd + "\nafter\n";
  EXPECT_EQ(fill_document(text, blocks, "README.md", &found),
            "before\n" + kStart + "rendered\n" + kEnd + "\nafter\n");
  EXPECT_EQ(found, std::vector<std::string>{"readme-tier-times"});
  EXPECT_THROW(fill_document("<!-- generated: nope (mpmstab documents writes this block from "
                             "results/; do not edit) -->\nx\n<!-- end generated: nope -->",
                             blocks, "README.md"),
               InputError);
  EXPECT_THROW(fill_document("a\n" + kStart + "no end\n", blocks, "README.md"), InputError);
  EXPECT_THROW(fill_document("a\n" + kEnd + "\n", blocks, "README.md"), InputError);
}

TEST(Documents, CheckFailsWhenABlockIsEditedByHandOrItsResultChanges) {
  const auto dir = std::filesystem::temp_directory_path() / "mpmstab_documents_test";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir / "results");
  auto timings = [&](double wall) {
    std::ofstream(dir / "results" / "timings.json")
        << "{\"(make reproduce)\": {\"cases\": 10, \"computed\": 10, \"particle_steps\": 1e6, "
           "\"compute_seconds\": 2, \"threads\": 2, \"cpu\": \"x\", \"commit\": \"abcdef012\", "
           "\"wall_seconds\": "
        << wall << "}}";
  };
  timings(15);
  const auto doc = dir / "README.md";
  std::ofstream(doc) << "# t\n" << kStart << kEnd << "\n";
  const std::string results = (dir / "results").string();
  auto run = [&](const std::string& words) {
    return test_support::run_mpmstab("documents " + words + " --results " + results);
  };
  EXPECT_EQ(run("--check " + doc.string()).status, 1);  // empty block: not what results give
  ASSERT_EQ(run(doc.string()).status, 0);
  EXPECT_NE(slurp(doc).find("15 s"), std::string::npos) << slurp(doc);
  EXPECT_EQ(run("--check " + doc.string()).status, 0);
  // Edited by hand.
  std::string text = slurp(doc);
  text.replace(text.find("15 s"), 5, "0.9 s");
  std::ofstream(doc) << text;
  const auto edited = run("--check " + doc.string());
  EXPECT_EQ(edited.status, 1);
  EXPECT_NE(edited.output.find("README.md"), std::string::npos) << edited.output;
  ASSERT_EQ(run(doc.string()).status, 0);
  // The result changed and the document was not rewritten.
  timings(25);
  EXPECT_EQ(run("--check " + doc.string()).status, 1);
  // A malformed document is refused and left as it was.
  std::ofstream(doc) << "# t\n" << kStart << "no end\n";
  const std::string before = slurp(doc);
  EXPECT_EQ(run(doc.string()).status, 2);
  EXPECT_EQ(slurp(doc), before);
  std::filesystem::remove_all(dir);
}

// make timings publishes this machine's timings and keeps the last tier run of every other
// machine the published file held, under "(<label> on <cpu>)"; README's table shows each.
// The tables of outcomes, failure reasons and accuracy classes that docs/studies.md shows are
// the code's own lists: every value of each enum has a definition and a row, in enum order, and
// the committed document holds each generated table as the code writes it now.
TEST(Documents, TheVerdictTablesAreTheCodesOwnLists) {
  const auto outcomes = all_outcomes();
  ASSERT_EQ(outcomes.size(), std::size_t(Outcome::too_short) + 1);
  EXPECT_EQ(all_failure_reasons().back(), FailureReason::dt_collapse);
  EXPECT_EQ(all_accuracy_classes().size(), std::size_t(Accuracy::meaningless) + 1);
  for (const Outcome o : outcomes)
    EXPECT_NE(outcomes_table().find("| `" + std::string(to_string(o)) + "` | " + definition(o)),
              std::string::npos)
        << to_string(o);
  EXPECT_NE(definition(Outcome::stable).find(std::to_string(kMinStepsToJudge)), std::string::npos);
  std::ifstream in(std::filesystem::path(MPMSTAB_SOURCE_DIR) / "docs" / "studies.md");
  std::stringstream doc;
  doc << in.rdbuf();
  for (const std::string& t : {outcomes_table(), failure_reasons_table(), accuracy_classes_table()})
    EXPECT_NE(doc.str().find(t), std::string::npos) << t;
}

// A report calls a run stable only over at least kMinWavePasses wave passes, and always with its
// accuracy class and error over time per A beside it; a shorter run is said to be too short.
TEST(Documents, AVerdictCallsARunStableOnlyOverAWavePassAndWithItsAccuracy) {
  nlohmann::ordered_json r = {{"outcome", "stable"},
                              {"A", 0.01},
                              {"max_error_over_time", 0.0043},
                              {"cT", 2 * kMinWavePasses},
                              {"steps", 500}};
  EXPECT_FALSE(under_a_wave_pass(r));
  EXPECT_EQ(verdict_word(r), "stable");
  EXPECT_EQ(verdict(r), "stable, inaccurate (0.43 A)");
  r["cT"] = 0.5 * kMinWavePasses;
  EXPECT_TRUE(under_a_wave_pass(r));
  EXPECT_EQ(verdict_word(r).rfind("survived, c T = ", 0), 0u) << verdict_word(r);
  EXPECT_NE(verdict_word(r).find("too short to count as stable"), std::string::npos);
  EXPECT_EQ(verdict(r), verdict_word(r) + ", inaccurate (0.43 A)");
  r["cT"] = 2 * kMinWavePasses;
  r.erase("max_error_over_time");
  EXPECT_EQ(verdict(r), "stable (error over time not recorded)");
  // A value beside a verdict judged against a threshold prints on the side it was judged.
  EXPECT_EQ(beside_thresholds(0.0997, {kAccurateFraction, 1.0}), "0.0997");
  EXPECT_EQ(beside_thresholds(0.43, {kAccurateFraction, 1.0}), "0.43");
  EXPECT_EQ(beside_thresholds(3.006, {3.0}), "3.01");
  EXPECT_EQ(verdict_with_error(r, 0.0997), "stable, accurate (0.0997 A)");
  // An edge search's row gives the error of its run at the edge in a column of its own.
  EXPECT_EQ(verdict_with_error(r, 0.05), "stable, accurate (0.05 A)");
  r["outcome"] = "meaningless";
  EXPECT_FALSE(under_a_wave_pass(r));
  EXPECT_EQ(verdict(r), verdict_word(r));  // no class beside a run that is not stable
}

TEST(Documents, PublishedTimingsKeepEachMachinesLastTierRun) {
  const auto dir = std::filesystem::temp_directory_path() / "mpmstab_timings_test";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir / "cache");
  const auto entry = [](const char* cpu, double wall) {
    return nlohmann::ordered_json{
        {"cases", 10},  {"computed", 10}, {"particle_steps", 1e6}, {"compute_seconds", 2},
        {"threads", 2}, {"cpu", cpu},     {"commit", "abcdef012"}, {"wall_seconds", wall}};
  };
  std::ofstream(dir / "timings.json") << nlohmann::ordered_json{
      {"(make reproduce)", entry("Old CPU", 30)},
      {"(make studies)", entry("Old CPU", 480)},
      {"(make studies on Older CPU)",
       entry("Older CPU", 900)}}.dump(1);
  nlohmann::ordered_json fresh = entry("New CPU", 95);
  fresh["kernels"] = "AVX2";
  std::ofstream(dir / "cache" / "timings.json")
      << nlohmann::ordered_json{{"(make reproduce)", fresh}}.dump(1);
  // This machine's fresh build, recorded as `make` records it.
  const auto built =
      test_support::run_mpmstab("build-time --seconds 187.5 --jobs 2 --out " + dir.string());
  ASSERT_EQ(built.status, 0) << built.output;
  write_performance({}, dir / "no_benchmark.json", dir);
  const auto published = nlohmann::ordered_json::parse(slurp(dir / "timings.json"));
  EXPECT_EQ(published["(make reproduce)"]["cpu"], "New CPU");
  EXPECT_EQ(published["(make reproduce on Old CPU)"]["wall_seconds"], 30);
  EXPECT_EQ(published["(make studies)"]["cpu"], "Old CPU");  // no new studies run: kept as it was
  EXPECT_EQ(published["(make studies on Older CPU)"]["wall_seconds"], 900);
  EXPECT_EQ(published["(make)"]["wall_seconds"], 187.5);
  EXPECT_EQ(published["(make)"]["kernels"], kernel_instruction_set());
  const std::string table = document_blocks(dir).at("readme-tier-times");
  for (const char* shown :
       {"| New CPU, AVX2 kernels |", "| Old CPU |", "| Older CPU |", "95 s", "30 s", "480 s",
        "900 s", "| `make` | 188 s | a fresh build of the tool | – | 2 |"})
    EXPECT_NE(table.find(shown), std::string::npos) << shown << " in\n" << table;
  // performance.md names the kernels' instruction set where the run recorded it.
  const std::string performance = slurp(dir / "performance.md");
  EXPECT_NE(performance.find("on 2 threads (New CPU, AVX2 kernels)"), std::string::npos);
  EXPECT_NE(performance.find("on 2 threads (Older CPU)"), std::string::npos);
  EXPECT_NE(performance.find("**`make`.** The last fresh build of the tool"), std::string::npos);
  EXPECT_NE(performance.find("took **188 s** wall with 2 compile jobs"), std::string::npos);
  // Published again from the same measurements: the same file.
  const std::string before = slurp(dir / "timings.json");
  write_performance({}, dir / "no_benchmark.json", dir);
  EXPECT_EQ(slurp(dir / "timings.json"), before);
  std::filesystem::remove_all(dir);
}

// The runs a report computes itself (through cached_run, on the threads for_each_in_parallel
// starts) are counted in the account open on the thread that renders it, and a run found in the
// cache is not; performance.md adds them to their experiment's row.
TEST(Documents, TheRunsAReportMakesItselfAreCountedInItsExperiment) {
  const auto dir = std::filesystem::temp_directory_path() / "mpmstab_report_runs_test";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir / "cache");
  const ResultCache cache(dir / "cache");
  std::vector<RunParams> runs(3);
  for (std::size_t i = 0; i < runs.size(); ++i) {
    runs[i].T = 0.01 * static_cast<double>(i + 1);
    runs[i].dt = 1e-3;
  }
  RunAccount account;
  open_run_account(&account);
  const auto make_all = [&] {
    for_each_in_parallel(runs.size(), 2, [&](std::size_t i) { cached_run(cache, runs[i]); });
  };
  make_all();
  EXPECT_EQ(account.runs.load(), 3);
  // T = 0.01, 0.02, 0.03 at dt = 1e-3: 10 + 20 + 30 steps of 200 particles.
  EXPECT_DOUBLE_EQ(account.particle_steps.load(), 60.0 * 200.0);
  EXPECT_GT(account.seconds.load(), 0.0);
  make_all();  // every run from the cache now: nothing computed, nothing counted
  EXPECT_EQ(account.runs.load(), 3);
  open_run_account(nullptr);
  make_all();
  EXPECT_EQ(account.runs.load(), 3);
  // A report's account inside a tier's: a run counts in both; the tier's is open again after.
  {
    RunAccount tier;
    const RunAccountScope tier_scope(tier);
    RunAccount report;
    {
      const RunAccountScope report_scope(report);
      EXPECT_EQ(open_run_account(), &report);
      RunParams longer = runs[0];
      longer.T = 0.04;
      cached_run(cache, longer);
    }
    EXPECT_EQ(open_run_account(), &tier);
    EXPECT_EQ(report.runs.load(), 1);
    EXPECT_EQ(tier.runs.load(), 1);
    EXPECT_DOUBLE_EQ(tier.particle_steps.load(), 40.0 * 200.0);
  }
  EXPECT_EQ(open_run_account(), nullptr);

  // A row whose report made runs: counted in their column, and in the work and CPU time.
  std::ofstream(dir / "timings.json")
      << nlohmann::ordered_json{{"edge",
                                 {{"cases", 2},
                                  {"particle_steps", 1e6},
                                  {"compute_seconds", 1.0},
                                  {"sweep_wall_seconds", 1.0},
                                  {"cpu", "Some CPU"},
                                  {"per_case", nlohmann::ordered_json::array()},
                                  {"report_runs",
                                   {{"runs", 7}, {"particle_steps", 2e6}, {"cpu_seconds", 3.0}}}}}}
             .dump(1);
  write_performance(
      {load_spec(std::filesystem::path(MPMSTAB_SOURCE_DIR) / "experiments" / "edge.json")},
      dir / "no_benchmark.json", dir);
  const std::string md = slurp(dir / "performance.md");
  EXPECT_NE(md.find("| [edge](edge.md) | 2 | – | 7 | 3.0e6 | 4.00 s | 1.00 s |"), std::string::npos)
      << md;
  std::filesystem::remove_all(dir);
}

// The report runs the progress line expects, by experiment: the machine's own count (its cache's
// timings.json) before the published one, an experiment either counts, none for the others, and
// nothing from a file that cannot be read.
TEST(Documents, TheReportRunsExpectedAreTheMachinesOwnCountElseThePublishedOne) {
  const auto dir = std::filesystem::temp_directory_path() / "mpmstab_report_work_test";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir / "cache");
  const auto counted = [](double particle_steps) {
    return nlohmann::ordered_json{
        {"report_runs", {{"runs", 3}, {"particle_steps", particle_steps}, {"cpu_seconds", 1}}}};
  };
  std::ofstream(dir / "cache" / "timings.json")
      << nlohmann::ordered_json{{"sample", counted(5e6)}, {"edge", {{"cases", 2}}}}.dump(1);
  std::ofstream(dir / "timings.json")
      << nlohmann::ordered_json{{"sample", counted(9e6)}, {"advice", counted(2e6)}}.dump(1);
  EXPECT_EQ(published_report_work(dir),
            (std::map<std::string, double>{{"advice", 2e6}, {"sample", 5e6}}));
  std::ofstream(dir / "cache" / "timings.json") << "{ not json";
  EXPECT_EQ(published_report_work(dir),
            (std::map<std::string, double>{{"advice", 2e6}, {"sample", 9e6}}));
  std::filesystem::remove_all(dir);
}

// performance.md says on which CPU, kernels and commit the step kernel was benchmarked, and
// projects a tier's work at the kernel's speed only for a tier run on that same machine.
TEST(Documents, BenchmarkNamesItsMachineAndProjectsOnlyItsOwnTiers) {
  const auto dir = std::filesystem::temp_directory_path() / "mpmstab_bench_machine_test";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir / "cache");
  const auto tier = [](const char* cpu) {
    return nlohmann::ordered_json{
        {"cases", 10},  {"computed", 10}, {"particle_steps", 1e9}, {"compute_seconds", 8},
        {"threads", 2}, {"cpu", cpu},     {"kernels", "AVX2"},     {"wall_seconds", 5}};
  };
  // The studies tier counted the runs its reports made; the other was recorded before they were.
  nlohmann::ordered_json studies_tier = tier("Other CPU");
  studies_tier["report_runs"] = {{"runs", 12}, {"particle_steps", 1e8}, {"cpu_seconds", 1}};
  std::ofstream(dir / "timings.json") << nlohmann::ordered_json{
      {"(make reproduce)", tier("Bench CPU")},
      {"(make studies)", studies_tier}}.dump(1);
  const auto figure = [](const char* name, const char* aggregate, double ns) {
    return nlohmann::ordered_json{{"name", std::string(name) + "_" + aggregate},
                                  {"run_name", name},
                                  {"aggregate_name", aggregate},
                                  {"label", "gimp"},
                                  {"ns_per_particle_step", ns}};
  };
  nlohmann::ordered_json bench = {
      {"context",
       {{"date", "2026-01-02"},
        {"host_name", "box"},
        {"num_cpus", 2},
        {"mhz_per_cpu", 3000},
        {"cpu", "Bench CPU"},
        {"kernels", "AVX2"},
        {"commit", "0123456789abcdef"},
        {"dirty", "false"}}},
      {"benchmarks",
       {figure("BM_StepInstrumented", "median", 4.0), figure("BM_StepInstrumented", "cv", 0.01)}}};
  std::ofstream(dir / "bench.json") << bench.dump(1);
  write_performance({}, dir / "bench.json", dir);
  const std::string md = slurp(dir / "performance.md");
  EXPECT_NE(md.find("Measured 2026-01-02 on Bench CPU, AVX2 kernels (box, 2 CPUs at 3000 MHz), "
                    "commit 0123456,"),
            std::string::npos)
      << md;
  EXPECT_EQ(md.find("with uncommitted changes"), std::string::npos);
  bench["context"]["dirty"] = "true";  // measured on a tree with changes not committed: said so
  std::ofstream(dir / "bench.json") << bench.dump(1);
  write_performance({}, dir / "bench.json", dir);
  EXPECT_NE(slurp(dir / "performance.md").find("commit 0123456 with uncommitted changes,"),
            std::string::npos);
  // 1e9 particle-steps at 4 ns on 2 threads: 2 s, said of the run on the benchmark's machine only.
  const auto reproduce = md.find("**`make reproduce`.**");
  const auto studies = md.find("**`make studies`.**");
  ASSERT_NE(reproduce, std::string::npos);
  ASSERT_NE(studies, std::string::npos);
  const auto projection = md.find("as benchmarked above on the same machine");
  EXPECT_NE(projection, std::string::npos);
  EXPECT_EQ(md.find("as benchmarked above", projection + 1), std::string::npos);
  EXPECT_LT(reproduce, projection);
  EXPECT_LT(projection, studies);
  const auto left_out = md.find("the runs its reports made themselves not");
  const auto included = md.find(
      "follow-up runs and the 12 runs its reports made themselves "
      "included");
  EXPECT_LT(reproduce, left_out);
  EXPECT_LT(left_out, studies);
  EXPECT_LT(studies, included);
  EXPECT_NE(included, std::string::npos);
  std::filesystem::remove_all(dir);
}

// A tier run that found most of its cases in the cache does not measure the tier: it does not
// replace the published run of the same CPU that computed more of them; one that computed as many
// does, and one that computed none is not published.
TEST(Documents, PublishedTimingsKeepTheTierRunThatComputedMore) {
  const auto dir = std::filesystem::temp_directory_path() / "mpmstab_timings_computed_test";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir / "cache");
  const auto entry = [](double computed, double wall) {
    return nlohmann::ordered_json{
        {"cases", 10},  {"computed", computed}, {"particle_steps", 1e6}, {"compute_seconds", 2},
        {"threads", 2}, {"cpu", "This CPU"},    {"commit", "abcdef012"}, {"wall_seconds", wall}};
  };
  std::ofstream(dir / "timings.json") << nlohmann::ordered_json{
      {"(make reproduce)", entry(10, 30)},
      {"(make studies on This CPU)",
       entry(10, 480)}}.dump(1);
  std::ofstream(dir / "cache" / "timings.json") << nlohmann::ordered_json{
      {"(make reproduce)", entry(1, 3)},
      {"(make studies)", entry(10, 470)},
      {"(reproduce)", entry(0, 2)}}.dump(1);
  write_performance({}, dir / "no_benchmark.json", dir);
  const auto published = nlohmann::ordered_json::parse(slurp(dir / "timings.json"));
  EXPECT_EQ(published["(make reproduce)"]["wall_seconds"], 30);  // the cached run measured less
  EXPECT_EQ(published["(make studies)"]["wall_seconds"], 470);   // as many computed: the newer
  EXPECT_FALSE(published.contains("(make studies on This CPU)"));
  EXPECT_FALSE(published.contains("(reproduce)"));  // every case from the cache: measured nothing
  std::filesystem::remove_all(dir);
}

// performance.md's groups of cases by experiment and time step: each group's CPU time is the sum
// of its cases' own, the groups come costliest first, and an experiment whose timings were
// measured on other cases than its spec now holds is left out and named.
TEST(Documents, PerformanceGroupsTheCpuTimeByExperimentAndTimeStep) {
  const auto dir = std::filesystem::temp_directory_path() / "mpmstab_groups_test";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  const std::filesystem::path experiments =
      std::filesystem::path(MPMSTAB_SOURCE_DIR) / "experiments";
  const std::vector<Spec> specs = {load_spec(experiments / "table1.json"),
                                   load_spec(experiments / "table2.json")};
  // table1: 1 s per case at dt = 1e-7, 0.01 s at every other step; table2 measured on other cases.
  nlohmann::ordered_json timings;
  double expected_small = 0;
  std::size_t at_1e7 = 0;
  for (const auto& c : specs[0].cases) {
    const bool big = c.params.dt == 1e-7;
    at_1e7 += big;
    if (!big && c.params.dt == 1e-6) expected_small += 0.01;
    timings["table1"]["per_case"].push_back(
        {{"key", case_key(c.params)}, {"wall_seconds", big ? 1.0 : 0.01}});
  }
  for (const auto& c : specs[1].cases)
    timings["table2"]["per_case"].push_back(
        {{"key", case_key(c.params) + "x"}, {"wall_seconds", 5.0}});
  for (const char* name : {"table1", "table2"}) {
    timings[name]["cases"] = timings[name]["per_case"].size();
    for (const char* k : {"sweep_wall_seconds", "compute_seconds", "particle_steps"})
      timings[name][k] = 1.0;
  }
  std::ofstream(dir / "timings.json") << timings.dump(1);
  write_performance(specs, dir / "no_benchmark.json", dir);
  const std::string md = slurp(dir / "performance.md");
  ASSERT_EQ(at_1e7, 2u);
  const auto first = md.find("| table1 | dt = 1e-7 | 2 | " + seconds(2.0) + " |");
  const auto second = md.find("| table1 | dt = 1e-6 | 16 | " + seconds(expected_small) + " |");
  EXPECT_NE(first, std::string::npos) << md;
  EXPECT_NE(second, std::string::npos) << md;
  EXPECT_LT(first, second);
  EXPECT_NE(md.find("left out, their timings measured on other cases than their spec's: table2"),
            std::string::npos);
  EXPECT_EQ(md.find("| table2 |"), std::string::npos);  // in no group
  std::filesystem::remove_all(dir);
}

// performance.md counts an experiment's follow-up runs in it: a Table 1 cell near its edge asks
// for an ensemble of layouts once it is done, and those runs' particle-steps and CPU time, read
// back from the cache, join the case's; a follow-up the cache no longer holds is said so and
// adds nothing.
TEST(Documents, PerformanceCountsTheFollowUpRunsInTheExperimentThatAskedForThem) {
  namespace fs = std::filesystem;
  const fs::path dir = fs::temp_directory_path() / "mpmstab_follow_up_work_test";
  fs::remove_all(dir);
  fs::create_directories(dir / "out");
  // A meaningless run near its edge (MPM, E = 4, A = 0.05, dt = 1e-3): table1 reruns it as an
  // ensemble of layouts.
  std::ofstream(dir / "table1.json")
      << R"({"name": "table1", "title": "T", "description": "d", "report": "table1", )"
      << R"("tier": "paper", "reference": ")"
      << (fs::path(MPMSTAB_SOURCE_DIR) / "reference" / "paper" / "table1.csv").generic_string()
      << R"(", "record": ["error_over_time", "dt_stable"], "defaults": {"T": 1, "cells": 100, )"
      << R"("ppc": 2, "bc": "dirichlet"}, "cases": [{"A": 0.05, "E": 4.0, "method": "mpm", )"
      << R"("dt": 0.001}]})";
  const auto swept = test_support::run_mpmstab("sweep " + (dir / "table1.json").string() +
                                               " --out " + (dir / "out").string());
  ASSERT_EQ(swept.status, 0) << swept.output;
  const Spec spec = load_spec(dir / "table1.json");
  // Every record in the cache: the case's and its follow-ups', by file.
  std::map<fs::path, std::pair<double, double>> records;  // file -> particle-steps, seconds
  double steps = 0, secs = 0;
  for (const auto& f : fs::directory_iterator(dir / "out" / "cache")) {
    if (f.path().extension() != ".json" || f.path().filename() == "timings.json") continue;
    const auto rec = nlohmann::ordered_json::parse(slurp(f.path()));
    const double w =
        rec["result"]["steps"].get<double>() * rec["result"]["particles"].get<double>();
    records[f.path()] = {w, rec["timing"]["wall_seconds"].get<double>()};
    steps += w;
    secs += rec["timing"]["wall_seconds"].get<double>();
  }
  ASSERT_EQ(records.size(), 9u);  // the case and its 8 layouts
  // The follow-up runs are published beside the report, one row each, and the report links them.
  std::istringstream follow_csv(slurp(dir / "out" / "table1_follow_up.csv"));
  int data_rows = 0;
  for (std::string line; std::getline(follow_csv, line);)
    data_rows += !line.empty() && line[0] != '#';
  EXPECT_EQ(data_rows, 1 + 8);  // the column names and the 8 layouts
  EXPECT_NE(slurp(dir / "out" / "table1.md").find("[table1_follow_up.csv](table1_follow_up.csv)"),
            std::string::npos);
  const auto row = [&] {
    write_performance({spec}, dir / "no_benchmark.json", dir / "out");
    const std::string md = slurp(dir / "out" / "performance.md");
    const auto at = md.find("| [table1](table1.md) |");
    return at == std::string::npos ? md : md.substr(at, md.find('\n', at) - at);
  };
  EXPECT_EQ(
      row().rfind(
          "| [table1](table1.md) | 1 | 8 | – | " + sci(steps) + " | " + seconds(secs) + " | ", 0),
      0u)
      << row();
  // Published in timings.json beside the case's timing: the row reads the same without the cache
  // (a machine whose cache does not hold that machine's records).
  fs::rename(dir / "out" / "cache", dir / "cache_elsewhere");
  EXPECT_EQ(
      row().rfind(
          "| [table1](table1.md) | 1 | 8 | – | " + sci(steps) + " | " + seconds(secs) + " | ", 0),
      0u)
      << row();
  fs::rename(dir / "cache_elsewhere", dir / "out" / "cache");
  FollowUpWork work = follow_up_work(spec, dir / "out");
  EXPECT_EQ(work.runs, 8u);
  EXPECT_EQ(work.cached, 8u);
  EXPECT_EQ(work.ns_per_particle_step.size(), 8u);
  // One layout's record gone from the cache: still asked for, said so, its work left out.
  const auto case_file = dir / "out" / "cache" / (case_key(spec.cases[0].params) + ".json");
  ASSERT_TRUE(records.count(case_file));
  auto member = records.begin();
  if (member->first == case_file) ++member;
  fs::remove(member->first);
  work = follow_up_work(spec, dir / "out");
  EXPECT_EQ(work.runs, 8u);
  EXPECT_EQ(work.cached, 7u);
  EXPECT_DOUBLE_EQ(work.particle_steps, steps - records[case_file].first - member->second.first);
  EXPECT_NE(
      row().find("| 1 | 8 (1 not in the cache) | – | " + sci(steps - member->second.first) + " | "),
      std::string::npos)
      << row();
  fs::remove_all(dir);
}

}  // namespace
}  // namespace mpmstab
