// The file layer: strict JSON, safe reads and writes, report sets published whole, the folder
// lock, stale temporaries, cache integrity and a closed standard output.
#include <fcntl.h>
#include <signal.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <gtest/gtest.h>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <thread>

#include "cache.hpp"
#include "files.hpp"
#include "result_json.hpp"
#include "run/run.hpp"
#include "strict_json.hpp"
#include "support.hpp"

namespace {

namespace fs = std::filesystem;
using mpmstab::InputError;
using mpmstab::test_support::run_mpmstab;
using ojson = nlohmann::ordered_json;

class Files : public ::testing::Test {
 protected:
  fs::path dir;
  void SetUp() override {
    dir = fs::temp_directory_path() /
          ("mpmstab_files_" + std::to_string(::getpid()) + "_" +
           ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir);
    fs::create_directories(dir);
  }
  void TearDown() override { fs::remove_all(dir); }
  static std::string read(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
  }
  void write(const std::string& name, const std::string& text) const {
    std::ofstream(dir / name) << text;
  }
  std::string message_of(const std::string& text) const {
    try {
      mpmstab::parse_json_strict<ojson>(text, dir / "x.json");
    } catch (const InputError& e) {
      return e.what();
    }
    return "";
  }
  // A spec of two quick cases.
  fs::path quick_spec() const {
    const fs::path spec = dir / "quick.json";
    std::ofstream(spec) << R"({"name": "quick", "report": "cases",
      "defaults": {"T": 0.01, "cells": 10, "dt": 1e-3},
      "cases": [{"method": "gimp", "E": 4, "A": 0.01}, {"method": "mpm", "E": 4, "A": 0.01}]})";
    return spec;
  }
};

TEST_F(Files, StrictJsonRefusesWhatJsonWouldReadSilently) {
  EXPECT_NE(message_of(R"({"a": 1, "a": 2})").find("x.json: a: is given twice"), std::string::npos);
  EXPECT_NE(message_of(R"({"c": [{"E": 1}, {"E": 1, "E": 2}]})").find("c[1].E: is given twice"),
            std::string::npos);
  EXPECT_NE(message_of(R"({"c": [[1, 2], {"k": {"x": 1, "x": 1}}]})").find("c[1].k.x: is given"),
            std::string::npos);
  EXPECT_NE(message_of("\xEF\xBB\xBF{}").find("byte-order mark"), std::string::npos);
  EXPECT_NE(message_of(R"({"t": ["ok", "a\nb"]})")
                .find("t[1]: contains the control character "
                      "U+000A"),
            std::string::npos);
  EXPECT_NE(message_of(R"({"x": 1e999})").find("x: malformed JSON: number overflow"),
            std::string::npos);
  EXPECT_NE(message_of(R"({"x": 1,})").find("malformed JSON at line 1"), std::string::npos);
  // What stays accepted: the same key in two objects, unicode, -0 as 0.
  const ojson ok = mpmstab::parse_json_strict<ojson>(
      R"({"a": {"k": 1}, "b": {"k": -0.0}, "t": "Zürich – ∞"})", dir / "x.json");
  EXPECT_EQ(ok["b"]["k"].get<double>(), 0.0);
  EXPECT_FALSE(std::signbit(ok["b"]["k"].get<double>()));
}

TEST_F(Files, ReadsOnlyBoundedRegularFilesAndNeverBlocks) {
  write("a.txt", "abc");
  EXPECT_EQ(mpmstab::read_input(dir / "a.txt"), "abc");
  EXPECT_FALSE(mpmstab::read_if_present(dir / "absent").has_value());
  EXPECT_THROW(mpmstab::read_input(dir / "absent"), InputError);
  EXPECT_THROW(mpmstab::read_input(dir / "a.txt", 2), InputError);  // over the limit
  ASSERT_EQ(::mkfifo((dir / "fifo").c_str(), 0644), 0);
  const auto start = std::chrono::steady_clock::now();
  EXPECT_THROW(mpmstab::read_input(dir / "fifo"), InputError);  // would block without a writer
  EXPECT_THROW(mpmstab::read_input("/dev/zero"), InputError);   // would never end
  EXPECT_THROW(mpmstab::read_input(dir), InputError);
  EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(2));
}

TEST_F(Files, WritesReplaceRegularFilesOnlyAndLeaveNoTemporary) {
  const fs::path target = dir / "r.txt";
  mpmstab::write_file_atomically(target, "one");
  mpmstab::write_file_atomically(target, "two");
  EXPECT_EQ(read(target), "two");
  write("outside", "precious");
  fs::create_symlink(dir / "outside", dir / "link");
  ASSERT_EQ(::mkfifo((dir / "fifo").c_str(), 0644), 0);
  fs::create_directories(dir / "sub");
  for (const char* name : {"link", "fifo", "sub"}) {
    try {
      mpmstab::write_file_atomically(dir / name, "x");
      ADD_FAILURE() << name << " was written over";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find((dir / name).string()), std::string::npos);
    }
  }
  EXPECT_THROW(mpmstab::write_file_atomically("/dev/null", "x"), InputError);
  EXPECT_EQ(read(dir / "outside"), "precious");
  // Nothing but the files made above: no temporary left behind.
  std::size_t entries = 0;
  for ([[maybe_unused]] const auto& e : fs::directory_iterator(dir))
    ++entries;
  EXPECT_EQ(entries, 5u);
}

TEST_F(Files, AStreamedFileAppearsOnlyWhenCommitted) {
  const fs::path target = dir / "h.csv";
  write("h.csv", "old");
  {
    mpmstab::FileWriter w(target);
    w.write("new ");
    w.write(std::string(3u << 20, 'x'));  // past the buffer: on disk in the temporary
    EXPECT_EQ(read(target), "old");
  }  // not committed: nothing changes
  EXPECT_EQ(read(target), "old");
  mpmstab::FileWriter w(target);
  w.write("new");
  w.commit();
  EXPECT_EQ(read(target), "new");
  std::size_t entries = 0;
  for ([[maybe_unused]] const auto& e : fs::directory_iterator(dir))
    ++entries;
  EXPECT_EQ(entries, 1u);
}

TEST_F(Files, ABatchPublishesAllOrNothing) {
  write("b.txt", "old b");
  fs::create_directories(dir / "c.txt");  // a folder where the batch's last file goes
  {
    mpmstab::ReportBatch batch;
    mpmstab::write_if_changed(dir / "a.txt", "new a");
    mpmstab::write_if_changed(dir / "b.txt", "new b");
    mpmstab::write_if_changed(dir / "c.txt", "new c");
    EXPECT_FALSE(fs::exists(dir / "a.txt"));  // collected, not written
    EXPECT_THROW(batch.publish(), InputError);
  }
  EXPECT_FALSE(fs::exists(dir / "a.txt"));
  EXPECT_EQ(read(dir / "b.txt"), "old b");
  fs::remove(dir / "c.txt");
  mpmstab::ReportBatch batch;
  mpmstab::write_if_changed(dir / "a.txt", "new a");
  mpmstab::write_if_changed(dir / "b.txt", "old b");  // unchanged: not rewritten
  EXPECT_EQ(batch.publish(), 1u);
  EXPECT_EQ(read(dir / "a.txt"), "new a");
}

TEST_F(Files, StaleTemporariesOfDeadWritersAreRemovedLiveOnesKept) {
  // pid 99999999 is above any pid_max (at most 4194304): that writer is gone.
  write(".r.md.99999999.0123456789abcdef.tmp", "stale");
  fs::create_directories(dir / ".99999999.0123456789abcdef.staging");
  const std::string live = ".r.md." + std::to_string(::getppid()) + ".0123456789abcdef.tmp";
  write(live, "in progress");
  write(".r.md.tmp", "not ours");
  EXPECT_EQ(mpmstab::remove_stale_temporaries(dir), 2u);
  EXPECT_FALSE(fs::exists(dir / ".r.md.99999999.0123456789abcdef.tmp"));
  EXPECT_FALSE(fs::exists(dir / ".99999999.0123456789abcdef.staging"));
  EXPECT_TRUE(fs::exists(dir / live));
  EXPECT_TRUE(fs::exists(dir / ".r.md.tmp"));
  // A sweep publishing into the folder removes them too.
  write(".quick.md.99999999.0123456789abcdef.tmp", "stale");
  const auto r = run_mpmstab("sweep " + quick_spec().string() + " --out " + dir.string());
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_FALSE(fs::exists(dir / ".quick.md.99999999.0123456789abcdef.tmp"));
}

TEST_F(Files, ASecondWriterWaitsForTheFolderLock) {
  const fs::path spec = quick_spec();
  const fs::path out = dir / "out";
  fs::create_directories(out);
  const int fd = ::open((out / ".mpmstab.lock").c_str(), O_RDWR | O_CREAT, 0644);
  ASSERT_GE(fd, 0);
  ASSERT_EQ(::flock(fd, LOCK_EX), 0);
  mpmstab::test_support::CliOutcome r{};
  std::thread sweep([&] { r = run_mpmstab("sweep " + spec.string() + " --out " + out.string()); });
  std::this_thread::sleep_for(std::chrono::milliseconds(1500));
  EXPECT_FALSE(fs::exists(out / "quick.md"));  // computed, waiting to publish
  ::flock(fd, LOCK_UN);
  ::close(fd);
  sweep.join();
  EXPECT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("waiting for " + (out / ".mpmstab.lock").string()), std::string::npos)
      << r.output;
  EXPECT_TRUE(fs::exists(out / "quick.md"));
}

TEST_F(Files, AClosedStandardOutputLosesNoReport) {
  // Standard output and error are a pipe whose reader is gone (mpmstab ... | head -0).
  int fd[2];
  ASSERT_EQ(::pipe(fd), 0);
  ::close(fd[0]);
  const std::string spec = quick_spec().string(), out = (dir / "out").string();
  const pid_t pid = ::fork();
  if (pid == 0) {
    ::dup2(fd[1], STDOUT_FILENO);
    ::dup2(fd[1], STDERR_FILENO);
    ::execl(MPMSTAB_BIN, MPMSTAB_BIN, "sweep", spec.c_str(), "--out", out.c_str(), nullptr);
    ::_exit(127);
  }
  ::close(fd[1]);
  int status = 0;
  ::waitpid(pid, &status, 0);
  EXPECT_TRUE(WIFEXITED(status)) << "killed by signal " << WTERMSIG(status);
  for (const char* f : {"quick.csv", "quick.json", "quick.md"})
    EXPECT_TRUE(fs::exists(dir / "out" / f)) << f;
  // and `run --json | head -0` exits without a crash
  int p2[2];
  ASSERT_EQ(::pipe(p2), 0);
  ::close(p2[0]);
  const pid_t run = ::fork();
  if (run == 0) {
    ::dup2(p2[1], STDOUT_FILENO);
    ::execl(MPMSTAB_BIN, MPMSTAB_BIN, "run", "--method", "gimp", "--E", "4", "--A", "0.01", "--dt",
            "1e-3", "--T", "0.01", "--json", nullptr);
    ::_exit(127);
  }
  ::close(p2[1]);
  ::waitpid(run, &status, 0);
  EXPECT_TRUE(WIFEXITED(status));
}

TEST_F(Files, ACacheRecordThatLiesIsRecomputedAndCounted) {
  const fs::path spec = quick_spec();
  const fs::path out = dir / "out";
  ASSERT_EQ(run_mpmstab("sweep " + spec.string() + " --out " + out.string()).status, 0);
  const std::string report = read(out / "quick.json");
  std::vector<fs::path> records;
  for (const auto& e : fs::directory_iterator(out / "cache"))  // records, not the timings
    if (e.path().extension() == ".json" && e.path().stem().string().size() == 16)
      records.push_back(e.path());
  ASSERT_EQ(records.size(), 2u);
  // 1. A hand-edited result: valid JSON, right shape, wrong number.
  ojson edited = ojson::parse(read(records[0]));
  ASSERT_TRUE(edited["result"]["max_error"].is_number());
  edited["result"]["max_error"] = 0.0;
  std::ofstream(records[0]) << edited.dump();
  // 2. A truncated record.
  const std::string whole = read(records[1]);
  std::ofstream(records[1]) << whole.substr(0, whole.size() / 2);
  const auto r = run_mpmstab("sweep " + spec.string() + " --out " + out.string());
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("2 computed, 0 from the cache"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("2 cache records failed their checksum or shape"), std::string::npos)
      << r.output;
  EXPECT_EQ(read(out / "quick.json"), report);  // the true values, not the edited one
  EXPECT_EQ(ojson::parse(read(records[1]))["result"], ojson::parse(whole)["result"]);  // whole
  const ojson timings = ojson::parse(read(out / "cache" / "timings.json"));
  EXPECT_EQ(timings["quick"]["cache_records_rejected"], 2);
  // 3. Records of the right shape from another case under this key, or without a checksum.
  ojson other = ojson::parse(read(records[0]));
  other["canonical"] = "solver=0;something else";
  std::ofstream(records[0]) << other.dump();
  ojson bare = ojson::parse(read(records[1]));
  bare.erase("checksum");
  std::ofstream(records[1]) << bare.dump();
  const auto again = run_mpmstab("sweep " + spec.string() + " --out " + out.string());
  EXPECT_NE(again.output.find("2 cache records failed"), std::string::npos) << again.output;
  EXPECT_EQ(read(out / "quick.json"), report);
  // 4. Untouched records are served from the cache.
  const auto third = run_mpmstab("sweep " + spec.string() + " --out " + out.string());
  EXPECT_NE(third.output.find("0 computed, 2 from the cache"), std::string::npos) << third.output;
  EXPECT_EQ(third.output.find("failed"), std::string::npos) << third.output;
}

TEST_F(Files, TheStreamedHistoryEqualsTheKeptOne) {
  mpmstab::RunParams p = mpmstab::test_support::quick_case();
  p.observe.history = true;
  p.observe.history_stride = 7;
  const mpmstab::RunResult kept = mpmstab::run(p);
  std::vector<mpmstab::HistoryRow> streamed;
  p.observe.history = false;
  const mpmstab::RunResult r =
      mpmstab::run(p, nullptr, [&](const mpmstab::HistoryRow& h) { streamed.push_back(h); });
  EXPECT_TRUE(r.history.empty());
  ASSERT_EQ(streamed.size(), kept.history.size());
  ASSERT_GT(streamed.size(), 10u);
  for (std::size_t i = 0; i < streamed.size(); ++i) {
    EXPECT_EQ(streamed[i].step, kept.history[i].step);
    EXPECT_EQ(streamed[i].error, kept.history[i].error);
    EXPECT_EQ(streamed[i].crossings, kept.history[i].crossings);
  }
}

// The fuzz seeds reach both answers of the cache reader: the committed record of the fuzz
// target's case passes every check, the other case's record (another key) is rejected.
TEST_F(Files, TheCacheFuzzSeedsPassAndFailAsIntended) {
  mpmstab::RunParams p = mpmstab::test_support::quick_case();
  p.E = 4;
  p.A = 0.01;
  p.dt = 1e-3;
  p.T = 0.01;
  p.cells = 10;
  p.observe.dt_stable = false;
  p.observe.crossings = false;
  const fs::path seeds = fs::path(MPMSTAB_SOURCE_DIR) / "tests/fuzz/seeds/cache";
  const auto good = mpmstab::ResultCache::check(read(seeds / "gimp.json"), "gimp.json", p);
  EXPECT_TRUE(good.record.has_value());
  const auto other =
      mpmstab::ResultCache::check(read(seeds / "mpm_other_case.json"), "mpm_other_case.json", p);
  EXPECT_TRUE(other.rejected);
}

// A record stored before a column existed is read with the value every run then had, where the
// record now puts it: a vibration run cached without "tip_load" reads tip_load 0 just before
// "policy", as a fresh record of the same case has it; every other value is kept.
TEST_F(Files, ACachedRecordWithoutTheTipLoadColumnIsReadWithItsValue) {
  mpmstab::RunParams p = mpmstab::test_support::quick_case();
  p.scene = mpmstab::SceneKind::vibration;
  p.T = 0.01;
  const nlohmann::ordered_json fresh = mpmstab::to_json(mpmstab::run(p));
  ASSERT_EQ(fresh["tip_load"], 0.0);
  const mpmstab::ResultCache cache(dir / "cache");
  cache.store(p, nlohmann::ordered_json{{"result", fresh}, {"provenance", {{"by", "test"}}}});
  const fs::path file = dir / "cache" / (mpmstab::case_key(p) + ".json");
  // The record as an earlier version wrote it: no "tip_load", checksummed as it was.
  auto old = nlohmann::ordered_json::parse(read(file));
  old["result"].erase("tip_load");
  old.erase("checksum");
  old["checksum"] = mpmstab::fnv1a_hex(mpmstab::canonical_parameters(p) + "\n" + old.dump());
  const auto found = mpmstab::ResultCache::check(old.dump(), file, p);
  ASSERT_TRUE(found.record.has_value());
  EXPECT_EQ((*found.record)["result"], fresh);
  std::vector<std::string> keys, fresh_keys;
  for (const auto& [key, value] : (*found.record)["result"].items())
    keys.push_back(key);
  for (const auto& [key, value] : fresh.items())
    fresh_keys.push_back(key);
  EXPECT_EQ(keys, fresh_keys);
}

// Two plots of one figure at once: each draws in a private staging folder, so neither reads the
// other's half-written image; both succeed and leave no staging folder behind.
TEST_F(Files, TwoPlotsOfOneFigureAtOnceDoNotCollide) {
  const std::string spec = std::string(MPMSTAB_SOURCE_DIR) + "/experiments/fig3.json";
  const std::string out = (dir / "out").string();
  ASSERT_EQ(run_mpmstab("sweep " + spec + " --out " + out).status, 0);
  mpmstab::test_support::CliOutcome a{}, b{};
  std::thread first([&] { a = run_mpmstab("plot " + spec + " --out " + out); });
  std::thread second([&] { b = run_mpmstab("plot " + spec + " --out " + out); });
  first.join();
  second.join();
  EXPECT_EQ(a.status, 0) << a.output;
  EXPECT_EQ(b.status, 0) << b.output;
  EXPECT_GT(fs::file_size(dir / "out" / "fig3.png"), 1000u);
  EXPECT_GT(fs::file_size(dir / "out" / "fig3.svg"), 1000u);
  for (const auto& e : fs::directory_iterator(dir / "out")) {
    const std::string name = e.path().filename().string();
    EXPECT_FALSE(name.ends_with(".staging") || name.ends_with(".tmp")) << name;
  }
}

}  // namespace
