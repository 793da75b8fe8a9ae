// Figures that tell the truth: each figure's data file holds what its title counts, and its
// gnuplot script reads the columns the data file has.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <numeric>
#include <sstream>
#include <string>
#include <vector>

#include "study.hpp"
#include "study_rows.hpp"
#include "support.hpp"

namespace mpmstab {
namespace {

using ojson = nlohmann::ordered_json;
using test_support::data_lines;
using test_support::study_row;

// The header line of a CSV (the first line that is not a '#' line).
std::string header_of(const std::string& csv) {
  std::istringstream in(csv);
  for (std::string line; std::getline(in, line);) {
    if (!line.empty() && line[0] != '#') return line;
  }
  return "";
}

std::string script(const std::string& name) {
  std::ifstream in(std::filesystem::path(MPMSTAB_SOURCE_DIR) / "experiments" / (name + ".gp"));
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// The title a figure's study gives the results document {cases, study}.
std::string subtitle(const std::string& study, const std::vector<ojson>& rows,
                     const StudyReport& report) {
  Spec spec;
  spec.name = std::string("s");
  ojson doc;
  doc["cases"] = rows;
  if (!report.json.is_null()) doc["study"] = report.json;
  return find_study(study)->figure_subtitle(spec, doc);
}

TEST(Figures, AHistoryFigureDrawsEveryRecordedStepItsTitleCounts) {
  ojson row = study_row("gimp", 1e4);
  test_support::fail_row(row, "nonpositive_F");
  row["failure_step"] = 3;
  ojson record;
  record["result"] = row;
  record["history"] = ojson::array();
  for (int k = 1; k <= 3; ++k) {
    record["history"].push_back({{"step", k},
                                 {"time", 1e-4 * k},
                                 {"error", 1e-6 * k},
                                 {"dt_stable", 1e-6},
                                 {"crossings", 10 * k}});
  }
  Spec spec;
  spec.name = std::string("fig");
  spec.title = std::string("Fig");
  spec.study = find_study("figure");
  CaseSpec c;
  c.params.E = 1e4;
  c.params.dt = 1e-4;
  spec.cases = {c};
  SweepOutcome outcome;
  outcome.records = {record};
  const std::vector<ojson> rows = {row};
  const std::filesystem::path out = std::filesystem::temp_directory_path();
  const std::string header = "# header\n";
  const StudyInputs inputs;
  const std::vector<ojson> follow_up;
  const StudyReport report =
      spec.study->report(ReportContext{spec, rows, outcome, out, header, inputs, follow_up});
  ASSERT_TRUE(report.data_csv);
  EXPECT_EQ(data_lines(*report.data_csv).size(), 3u);
  const std::string title = subtitle("figure", rows, report);
  EXPECT_NE(title.find("3 recorded steps drawn"), std::string::npos) << title;
  EXPECT_NE(title.find("unstable: nonpositive_F at step 3"), std::string::npos) << title;
  // fig2.gp and fig3.gp read the columns the data file has.
  EXPECT_NE(script("fig2").find(header_of(*report.data_csv)), std::string::npos);
  EXPECT_NE(script("fig3").find(header_of(*report.data_csv)), std::string::npos);
}

TEST(Figures, TheExtremesFigureDrawsEveryCaseOnceAtTheSpotsItsTitleCounts) {
  std::vector<ojson> rows;
  for (double E : {4.0, 64.0, 1e4}) {
    ojson r = study_row("gimp", E);
    rows.push_back(r);  // three cases at one spot (same Courant number and A/h)
  }
  ojson unstable = study_row("mpm", 4);
  test_support::fail_row(unstable, "left_domain");
  rows.push_back(unstable);
  const StudyReport report = test_support::study_report("extremes", rows);
  ASSERT_TRUE(report.data_csv);
  const auto lines = data_lines(*report.data_csv);
  int cases = 0;
  for (const auto& line : lines) {  // method,courant,A_over_h,verdict,cases,name
    const std::string head = line.substr(0, line.rfind(','));
    cases += std::stoi(head.substr(head.rfind(',') + 1));
  }
  EXPECT_EQ(cases, 4);          // every case is drawn
  EXPECT_EQ(lines.size(), 2u);  // at two spots
  const std::string title = subtitle("extremes", rows, report);
  EXPECT_NE(title.find("4 cases at 2 spots"), std::string::npos) << title;
  EXPECT_NE(script("extremes").find(header_of(*report.data_csv)), std::string::npos)
      << header_of(*report.data_csv);
}

// Every figure draws from its committed data with gnuplot printing nothing: no warning (such as
// "difficulty fitting plot titles into key", which extremes.gp once printed) and no error.
TEST(Figures, EveryFigureDrawsFromItsCommittedDataWithoutAWord) {
  namespace fs = std::filesystem;
  const fs::path source = MPMSTAB_SOURCE_DIR;
  const fs::path dir = fs::temp_directory_path() / ("mpmstab_figures_" + std::to_string(getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  const auto listed = test_support::run_program(
      MPMSTAB_BIN, {MPMSTAB_BIN, "list", (source / "experiments").string(), "--figures"});
  ASSERT_EQ(listed.status, 0) << listed.output;
  std::istringstream specs(listed.output);
  int drawn = 0;
  for (std::string spec; std::getline(specs, spec);) {
    const std::string name = fs::path(spec).stem().string();
    for (const std::string& file : {name + ".json", name + "_data.csv"})
      fs::copy_file(source / "results" / file, dir / file);
    const auto plotted =
        test_support::run_program(MPMSTAB_BIN, {MPMSTAB_BIN, "plot", spec, "--out", dir.string()});
    EXPECT_EQ(plotted.status, 0) << name << ": " << plotted.output;
    EXPECT_EQ(plotted.output, "") << name;
    EXPECT_TRUE(fs::exists(dir / (name + ".png"))) << name;
    EXPECT_TRUE(fs::exists(dir / (name + ".svg"))) << name;
    ++drawn;
  }
  EXPECT_GT(drawn, 0);
  fs::remove_all(dir);
}

}  // namespace
}  // namespace mpmstab
