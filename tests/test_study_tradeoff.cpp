// The trade study's reading of its rows: cost in particle-steps (the Pareto front and the
// cheapest setting for each accuracy, named only once its runs at the paper's largest amplitude
// and over 4 x c T pass), only a stable run reaching an accuracy, the runs of each policy by how
// they ended, each parameter's stable range with a 1.5x margin of stable rows and naming them, no
// recommendation of its own (advice.md's), every claim saying where it was measured, and a figure
// whose data and title count the runs it draws.
#include <gtest/gtest.h>

#include <algorithm>
#include <set>
#include <sstream>

#include "choice/advice_rule.hpp"
#include "csv.hpp"
#include "study_rows.hpp"

namespace mpmstab {
namespace {

using ojson = nlohmann::ordered_json;
using test_support::line_with;
using test_support::study_row;

ojson fixed_run(double dt, double error, int steps, int particles = 200) {
  ojson r = study_row("gimp", 4);
  r["dt"] = dt;
  r["max_error_over_time"] = error;
  r["steps"] = steps;
  r["particles"] = particles;
  return r;
}

// A run under `policy` ("cfl", "adaptive") with its parameter C or s at `value`.
ojson policy_run(const std::string& method, double E, const std::string& policy, double value) {
  ojson r = study_row(method, E);
  r["policy"] = policy;
  r["dt"] = nullptr;
  r[policy == "cfl" ? "cfl_factor" : "safety"] = value;
  return r;
}

ojson failed(ojson r, const std::string& reason) {
  test_support::fail_row(r, reason);
  return r;
}

ojson meaningless(ojson r) {
  test_support::meaningless_row(r);
  return r;
}

std::string markdown(const std::vector<ojson>& rows) {
  return test_support::study_report("tradeoff", rows).markdown;
}

// The verifying runs of row `of`, as the engine tags them: at A = 0.05 with an error over time of
// `larger` times the row's error / A, and over 4 x c T with `longer` times its error.
std::vector<ojson> verifying(const ojson& row, std::size_t of, double larger = 1,
                             double longer = 1) {
  ojson big = row, long_run = row;
  big["A"] = 0.05;
  big["max_error_over_time"] = row["max_error_over_time"].get<double>() / 0.015 * 0.05 * larger;
  long_run["T"] = row["T"].get<double>() * 4;
  long_run["cT"] = row["cT"].get<double>() * 4;
  long_run["max_error_over_time"] = row["max_error_over_time"].get<double>() * longer;
  big[kFollowUpOf] = long_run[kFollowUpOf] = of;
  big[kFollowUpRole] = "A = 0.05";
  long_run[kFollowUpRole] = "4 x c T";
  return {big, long_run};
}

// Every row's verifying runs, all passing.
std::vector<ojson> all_verified(const std::vector<ojson>& rows) {
  std::vector<ojson> out;
  for (std::size_t i = 0; i < rows.size(); ++i)
    if (rows[i]["outcome"] == "stable")
      for (const ojson& v : verifying(rows[i], i))
        out.push_back(v);
  return out;
}

TEST(TradeoffStudy, ParetoFrontAndCheapestSettingRankByParticleSteps) {
  std::vector<ojson> rows = {
      fixed_run(1e-3, 2e-4, 1000),       // 2e5 particle-steps, reaches 1e-3 only
      fixed_run(1e-4, 5e-6, 4000),       // 8e5, the only one to reach 1e-5
      fixed_run(2e-4, 5e-4, 6000),       // 1.2e6: dominated by dt=1e-3
      fixed_run(5e-5, 9e-5, 2000),       // 4e5: reaches 1e-4 more cheaply than dt=1e-4
      fixed_run(3e-4, 8e-5, 500, 1600),  // fewest steps, but 8e5 particle-steps: dominated
      fixed_run(4e-4, 8e-6, 1000, 800),  // 8e5 as dt=1e-4: equal cost, larger error
      fixed_run(1e-5, 1e-7, 100)};       // cheapest and best, but meaningless: reaches nothing
  test_support::meaningless_row(rows[6]);
  const std::string md = test_support::study_report("tradeoff", rows, all_verified(rows)).markdown;

  const std::string cheapest = line_with(md, "| 4 |");
  EXPECT_NE(cheapest.find("| gimp fixed dt=1e-3: 2.0e-4 in 2.0e5 particle-steps (1000 steps); "
                          "verified, A = 0.05: 1.3e-2 A, 4 x c T: 1.3e-2 A"),
            std::string::npos)
      << cheapest;
  EXPECT_NE(cheapest.find("| gimp fixed dt=5e-5: 9.0e-5 in 4.0e5 particle-steps (2000 steps); "),
            std::string::npos)
      << cheapest;
  // dt=1e-4 and dt=4e-4 cost the same; the smaller error ranks first.
  EXPECT_NE(cheapest.find("| gimp fixed dt=1e-4: 5.0e-6 in 8.0e5 particle-steps (4000 steps); "),
            std::string::npos)
      << cheapest;

  for (const char* on_front : {"dt=1e-3", "dt=5e-5", "dt=1e-4"}) {
    EXPECT_NE(line_with(md, std::string("| gimp fixed ") + on_front + " |").find("**yes**"),
              std::string::npos)
        << on_front;
  }
  for (const char* off_front : {"dt=2e-4", "dt=3e-4", "dt=4e-4", "dt=1e-5"}) {
    EXPECT_EQ(line_with(md, std::string("| gimp fixed ") + off_front + " |").find("**yes**"),
              std::string::npos)
        << off_front;
  }
  EXPECT_NE(line_with(md, "| gimp fixed dt=3e-4 |").find("| 500 | 8.0e5 |"), std::string::npos);
  EXPECT_NE(md.find("The cheapest setting for a target accuracy, in particle-steps, that passes "
                    "its verifying runs is gimp fixed in 3 of the 3 (E, target) pairs"),
            std::string::npos)
      << md;
}

// The cheapest run reaching a target is named only when it is stable within the target at the
// paper's largest amplitude (the same error over time / A) and over 4 x c T; else the cheapest
// that is, with the cheaper ones that failed and where.
TEST(TradeoffStudy, TheCheapestSettingIsNamedOnlyOnceItsVerifyingRunsPass) {
  const std::vector<ojson> rows = {fixed_run(1e-3, 2e-4, 1000), fixed_run(5e-4, 3e-4, 2000),
                                   fixed_run(2e-4, 4e-4, 5000), fixed_run(1e-4, 5e-4, 10000)};
  // The verifying runs of rows 0 to 2, row 2's at A = 0.05 with `larger` times its error / A.
  auto follow_ups = [&](double larger) {
    std::vector<ojson> out;
    for (std::size_t i = 0; i < 3; ++i)
      for (const ojson& v : verifying(rows[i], i, i == 2 ? larger : 1, i == 1 ? 4 : 1))
        out.push_back(v);
    test_support::fail_row(out[0], "nonpositive_F");  // dt = 1e-3 fails at A = 0.05
    return out;  // dt = 5e-4: over 4 x c T, 4 x 3e-4 / 0.015 A = 0.08 A > the target 0.0667 A
  };
  // dt = 2e-4 at A = 0.05: 1.99 x 4e-4 / 0.015 A = 0.053 A, within the same error / A, 0.0667 A.
  const auto report = test_support::study_report("tradeoff", rows, follow_ups(1.99));
  const std::string cell = line_with(report.markdown, "| 4 |");
  EXPECT_NE(cell.find("| gimp fixed dt=2e-4: 4.0e-4 in 1.0e6 particle-steps (5000 steps); "
                      "verified, A = 0.05: 5.3e-2 A, 4 x c T: 2.7e-2 A; cheaper, failed: gimp "
                      "fixed dt=1e-3 (A = 0.05: unstable); gimp fixed dt=5e-4 (4 x c T: stable, "
                      "error over time 8.0e-2 A > the target 0.0667 A) |"),
            std::string::npos)
      << cell;
  // At 3.3 x its error / A, 0.088 A, dt = 2e-4 fails too: none of the 3 cheapest passed (the
  // fourth is not tried).
  const std::string none = line_with(markdown(rows), "| 4 |");
  EXPECT_NE(
      line_with(test_support::study_report("tradeoff", rows, follow_ups(3.3)).markdown, "| 4 |")
          .find("| none passed of the 3 cheapest of 4 reaching it: gimp fixed dt=1e-3 (A = "
                "0.05: unstable); gimp fixed dt=5e-4 (4 x c T: stable, error over time "
                "8.0e-2 A > the target 0.0667 A); gimp fixed dt=2e-4 (A = 0.05: stable, "
                "error over time 8.8e-2 A > the target 0.0667 A) |"),
      std::string::npos);
  // Without its verifying runs no setting is named.
  EXPECT_NE(none.find("| none passed of the 3 cheapest of 4 reaching it: gimp fixed dt=1e-3 (A = "
                      "0.05: not run)"),
            std::string::npos)
      << none;
  // The claim counts the pairs with a verified setting and says where it was measured.
  const auto claim = std::find_if(report.claims.begin(), report.claims.end(),
                                  [](const Claim& c) { return c.id == "cheapest-verified-bar"; });
  ASSERT_NE(claim, report.claims.end());
  EXPECT_EQ(render(*claim, claim->evidence),
            "1 of 1 pairs; 0 without a passing setting among their 3 cheapest");
  EXPECT_EQ(claim->measured_on, "A = 0.015 and 0.05; c T = 2 and 8; 100 cells; bar");
}

// Each setting named is said to lie beyond its method and policy's stable range with a margin
// where it does.
TEST(TradeoffStudy, ACheapestSettingBeyondItsStableRangeSaysSo) {
  std::vector<ojson> rows;
  for (double C : {0.25, 0.5, 1.0}) {
    ojson r = policy_run("gimp", 4, "cfl", C);
    r["steps"] = int(200 / C);
    r["max_error_over_time"] = 2e-5;
    rows.push_back(r);
  }
  test_support::fail_row(rows[2], "nonpositive_F");  // C = 1 fails: the range stops at 0.25
  const auto md = test_support::study_report("tradeoff", rows, all_verified(rows)).markdown;
  EXPECT_NE(line_with(md, "| gimp cfl |").find("| C up to 0.25 |"), std::string::npos) << md;
  EXPECT_NE(line_with(md, "| 4 |")
                .find("| gimp cfl C=0.5: 2.0e-5 in 8.0e4 particle-steps (400 steps); verified, "
                      "A = 0.05: 1.3e-3 A, 4 x c T: 1.3e-3 A; outside gimp cfl's stable range "
                      "with margin (C up to 0.25) |"),
            std::string::npos)
      << md;
  EXPECT_NE(md.find("in 2 of the 2 (E, target) pairs some run reaches; at 0 of them none of the "
                    "3 cheapest passes (verified on A = 0.015 and 0.05; c T = 2 and 8; 100 cells; "
                    "bar). In 2 of the 2 pairs with one, the setting named lies beyond its method "
                    "and policy's stable range with a margin"),
            std::string::npos)
      << md;
}

// Per scene, E and target the kVerified cheapest runs reaching it are asked for again at the
// paper's largest amplitude and at 4 x T, each once.
TEST(TradeoffStudy, TheCheapestRunsAreAskedForAtTheLargestAmplitudeAndFourTimesTheLength) {
  std::vector<ojson> rows;
  for (int k = 0; k < 12; ++k)
    rows.push_back(fixed_run(1e-3 / (k + 1), 1e-5 * (k + 1), 1000 * (k + 1)));
  ojson other = rows[0];
  other["scene"] = "steffen";
  rows.push_back(other);
  Spec spec;
  spec.study = find_study("tradeoff");
  for (const auto& r : rows) {
    CaseSpec c;
    c.params.E = r["E"].get<double>();
    c.params.A = r["A"].get<double>();
    c.params.T = r["T"].get<double>();
    spec.cases.push_back(c);
  }
  const StudyInputs inputs;
  const auto asked = spec.study->follow_up(FollowUpContext{spec, rows, inputs});
  // The 3 cheapest of the bar's twelve, and the one of steffen: two runs each.
  ASSERT_EQ(asked.size(), 8u);
  std::set<std::size_t> of;
  for (const FollowUp& f : asked) {
    of.insert(f.of);
    if (f.role == "A = 0.05") {
      EXPECT_EQ(f.params.A, kPaperLargestA);
      EXPECT_EQ(f.params.T, 1.0);
    } else {
      EXPECT_EQ(f.role, "4 x c T");
      EXPECT_EQ(f.params.A, 0.015);
      EXPECT_EQ(f.params.T, 4.0);
    }
  }
  EXPECT_EQ(of, (std::set<std::size_t>{0, 1, 2, 12}));
}

// The paper's largest amplitude, at which every cheapest setting is verified, is the largest A of
// the transcribed Table 1.
TEST(TradeoffStudy, ThePapersLargestAmplitudeIsTableOnesLargest) {
  const CsvTable paper =
      read_csv(std::filesystem::path(MPMSTAB_SOURCE_DIR) / "reference" / "paper" / "table1.csv");
  double largest = 0;
  for (const auto& row : paper.rows)
    largest = std::max(largest, std::stod(row.at("A")));
  EXPECT_EQ(largest, kPaperLargestA);
}

// Every claim says where the runs that decide it lie.
TEST(TradeoffStudy, EveryClaimSaysWhereItWasMeasured) {
  std::vector<ojson> rows;
  for (double E : {4.0, 64.0, 1000.0}) {
    for (const char* m : {"gimp", "mpm"}) {
      rows.push_back(policy_run(m, E, "cfl", 0.5));
      rows.push_back(policy_run(m, E, "adaptive", 1));
      ojson fine = policy_run(m, E, "cfl", 0.5);
      fine["cells"] = 400;
      rows.push_back(fine);
    }
  }
  const auto report = test_support::study_report("tradeoff", rows, all_verified(rows));
  ASSERT_EQ(report.claims.size(), 5u);
  for (const auto& c : report.claims)
    EXPECT_NE(c.measured_on.find("A = 0.015"), std::string::npos) << c.id << ": " << c.measured_on;
}

TEST(TradeoffStudy, NoWallTimeIsReadAndTheReportLinksWhereTheyAre) {
  std::vector<ojson> rows = {fixed_run(1e-3, 2e-4, 1000), fixed_run(1e-4, 5e-6, 4000)};
  rows[0]["wall_seconds"] = 987.654;  // a column rows no longer have: never read
  rows[1]["wall_seconds"] = 0.000123;
  const auto report = test_support::study_report("tradeoff", rows);
  for (const std::string& out : {report.markdown, *report.data_csv, report.json.dump()}) {
    EXPECT_EQ(out.find("987"), std::string::npos) << out;
    EXPECT_EQ(out.find("0.000123"), std::string::npos) << out;
    EXPECT_EQ(out.find("wall_seconds"), std::string::npos) << out;
  }
  EXPECT_NE(report.markdown.find("[performance.md](performance.md)"), std::string::npos);
  EXPECT_EQ(report.markdown, test_support::study_report("tradeoff", rows).markdown);
}

TEST(TradeoffStudy, NoStableRangeWhereARowUpTo1_5TimesTheValueIsUnstableOrMeaningless) {
  std::vector<ojson> rows;
  for (double E : {4.0, 1e4}) {
    for (double s : {1.0, 2.0, 3.0, 4.0, 6.0}) {
      // GIMP fails at s = 4 at E = 1e4 only (s = 6 survives there); MPM's s = 3 is meaningless
      // at E = 4.
      ojson g = policy_run("gimp", E, "adaptive", s);
      rows.push_back(E == 1e4 && s == 4 ? failed(g, "nonpositive_F") : g);
      ojson m = policy_run("mpm", E, "adaptive", s);
      rows.push_back(E == 4 && s == 3 ? meaningless(m) : m);
    }
  }
  const std::string md = markdown(rows);
  // s = 3 would need every row up to s = 4.5 (checked at s = 6), and s = 4 fails.
  const std::string gimp = line_with(md, "| gimp adaptive |");
  EXPECT_NE(gimp.find("| s up to 2 |"), std::string::npos) << gimp;
  EXPECT_NE(
      gimp.find("| s = 3: gimp adaptive s=4 at E = 10000 (bar): \\* nonpositive_F at step 10"),
      std::string::npos)
      << gimp;
  // s = 2 would need s = 3, which is meaningless at E = 4.
  const std::string mpm = line_with(md, "| mpm adaptive |");
  EXPECT_NE(mpm.find("| s up to 1 |"), std::string::npos) << mpm;
  EXPECT_NE(mpm.find("| s = 2: mpm adaptive s=3 at E = 4 (bar): meaningless"), std::string::npos)
      << mpm;
  // A stable range is a description: no setting of these rows (no spectral limit recorded) is
  // recommended.
  EXPECT_EQ(md.find("| 4 | 1e-3 |"), std::string::npos) << md;

  // With the smallest value failing, no value.
  rows = {failed(policy_run("mpm", 4, "cfl", 0.1), "dt_collapse"), policy_run("mpm", 4, "cfl", 0.2),
          policy_run("mpm", 4, "cfl", 0.4)};
  const std::string none = line_with(markdown(rows), "| mpm cfl |");
  EXPECT_NE(none.find("| no value | – | – | C = 0.1: mpm cfl C=0.1 at E = 4 (bar): \\* "
                      "dt_collapse"),
            std::string::npos)
      << none;

  // The stable range rests on every scene: a meaningless run of the second scene withholds it.
  rows = {policy_run("gimp", 4, "cfl", 0.1), policy_run("gimp", 4, "cfl", 0.25),
          policy_run("gimp", 4, "cfl", 0.5)};
  for (ojson r : std::vector<ojson>(rows)) {
    r["scene"] = "steffen";
    rows.push_back(r["cfl_factor"] == 0.25 ? meaningless(r) : r);
  }
  const std::string scenes = line_with(markdown(rows), "| gimp cfl |");
  EXPECT_NE(scenes.find("| no value | – | – | C = 0.1: gimp cfl C=0.25 at E = 4 "
                        "(steffen): meaningless"),
            std::string::npos)
      << scenes;
}

TEST(TradeoffStudy, StableRangeNamesItsRowsAndTheValueCheckedBeyondIt) {
  std::vector<ojson> rows;
  for (double E : {4.0, 1e4}) {
    for (double C : {0.1, 0.25, 0.5}) {
      rows.push_back(policy_run("gimp", E, "cfl", C));
    }
  }
  ojson fine = policy_run("gimp", 4, "cfl", 0.5);
  fine["cells"] = 400;
  rows.push_back(fine);
  const std::string md = markdown(rows);
  const std::string gimp = line_with(md, "| gimp cfl |");
  EXPECT_NE(gimp.find("| C up to 0.25 | 7 rows: gimp cfl C = 0.1..0.5 at E = 4 and 10000 (A = "
                      "0.015; c T = 2 and 100; 100 and 400 cells; bar), all stable | C = 0.5 "
                      "(1.5x = 0.375) |"),
            std::string::npos)
      << gimp;
  // C = 0.5 is stable everywhere, but nothing was run at 0.75 or beyond.
  EXPECT_NE(gimp.find("| C = 0.5: no row at 1.5x (C = 0.75) at E = 4 and 10000; margin not "
                      "checked |"),
            std::string::npos)
      << gimp;

  // A margin run at one E only does not check the other.
  rows.push_back(policy_run("gimp", 4, "cfl", 0.8));
  const std::string one_E = line_with(markdown(rows), "| gimp cfl |");
  EXPECT_NE(one_E.find("| C up to 0.25 |"), std::string::npos) << one_E;
  EXPECT_NE(one_E.find("| C = 0.5: no row at 1.5x (C = 0.75) at E = 10000; margin not checked"),
            std::string::npos)
      << one_E;

  // A single value has nothing beyond it: no stable range.
  const std::string single =
      line_with(markdown({policy_run("gimp", 4, "cfl", 0.5)}), "| gimp cfl |");
  EXPECT_NE(single.find("| no value |"), std::string::npos) << single;
  EXPECT_NE(single.find("margin not checked"), std::string::npos) << single;
}

// The study measures and links to advice.md for every recommendation: it makes none of its own.
TEST(TradeoffStudy, RecommendsNothingAndLinksToTheAdvice) {
  const auto report = test_support::study_report("tradeoff", {policy_run("gimp", 4, "cfl", 0.5)});
  EXPECT_NE(report.markdown.find("[advice.md](advice.md)"), std::string::npos);
  for (const auto& c : report.claims)
    EXPECT_NE(c.id.rfind("recommended-", 0), 0u) << c.id;
  EXPECT_FALSE(report.json.contains("recommended"));
}

TEST(TradeoffStudy, RunsThatStoppedAreCountedPerPolicyAndReason) {
  ojson min_run = policy_run("gimp", 4, "adaptive", 4);
  min_run["policy"] = "min";
  min_run["cfl_factor"] = 0.5;
  const std::vector<ojson> rows = {fixed_run(1e-4, 1e-5, 10000),
                                   meaningless(fixed_run(1e-3, 1e-5, 1000)),
                                   failed(policy_run("gimp", 4, "cfl", 0.9), "nonpositive_F"),
                                   policy_run("gimp", 4, "cfl", 0.5),
                                   failed(policy_run("gimp", 4, "adaptive", 16), "dt_collapse"),
                                   failed(policy_run("gimp", 4, "adaptive", 8), "dt_collapse"),
                                   failed(policy_run("gimp", 4, "adaptive", 4), "left_domain"),
                                   policy_run("gimp", 4, "adaptive", 1),
                                   failed(min_run, "dt_collapse")};
  const auto report = test_support::study_report("tradeoff", rows);
  const std::string& md = report.markdown;
  EXPECT_NE(md.find("| policy | runs | stable | meaningless | unstable | dt_collapse | left_domain "
                    "| nonpositive_F |"),
            std::string::npos)
      << md;
  EXPECT_NE(md.find("| fixed | 2 | 1 | 1 | 0 | 0 | 0 | 0 |"), std::string::npos) << md;
  EXPECT_NE(md.find("| cfl | 2 | 1 | 0 | 1 | 0 | 0 | 1 |"), std::string::npos) << md;
  EXPECT_NE(md.find("| adaptive | 4 | 1 | 0 | 3 | 2 | 1 | 0 |"), std::string::npos) << md;
  EXPECT_NE(md.find("| min | 1 | 0 | 0 | 1 | 1 | 0 | 0 |"), std::string::npos) << md;

  const ojson& endings = report.json["endings"]["bar"];
  EXPECT_EQ(endings["adaptive"]["failure_reasons"]["dt_collapse"], 2);
  EXPECT_EQ(endings["min"]["failure_reasons"]["dt_collapse"], 1);
  EXPECT_EQ(endings["cfl"]["failure_reasons"]["dt_collapse"], 0);
  EXPECT_EQ(endings["cfl"]["failure_reasons"]["nonpositive_F"], 1);
  EXPECT_EQ(endings["fixed"]["meaningless"], 1);
}

TEST(TradeoffStudy, DataFileHasOneRowPerDrawnRunAndTheTitleCountsThem) {
  std::vector<ojson> rows = {fixed_run(1e-4, 1e-5, 10000),
                             failed(fixed_run(1e-3, 1e-5, 1000), "non_finite"),
                             meaningless(fixed_run(3e-4, 1e-5, 3334)),
                             policy_run("gimp", 64, "cfl", 0.5),
                             failed(policy_run("mpm", 64, "adaptive", 8), "dt_collapse"),
                             policy_run("mpm", 64, "adaptive", 1)};
  ojson fine = policy_run("gimp", 64, "cfl", 0.5);
  fine["cells"] = 400;
  fine["particles"] = 800;
  fine["steps"] = 800;
  rows.push_back(fine);
  ojson other_scene = fixed_run(1e-4, 1e-5, 10000);  // in the tables only
  other_scene["scene"] = "steffen";
  rows.push_back(other_scene);

  const std::string data = *test_support::study_report("tradeoff", rows).data_csv;
  const auto lines = test_support::data_lines(data);
  ASSERT_EQ(lines.size(), 4u) << data;
  EXPECT_NE(
      data.find("E,panel,series,method,policy,cells,grid,particle_steps,steps,error,pareto\n"),
      std::string::npos)
      << data;
  // The last column marks the Pareto front of each E: at E = 64 the run on 400 cells is cheaper
  // at the same error, so it alone is on it.
  EXPECT_EQ(lines[0], "4,0,0,1,0,100,0,2000000,10000,1e-05,1");
  EXPECT_EQ(lines[1], "64,1,1,1,1,100,0,2000000,10000,1e-05,0");
  EXPECT_EQ(lines[2], "64,1,2,0,2,100,0,2000000,10000,1e-05,0");
  EXPECT_EQ(lines[3], "64,1,3,1,1,400,1,640000,800,1e-05,1");

  Spec spec;
  spec.name = std::string("tradeoff");
  ojson doc = {{"cases", rows}};
  const std::string subtitle = find_study("tradeoff")->figure_subtitle(spec, doc);
  EXPECT_EQ(subtitle,
            "4 of 7 runs of the scene bar drawn; left out: 2 unstable, 1 meaningless; every run "
            "of every scene is in tradeoff.md");
  EXPECT_EQ(subtitle.find('\''), std::string::npos);
  EXPECT_NE(data.find("# 4 of 7 runs of the scene bar drawn"), std::string::npos) << data;
}

}  // namespace
}  // namespace mpmstab

namespace mpmstab {
namespace {

// Every run of the bar under the CFL rule at C = 0.5 has a periodic twin among the follow-up
// runs (after the confirming runs): the table sets the two errors side by side.
TEST(TradeoffStudy, ThePeriodicTwinShowsWhatTheWallsCost) {
  ojson run = test_support::study_row("gimp", 4);
  run["policy"] = "cfl";
  run["cfl_factor"] = 0.5;
  run["dt"] = nullptr;
  ojson twin = run;
  twin["bc"] = "periodic";
  twin["max_error_over_time"] = 5e-6;
  twin[kFollowUpOf] = 0;  // asked for the run of row 0, as its periodic twin
  twin[kFollowUpRole] = "periodic twin";
  const auto report = test_support::study_report("tradeoff", {run}, {twin});
  EXPECT_NE(report.markdown.find("| gimp | 4 | 100 | 1.0e-5 | 5.0e-6 | 0.5 |"), std::string::npos)
      << report.markdown;
  // A follow-up asked for another row, or in another role, is not this run's twin.
  ojson stray = twin;
  stray[kFollowUpRole] = "ensemble member";
  EXPECT_EQ(
      test_support::study_report("tradeoff", {run}, {stray}).markdown.find("What the walls cost"),
      std::string::npos);
  // Without the follow-up runs the section is left out.
  EXPECT_EQ(test_support::study_report("tradeoff", {run}).markdown.find("What the walls cost"),
            std::string::npos);
}

}  // namespace
}  // namespace mpmstab
