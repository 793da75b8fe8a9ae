// The study registry: every spec in experiments/ names a study the program knows and every
// study is used by a spec; `mpmstab list` runs each experiment after the ones it reads; a study
// without cases is written from its inputs; and the "add a study" recipe of
// docs/architecture.md works: one study declaration and one spec, nothing else.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

#include "report.hpp"
#include "spec.hpp"
#include "study.hpp"
#include "support.hpp"
#include "sweep.hpp"

namespace mpmstab {
namespace {

namespace fs = std::filesystem;
using ojson = nlohmann::ordered_json;

// The recipe's example, declared here as a study file would declare it: a report that counts
// the runs that reached T, read from the rows, and a figure-free Markdown body; its index
// paragraph reads that count from what the report published, not counting again.
const StudyRegistration kThrowaway{{
    .name = "throwaway",
    .summary = "how many runs reached T (the architecture recipe's example)",
    .records = {.error_over_time = true},
    .report =
        [](const ReportContext& c) {
          int stable = 0;
          for (const auto& r : c.rows)
            stable += r["outcome"] != "unstable";
          return StudyReport{.markdown = "## Results\n\n" + std::to_string(stable) + " of " +
                                         std::to_string(c.rows.size()) + " runs reached T.\n",
                             .json = {{"stable", stable}}};
        },
    .index =
        [](const Spec& spec, const std::vector<ojson>& rows, const ojson& published) {
          return "**What it shows.** " + std::to_string(rows.size()) + " runs, " +
                 published["stable"].dump() + " reached T: [" + spec.name + ".md](" + spec.name +
                 ".md).\n\n";
        },
}};
// Studies registered by this test program only.
const std::set<std::string> kTestStudies = {"throwaway"};

std::string read(const fs::path& p) {
  std::ifstream in(p);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

std::vector<Spec> project_specs() {
  std::vector<Spec> specs;
  for (const auto& e : fs::directory_iterator(fs::path(MPMSTAB_SOURCE_DIR) / "experiments")) {
    if (e.path().extension() == ".json") specs.push_back(load_spec(e.path()));
  }
  return specs;
}

TEST(StudyRegistry, EverySpecNamesAKnownStudyAndEveryStudyHasASpec) {
  const auto specs = project_specs();
  ASSERT_GE(specs.size(), 14u);
  std::set<std::string> used;
  for (const auto& s : specs) {
    ASSERT_NE(s.study, nullptr) << s.path;
    EXPECT_EQ(find_study(s.study->name), s.study) << s.path;
    EXPECT_EQ(s.path.stem(), s.name) << "a spec's name is its file name";
    used.insert(s.study->name);
  }
  std::set<std::string> known;
  for (const Study* study : all_studies()) {
    if (kTestStudies.count(study->name)) continue;
    known.insert(study->name);
    EXPECT_TRUE(used.count(study->name)) << "no spec in experiments/ uses " << study->name;
    EXPECT_FALSE(study->summary.empty()) << study->name;
    EXPECT_TRUE(study->index) << study->name << " has no paragraph for the index";
    EXPECT_EQ(study->has_cases, static_cast<bool>(study->report)) << study->name;
    EXPECT_EQ(!study->has_cases, static_cast<bool>(study->write_derived)) << study->name;
    EXPECT_EQ(study->figure, static_cast<bool>(study->figure_subtitle)) << study->name;
  }
  EXPECT_EQ(known, used);
  // A study that draws a figure has its script beside the specs that use it.
  for (const auto& s : specs) {
    if (s.study->figure) {
      EXPECT_TRUE(fs::exists(s.path.parent_path() / (s.name + ".gp"))) << s.name;
    }
  }
}

// A follow-up run is found by what it was asked for, the case it serves and its role, in the
// order asked; never by its position among the others.
TEST(FollowUps, AreFoundByTheCaseTheyServeAndTheirRole) {
  auto row = [](ojson of, const char* role, int id) {
    return ojson{{kFollowUpOf, of}, {kFollowUpRole, role}, {"id", id}};
  };
  const std::vector<ojson> follow_up = {row(1, "twin", 0),   row(0, "member", 1),
                                        row(1, "member", 2), row(nullptr, "problem 1", 3),
                                        row(1, "member", 4), ojson{{"id", 5}}};
  auto ids = [&](std::size_t of, const char* role) {
    std::vector<int> out;
    for (const ojson* r : follow_ups_of(follow_up, of, role))
      out.push_back(r->at("id").get<int>());
    return out;
  };
  EXPECT_EQ(ids(1, "member"), (std::vector<int>{2, 4}));
  EXPECT_EQ(ids(0, "member"), (std::vector<int>{1}));
  EXPECT_EQ(ids(1, "twin"), (std::vector<int>{0}));
  EXPECT_EQ(ids(FollowUp::kNoCase, "problem 1"), (std::vector<int>{3}));
  EXPECT_TRUE(ids(2, "member").empty());
  EXPECT_TRUE(ids(0, "twin").empty());
}

TEST(StudyRegistry, AnUnknownStudyIsRefusedWithTheKnownOnes) {
  try {
    parse_spec(R"({"name": "x", "report": "tabel1", "cases": []})", "x.json");
    FAIL() << "accepted";
  } catch (const SpecError& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("x.json: report: unknown value 'tabel1'"), std::string::npos) << m;
    EXPECT_NE(m.find("did you mean 'table1'"), std::string::npos) << m;
    for (const Study* s : all_studies())
      EXPECT_NE(m.find(s->name), std::string::npos) << m;
  }
}

class Studies : public ::testing::Test {
 protected:
  fs::path dir = fs::temp_directory_path() / ("mpmstab_studies_" + std::to_string(::getpid()));
  void SetUp() override {
    fs::remove_all(dir);
    fs::create_directories(dir / "out");
  }
  void TearDown() override { fs::remove_all(dir); }
};

// Every experiment runs after the experiments whose results its study reads, then in the order
// of index_order; the figure list holds exactly the studies that draw one.
TEST_F(Studies, ListRunsEachExperimentAfterItsInputs) {
  const auto o =
      test_support::run_mpmstab("list " + std::string(MPMSTAB_SOURCE_DIR) + "/experiments");
  ASSERT_EQ(o.status, 0) << o.output;
  std::vector<std::string> order;
  std::istringstream in(o.output);
  for (std::string line; std::getline(in, line);)
    order.push_back(fs::path(line).stem().string());
  const auto specs = project_specs();
  ASSERT_EQ(order.size(), specs.size());
  auto at = [&](const std::string& name) {
    return std::find(order.begin(), order.end(), name) - order.begin();
  };
  for (const auto& s : specs) {
    for (const auto& input : s.inputs)
      EXPECT_LT(at(input.name), at(s.name)) << input.name << " must run before " << s.name;
  }
  const auto figures = test_support::run_mpmstab("list " + std::string(MPMSTAB_SOURCE_DIR) +
                                                 "/experiments --figures");
  ASSERT_EQ(figures.status, 0);
  for (const auto& s : specs) {
    EXPECT_EQ(figures.output.find("/" + s.name + ".json") != std::string::npos, s.study->figure)
        << s.name;
  }
  // In another folder too; a spec whose name is not its file name is refused, naming it.
  std::ofstream(dir / "table1.json") << R"({"name": "table1", "report": "table1",
      "reference": "p.csv", "cases": [{"E": 4, "A": 0.01, "method": "gimp", "dt": 1e-3}]})";
  EXPECT_EQ(test_support::run_mpmstab("list " + dir.string()).status, 0);
  std::ofstream(dir / "other.json") << R"({"name": "misnamed", "report": "table1",
      "reference": "p.csv", "cases": [{"E": 4, "A": 0.01, "method": "gimp", "dt": 1e-3}]})";
  const auto misnamed = test_support::run_mpmstab("list " + dir.string());
  EXPECT_EQ(misnamed.status, 2);
  EXPECT_NE(misnamed.output.find("other.json"), std::string::npos) << misnamed.output;
}

// The recipe: a spec naming the throwaway study is swept and reported through the engine with
// nothing but the declaration above.
// The two tiers (docs/engineering.md, "Two tiers"): make reproduce runs the paper's tier, make
// studies the rest with the paper experiments it reads; a paper experiment reads only paper
// experiments, so that no report depends on which tier ran first.
TEST_F(Studies, EachTierRunsWhatItReadsAndThePaperReadsOnlyThePaper) {
  const std::string experiments = std::string(MPMSTAB_SOURCE_DIR) + "/experiments";
  auto listed = [](const std::string& output) {
    std::vector<std::string> names;
    std::istringstream in(output);
    for (std::string line; std::getline(in, line);)
      names.push_back(fs::path(line).stem().string());
    return names;
  };
  const auto paper = test_support::run_mpmstab("list " + experiments + " --tier paper");
  const auto studies = test_support::run_mpmstab("list " + experiments + " --tier studies");
  ASSERT_EQ(paper.status, 0) << paper.output;
  ASSERT_EQ(studies.status, 0) << studies.output;
  const auto specs = project_specs();
  std::map<std::string, const Spec*> by_name;
  for (const auto& s : specs)
    by_name[s.name] = &s;
  const std::vector<std::string> in_paper = listed(paper.output),
                                 in_studies = listed(studies.output);
  const auto has = [](const std::vector<std::string>& v, const std::string& n) {
    return std::find(v.begin(), v.end(), n) != v.end();
  };
  for (const auto& s : specs) {
    // Every experiment is in its tier's list; the paper's list holds only the paper's.
    EXPECT_TRUE(has(s.tier == Tier::paper ? in_paper : in_studies, s.name)) << s.name;
    if (s.tier == Tier::studies) {
      EXPECT_FALSE(has(in_paper, s.name)) << s.name;
    }
    for (const auto& input : s.inputs) {
      if (s.tier == Tier::paper) {
        EXPECT_EQ(by_name.at(input.name)->tier, Tier::paper) << s.name;
      }
      // Each list runs what its experiments read.
      if (has(in_studies, s.name)) {
        EXPECT_TRUE(has(in_studies, input.name)) << input.name;
      }
    }
  }
  // The paper's own experiments: its tables, figures, the peers and the comparison.
  for (const char* n : {"table1", "table2", "fig1", "fig2", "fig3", "peers", "comparison"})
    EXPECT_TRUE(has(in_paper, n)) << n;
  EXPECT_FALSE(has(in_paper, "variants"));

  // A paper experiment that reads a studies experiment is refused, naming it.
  std::ofstream(dir / "table1.json") << R"({"name": "table1", "report": "table1", "tier":
      "studies", "reference": "p.csv", "cases": [{"E": 4, "A": 0.01, "method": "gimp", "dt":
      1e-3}]})";
  std::ofstream(dir / "comparison.json")
      << R"({"name": "comparison", "report": "comparison", "tier": "paper"})";
  const auto refused = test_support::run_mpmstab("list " + dir.string() + " --tier studies");
  EXPECT_EQ(refused.status, 2);
  EXPECT_NE(refused.output.find("comparison.json: a paper experiment reads 'table1'"),
            std::string::npos)
      << refused.output;
  const auto bad = test_support::run_mpmstab("list " + dir.string() + " --tier all");
  EXPECT_EQ(bad.status, 2);
  std::ofstream(dir / "table1.json") << R"({"name": "table1", "report": "table1", "tier":
      "both", "reference": "p.csv", "cases": [{"E": 4, "A": 0.01, "method": "gimp", "dt":
      1e-3}]})";
  const auto unknown = test_support::run_mpmstab("list " + dir.string());
  EXPECT_EQ(unknown.status, 2);
  EXPECT_NE(unknown.output.find("tier: unknown value 'both'"), std::string::npos) << unknown.output;
}

TEST_F(Studies, ANewStudyNeedsOnlyItsDeclarationAndASpec) {
  std::ofstream(dir / "count.json") << R"({"name": "count", "title": "Count",
      "report": "throwaway", "record": ["error_over_time"],
      "defaults": {"T": 0.05, "cells": 20, "dt": 1e-4},
      "cases": [{"E": 4, "A": 0.015, "method": "gimp"}, {"E": 1e4, "A": 0.05,
                 "method": "mpm", "dt": 1e-3}]})";
  const Spec spec = load_spec(dir / "count.json");
  ASSERT_EQ(spec.study->name, "throwaway");
  SweepOptions o;
  o.quiet = true;
  const SweepOutcome outcome = run_sweep(spec, o);
  write_reports(spec, outcome, dir / "out");
  const std::string md = read(dir / "out/count.md");
  const int stable = (outcome.records[0]["result"]["outcome"] != "unstable") +
                     (outcome.records[1]["result"]["outcome"] != "unstable");
  EXPECT_NE(md.find(std::to_string(stable) + " of 2 runs reached T."), std::string::npos) << md;
  const auto doc = ojson::parse(read(dir / "out/count.json"));
  EXPECT_EQ(doc["report"], "throwaway");
  EXPECT_EQ(doc["study"]["stable"], stable);
  EXPECT_TRUE(fs::exists(dir / "out/count.csv"));
  EXPECT_FALSE(fs::exists(dir / "out/count_data.csv"));  // no figure declared
  write_index({spec}, dir / "out");
  EXPECT_NE(read(dir / "out/README.md")
                .find("**What it shows.** 2 runs, " + std::to_string(stable) + " reached T"),
            std::string::npos);
}

// A study without cases (the comparison) is written from its declared inputs; a missing
// required input is named, and nothing is written.
TEST_F(Studies, ADerivedStudyReadsItsDeclaredInputs) {
  std::ofstream(dir / "paper.csv") << "A,E,dt,method,dt_stable,max_error,confidence,evidence\n"
                                      "0.015,4,1e-3,GIMP,2e-3,1e-5,high,\n";
  std::ofstream(dir / "table1.json") << R"({"name": "table1", "report": "table1",
      "reference": "paper.csv", "record": ["error_over_time", "dt_stable"],
      "defaults": {"E": 4, "A": 0.015, "T": 0.1, "dt": 1e-3}, "cases": [{"method": "gimp"}]})";
  std::ofstream(dir / "comparison.json") << R"({"name": "comparison", "report": "comparison"})";
  const std::string out = " --out " + (dir / "out").string();
  auto o = test_support::run_mpmstab("sweep " + (dir / "comparison.json").string() + out);
  EXPECT_EQ(o.status, 2) << o.output;
  EXPECT_NE(o.output.find("table1.json does not exist: run mpmstab sweep"), std::string::npos)
      << o.output;
  EXPECT_FALSE(fs::exists(dir / "out/comparison.md"));
  ASSERT_EQ(test_support::run_mpmstab("sweep " + (dir / "table1.json").string() + out).status, 0);
  o = test_support::run_mpmstab("sweep " + (dir / "comparison.json").string() + out);
  ASSERT_EQ(o.status, 0) << o.output;
  EXPECT_NE(read(dir / "out/comparison.md").find("0.015"), std::string::npos);
  EXPECT_NE(read(dir / "out/comparison.csv").find("gimp,4,0.015,0.001,"), std::string::npos);
  // Its spec takes no cases.
  std::ofstream(dir / "bad.json") << R"({"name": "bad", "report": "comparison",
      "cases": [{"E": 4, "A": 0.015, "method": "gimp", "dt": 1e-3}]})";
  o = test_support::run_mpmstab("sweep " + (dir / "bad.json").string() + out);
  EXPECT_EQ(o.status, 2);
  EXPECT_NE(o.output.find("bad.json: cases: a comparison study has no cases"), std::string::npos)
      << o.output;
}

}  // namespace
}  // namespace mpmstab
