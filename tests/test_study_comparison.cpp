// The comparison study: which of our errors is set beside the paper's Max Error, from its own
// spec or from the specs of its inputs, and the options it refuses; a meaningless run is never
// counted as agreeing; the sections of the paper's Figs. 1-3, from synthetic inputs.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <nlohmann/json.hpp>
#include <set>
#include <string>

#include "agreement/comparison.hpp"
#include "study_rows.hpp"
#include "support.hpp"

using Outcome = mpmstab::test_support::CliOutcome;
using mpmstab::test_support::run_mpmstab;

namespace {

// mpmstab compare --error-at: which of our errors is set beside the paper's Max Error.
class CompareErrorAt : public ::testing::Test {
 protected:
  std::filesystem::path dir =
      std::filesystem::temp_directory_path() / ("mpmstab_compare_" + std::to_string(::getpid()));
  void SetUp() override {
    std::filesystem::remove_all(dir);
    std::filesystem::create_directories(dir);
    std::ofstream(dir / "paper.csv") << "A,E,dt,method,dt_stable,max_error,confidence,evidence\n"
                                        "0.015,4,1e-3,GIMP,2e-3,1e-5,high,\n"
                                        "0.015,4,1e-3,MPM,5e-3,5e-5,high,\n";
    std::ofstream(dir / "t.json") << R"({"name": "t", "report": "table1",
        "reference": "paper.csv", "record": ["error_over_time", "dt_stable"],
        "defaults": {"E": 4, "A": 0.015, "T": 1, "dt": 1e-3},
        "cases": [{"method": "gimp"}, {"method": "mpm"}]})";
  }
  void TearDown() override { std::filesystem::remove_all(dir); }
  std::string read(const std::filesystem::path& p) {
    std::ifstream in(p);
    return std::string(std::istreambuf_iterator<char>(in), {});
  }
};

TEST_F(CompareErrorAt, ChoosesTheErrorComparedWithThePapers) {
  const std::string out = " --out " + (dir / "out").string();
  ASSERT_EQ(run_mpmstab("sweep " + (dir / "t.json").string() + out).status, 0);
  const auto rows = nlohmann::json::parse(read(dir / "out/t.json"))["cases"];
  const double at_T = rows[0]["max_error"].get<double>();
  const double over_time = rows[0]["max_error_over_time"].get<double>();
  ASSERT_NE(at_T, over_time);
  auto shown = [](double v) {  // as the report prints it
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.1e", v);
    std::string s = buf;
    const auto e = s.find("e-0");
    return e == std::string::npos ? s : s.erase(e + 2, 1);
  };

  Outcome o = run_mpmstab("compare " + (dir / "t.json").string() + out);
  ASSERT_EQ(o.status, 0) << o.output;
  std::string md = read(dir / "out/comparison.md");
  EXPECT_NE(md.find("max error at T (`max_error`)"), std::string::npos);
  EXPECT_NE(md.find("| " + shown(at_T) + " |"), std::string::npos) << shown(at_T);
  // The variants study is of the studies tier: linked from each class, never read.
  EXPECT_NE(md.find("are in the studies tier (`make studies`): [variants.md#"), std::string::npos);

  o = run_mpmstab("compare " + (dir / "t.json").string() + out + " --error-at max_over_time");
  ASSERT_EQ(o.status, 0) << o.output;
  md = read(dir / "out/comparison.md");
  EXPECT_NE(md.find("max error over the run (`max_error_over_time`"), std::string::npos);
  EXPECT_NE(md.find("| " + shown(over_time) + " |"), std::string::npos) << shown(over_time);

  // A bad value is refused, naming the option.
  o = run_mpmstab("compare " + (dir / "t.json").string() + out + " --error-at end");
  EXPECT_EQ(o.status, 2);
  EXPECT_NE(o.output.find("--error-at: unknown value 'end' (expected T or max_over_time)"),
            std::string::npos)
      << o.output;
  o = run_mpmstab("compare --help");
  EXPECT_EQ(o.status, 0);
  EXPECT_NE(o.output.find("--error-at"), std::string::npos);
}

// The same through the comparison's own spec, which finds table1.json beside it.
TEST_F(CompareErrorAt, TheComparisonSpecReadsTheTableBesideIt) {
  std::ofstream(dir / "table1.json") << R"({"name": "table1", "report": "table1",
      "reference": "paper.csv", "record": ["error_over_time", "dt_stable"],
      "defaults": {"E": 4, "A": 0.015, "T": 1, "dt": 1e-3},
      "cases": [{"method": "gimp"}, {"method": "mpm"}]})";
  std::ofstream(dir / "comparison.json") << R"({"name": "comparison", "report": "comparison"})";
  const std::string out = " --out " + (dir / "out").string();
  Outcome o = run_mpmstab("compare " + (dir / "comparison.json").string() + out);
  EXPECT_EQ(o.status, 2) << o.output;  // table1 has not been run into out/
  EXPECT_NE(o.output.find("table1.json does not exist"), std::string::npos) << o.output;
  ASSERT_EQ(run_mpmstab("sweep " + (dir / "table1.json").string() + out).status, 0);
  o = run_mpmstab("compare " + (dir / "comparison.json").string() + out +
                  " --error-at max_over_time");
  ASSERT_EQ(o.status, 0) << o.output;
  EXPECT_NE(read(dir / "out/comparison.md").find("max error over the run (`max_error_over_time`"),
            std::string::npos);
  // sweep writes the same report as compare does without options.
  ASSERT_EQ(run_mpmstab("compare " + (dir / "comparison.json").string() + out).status, 0);
  const std::string by_compare = read(dir / "out/comparison.md");
  std::filesystem::remove(dir / "out/comparison.md");
  ASSERT_EQ(run_mpmstab("sweep " + (dir / "comparison.json").string() + out).status, 0);
  EXPECT_EQ(read(dir / "out/comparison.md"), by_compare);
}

}  // namespace

namespace mpmstab {
namespace {

namespace fs = std::filesystem;
using ojson = nlohmann::ordered_json;
using test_support::fail_row;
using test_support::line_with;
using test_support::meaningless_row;
using test_support::study_row;

// A meaningless run survived to T, but its answer is as large as the solution: it agrees with
// neither of the paper's verdicts and is counted on its own.
TEST(ComparisonVerdicts, AMeaninglessRowIsNotCountedAsAgreeing) {
  PaperCell stable{paper_value("2e-3"), paper_value("1e-5"), "high", "", true};
  PaperCell unstable{paper_value("*"), paper_value("*"), "high", "", true};
  ojson row = study_row("gimp", 4);
  row["max_error"] = 1.2e-5;  // within a factor 3 of the paper's: agrees while stable
  CellVerdict v = classify(row, &stable, {}, ErrorAt::T);
  EXPECT_EQ(v.cls, "agree-stable");
  EXPECT_TRUE(v.agrees());

  meaningless_row(row);
  for (const PaperCell* paper : {&stable, &unstable}) {
    v = classify(row, paper, {}, ErrorAt::T);
    EXPECT_EQ(v.cls, "ours-meaningless");
    EXPECT_FALSE(v.agrees());
    EXPECT_FALSE(v.same_verdict());
    EXPECT_FALSE(v.error_ratio);
    EXPECT_FALSE(v.dt_stable_ratio);
    AgreementCounts counts;
    counts.add(v);
    EXPECT_EQ(counts.verdicts_compared, 1);
    EXPECT_EQ(counts.verdicts_agree, 0);
    EXPECT_EQ(counts.meaningless, 1);
    EXPECT_EQ(counts.errors_compared, 0);
  }
  EXPECT_EQ(classify(row, &stable, {}, ErrorAt::T).verdict, "paper stable, ours meaningless");
  const ComparisonClass* k = find_class("ours-meaningless");
  ASSERT_NE(k, nullptr);
  EXPECT_NE(k->kind, ClassKind::agreement);
}

// The classes come from one list, each with a definition of what its predicate decides; every
// class a failure can be put in is on it, and the predicates are tested in the order the
// definitions state.
TEST(ComparisonClasses, OneListDefinesEveryClassThePredicatesReturn) {
  std::set<std::string> ids;
  const std::string table = comparison_classes_markdown();
  for (const ComparisonClass& k : comparison_classes()) {
    EXPECT_TRUE(ids.insert(k.id).second) << k.id;
    EXPECT_FALSE(k.title.empty()) << k.id;
    EXPECT_GT(k.definition.size(), k.title.size()) << k.id;
    EXPECT_NE(
        table.find(std::string("| `") + k.id + "` | " + k.title + " | " + k.definition + " |"),
        std::string::npos)
        << k.id;
  }
  EXPECT_FALSE(explained_definition().empty());

  // A failed run of the bar, paper stable, at c dt / h = C against a spectral limit of 0.756
  // and, for gimp A = 0.015, a scan edge of 0.9.
  const CourantEdges edges = {{{"gimp", Key(0.015, "A")}, 0.9}};
  auto failed = [](const char* method, double C, const char* reason) {
    ojson r = study_row(method, 4);
    r["courant"] = C;
    r["courant_spectral"] = 0.756;
    fail_row(r, reason);
    return r;
  };
  const std::vector<std::pair<ojson, std::string>> cases = {
      {failed("gimp", 0.8, "left_domain"), "above-spectral-limit"},  // above the limit first
      {failed("mpm", 1.0, "nonpositive_F"), "above-spectral-limit"},
      {failed("gimp", 0.756, "nonpositive_F"), "other-failure"},  // at the limit, below the edge
      {failed("gimp", 0.5, "left_domain"), "gimp-wall-exit"},
      {failed("mpm", 0.5, "nonpositive_F"), "mpm-crossing-failure"},
      {failed("mpm", 0.5, "left_domain"), "other-failure"},
  };
  for (const auto& [row, cls] : cases) {
    EXPECT_EQ(failure_class(row, edges), cls) << row.dump();
    EXPECT_TRUE(ids.count(failure_class(row, edges)));
  }
  // With an edge at or below the run's C (and the run at or below the limit): above-our-edge.
  const CourantEdges low_edge = {{{"gimp", Key(0.015, "A")}, 0.5}};
  EXPECT_EQ(failure_class(failed("gimp", 0.5, "left_domain"), low_edge), "above-our-edge");
}

// The comparison written from synthetic inputs: two Table 1 cells and the three figures, with
// the paper's figures transcribed beside its Table 1.
class ComparisonFigures : public ::testing::Test {
 protected:
  fs::path dir = fs::temp_directory_path() / ("mpmstab_cmp_figures_" + std::to_string(::getpid()));
  Spec table1;
  StudyInputs inputs;

  void SetUp() override {
    fs::remove_all(dir);
    fs::create_directories(dir);
    std::ofstream(dir / "paper.csv") << "A,E,dt,method,dt_stable,max_error,confidence,evidence\n"
                                        "0.015,4,1e-3,GIMP,2e-3,1e-5,high,\n"
                                        "0.015,4,1e-3,MPM,5e-3,5e-5,high,\n";
    write_figures("8500");
    std::ofstream(dir / "table1.json") << R"({"name": "table1", "report": "table1",
        "reference": "paper.csv", "record": ["error_over_time", "dt_stable"],
        "defaults": {"E": 4, "A": 0.015, "T": 1, "dt": 1e-3},
        "cases": [{"method": "gimp"}, {"method": "mpm"}]})";
    table1 = load_spec(dir / "table1.json");

    ojson gimp = study_row("gimp", 4), mpm = study_row("mpm", 4);
    gimp["dt"] = mpm["dt"] = 1e-3;
    gimp["max_error"] = 1.2e-5;  // agrees with the paper's 1e-5
    meaningless_row(mpm);        // would agree by its error at T, but is meaningless
    mpm["max_error"] = 5e-5;
    input("table1", {gimp, mpm}).spec = &table1;

    // Figs. 1 and 2: the same case, failing at step 11440 where the paper's run reaches T.
    ojson fig2 = figure_row(1e-5);
    fail_row(fig2, "left_domain");
    fig2["steps"] = fig2["failure_step"] = 11440;
    fig2["failure_time"] = 0.1144;
    fig2["max_error_over_time"] = 0.108;
    fig2["crossings"] = 22880;  // 2 per step
    fig2["dt_stable_min"] = 5e-8;
    ojson& doc2 = input("fig2", {fig2}).doc;
    doc2["history"] = ojson::array();
    for (int step : {20, 40, 60, 80, 100, 120, 5000, 11420, 11439}) {
      doc2["history"].push_back({{"step", step},
                                 {"time", step * 1e-5},
                                 {"error", step == 5000 ? 0.108 : 1e-3},
                                 {"dt_stable", step == 11420 ? 5e-8 : 1e-6},
                                 {"crossings", step}});
    }
    // Fig. 3: failing at step 14, ten times Fig. 2's step. By each time both histories record
    // (every 20th step of Fig. 2, each step of Fig. 3), it has crossed as often as Fig. 2's run;
    // its error is Fig. 2's up to t = 8e-4 and ten times it from t = 1e-3 on.
    ojson fig3 = figure_row(1e-4);
    fail_row(fig3, "nonpositive_F");
    fig3["steps"] = fig3["failure_step"] = 14;
    fig3["failure_time"] = 1.4e-3;
    fig3["crossings"] = 420;
    input("fig3", {fig3}).doc["history"] = fig3_history(1);

    // The variant runs of Fig. 2's case: periodic boundaries reach T with an error below A, the
    // ghost nodes reach T as a meaningless run.
    ojson periodic = figure_row(1e-5), ghost = figure_row(1e-5);
    periodic["bc"] = "periodic";
    periodic["steps"] = 100000;
    ghost["walls"] = "ghost";
    ghost["steps"] = 100000;
    meaningless_row(ghost);
    ghost["max_error_over_time"] = 0.15;
    input("fig2_variants", {fig2, periodic, ghost});
  }
  void TearDown() override { fs::remove_all(dir); }

  // Fig. 3's history: at step s (t = s 1e-4), `crossing_factor` times the crossings of Fig. 2's
  // run by then (10 s), an error of 1e-3 up to step 8, 1e-2 from step 10 on, and a bound that
  // shrinks to its last step, 13, before the failure at step 14.
  static ojson fig3_history(int crossing_factor) {
    ojson h = ojson::array();
    for (int step = 1; step <= 13; ++step) {
      h.push_back({{"step", step},
                   {"time", step * 1e-4},
                   {"error", step >= 10 ? 1e-2 : 1e-3},
                   {"dt_stable", 1e-6 / step},
                   {"crossings", crossing_factor * 10 * step}});
    }
    return h;
  }
  std::string claims_csv() {
    std::ifstream in(dir / "out/comparison_claims.csv");
    return std::string(std::istreambuf_iterator<char>(in), {});
  }

  // The transcription of the figures, with Fig. 3's failure at `fig3_steps`.
  void write_figures(const std::string& fig3_steps) {
    std::ofstream(dir / "figures.csv")
        << "figure,method,E,A,dt,quantity,value,confidence,section,evidence\n"
           "fig1,GIMP,1e4,6e-2,1e-5,outcome,survived,high,section 5.2,'end of integration'\n"
           "fig1,GIMP,1e4,6e-2,1e-5,steps,100000,high,section 5.2,'end of integration'\n"
           "fig2,GIMP,1e4,6e-2,1e-5,outcome,survived,medium,section 5.2,'Figure 2 shows'\n"
           "fig2,GIMP,1e4,6e-2,1e-5,steps,100000,medium,section 5.2,'Figure 2 shows'\n"
           "fig2,GIMP,1e4,6e-2,1e-5,peak_error,?,,Fig. 2,only in the plot\n"
           "fig3,GIMP,1e4,6e-2,1e-4,outcome,unstable,high,section 5.2,'the calculation fails'\n"
           "fig3,GIMP,1e4,6e-2,1e-4,steps,"
        << fig3_steps
        << ",medium,section 5.2,'the calculation fails'\n"
           "fig3,GIMP,1e4,6e-2,1e-4,bound_min_step,"
        << fig3_steps
        << ",medium,section 5.2,'shrinks at that point'\n"
           "fig3,GIMP,1e4,6e-2,1e-4,crossing_errors,more than fig2,medium,section 5.2,"
           "'more grid-crossing errors'\n";
  }
  // The bar with E = 1e4 (c = 100) on 100 cells: c dt / h = 1e4 dt.
  static ojson figure_row(double dt) {
    ojson r = study_row("gimp", 1e4);
    r["A"] = 0.06;
    r["dt"] = dt;
    r["courant"] = 1e4 * dt;
    r["courant_spectral"] = 0.756;  // GIMP, USL, FLIP, 2 particles per cell (spectral.md)
    for (const auto& [key, value] : {std::pair{"position_update", "grid"},
                                     {"walls", "clip"},
                                     {"transfer", "flip"},
                                     {"update", "usl"},
                                     {"body_force_time", "start"}}) {
      r[key] = value;
    }
    return r;
  }
  StudyInput& input(const std::string& name, const std::vector<ojson>& rows) {
    StudyInput& in = inputs[name];
    in.doc["cases"] = rows;
    return in;
  }
  std::string comparison() {
    fs::create_directories(dir / "out");
    write_comparison(inputs, dir / "out");
    std::ifstream in(dir / "out/comparison.md");
    return std::string(std::istreambuf_iterator<char>(in), {});
  }
  // The part of the report from a figure's heading to the next one.
  static std::string section(const std::string& md, const std::string& figure) {
    const auto at = md.find("<a id=\"" + figure + "\"></a>");
    if (at == std::string::npos) return "";
    return md.substr(at, md.find("<a id=\"fig", at + 1) - at);
  }
};

TEST_F(ComparisonFigures, SectionsSetThePapersObservablesBesideOurs) {
  const std::string md = comparison();
  ASSERT_NE(md.find("## Figures 1-3: the paper's observables beside ours"), std::string::npos);

  const std::string fig2 = section(md, "fig2");
  ASSERT_NE(fig2.find("### Fig. 2: gimp, E = 10000, A = 0.06, dt = 1e-5"), std::string::npos)
      << fig2;
  EXPECT_EQ(
      line_with(fig2, "| run |"),
      "| run | reaches T | \\* left_domain at step 11440 (t = 1.1e-1) | differ: ours fails |");
  EXPECT_EQ(line_with(fig2, "| steps |"),
            "| steps | 100000 | 11440 of 100000 | differ: ours 0.11x |");
  EXPECT_EQ(line_with(fig2, "| peak error over time |"),
            "| peak error over time | not stated | 1.1e-1 = 1.8 A (step 5000) | – |");
  EXPECT_EQ(line_with(fig2, "| eq. (108) bound, minimum |"),
            "| eq. (108) bound, minimum | not stated | 5.0e-8 (step 11420) | – |");
  EXPECT_NE(line_with(fig2, "| eq. (108) bound, smallest at |")
                .find("step 11420 (failure at step 11440); 0.05 x its median"),
            std::string::npos)
      << fig2;
  EXPECT_EQ(line_with(fig2, "| grid crossings |"),
            "| grid crossings | not stated | 22880 by t = 1.1e-1 (the run's end) | – |");
  EXPECT_NE(fig2.find("Class: [gimp-wall-exit](#gimp-wall-exit)"), std::string::npos) << fig2;
  EXPECT_NE(fig2.find("- 'Figure 2 shows'"), std::string::npos) << fig2;

  // Fig. 1 is not run; its variant runs are Fig. 2's, shown under Fig. 2.
  const std::string fig1 = section(md, "fig1");
  EXPECT_NE(fig1.find("*Our run of it (`experiments/fig1.json`) has not been run"),
            std::string::npos)
      << fig1;
  // A stable run is shown with its error over time per A and its accuracy class.
  EXPECT_NE(fig2.find("| bc = periodic | stable, accurate (0.00017 A) | 100000 |"),
            std::string::npos)
      << fig2;
  EXPECT_NE(fig2.find("1 of 3 of these runs reproduce the paper's run: bc = periodic."),
            std::string::npos)
      << fig2;
  EXPECT_NE(fig2.find("Reaching T only as meaningless runs (error over time at least A): walls "
                      "= ghost (2.5 A)."),
            std::string::npos)
      << fig2;

  // Fig. 3: both fail, ours far sooner: the class of our failure (Courant 1). Its bound is
  // smallest at the last step before its failure, where the paper has it. Against Fig. 2 at
  // equal times, not per step: as many crossings at each of the 6 times both record, and an
  // error per crossing more than 3 times Fig. 2's at 2 of them; but those times span 0.14% of
  // the paper's run (8500 steps of 1e-4): not tested, and the claims count no time.
  const std::string fig3 = section(md, "fig3");
  EXPECT_EQ(line_with(fig3, "| run |"),
            "| run | fails | \\* nonpositive_F at step 14 (t = 1.4e-3) | agree |");
  EXPECT_EQ(line_with(fig3, "| steps |"), "| steps | 8500 | 14 of 10000 | differ: ours 0.0016x |");
  const std::string bound = line_with(fig3, "| eq. (108) bound, smallest at |");
  EXPECT_NE(bound.find("| step 8500, the paper's failure | step 13 (failure at step 14; the last "
                       "step recorded);"),
            std::string::npos)
      << bound;
  EXPECT_EQ(bound.substr(bound.rfind(" | ")), " | agree: both at the failure |") << bound;
  EXPECT_EQ(line_with(fig3, "| grid crossings by equal times, against Fig. 2 |"),
            "| grid crossings by equal times, against Fig. 2 | more grid-crossing errors than Fig. "
            "2 | more at 0 of 6 times (6 within a factor 3, 0 fewer; t = 2.0e-4 to 1.2e-3; ours / "
            "theirs 1 to 1) | not tested: 0.14% of the paper's run |");
  EXPECT_EQ(line_with(fig3, "| error in u per grid crossing by equal times, against Fig. 2 |"),
            "| error in u per grid crossing by equal times, against Fig. 2 | more grid-crossing "
            "errors than Fig. 2 | more at 2 of 6 times (4 within a factor 3, 0 fewer; t = 2.0e-4 "
            "to 1.2e-3; ours / theirs 1 to 10) | not tested: 0.14% of the paper's run |");
  EXPECT_EQ(line_with(fig3, "| 1.2e-3 |"), "| 1.2e-3 | 120 | 120 | 1.0e-2 | 1.0e-3 | 10 |");
  EXPECT_NE(fig3.find("They span 0.14% of the paper's run of Fig. 3 (to t = 8.5e-1; Fig. 3's "
                      "error in u reaches 0.17 A there, Fig. 2's 0.017 A), less than the 33% that "
                      "tests the paper's text: the rows read *not tested*."),
            std::string::npos)
      << fig3;
  EXPECT_EQ(fig3.find("per step)"), std::string::npos) << fig3;
  EXPECT_NE(claims_csv().find("fig3-crossings-vs-fig2,vacuous,"), std::string::npos)
      << claims_csv();
  EXPECT_NE(claims_csv().find("fig3-error-per-crossing-vs-fig2,vacuous,"), std::string::npos);
  EXPECT_NE(fig3.find("Class: [above-spectral-limit](#above-spectral-limit)"), std::string::npos)
      << fig3;
  EXPECT_NE(fig3.find("*No variant runs of this case have been run"), std::string::npos) << fig3;

  EXPECT_NE(md.find("[fig1](#fig1): not run; [fig2](#fig2): gimp-wall-exit; [fig3](#fig3): "
                    "above-spectral-limit"),
            std::string::npos);
}

TEST_F(ComparisonFigures, MoreCrossingsAtEqualTimesTurnTheVerdictAndTheClaim) {
  // The paper's run of Fig. 3 failing at step 20 (t = 2e-3): the times both record span 60% of it.
  write_figures("20");
  inputs["fig3"].doc["history"] = fig3_history(4);
  const std::string fig3 = section(comparison(), "fig3");
  EXPECT_NE(line_with(fig3, "| grid crossings by equal times, against Fig. 2 |")
                .find("| more at 6 of 6 times (0 within a factor 3, 0 fewer;"),
            std::string::npos)
      << fig3;
  EXPECT_EQ(
      line_with(fig3, "| grid crossings by equal times, against Fig. 2 |")
          .substr(line_with(fig3, "| grid crossings by equal times, against Fig. 2 |").size() - 9),
      "| agree |");
  EXPECT_NE(claims_csv().find("fig3-crossings-vs-fig2,yes,"), std::string::npos) << claims_csv();
  // Four times the crossings with the same errors: a quarter of the error per crossing early on.
  EXPECT_NE(claims_csv().find("fig3-error-per-crossing-vs-fig2,no,"), std::string::npos);
}

TEST_F(ComparisonFigures, AFigureWithoutAHistoryIsNotComparedAtEqualTimes) {
  inputs["fig3"].doc.erase("history");
  const std::string fig3 = section(comparison(), "fig3");
  EXPECT_NE(fig3.find("| no time both runs record | – |"), std::string::npos) << fig3;
  EXPECT_NE(fig3.find("share no recorded time"), std::string::npos) << fig3;
  EXPECT_NE(claims_csv().find("fig3-crossings-vs-fig2,vacuous,"), std::string::npos)
      << claims_csv();
}

// A cell is explained when its rerun with one choice changed alone (periodic boundaries, in the
// walls experiment) agrees with the paper; the report counts per class, and says how many are
// left unexplained.
TEST_F(ComparisonFigures, ACellIsExplainedOnlyByARerunThatAgrees) {
  ojson periodic = study_row("mpm", 4);
  periodic["dt"] = 1e-3;
  periodic["bc"] = "periodic";
  periodic["max_error"] = 6e-5;  // within a factor 3 of the paper's 5e-5
  input("walls", {periodic});
  std::string md = comparison();
  EXPECT_EQ(line_with(md, "](#ours-meaningless) |")
                .substr(line_with(md, "](#ours-meaningless) |").find(") | ")),
            ") | 1 | 1 of 1 | 0 | 1 of 1 |");
  EXPECT_NE(md.find("Of the 1 cells that disagree with the paper, a rerun explains 1 and leaves "
                    "0 unexplained"),
            std::string::npos);
  EXPECT_NE(md.find("**Explained by a rerun:** 1 of 1 (0 unexplained; the walls experiment "
                    "reruns 1 of 1 with periodic boundaries): mpm E=4 A=0.015 dt=1e-3."),
            std::string::npos)
      << md;

  // A rerun that is itself meaningless reaches T but does not agree: the cell stays unexplained.
  meaningless_row(inputs["walls"].doc["cases"][0]);
  md = comparison();
  EXPECT_EQ(line_with(md, "](#ours-meaningless) |")
                .substr(line_with(md, "](#ours-meaningless) |").find(") | ")),
            ") | 1 | 0 of 1 | 1 | 1 of 1 |");
  EXPECT_NE(md.find("a rerun explains 0 and leaves 1 unexplained"), std::string::npos);
  EXPECT_NE(claims_csv().find("every-disagreement-explained,"), std::string::npos);
  // A rerun on another grid is another case: it reruns nothing.
  inputs["walls"].doc["cases"][0]["cells"] = 10;
  md = comparison();
  EXPECT_EQ(line_with(md, "](#ours-meaningless) |")
                .substr(line_with(md, "](#ours-meaningless) |").find(") | ")),
            ") | 1 | 0 of 1 | 1 | 0 of 1 |");
}

// eq108's runs of the cells on a coarser grid, against the paper's dt stable: the summary and
// the dt_stable section say how many are within the factor, and name each cell beyond it.
TEST_F(ComparisonFigures, ACoarserGridsBoundIsSetAgainstThePapersColumn) {
  ojson within = study_row("gimp", 4), beyond = study_row("mpm", 4);
  for (ojson* r : {&within, &beyond}) {
    (*r)["dt"] = 1e-3;
    (*r)["cells"] = 10;
  }
  within["dt_stable_min"] = 1.5e-3;  // 0.75 times the paper's 2e-3
  beyond["dt_stable_min"] = 5e-4;    // 0.1 times the paper's 5e-3
  input("eq108", {within, beyond});
  const std::string md = comparison();
  EXPECT_EQ(line_with(md, "| our dt_stable / paper's on a grid of 10 cells"),
            "| our dt_stable / paper's on a grid of 10 cells (h = 0.1, [eq108.md](eq108.md)) | "
            "within a factor 3 in 1 of 2 cells ([below](#dt-stable)) |");
  EXPECT_NE(md.find("gives the paper's column within a factor 3 in 1 of 2 cells where both are "
                    "measured (A = 0.015; c T = 2; 10 cells; bar): ours / paper 0.1 to 0.75, 0.75 "
                    "in those within it. Beyond it: mpm E=4 A=0.015 dt=1e-3, 0.1 times the "
                    "paper's 5.0e-3, transcribed with high confidence."),
            std::string::npos)
      << md;
}

TEST_F(ComparisonFigures, AChangedPaperValueChangesTheVerdict) {
  std::string fig3 = section(comparison(), "fig3");
  EXPECT_EQ(line_with(fig3, "| steps |"), "| steps | 8500 | 14 of 10000 | differ: ours 0.0016x |");
  EXPECT_NE(fig3.find("Class: [above-spectral-limit]"), std::string::npos) << fig3;

  write_figures("20");
  fig3 = section(comparison(), "fig3");
  EXPECT_EQ(line_with(fig3, "| steps |"), "| steps | 20 | 14 of 10000 | agree |");
  EXPECT_NE(fig3.find("Class: [agree-unstable]"), std::string::npos) << fig3;
}

TEST_F(ComparisonFigures, AMeaninglessRunAgreesWithNeitherVerdict) {
  std::string md = comparison();
  // Table 1: the meaningless MPM cell is counted on its own, not with the agreeing one.
  EXPECT_EQ(line_with(md, "| stability verdicts agreeing |"),
            "| stability verdicts agreeing | 1 of 2 (every cell with a readable paper value, the "
            "sensitive ones by their verdict as run: the cells table1.md counts) |");
  EXPECT_EQ(line_with(md, "| ours meaningless (agreeing with neither verdict) |"),
            "| ours meaningless (agreeing with neither verdict) | 1 of 2 |");
  EXPECT_EQ(line_with(md, "| paper stable |"), "| paper stable | 1 | 1 | 0 |");
  EXPECT_NE(line_with(md, "| 4 | 0.015 | 1e-3 | mpm |").find("| stable | meaningless |"),
            std::string::npos);
  EXPECT_NE(line_with(md, "| 4 | 0.015 | 1e-3 | mpm |").find("[ours-meaningless]"),
            std::string::npos);
  std::ifstream csv(dir / "out/comparison.csv");
  const std::string verdicts(std::istreambuf_iterator<char>(csv), {});
  EXPECT_NE(verdicts.find("mpm,4,0.015,0.001,\"paper stable, ours meaningless\",ours-meaningless"),
            std::string::npos)
      << verdicts;

  // A figure whose run reaches T as a meaningless run does not agree with the paper's.
  ojson& fig2 = inputs["fig2"].doc["cases"][0];
  fig2 = figure_row(1e-5);
  fig2["steps"] = 100000;
  meaningless_row(fig2);
  md = comparison();
  const std::string section2 = section(md, "fig2");
  EXPECT_EQ(line_with(section2, "| run |"),
            "| run | reaches T | meaningless (survived; error over time reached A) | differ: ours "
            "meaningless |");
  EXPECT_NE(section2.find("Class: [ours-meaningless]"), std::string::npos) << section2;
}

}  // namespace
}  // namespace mpmstab
