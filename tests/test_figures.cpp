// Figures that tell the truth: each figure's data file holds what its title counts, and its
// gnuplot script reads the columns the data file has; and a PNG figure depends only on its data,
// never on the fonts or the font settings of the machine that draws it.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cerrno>
#include <filesystem>
#include <fstream>
#include <numeric>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

extern char** environ;

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

// The bytes of a file ("" when absent).
std::string bytes_of(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// This process's environment with `overrides` ("NAME=value") put in place of the variables of
// those names.
std::vector<std::string> environment_with(const std::vector<std::string>& overrides) {
  std::vector<std::string> env;
  for (char** e = environ; *e != nullptr; ++e) {
    const std::string entry = *e;
    const std::string name = entry.substr(0, entry.find('=') + 1);
    bool replaced = false;
    for (const auto& o : overrides)
      replaced = replaced || o.rfind(name, 0) == 0;
    if (!replaced) env.push_back(entry);
  }
  env.insert(env.end(), overrides.begin(), overrides.end());
  return env;
}

// Runs build/mpmstab with `args` (no shell) in the folder `cwd` and the environment `env`; its
// exit status and all it prints.
test_support::CliOutcome run_mpmstab_in(const std::filesystem::path& cwd,
                                        std::vector<std::string> args,
                                        std::vector<std::string> env) {
  args.insert(args.begin(), MPMSTAB_BIN);
  return test_support::run_program(MPMSTAB_BIN, std::move(args), cwd.string(), std::move(env));
}

// A fontconfig configuration: the machine's own (/etc/fonts/fonts.conf) followed by `rules`.
std::string fontconfig_with(const std::string& rules) {
  return "<?xml version=\"1.0\"?>\n<!DOCTYPE fontconfig SYSTEM \"urn:fontconfig:fonts.dtd\">\n"
         "<fontconfig>\n  <include ignore_missing=\"yes\">/etc/fonts/fonts.conf</include>\n" +
         rules + "</fontconfig>\n";
}

// A PNG figure is the same, byte for byte, on every machine that has the project's packages:
// drawn once in this process's environment and then on "machines" whose fonts or font settings
// differ, it does not change. Each other machine is an environment of the plot command: a
// fontconfig configuration that makes another installed font (DejaVu Serif, of
// fonts-dejavu-core) the first choice for every family a script may name (sans, Arial, DejaVu
// Sans, the terminal's default), as a machine with other fonts or aliases resolves them
// differently; one with other rendering settings (full hinting, subpixel antialiasing, as
// dpkg-reconfigure fontconfig-config sets them); a user's fontconfig file; and a user's gnuplot
// start-up file that sets the title and label fonts. The SVG, which only names its fonts, is
// required to stay the same as well. The output folders are relative, as in `make figures`.
TEST(Figures, APngDependsOnItsDataNotOnTheMachinesFonts) {
  namespace fs = std::filesystem;
  const fs::path source = MPMSTAB_SOURCE_DIR;
  const fs::path dir = fs::temp_directory_path() / ("mpmstab_fonts_" + std::to_string(getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir / "home" / ".config" / "fontconfig");
  const std::string serif_first =
      "  <match target=\"pattern\">\n"
      "    <edit name=\"family\" mode=\"prepend\" binding=\"strong\">"
      "<string>DejaVu Serif</string></edit>\n  </match>\n";
  std::ofstream(dir / "serif.conf") << fontconfig_with(serif_first);
  std::ofstream(dir / "rendering.conf") << fontconfig_with(
      "  <match target=\"font\">\n"
      "    <edit name=\"hintstyle\" mode=\"assign\"><const>hintfull</const></edit>\n"
      "    <edit name=\"rgba\" mode=\"assign\"><const>rgb</const></edit>\n"
      "    <edit name=\"lcdfilter\" mode=\"assign\"><const>lcdlight</const></edit>\n"
      "  </match>\n");
  std::ofstream(dir / "home" / ".config" / "fontconfig" / "fonts.conf")
      << "<?xml version=\"1.0\"?>\n<fontconfig>\n"
      << serif_first << "</fontconfig>\n";
  std::ofstream(dir / "home" / ".gnuplot")
      << "set title font \"DejaVu Serif,16\"\nset xlabel font \",14\"\n";
  const std::string home = (dir / "home").string();
  const std::vector<std::pair<std::string, std::vector<std::string>>> machines = {
      {"this machine", environment_with({})},
      {"DejaVu Serif first for every family (FONTCONFIG_FILE)",
       environment_with({"FONTCONFIG_FILE=" + (dir / "serif.conf").string()})},
      {"full hinting and subpixel antialiasing (FONTCONFIG_FILE)",
       environment_with({"FONTCONFIG_FILE=" + (dir / "rendering.conf").string()})},
      {"a user's fontconfig file putting DejaVu Serif first (XDG_CONFIG_HOME)",
       environment_with({"XDG_CONFIG_HOME=" + home + "/.config"})},
      {"a user's ~/.gnuplot setting the title and label fonts (HOME)",
       environment_with({"HOME=" + home})},
  };
  // A figure of a title, axis labels, tic labels and a key that draws in a fraction of a second.
  const std::string name = "spectral_edge";
  std::string png;
  std::string svg;
  for (std::size_t m = 0; m < machines.size(); ++m) {
    const std::string folder = "out" + std::to_string(m);
    const fs::path out = dir / folder;
    fs::create_directories(out);
    for (const std::string& file : {name + ".json", name + "_data.csv"})
      fs::copy_file(source / "results" / file, out / file);
    const auto plotted = run_mpmstab_in(
        dir, {"plot", (source / "experiments" / (name + ".json")).string(), "--out", folder},
        machines[m].second);
    ASSERT_EQ(plotted.status, 0) << machines[m].first << ": " << plotted.output;
    EXPECT_EQ(plotted.output, "") << machines[m].first;
    if (m == 0) {
      png = bytes_of(out / (name + ".png"));
      svg = bytes_of(out / (name + ".svg"));
      ASSERT_FALSE(png.empty());
      ASSERT_FALSE(svg.empty());
      continue;
    }
    EXPECT_TRUE(bytes_of(out / (name + ".png")) == png)
        << name << ".png differs on a machine with " << machines[m].first;
    EXPECT_TRUE(bytes_of(out / (name + ".svg")) == svg)
        << name << ".svg differs on a machine with " << machines[m].first;
  }
  fs::remove_all(dir);
}

// Every gnuplot script draws its PNG text in the one font the project's packages install: each
// pngcairo terminal names "DejaVu Sans"; every other font option names it too, directly or
// through the script's variable `face`, which the PNG branch sets to it (the SVG branch names
// the SVG's own font, which only the viewer resolves); and that font's package,
// fonts-dejavu-core, is among the Makefile's DEB_PACKAGES, installed where mpmstab plot looks.
TEST(Figures, EveryScriptNamesTheFontTheDependenciesInstall) {
  namespace fs = std::filesystem;
  const fs::path source = MPMSTAB_SOURCE_DIR;
  const std::string makefile = bytes_of(source / "Makefile");
  const auto begin = makefile.find("DEB_PACKAGES :=");
  ASSERT_NE(begin, std::string::npos);
  std::string packages;
  for (std::size_t at = begin; at < makefile.size();) {
    const auto end = makefile.find('\n', at);
    const std::string line = makefile.substr(at, end - at);
    packages += " " + line + " ";
    if (line.empty() || line.back() != '\\' || end == std::string::npos) break;
    at = end + 1;
  }
  EXPECT_NE(packages.find(" fonts-dejavu-core "), std::string::npos) << packages;
  EXPECT_TRUE(fs::is_regular_file("/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf"));

  const std::regex named_font(R"re(font\s+"([^",]*),)re");
  int scripts = 0;
  for (const auto& entry : fs::directory_iterator(source / "experiments")) {
    if (entry.path().extension() != ".gp") continue;
    ++scripts;
    const std::string file = entry.path().filename().string();
    std::istringstream in(bytes_of(entry.path()));
    bool uses_face = false;
    bool png_face = false;  // `face = "DejaVu Sans"` on the line before the pngcairo terminal
    std::string previous;
    for (std::string line; std::getline(in, line); previous = line) {
      const auto first = line.find_first_not_of(" \t");
      if (first == std::string::npos || line[first] == '#') continue;  // a comment line
      if (line.find("pngcairo") != std::string::npos) {
        EXPECT_NE(line.find("font \"DejaVu Sans,"), std::string::npos) << file << ": " << line;
        png_face = png_face || previous.find("face = \"DejaVu Sans\"") != std::string::npos;
      }
      if (line.find("font face") != std::string::npos) uses_face = true;
      if (line.find("terminal svg") != std::string::npos) continue;
      for (std::sregex_iterator it(line.begin(), line.end(), named_font), end; it != end; ++it) {
        EXPECT_EQ((*it)[1].str(), "DejaVu Sans") << file << ": " << line;
      }
      if (line.find("font \",") != std::string::npos ||
          line.find("font \"\"") != std::string::npos) {
        ADD_FAILURE() << file << ": a font option without a face: " << line;
      }
    }
    if (uses_face) {
      EXPECT_TRUE(png_face) << file << ": `face` is not DejaVu Sans for the PNG";
    }
  }
  EXPECT_GT(scripts, 10);
}

}  // namespace
}  // namespace mpmstab
