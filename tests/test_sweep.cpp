// Sweeps: results independent of --jobs, the cache reruns nothing unchanged, and bad specs are
// refused before anything is written.
#include <gtest/gtest.h>

#include <array>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <random>
#include <sstream>

#include "analysis/spectral.hpp"
#include "cache.hpp"
#include "cached_run.hpp"
#include "progress.hpp"
#include "report.hpp"
#include "result_json.hpp"
#include "run/run.hpp"
#include "scenes/validate.hpp"
#include "spec.hpp"
#include "support.hpp"
#include "sweep.hpp"

namespace mpmstab {
namespace {

namespace fs = std::filesystem;

class Sweeps : public ::testing::Test {
 protected:
  fs::path dir = fs::temp_directory_path() / ("mpmstab_sweep_test_" + std::to_string(::getpid()));
  void SetUp() override {
    fs::remove_all(dir);
    fs::create_directories(dir);
    std::ofstream(dir / "small.json") << R"({
      "name": "small", "title": "Small", "report": "table2", "reference": "paper2.csv",
      "record": ["crossings", "error_over_time"],
      "defaults": {"T": 0.05, "cells": 20, "dt": 1e-4},
      "cases": [
        {"E": 4, "A": 0.015, "method": "gimp"}, {"E": 4, "A": 0.015, "method": "mpm"},
        {"E": 64, "A": 0.05, "method": "gimp"}, {"E": 64, "A": 0.05, "method": "mpm"},
        {"E": 1e4, "A": 0.05, "method": "gimp", "dt": 1e-3}
      ]})";
    std::ofstream(dir / "paper2.csv") << "E,crossings_A0.015,crossings_A0.05,dt_sound,note\n4,300,"
                                         "1000,0.5,\n64,1300,4000,0.125,\n"
                                         "10000,15000,55000,0.01,\n";
  }
  void TearDown() override { fs::remove_all(dir); }

  std::string read(const fs::path& p) {
    std::ifstream in(p);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
  }
  // CSV rows without the '#' lines (every column is a result: timings are kept apart).
  std::vector<std::string> deterministic_rows(const fs::path& csv) {
    std::vector<std::string> rows;
    std::istringstream in(read(csv));
    for (std::string line; std::getline(in, line);) {
      if (line.empty() || line[0] == '#') continue;
      rows.push_back(line);
    }
    return rows;
  }
  // Every file of a results folder but its cache, by name.
  std::map<std::string, std::string> files(const fs::path& out) {
    std::map<std::string, std::string> content;
    for (const auto& e : fs::directory_iterator(out)) {
      if (e.is_regular_file()) content[e.path().filename().string()] = read(e.path());
    }
    return content;
  }
  SweepOutcome sweep(const Spec& spec, int jobs, const fs::path& out, bool force = false) {
    SweepOptions o;
    o.jobs = jobs;
    o.force = force;
    o.cache = out / "cache";
    const SweepOutcome r = run_sweep(spec, o);
    write_reports(spec, r, out);
    return r;
  }
};

TEST_F(Sweeps, ResultsDoNotDependOnTheNumberOfJobs) {
  const Spec spec = load_spec(dir / "small.json");
  sweep(spec, 1, dir / "one");
  sweep(spec, 2, dir / "two");
  sweep(spec, 5, dir / "five");
  const auto one = deterministic_rows(dir / "one/small.csv");
  ASSERT_EQ(one.size(), 6u);  // header + 5 cases
  EXPECT_EQ(one, deterministic_rows(dir / "two/small.csv"));
  EXPECT_EQ(one, deterministic_rows(dir / "five/small.csv"));
}

// A file changes only when a result changes: recomputing every case (another number of jobs,
// another wall time) rewrites no report; the machine's timings go to the ignored cache folder.
TEST_F(Sweeps, RecomputingChangesOnlyTheMachinesTimings) {
  const Spec spec = load_spec(dir / "small.json");
  sweep(spec, 1, dir / "out");
  const auto before = files(dir / "out");
  const std::string timings_before = read(dir / "out/cache/timings.json");
  sweep(spec, 2, dir / "out", true);
  const auto after = files(dir / "out");
  EXPECT_EQ(before, after);
  EXPECT_FALSE(after.count("timings.json"));
  const std::string timings_after = read(dir / "out/cache/timings.json");
  EXPECT_NE(timings_before, timings_after);
  const auto timings = nlohmann::ordered_json::parse(timings_after);
  EXPECT_EQ(timings["small"]["per_case"].size(), 5u);
  EXPECT_EQ(timings["small"]["threads"], "2");  // of the sweep that computed the cases
  // The build that computed them: its commit (or "unknown" outside a git checkout) and machine.
  EXPECT_FALSE(timings["small"]["commit"].get<std::string>().empty());
  EXPECT_TRUE(timings["small"].contains("dirty"));
  EXPECT_FALSE(timings["small"]["cpu"].get<std::string>().empty());
  for (const auto& [name, text] : after)
    EXPECT_EQ(text.find("wall_seconds"), std::string::npos) << name;
}

TEST_F(Sweeps, TheCacheRerunsNothingUnchangedAndOnlyWhatChanged) {
  const Spec spec = load_spec(dir / "small.json");
  const SweepOutcome first = sweep(spec, 2, dir / "out");
  EXPECT_EQ(first.computed, 5);
  const std::string md = read(dir / "out/small.md");
  const std::string csv = read(dir / "out/small.csv");

  const SweepOutcome again = sweep(spec, 2, dir / "out");
  EXPECT_EQ(again.computed, 0);
  EXPECT_EQ(again.cached, 5);
  // Reports are byte for byte the same: nothing of the rerun leaks into them.
  EXPECT_EQ(read(dir / "out/small.md"), md);
  EXPECT_EQ(read(dir / "out/small.csv"), csv);

  // One changed case is computed again, and only that one.
  Spec changed = spec;
  changed.cases[1].params.A = 0.02;
  EXPECT_EQ(sweep(changed, 2, dir / "out").computed, 1);

  // --force computes everything.
  EXPECT_EQ(sweep(spec, 2, dir / "out", true).computed, 5);
}

TEST_F(Sweeps, KeysChangeWithEveryParameterAndWithWhatIsRecorded) {
  RunParams p;
  const std::string base = case_key(p);
  std::vector<RunParams> variants(9, p);
  variants[0].E = 4.000000000000001;
  variants[1].dt *= 2;
  variants[2].method = Method::mpm;
  variants[3].bc = Boundary::periodic;
  variants[4].ppc = 3;
  variants[5].position_update = PositionUpdate::particle;
  variants[6].stable.sigma = StressScaling::raw;
  variants[7].observe.history = true;
  variants[8].observe.crossings = false;
  std::set<std::string> keys{base};
  for (const auto& v : variants)
    keys.insert(case_key(v));
  EXPECT_EQ(keys.size(), variants.size() + 1);
}

// Two variants that differ only in the error they compare run the same parameters: the sweep
// runs each once and both rows carry the same record.
TEST_F(Sweeps, ARepeatedRunIsComputedOnce) {
  std::ofstream(dir / "base.json") << R"({"name": "base", "report": "table1",
      "reference": "paper1.csv", "record": ["error_over_time"],
      "defaults": {"T": 0.02, "cells": 20, "dt": 1e-4},
      "cases": [{"E": 4, "A": 0.015, "method": "gimp"}, {"E": 4, "A": 0.015, "method": "mpm"}]})";
  std::ofstream(dir / "v.json") << R"({"name": "v", "report": "variants", "cases_from": "base.json",
      "variants": [{"name": "default"}, {"name": "over-time", "error_at": "max_over_time"},
                   {"name": "pic", "set": {"transfer": "pic"}}]})";
  const Spec spec = load_spec(dir / "v.json");
  ASSERT_EQ(spec.cases.size(), 6u);
  SweepOptions o;
  o.jobs = 2;
  o.cache = dir / "out/cache";
  const SweepOutcome first = run_sweep(spec, o);
  EXPECT_EQ(first.computed, 4);
  EXPECT_EQ(first.shared, 2);
  EXPECT_EQ(first.cached, 0);
  EXPECT_EQ(first.records[0], first.records[2]);
  EXPECT_EQ(first.records[1], first.records[3]);
  std::size_t files = 0;
  for ([[maybe_unused]] const auto& f : fs::directory_iterator(dir / "out/cache"))
    ++files;
  EXPECT_EQ(files, 4u);
  // Without a cache (make check) the repeated run is still computed once.
  SweepOptions no_cache;
  no_cache.jobs = 3;
  const SweepOutcome again = run_sweep(spec, no_cache);
  EXPECT_EQ(again.computed, 4);
  EXPECT_EQ(again.shared, 2);
  EXPECT_EQ(again.records[0]["result"]["max_error"], first.records[0]["result"]["max_error"]);
  // A spec built in code with the same case twice (the parser refuses that in a file).
  Spec twice = load_spec(dir / "small.json");
  twice.cases.push_back(twice.cases.front());
  EXPECT_EQ(run_sweep(twice, no_cache).computed, 5);
}

// Cases that differ only in eq. (108)'s options share one run; each record is the one its own
// run gives (timing aside), whatever the job count, with or without a cache. Under the adaptive
// policy, which steps by eq. (108), the options change the trajectory and each case runs alone.
TEST_F(Sweeps, CasesDifferingOnlyInEq108OptionsShareOneRun) {
  std::ofstream(dir / "eq.json") << R"({"name": "eq", "report": "cases",
      "record": ["error_over_time", "dt_stable"],
      "defaults": {"T": 0.05, "cells": 20, "method": "gimp", "A": 0.05},
      "cases": [
        {"E": 64, "dt": 1e-4}, {"E": 64, "dt": 1e-4, "dt_stable_sigma": "raw"},
        {"E": 64, "dt": 1e-4, "dt_stable_vnorm": "max"},
        {"E": 64, "dt": 1e-4, "dt_stable_sigma": "raw", "dt_stable_vnorm": "max"},
        {"E": 100, "dt": 1e-4, "dt_stable_sigma": "raw"},
        {"E": 64, "policy": "adaptive", "safety": 0.5},
        {"E": 64, "policy": "adaptive", "safety": 0.5, "dt_stable_sigma": "raw"}]})";
  const Spec spec = load_spec(dir / "eq.json");
  SweepOptions o;
  o.jobs = 2;
  o.cache = dir / "out/cache";
  const SweepOutcome shared = run_sweep(spec, o);
  ASSERT_EQ(shared.computed, 7);
  std::map<int, int> runs_giving;  // records_of_run -> records
  for (const auto& rec : shared.records) {
    const auto& t = rec["timing"];
    ++runs_giving[t.contains("records_of_run") ? t["records_of_run"].get<int>() : 1];
  }
  EXPECT_EQ(runs_giving[4], 4);  // the four options of E = 64 at a fixed dt
  EXPECT_EQ(runs_giving[1], 3);  // E = 100 alone, and the adaptive cases
  for (std::size_t i = 0; i < spec.cases.size(); ++i) {
    SCOPED_TRACE(i);
    Spec one = spec;
    one.cases = {spec.cases[i]};
    const SweepOutcome alone = run_sweep(one, SweepOptions{});
    EXPECT_EQ(deterministic_part(alone.records[0]), deterministic_part(shared.records[i]));
  }
  EXPECT_NE(shared.records[0]["result"]["dt_stable_min"],
            shared.records[1]["result"]["dt_stable_min"]);
  EXPECT_NE(shared.records[5]["result"]["steps"], shared.records[6]["result"]["steps"]);
  // The shared run's work counts once: each of its four records carries a quarter.
  const auto& r0 = shared.records[0]["result"];
  EXPECT_DOUBLE_EQ(record_particle_steps(shared.records[0]),
                   r0["steps"].get<double>() * r0["particles"].get<double>() / 4);
  // From the cache, a case whose partners are cached is not computed again; without a cache
  // (make check) the run is shared too.
  std::size_t file = 0;
  for (const auto& f : fs::directory_iterator(dir / "out/cache"))
    if (++file == 2) fs::remove(f.path());
  const SweepOutcome again = run_sweep(spec, o);
  EXPECT_EQ(again.computed, 1);
  EXPECT_EQ(again.cached, 6);
  SweepOptions no_cache;
  no_cache.jobs = 1;
  const SweepOutcome check = run_sweep(spec, no_cache);
  for (std::size_t i = 0; i < spec.cases.size(); ++i)
    EXPECT_EQ(deterministic_part(check.records[i]), deterministic_part(shared.records[i]));
}

TEST_F(Sweeps, UnstableCasesAreReportedNotFatal) {
  const Spec spec = load_spec(dir / "small.json");
  const SweepOutcome r = sweep(spec, 2, dir / "out");
  EXPECT_EQ(r.unstable, 1);  // E = 1e4 at dt = 1e-3: Courant 2
  EXPECT_NE(read(dir / "out/small.md").find("\\* "), std::string::npos);
}

// The work of each case as last published (steps times particles of its record, by key), which
// estimates it in the next queue; none where the results are absent or unreadable. Results do not
// depend on it: a queue that reads it writes the same rows.
TEST_F(Sweeps, PublishedRecordsGiveEachCaseItsWork) {
  const Spec spec = load_spec(dir / "small.json");
  EXPECT_TRUE(published_work(spec, dir / "out").empty());  // nothing published yet
  const SweepOutcome r = sweep(spec, 2, dir / "out");
  const std::map<std::string, double> work = published_work(spec, dir / "out");
  ASSERT_EQ(work.size(), spec.cases.size());
  for (std::size_t i = 0; i < spec.cases.size(); ++i) {
    const auto& result = r.records[i]["result"];
    EXPECT_EQ(work.at(case_key(spec.cases[i].params)),
              result["steps"].get<double>() * result["particles"].get<double>());
  }
  // The unstable case's work is what it ran, not a run to T.
  EXPECT_LT(work.at(case_key(spec.cases[4].params)),
            case_cost(spec.cases[4].params, CaseWork::run));
  SweepOptions o;
  o.jobs = 2;
  o.published = dir / "out";
  write_reports(spec, run_sweep(spec, o), dir / "again");
  EXPECT_EQ(deterministic_rows(dir / "out/small.csv"), deterministic_rows(dir / "again/small.csv"));
  // An ensemble's member (a perturbed layout) is estimated by the case it perturbs.
  RunParams member = spec.cases[4].params;
  member.layout.shift = 1e-9;
  EXPECT_EQ(estimated_work(member, "", CaseWork::run, work),
            work.at(case_key(spec.cases[4].params)));
  member.dt /= 2;  // another run: the estimate from its parameters
  EXPECT_EQ(estimated_work(member, "", CaseWork::run, work), case_cost(member, CaseWork::run));
  std::ofstream(dir / "out/small.json") << "{ not json";
  EXPECT_TRUE(published_work(spec, dir / "out").empty());
}

int run_cli(const std::string& args) {
  return test_support::run_mpmstab(args).status;
}

// Several specs in one queue (mpmstab reproduce): the same records and reports as a sweep of
// each, a case repeated across specs computed once, and bad input refused before anything is
// written.
TEST_F(Sweeps, OneQueueForSeveralSpecsGivesTheSameResultsAndRunsARepeatedCaseOnce) {
  std::ofstream(dir / "paper1.csv") << "A,E,dt,method,dt_stable,max_error,confidence,evidence\n"
                                       "0.015,4,1e-4,GIMP,4e-3,1e-5,high,\n"
                                       "0.015,4,1e-4,MPM,1e-2,1e-5,high,\n";
  std::ofstream(dir / "base.json") << R"({"name": "base", "report": "table1",
      "reference": "paper1.csv", "record": ["error_over_time"],
      "defaults": {"T": 0.02, "cells": 20, "dt": 1e-4},
      "cases": [{"E": 4, "A": 0.015, "method": "gimp"}, {"E": 4, "A": 0.015, "method": "mpm"}]})";
  std::ofstream(dir / "v.json") << R"({"name": "v", "report": "variants", "cases_from": "base.json",
      "variants": [{"name": "default"}, {"name": "pic", "set": {"transfer": "pic"}}]})";
  const std::vector<Spec> specs = {load_spec(dir / "small.json"), load_spec(dir / "base.json"),
                                   load_spec(dir / "v.json")};
  // Each alone.
  for (const auto& spec : specs)
    sweep(spec, 1, dir / "alone");
  // In one queue: v's two default cases are base's, computed once.
  SweepOptions o;
  o.jobs = 3;
  o.cache = dir / "queue/cache";
  std::vector<std::size_t> order;
  const std::vector<SweepOutcome> outcomes =
      run_sweeps({&specs[0], &specs[1], &specs[2]}, o, [&](std::size_t s, SweepOutcome& r) {
        order.push_back(s);
        write_reports(specs[s], r, dir / "queue");
      });
  ASSERT_EQ(order.size(), 3u);
  std::size_t cache_files = 0;  // records: <16 hex digits of the key>.json
  for (const auto& f : fs::directory_iterator(dir / "queue/cache"))
    cache_files += f.path().extension() == ".json" && f.path().stem().string().size() == 16;
  EXPECT_EQ(cache_files, 5u + 2u + 2u);  // small's 5, base's 2, v's 2 with pic; v's defaults shared
  for (const char* name : {"small", "base", "v"}) {
    for (const char* ext : {".csv", ".json"}) {
      EXPECT_EQ(deterministic_rows(dir / "queue" / (std::string(name) + ext)),
                deterministic_rows(dir / "alone" / (std::string(name) + ext)))
          << name << ext;
    }
  }
  // The command: every spec given, a study that reads another written after it.
  std::ofstream(dir / "paper_t1.csv") << read(dir / "paper1.csv");
  const auto [status, output] = test_support::run_mpmstab(
      "reproduce " + (dir / "small.json").string() + " " + (dir / "base.json").string() + " " +
      (dir / "v.json").string() + " --jobs 2 --out " + (dir / "cli").string());
  ASSERT_EQ(status, 0) << output;
  EXPECT_NE(output.find("[reproduce] 9/9 cases"), std::string::npos) << output;
  EXPECT_NE(output.find("[reproduce] 3 experiments in"), std::string::npos) << output;
  EXPECT_EQ(read(dir / "cli/small.csv").empty(), false);
  EXPECT_NE(read(dir / "cli/cache/timings.json").find("\"(reproduce)\""), std::string::npos);
  // --label names the run's entry; a label that is not a plain name is refused.
  auto reproduce_labelled = [&](const std::string& label) {
    return test_support::run_program(
               MPMSTAB_BIN, {MPMSTAB_BIN, "reproduce", (dir / "small.json").string(), "--label",
                             label, "--out", (dir / "cli").string()})
        .status;
  };
  ASSERT_EQ(reproduce_labelled("make studies"), 0);
  EXPECT_NE(read(dir / "cli/cache/timings.json").find("\"(make studies)\""), std::string::npos);
  EXPECT_EQ(reproduce_labelled("$(touch x)"), 2);
  EXPECT_EQ(reproduce_labelled(""), 2);
  EXPECT_FALSE(fs::exists(dir / "cli/timings.json"));  // published only by mpmstab performance
  // Refused before any work: a missing spec, a bad option, no spec, two specs of one name.
  const std::string before = read(dir / "cli/small.csv");
  EXPECT_EQ(run_cli("reproduce " + (dir / "small.json").string() + " " +
                    (dir / "absent.json").string() + " --out " + (dir / "cli").string()),
            2);
  EXPECT_EQ(run_cli("reproduce " + (dir / "small.json").string() + " --jobs 0"), 2);
  EXPECT_EQ(run_cli("reproduce"), 2);
  EXPECT_EQ(run_cli("reproduce " + (dir / "small.json").string() + " " +
                    (dir / "small.json").string() + " --out " + (dir / "cli").string()),
            2);
  EXPECT_EQ(read(dir / "cli/small.csv"), before);
}

// A study that reads another experiment is written after it, whatever the order given: the
// spectral study shows the spectral_edge experiment's measured edge even when listed first.
// Specs added while the queue runs (make reproduce adds each experiment's follow-up runs as its
// cases finish): their cases join the same queue, a case already computed or waiting gives its
// record, and every record is the one a sweep of that spec alone gives.
TEST_F(Sweeps, ASpecAddedWhileTheQueueRunsJoinsItAndGetsTheRecordsOfItsOwnSweep) {
  std::ofstream(dir / "more.json") << R"({
      "name": "more", "title": "More", "report": "table2", "reference": "paper2.csv",
      "record": ["crossings", "error_over_time"],
      "defaults": {"T": 0.05, "cells": 20, "dt": 1e-4},
      "cases": [
        {"E": 4, "A": 0.015, "method": "gimp"}, {"E": 64, "A": 0.05, "method": "mpm"},
        {"E": 16, "A": 0.05, "method": "gimp"}
      ]})";
  const Spec small = load_spec(dir / "small.json"), more = load_spec(dir / "more.json");
  SweepOptions o;
  o.jobs = 2;
  o.cache = dir / "queue/cache";
  o.quiet = true;
  SweepQueue queue(o, "test");
  EXPECT_EQ(queue.add(small), 0u);
  std::vector<std::size_t> order;
  std::size_t added = 0;
  const std::vector<SweepOutcome> outcomes = queue.run([&](std::size_t b, SweepOutcome&) {
    order.push_back(b);
    if (b == 0) added = queue.add(more);  // from the caller's thread, while the queue runs
  });
  ASSERT_EQ(added, 1u);
  ASSERT_EQ(order, (std::vector<std::size_t>{0, 1}));
  ASSERT_EQ(outcomes.size(), 2u);
  // One run per distinct case over both: small's 5 and more's one new case.
  std::size_t cache_files = 0;
  for (const auto& f : fs::directory_iterator(dir / "queue/cache"))
    cache_files += f.path().extension() == ".json" && f.path().stem().string().size() == 16;
  EXPECT_EQ(cache_files, 6u);
  // Every record is its own sweep's.
  SweepOptions alone;
  alone.quiet = true;
  const SweepOutcome reference = run_sweep(more, alone);
  for (std::size_t i = 0; i < more.cases.size(); ++i)
    EXPECT_EQ(deterministic_part(outcomes[1].records[i]), deterministic_part(reference.records[i]))
        << i;
}

// The runs a report makes itself while it renders on the caller's thread (make reproduce) count in
// the queue's report account, through the report's own, and only those computed.
TEST_F(Sweeps, TheRunsOfAReportRenderedWhileTheQueueRunsCountInItsAccount) {
  const Spec small = load_spec(dir / "small.json");
  SweepOptions o;
  o.jobs = 2;
  o.cache = dir / "queue/cache";
  o.quiet = true;
  SweepQueue queue(o, "test");
  queue.add(small);
  queue.expect(1e6);  // the report's runs, as published
  const ResultCache cache(o.cache);
  RunParams p;
  p.T = 0.01;
  p.dt = 1e-3;
  RunAccount report;
  {
    const RunAccountScope counting(queue.report_account());
    queue.run([&](std::size_t, SweepOutcome&) {
      const RunAccountScope rendering(report);
      cached_run(cache, p);
      cached_run(cache, p);  // from the cache: not counted
      queue.reports_rendered(1e6);
    });
  }
  EXPECT_EQ(open_run_account(), nullptr);  // the scopes closed
  EXPECT_EQ(report.runs.load(), 1);
  EXPECT_EQ(queue.report_account().runs.load(), 1);
  // 10 steps of 200 particles.
  EXPECT_DOUBLE_EQ(queue.report_account().particle_steps.load(), 2000.0);
}

// A queue given no spec runs nothing and ends (reproduce --follow-ups of specs that ask for no
// follow-up run builds none).
TEST(SweepQueueEmpty, RunsNothingAndEnds) {
  SweepOptions o;
  o.jobs = 2;
  o.quiet = true;
  SweepQueue queue(o, "empty");
  bool called = false;
  EXPECT_TRUE(queue.run([&](std::size_t, SweepOutcome&) { called = true; }).empty());
  EXPECT_FALSE(called);
}

// The dense spectral analyses a run asks for count in the queue's estimate: one for a layout
// that is not uniform where the spec records `spectral`, none for a uniform layout (Bloch's),
// and more for the spectral policy as the layout moves.
TEST(Scheduling, DenseAnalysesAreCountedWhereARunAsksForThem) {
  RunParams p;
  p.cells = 50;
  EXPECT_FALSE(dense_analyses(p).initial_key);  // uniform: Bloch's limit
  p.observe.spectral = true;
  EXPECT_FALSE(dense_analyses(p).initial_key);
  p.layout.jitter = 0.1;
  const DenseAnalyses jittered = dense_analyses(p);
  ASSERT_TRUE(jittered.initial_key);
  EXPECT_EQ(jittered.later, 0);
  EXPECT_EQ(*jittered.initial_key, spectral_analysis_key(p, SpectralAnalysis::dense));
  // n = 2 values x 100 particles.
  EXPECT_DOUBLE_EQ(dense_analysis_cost(p), kDenseAnalysisCost * 200.0 * 200.0 * 200.0);
  p.observe.spectral = false;
  EXPECT_FALSE(dense_analyses(p).initial_key);
  p.stepping.policy = TimeStepPolicy::spectral;
  p.A = 0.1;  // 5 cells: at most 6 analyses more as the layout moves
  EXPECT_TRUE(dense_analyses(p).initial_key);
  EXPECT_DOUBLE_EQ(dense_analyses(p).later, 6);
}

// The time to go counts what the running tasks have done (their runs count it as they go) and
// the follow-up work expected from the last published results until the real one replaces it.
TEST(ProgressLine, RunningAndExpectedWorkCountInTheTimeToGo) {
  ProgressCounter c(2, 100);
  EXPECT_FALSE(c.seconds_to_go(10));  // nothing done yet
  c.running(25);                      // a quarter done, in 10 s
  ASSERT_TRUE(c.seconds_to_go(10));
  EXPECT_DOUBLE_EQ(*c.seconds_to_go(10), 30);
  c.expect(100);  // follow-up runs expected
  EXPECT_DOUBLE_EQ(*c.seconds_to_go(10), 70);
  c.running(0);
  c.finished(false, 50, 50, false);
  c.finished(false, 50, 50, false);
  EXPECT_FALSE(c.finished());  // the expected work is still to come
  EXPECT_DOUBLE_EQ(c.remaining_cost(), 100);
  c.add(1, 80, 100);  // the real follow-ups replace the expectation
  EXPECT_DOUBLE_EQ(c.remaining_cost(), 80);
  c.finished(false, 80, 80, false);
  EXPECT_TRUE(c.finished());
  EXPECT_NE(c.text("reproduce", 20).find("done"), std::string::npos);
}

// The runs a report makes itself are expected from its last published count, counted as running
// while it renders, and as done once it is written, where the expectation leaves the total.
TEST(ProgressLine, ReportRunsCountAsRunningThenDone) {
  ProgressCounter c(1, 100);
  c.expect(300);  // the report's runs, as published
  c.finished(false, 100, 100, false);
  EXPECT_FALSE(c.finished());  // every case done; the report still to render
  EXPECT_DOUBLE_EQ(c.remaining_cost(), 300);
  c.running(150);  // half of it made so far
  EXPECT_DOUBLE_EQ(c.remaining_cost(), 150);
  ASSERT_TRUE(c.seconds_to_go(25));
  EXPECT_DOUBLE_EQ(*c.seconds_to_go(25), 15);  // 250 done in 25 s, 150 to go
  c.running(0);
  c.finished_work(200, 300);  // it made 200 in all
  EXPECT_TRUE(c.finished());
  EXPECT_DOUBLE_EQ(c.remaining_cost(), 0);
  EXPECT_NE(c.text("reproduce", 30).find("3e+02 particle-steps computed"), std::string::npos)
      << c.text("reproduce", 30);
}

TEST(ProgressLine, WorkAddedWhileTheQueueRunsJoinsTheTotal) {
  ProgressCounter c(2, 100);
  c.finished(false, 50, 50, false);
  EXPECT_DOUBLE_EQ(c.remaining_cost(), 50);
  c.add(3, 300);  // a spec's follow-up runs
  EXPECT_EQ(c.runs(), 5u);
  EXPECT_DOUBLE_EQ(c.remaining_cost(), 350);
  EXPECT_NE(c.text("reproduce", 10).find("1/5 cases"), std::string::npos) << c.text("r", 10);
}

TEST_F(Sweeps, OneQueueWritesAnExperimentAfterTheOnesItReads) {
  std::ofstream(dir / "spectral_edge.json") << R"({"name": "spectral_edge", "title": "E",
      "report": "spectral_edge", "record": ["error_over_time"],
      "defaults": {"E": 1, "T": 2, "cells": 10, "ppc": 2},
      "cases": [{"method": "mpm", "A": 1e-6}]})";
  std::ofstream(dir / "spectral.json") << R"({"name": "spectral", "title": "S",
      "report": "spectral", "record": ["error_over_time", "dt_stable"],
      "defaults": {"E": 1, "A": 1e-6, "T": 2, "cells": 10, "policy": "spectral"},
      "cases": [{"method": "mpm", "safety": 0.95}, {"method": "mpm", "safety": 1.05}]})";
  const auto [status, output] = test_support::run_mpmstab(
      "reproduce " + (dir / "spectral.json").string() + " " +
      (dir / "spectral_edge.json").string() + " --jobs 2 --out " + (dir / "out").string());
  ASSERT_EQ(status, 0) << output;
  EXPECT_LT(output.find("[spectral_edge] 1 cases"), output.find("[spectral] 2 cases")) << output;
  const std::string md = read(dir / "out/spectral.md");
  const std::string start = "| mpm | 0.7559 | bloch | ";
  const auto row = md.find(start);
  ASSERT_NE(row, std::string::npos) << md;
  // The measured edge column holds a number (the input was read), not "–".
  const char first = md[row + start.size()];
  EXPECT_TRUE(first >= '0' && first <= '9') << md.substr(row, 80);
}

// A refused command leaves the file system as it found it: the --out folder is made only after
// every argument and input was checked.
TEST_F(Sweeps, ARefusedCommandMakesNoOutputFolder) {
  std::ofstream(dir / "broken.json") << R"({"name": "broken", "report": "cases", "cases": [)";
  // Refused only when its inputs are checked, after the options and the spec: the reference
  // table it names does not exist.
  std::ofstream(dir / "unreferenced.json")
      << R"({"name": "u", "report": "table1", "reference": "nope.csv", "cases": [)"
      << R"({"method": "gimp", "E": 4, "A": 0.01, "dt": 1e-3, "T": 0.01}]})";
  const std::string small = (dir / "small.json").string(), broken = (dir / "broken.json").string();
  const std::vector<std::string> refused = {
      "sweep " + broken + " --out ",
      "reproduce " + small + " " + broken + " --out ",
      "sweep " + small + " --jobs 0 --out ",
      "sweep " + small + " --timing sometimes --out ",
      "reproduce " + small + " --jobs -3 --out ",
      "sweep " + (dir / "unreferenced.json").string() + " --out ",
      "reproduce " + small + " " + (dir / "unreferenced.json").string() + " --out ",
  };
  int n = 0;
  for (const std::string& command : refused) {
    const fs::path out = dir / ("never_" + std::to_string(n++)) / "out";
    EXPECT_EQ(run_cli(command + out.string()), 2) << command;
    EXPECT_FALSE(fs::exists(out.parent_path())) << command;
  }
  // The same folder is made by a command that runs.
  EXPECT_EQ(run_cli("sweep " + small + " --out " + (dir / "made/out").string()), 0);
  EXPECT_TRUE(fs::is_regular_file(dir / "made/out/small.md"));
}

TEST_F(Sweeps, CommandLineRefusesBadSpecsAndLeavesResultsUntouched) {
  const fs::path out = dir / "out";
  ASSERT_EQ(run_cli("sweep " + (dir / "small.json").string() + " --jobs 2 --out " + out.string()),
            0);
  const std::string before = read(out / "small.csv");
  std::ofstream(dir / "bad.json") << R"({"name": "small", "report": "figure", "cases": [)"
                                     R"({"method": "gimp", "E": 4, "A": 0.01, "dt": -1}]})";
  const auto [status, output] =
      test_support::run_mpmstab("sweep " + (dir / "bad.json").string() + " --out " + out.string());
  EXPECT_EQ(status, 2);
  EXPECT_NE(output.find("cases[0].dt"), std::string::npos) << output;
  EXPECT_EQ(read(out / "small.csv"), before);
  EXPECT_EQ(run_cli("sweep " + (dir / "small.json").string() + " --jobs 0"), 2);
  EXPECT_EQ(run_cli("sweep " + (dir / "small.json").string() + " --out /proc/none"), 2);
  EXPECT_EQ(run_cli("sweep " + dir.string()), 2);  // a directory
  EXPECT_EQ(run_cli("sweep"), 2);
}

// No minus sign before a digit ("particle-steps" keeps its hyphen).
bool no_negative_number(const std::string& line) {
  for (std::size_t i = 0; i + 1 < line.size(); ++i)
    if (line[i] == '-' && std::isdigit(static_cast<unsigned char>(line[i + 1]))) return false;
  return true;
}

// The progress line of a queue whose every case comes from the cache (the second make
// reproduce): the estimates subtracted one by one leave a rounding residue, which the line must
// not show as a negative total or a negative time.
TEST(ProgressLine, AFullyCachedQueueIsDoneWithNothingComputed) {
  const std::vector<double> costs = {0.1, 0.2, 0.3, 1e-5, 7.7e6, 3.3e-4};
  double total = 0;
  for (double c : costs)
    total += c;
  ProgressCounter counter(costs.size(), total);
  for (double c : costs)
    counter.finished(true, c, 0, false);
  EXPECT_EQ(counter.remaining_cost(), 0.0);
  ASSERT_TRUE(counter.seconds_to_go(0.5).has_value());
  EXPECT_EQ(*counter.seconds_to_go(0.5), 0.0);
  const std::string line = counter.text("reproduce", 0.5);
  EXPECT_NE(line.find("6/6 cases"), std::string::npos) << line;
  EXPECT_NE(line.find("0 particle-steps computed, 6 cases from the cache"), std::string::npos)
      << line;
  EXPECT_NE(line.find("done"), std::string::npos) << line;
  EXPECT_TRUE(no_negative_number(line)) << line;
}

// A queue of one case: no time to go until it is known, then done; never negative.
TEST(ProgressLine, AQueueOfOneCaseEstimatesThenIsDone) {
  ProgressCounter counter(1, 4e6);
  for (double elapsed : {0.0, 0.5, 3.0, 100.0}) {
    const std::string line = counter.text("one", elapsed);
    EXPECT_NE(line.find("0/1 cases"), std::string::npos) << line;
    EXPECT_NE(line.find("0 of ~4e+06 particle-steps"), std::string::npos) << line;
    EXPECT_NE(line.find("estimating"), std::string::npos) << line;  // nothing measured yet
    EXPECT_TRUE(no_negative_number(line)) << line;
  }
  counter.finished(false, 4e6, 5.2e6, true);
  const std::string line = counter.text("one", 2.0);
  EXPECT_NE(line.find("1/1 cases, 1 unstable, 5.2e+06 particle-steps computed"), std::string::npos)
      << line;
  EXPECT_NE(line.find("done"), std::string::npos) << line;
}

// The time to go is the estimate left at the rate measured so far, and it is withheld where too
// little is done to say (a tiny first case would predict years). Where the finished runs did
// other work than estimated (a run that stopped before T), it is the geometric mean of the
// estimate left at their estimates' rate and at their work's rate.
TEST(ProgressLine, TimeToGoFollowsTheMeasuredRateAndIsWithheldWhenAbsurd) {
  ProgressCounter counter(3, 3e6);
  counter.finished(false, 1e6, 1e6, false);
  ASSERT_TRUE(counter.seconds_to_go(10).has_value());
  EXPECT_NEAR(*counter.seconds_to_go(10), 20, 1e-9);  // 2e6 left at 1e5 per second
  EXPECT_NE(counter.text("q", 10).find("1e+06 of ~3e+06 particle-steps"), std::string::npos);
  EXPECT_NE(counter.text("q", 10).find("~20 s to go"), std::string::npos);
  ProgressCounter early(3, 3e6);
  early.finished(false, 1e6, 0.25e6, true);  // stopped a quarter of the way in
  // 2e6 left: 20 s at 1e5 estimated per second, 80 s at 2.5e4 done per second.
  EXPECT_NEAR(*early.seconds_to_go(10), 40, 1e-9);
  ProgressCounter tiny(2, 1e9);
  tiny.finished(false, 1, 1, false);  // one particle-step in a second: 1e9 s to go
  EXPECT_FALSE(tiny.seconds_to_go(1).has_value());
  EXPECT_NE(tiny.text("q", 1).find("estimating"), std::string::npos);
}

// Work done once (docs/engineering.md): PIC and APIC cases that differ only in the position update
// share one run, because their records are the same but for that column. Checked on random
// cases (fixed seed) over every basis, both transfers, every update order and four scenes, at
// Courant numbers from 0.05 to 1.5 (some fail); FLIP, where the two updates differ, is the
// control.
TEST(ProgressLine, TheTimeToGoIsJudgedAgainstTheTruthAfterTheFirstTenthAndBeforeTheLastTwentieth) {
  // A queue of 100 s whose line said 2x the truth at 5 s (not judged: the first 10%), 1.5x at
  // 20 s, 0.8x at 50 s and 10x at 98 s (not judged: the last 5%).
  const std::vector<std::pair<double, double>> shown = {{5, 190}, {20, 120}, {50, 40}, {98, 20}};
  const EstimateAccuracy a = estimate_accuracy(shown, 100);
  EXPECT_EQ(a.samples, 2u);
  EXPECT_DOUBLE_EQ(a.worst, 1.5);
  ASSERT_EQ(a.at.size(), 4u);  // the first estimate at or after 10, 25, 50 and 75% of the wall
  EXPECT_EQ(a.at[0], (std::vector<double>{0.2, 120, 80}));
  EXPECT_EQ(a.at[1], (std::vector<double>{0.5, 40, 50}));
  EXPECT_EQ(a.at[3], (std::vector<double>{0.98, 20, 2}));
  EXPECT_EQ(estimate_accuracy({}, 100).samples, 0u);
  EXPECT_EQ(estimate_accuracy(shown, 0).samples, 0u);
}

TEST(WorkDoneOnce, PicApicAndFmpmRecordsDoNotDependOnThePositionUpdate) {
  std::mt19937 random(35);
  const std::array methods = {Method::mpm,      Method::gimp,     Method::cpgimp,
                              Method::bspline2, Method::bspline3, Method::cpdi};
  const std::array updates = {UpdateOrder::usl, UpdateOrder::usf, UpdateOrder::musl};
  const std::array scenes = {SceneKind::bar, SceneKind::vibration, SceneKind::impulsive,
                             SceneKind::block};
  auto pick = [&](const auto& from) { return from[random() % from.size()]; };
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  auto without_update = [](RunParams p) {
    nlohmann::ordered_json j = to_json(run(p));
    j.erase("position_update");
    return j;
  };
  int failed = 0;
  const std::array transfers = {Transfer::pic, Transfer::apic, Transfer::fmpm};
  for (int k = 0; k < 36; ++k) {
    RunParams p;
    p.method = pick(methods);
    p.transfer = transfers[std::size_t(k) % transfers.size()];
    p.fmpm_order = 1 + k % 3;
    p.update = pick(updates);
    p.scene = pick(scenes);
    p.bc = p.scene == SceneKind::block ? Boundary::periodic : Boundary::dirichlet;
    p.cells = 32;
    p.E = std::pow(10.0, 4 * unit(random));
    p.A = (0.05 + unit(random)) / p.cells;
    p.dt = (0.05 + 1.45 * unit(random)) / p.cells / std::sqrt(p.E);
    p.T = 60 * p.dt;
    ASSERT_TRUE(validate(p).empty()) << k;
    ASSERT_TRUE(position_update_is_moot(p));
    RunParams q = p;
    q.position_update = PositionUpdate::particle;
    const auto grid = without_update(p);
    EXPECT_EQ(grid, without_update(q)) << k << ": " << grid.dump();
    failed += grid["outcome"] == "unstable";
  }
  EXPECT_GT(failed, 0);  // the identity holds for failed runs too
  RunParams flip;
  flip.method = Method::gimp;
  flip.E = 100;
  flip.A = 0.02;
  flip.dt = 1e-3;
  flip.T = 0.1;
  EXPECT_FALSE(position_update_is_moot(flip));
  RunParams flip_particle = flip;
  flip_particle.position_update = PositionUpdate::particle;
  EXPECT_NE(without_update(flip), without_update(flip_particle));
  // XPIC adds its correction to the particle's velocity, not to the grid's sum: not moot.
  flip.transfer = Transfer::xpic;
  EXPECT_FALSE(position_update_is_moot(flip));
  flip_particle.transfer = Transfer::xpic;
  EXPECT_NE(without_update(flip), without_update(flip_particle));
}

}  // namespace
}  // namespace mpmstab
