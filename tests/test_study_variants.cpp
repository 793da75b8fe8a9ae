// The variants study's arithmetic on a small synthetic input: per-method counts and medians with
// the comparison's rules, the classes under the default, what each variant fixes and breaks,
// the accounting criterion, and the line comparison.md prints for a class.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "agreement/variants.hpp"
#include "report_util.hpp"
#include "spec.hpp"
#include "study.hpp"
#include "study_rows.hpp"

namespace mpmstab {
namespace {

namespace fs = std::filesystem;
using ojson = nlohmann::ordered_json;

class VariantsStudyTest : public ::testing::Test {
 protected:
  fs::path dir = fs::temp_directory_path() / ("mpmstab_variants_" + std::to_string(::getpid()));
  void SetUp() override {
    fs::remove_all(dir);
    fs::create_directories(dir);
    std::ofstream(dir / "paper.csv") << "A,E,dt,method,dt_stable,max_error,confidence,evidence\n"
                                        "0.015,4,1e-3,GIMP,2e-3,1e-5,high,\n"
                                        "0.015,4,1e-3,MPM,5e-3,5e-5,high,\n"
                                        "0.015,4,1e-4,GIMP,2e-3,1e-5,high,\n"
                                        "0.015,4,1e-4,MPM,5e-3,5e-5,high,\n";
    std::ofstream(dir / "base.json") << R"({"name": "base", "report": "table1",
        "reference": "paper.csv", "record": ["error_over_time", "dt_stable"],
        "defaults": {"E": 4, "A": 0.015, "T": 0.01},
        "cases": [{"method": "gimp", "dt": 1e-3}, {"method": "mpm", "dt": 1e-3},
                  {"method": "gimp", "dt": 1e-4}, {"method": "mpm", "dt": 1e-4}]})";
    std::ofstream(dir / "v.json") << R"({"name": "v", "report": "variants",
        "cases_from": "base.json", "variants": [
          {"name": "default"},
          {"name": "ghost", "set": {"walls": "ghost"}, "methods": ["gimp"]},
          {"name": "pic", "set": {"transfer": "pic"}},
          {"name": "pic+ghost", "set": {"transfer": "pic", "walls": "ghost"}, "methods": ["gimp"]}]})";
    spec = load_spec(dir / "v.json");
  }
  void TearDown() override { fs::remove_all(dir); }

  static ojson stable(const char* method, double error, double steps = 10000,
                      bool meaningless = false) {
    return {{"method", method},
            {"A", 0.015},
            {"outcome", meaningless ? "meaningless" : "stable"},
            {"max_error", error},
            {"max_error_over_time", error * 2},
            {"dt_stable_min", 1e-4},
            {"courant", 0.2},
            {"failure_reason", nullptr},
            {"particles", 1},
            {"steps", steps}};
  }
  static ojson unstable(const char* method, const char* reason) {
    return {{"method", method},
            {"A", 0.015},
            {"outcome", "unstable"},
            {"max_error", nullptr},
            {"max_error_over_time", 1.0},
            {"dt_stable_min", nullptr},
            {"courant", 0.02},
            {"failure_reason", reason},
            {"particles", 1},
            {"steps", 5000}};
  }
  // Rows in spec order: default (gimp 1e-3, mpm 1e-3, gimp 1e-4, mpm 1e-4), ghost (gimp 1e-3,
  // gimp 1e-4), pic (all four), pic+ghost (gimp 1e-3, gimp 1e-4).
  std::vector<ojson> rows(double ghost_gimp_1e4_error) {
    return {// default: agree, MPM error 100x, GIMP error 10x, MPM failure where the paper is stable
            stable("gimp", 2e-5), stable("mpm", 5e-3), stable("gimp", 1e-4),
            unstable("mpm", "nonpositive_F"),
            // ghost: breaks the agreeing cell, brings the GIMP error class into agreement (or not)
            stable("gimp", 1e-3), stable("gimp", ghost_gimp_1e4_error),
            // pic: fixes the MPM error and makes the failing MPM run survive, meaninglessly
            stable("gimp", 2e-5), stable("mpm", 1e-4), stable("gimp", 1e-4),
            stable("mpm", 1e-2, 10000, true),
            // pic+ghost: nothing in agreement
            stable("gimp", 1e-3), stable("gimp", 1e-3)};
  }
  VariantsStudy study(double ghost_gimp_1e4_error) {
    return study_variants(spec, rows(ghost_gimp_1e4_error), read_paper_table1(spec), {});
  }
  Spec spec;
};

TEST_F(VariantsStudyTest, CountsFollowTheComparisonsRules) {
  const VariantsStudy s = study(2e-5);
  ASSERT_EQ(s.variants.size(), 4u);
  EXPECT_EQ(s.baseline, 0u);
  EXPECT_EQ(s.cells, 4);
  EXPECT_EQ(s.class_cells.at("agree-stable"), 1);
  EXPECT_EQ(s.class_cells.at("mpm-error-larger"), 1);
  EXPECT_EQ(s.class_cells.at("gimp-error-larger"), 1);
  EXPECT_EQ(s.class_cells.at("mpm-crossing-failure"), 1);

  const VariantOutcome& def = s.variants[0];
  EXPECT_EQ(def.agreeing, 1);
  EXPECT_EQ(def.breaks, 0);
  const auto& mpm = def.by_method.at("mpm");
  EXPECT_EQ(mpm.cells, 2);
  EXPECT_EQ(mpm.counts.verdicts_agree, 1);
  EXPECT_EQ(mpm.counts.verdicts_compared, 2);
  EXPECT_EQ(mpm.counts.errors_within, 0);
  EXPECT_EQ(mpm.counts.errors_compared, 1);
  EXPECT_DOUBLE_EQ(mpm.particle_steps, 15000);
  const auto& gimp = def.by_method.at("gimp");
  EXPECT_EQ(gimp.counts.errors_within, 1);
  EXPECT_EQ(gimp.counts.errors_compared, 2);
  EXPECT_DOUBLE_EQ(quantile(gimp.counts.error_ratios, 0.5), 6.0);  // ratios 2 and 10
  EXPECT_DOUBLE_EQ(def.particle_steps, 35000);

  // ghost ran the GIMP cells only: it breaks the agreeing one and fixes the error class.
  const VariantOutcome& ghost = s.variants[1];
  EXPECT_EQ(ghost.cells, 2);
  EXPECT_EQ(ghost.by_method.count("mpm"), 0u);
  EXPECT_EQ(ghost.agreeing, 1);
  EXPECT_EQ(ghost.agreeing_under_default, 1);
  EXPECT_EQ(ghost.breaks, 1);
  EXPECT_EQ(ghost.by_class.at("gimp-error-larger").agree, 1);
  EXPECT_EQ(ghost.by_class.count("mpm-error-larger"), 0u);

  // pic: the MPM error within 3x, and the MPM failure becomes a meaningless survivor, which
  // agrees with neither verdict of the paper (a meaningless run is never counted as agreeing).
  const VariantOutcome& pic = s.variants[2];
  EXPECT_EQ(pic.agreeing, 2);
  EXPECT_EQ(pic.breaks, 0);
  EXPECT_EQ(pic.by_class.at("mpm-error-larger").agree, 1);
  EXPECT_EQ(pic.by_class.at("mpm-crossing-failure").agree, 0);
  EXPECT_EQ(pic.by_class.at("mpm-crossing-failure").meaningless, 0);
  EXPECT_EQ(pic.by_class.at("gimp-error-larger").agree, 0);
  EXPECT_EQ(pic.by_method.at("mpm").counts.verdicts_agree, 1);
}

// The figure draws one point per cell where both are stable (kind 0 rows of its data file);
// its title counts exactly those.
TEST_F(VariantsStudyTest, TheFigureTitleCountsThePointsItDraws) {
  const VariantsStudy s = study(2.9e-5);
  int points = 0;
  for (const auto& line : test_support::data_lines(variants_data_csv(s, ""))) {
    const auto first = line.find(',');
    const auto second = line.find(',', first + 1);
    points += line.substr(second + 1, 2) == "0,";
  }
  EXPECT_GT(points, 0);
  nlohmann::ordered_json doc;
  doc["cases"] = rows(2.9e-5);
  doc["study"] = study_to_json(s);
  const std::string title = find_study("variants")->figure_subtitle(spec, doc);
  EXPECT_NE(title.find("Drawn: the " + std::to_string(points) + " of "), std::string::npos)
      << title << " (" << points << " points)";
}

TEST_F(VariantsStudyTest, TheFactor3RuleDecidesACellAtItsEdge) {
  // ours / paper = 2.9 agrees, 3.1 does not: the comparator's rule, not a local one.
  EXPECT_EQ(study(2.9e-5).variants[1].by_class.at("gimp-error-larger").agree, 1);
  const VariantsStudy moved = study(3.1e-5);
  EXPECT_EQ(moved.variants[1].by_class.at("gimp-error-larger").agree, 0);
  EXPECT_EQ(moved.variants[1].agreeing, 0);
  const ojson j = study_to_json(moved);
  EXPECT_EQ(j["classes"]["gimp-error-larger"]["variants"][1]["accounts"], "no");
  EXPECT_EQ(study_to_json(study(2.9e-5))["classes"]["gimp-error-larger"]["variants"][1]["accounts"],
            "yes");
}

// A class outcome: `covered` cells run, `agree` of them in full agreement.
VariantClassOutcome class_of(int covered, int agree) {
  VariantClassOutcome o;
  o.covered = covered;
  o.agree = agree;
  return o;
}

// A variant that brings a failing cell to the paper's verdict but not to its error does not
// account for it: the error ratio is shown beside the verdict agreement.
TEST_F(VariantsStudyTest, AVerdictWithoutTheErrorDoesNotAccountForACell) {
  std::vector<ojson> r = rows(2e-5);
  r[9] = stable("mpm", 1e-2);  // pic: the MPM failure survives, stable, 200 times the paper's
  const VariantsStudy s = study_variants(spec, r, read_paper_table1(spec), {});
  const VariantClassOutcome o = class_outcome(s.variants[2], "mpm-crossing-failure");
  EXPECT_EQ(o.covered, 1);
  EXPECT_EQ(o.verdict_agree, 1);
  EXPECT_EQ(o.agree, 0);
  ASSERT_EQ(o.error_ratios.size(), 1u);
  EXPECT_DOUBLE_EQ(o.error_ratios[0], 200);
  EXPECT_EQ(accounts_for(o, 1), Accounts::no);
  const ojson j = study_to_json(s);
  EXPECT_EQ(j["classes"]["mpm-crossing-failure"]["variants"][2]["accounts"], "no");
  EXPECT_EQ(j["classes"]["mpm-crossing-failure"]["variants"][2]["verdict_agree"], 1);
}

TEST_F(VariantsStudyTest, AccountingCriterionIsHalfOfTheClass) {
  EXPECT_EQ(accounts_for(class_of(4, 2), 4), Accounts::yes);
  EXPECT_EQ(accounts_for(class_of(2, 2), 4),
            Accounts::yes);  // half of the class, from a subset
  EXPECT_EQ(accounts_for(class_of(4, 1), 4), Accounts::partly);
  EXPECT_EQ(accounts_for(class_of(4, 0), 4), Accounts::no);
  EXPECT_EQ(accounts_for(class_of(0, 0), 4), Accounts::not_applicable);
  EXPECT_EQ(accounts_for(class_of(1, 1), 1), Accounts::yes);
}

TEST_F(VariantsStudyTest, ReportIsGeneratedFromTheNumbers) {
  const VariantsStudy s = study(2e-5);
  const ojson j = study_to_json(s);
  EXPECT_EQ(j["default"], "default");
  EXPECT_EQ(j["classes"]["mpm-error-larger"]["cells"], 1);

  const std::string md = variants_markdown(spec, s, false);
  EXPECT_NE(md.find("<a id=\"gimp-error-larger\"></a>"), std::string::npos);
  EXPECT_NE(md.find("<a id=\"above-spectral-limit\"></a>"),
            std::string::npos);  // empty: still there
  EXPECT_NE(md.find("Can account for this class (at least half of its 1 cell reach a max error "
                    "within a factor 3 of the paper's): `ghost` (1 of 1 agree; ours / paper 2; "
                    "the agreeing stable runs' error over time 2.7e-3 A, 0 of 1 not accurate, "
                    "breaking 1 cell"),
            std::string::npos)
      << md;
  EXPECT_NE(md.find("Classes that none accounts for: [mpm-crossing-failure]"), std::string::npos)
      << md;
  EXPECT_NE(md.find("Under the default, 1 of 4 cells agree fully"), std::string::npos) << md;

  const std::string csv = variants_data_csv(s, "");
  EXPECT_NE(csv.find("1,1,1,6,default\n"), std::string::npos) << csv;  // GIMP median of 2 and 10
  EXPECT_NE(csv.find("4,1,2,1,pic+ghost\n"), std::string::npos) << csv;
}

}  // namespace
}  // namespace mpmstab
