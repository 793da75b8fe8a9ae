// The parts of core/ (core/CMakeLists.txt, docs/architecture.md "The parts of core/"): every
// source lies in one part, includes the solver's headers by part ("step/grid.hpp"), and
// imports only from its own part or the parts below it.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <filesystem>
#include <fstream>
#include <optional>
#include <regex>
#include <string>
#include <vector>

namespace mpmstab {
namespace {

namespace fs = std::filesystem;

// The parts, bottom first.
constexpr std::array<std::string_view, 6> kParts = {"base",      "scenes",   "step",
                                                    "observers", "analysis", "run"};

std::optional<std::size_t> floor_of(std::string_view part) {
  const auto it = std::find(kParts.begin(), kParts.end(), part);
  if (it == kParts.end()) return std::nullopt;
  return std::size_t(it - kParts.begin());
}

struct Include {
  std::string file;    // the including file, relative to core/
  std::string target;  // the quoted include as written
};

// What is wrong with one include in core/: an unqualified or unknown target, or a part above
// the including file's. Empty when it is fine.
std::string layering_issue(const Include& inc) {
  const auto slash = inc.file.find('/');
  const auto from = floor_of(inc.file.substr(0, slash));
  if (slash == std::string::npos || !from) return inc.file + ": not inside a part of core/";
  const auto to_slash = inc.target.find('/');
  if (to_slash == std::string::npos) {
    return inc.file + ": includes \"" + inc.target + "\" without its part";
  }
  const auto to = floor_of(inc.target.substr(0, to_slash));
  if (!to) return inc.file + ": includes \"" + inc.target + "\" from no part of core/";
  if (*to > *from) {
    return inc.file + ": imports upwards, from " + std::string(kParts[*from]) + " to \"" +
           inc.target + "\"";
  }
  return {};
}

std::vector<Include> core_includes() {
  const fs::path core = fs::path(MPMSTAB_SOURCE_DIR) / "core";
  const std::regex quoted(R"re(^\s*#\s*include\s*"([^"]+)")re");
  std::vector<Include> out;
  for (const auto& e : fs::recursive_directory_iterator(core)) {
    const auto ext = e.path().extension();
    if (ext != ".cpp" && ext != ".hpp") continue;
    const std::string file = fs::relative(e.path(), core).generic_string();
    // Every file also stands as an include of base/, which every part may import, so that a
    // file including nothing of the solver is still checked for its folder.
    out.push_back({file, "base/"});
    std::ifstream in(e.path());
    for (std::string line; std::getline(in, line);) {
      std::smatch m;
      if (std::regex_search(line, m, quoted)) out.push_back({file, m[1]});
    }
  }
  return out;
}

TEST(Layout, EveryCoreSourceImportsOnlyDownwards) {
  const auto includes = core_includes();
  ASSERT_GT(includes.size(), 100u);
  std::vector<std::string> parts_seen;
  for (const auto& inc : includes) {
    EXPECT_EQ(layering_issue(inc), "");
    parts_seen.push_back(inc.file.substr(0, inc.file.find('/')));
  }
  for (const auto part : kParts) {
    EXPECT_NE(std::find(parts_seen.begin(), parts_seen.end(), part), parts_seen.end())
        << "part " << part << " holds no source";
  }
}

// The check catches each way of breaking the layering.
TEST(Layout, CheckRefusesUpwardUnqualifiedAndStrayIncludes) {
  EXPECT_EQ(layering_issue({"step/phases.cpp", "base/params.hpp"}), "");
  EXPECT_EQ(layering_issue({"step/phases.cpp", "step/grid.hpp"}), "");
  EXPECT_NE(layering_issue({"base/params.cpp", "analysis/spectral.hpp"}), "");
  EXPECT_NE(layering_issue({"scenes/scene.cpp", "step/grid.hpp"}), "");
  EXPECT_NE(layering_issue({"step/phases.cpp", "grid.hpp"}), "");
  EXPECT_NE(layering_issue({"step/phases.cpp", "engine/spec.hpp"}), "");
  EXPECT_NE(layering_issue({"params.cpp", "base/params.hpp"}), "");
}

// ---- experiments/: the engine, the studies by question, the commands
// ----------------------------- The engine names no study; a study's folder
// (experiments/studies/<question>/) includes its own files, shared/, the engine and core; shared/
// includes only itself, the engine and core; publish/ (the documents' generated blocks) and the
// commands may include any folder of studies.

// The folders of experiments/studies/: the questions, then the two that serve them.
constexpr std::array<std::string_view, 6> kQuestions = {"paper",    "agreement", "stability",
                                                        "accuracy", "choice",    "beyond_bar"};

bool is_question(std::string_view folder) {
  return std::find(kQuestions.begin(), kQuestions.end(), folder) != kQuestions.end();
}

// The folder an include names: its first path component, or "" for a bare name (an engine
// header, or a command's own).
std::string folder_of(const std::string& target) {
  const auto slash = target.find('/');
  return slash == std::string::npos ? std::string() : target.substr(0, slash);
}

// What is wrong with one include of experiments/, `file` relative to experiments/ (e.g.
// "studies/choice/tradeoff.cpp"). Empty when it is fine.
std::string harness_issue(const Include& inc) {
  const std::string to = folder_of(inc.target);
  const bool to_core = floor_of(to).has_value();
  const bool to_study = to == "shared" || to == "publish" || is_question(to);
  if (!to.empty() && !to_core && !to_study) {
    return inc.file + ": includes \"" + inc.target + "\" from no folder of core/ or the studies";
  }
  if (inc.file.rfind("engine/", 0) == 0) {
    return to_study ? inc.file + ": the engine includes the study header \"" + inc.target + "\""
                    : std::string();
  }
  if (inc.file.rfind("studies/", 0) != 0) return {};  // the commands: any folder
  const std::string rest = inc.file.substr(std::string("studies/").size());
  const std::string from = folder_of(rest);
  if (from.empty()) return inc.file + ": a study source outside the folders of its question";
  if (!to_study || to == from || to == "shared") return {};
  if (from == "publish") return {};  // the documents read every folder
  return inc.file + ": " +
         (from == "shared" ? "shared/ includes " : "a question's folder includes ") + "\"" +
         inc.target + "\" of another folder";
}

std::vector<Include> harness_includes() {
  const fs::path root = fs::path(MPMSTAB_SOURCE_DIR) / "experiments";
  const std::regex quoted(R"re(^\s*#\s*include\s*"([^"]+)")re");
  std::vector<Include> out;
  for (const auto& e : fs::recursive_directory_iterator(root)) {
    const auto ext = e.path().extension();
    if (ext != ".cpp" && ext != ".hpp") continue;
    const std::string file = fs::relative(e.path(), root).generic_string();
    out.push_back({file, "base/"});  // every file checked for its folder
    std::ifstream in(e.path());
    for (std::string line; std::getline(in, line);) {
      std::smatch m;
      if (std::regex_search(line, m, quoted)) out.push_back({file, m[1]});
    }
  }
  return out;
}

TEST(Layout, EveryStudyLivesInTheFolderOfItsQuestionAndIncludesOnlyWhatItMay) {
  const auto includes = harness_includes();
  ASSERT_GT(includes.size(), 300u);
  std::vector<std::string> folders_seen;
  for (const auto& inc : includes) {
    EXPECT_EQ(harness_issue(inc), "");
    if (inc.file.rfind("studies/", 0) == 0) folders_seen.push_back(folder_of(inc.file.substr(8)));
  }
  for (const auto q : kQuestions) {
    EXPECT_NE(std::find(folders_seen.begin(), folders_seen.end(), q), folders_seen.end())
        << "question folder " << q << " holds no source";
    EXPECT_TRUE(fs::exists(fs::path(MPMSTAB_SOURCE_DIR) / "experiments" / "studies" /
                           std::string(q) / "README.md"))
        << "question folder " << q << " opens with no README.md";
  }
}

TEST(Layout, HarnessCheckRefusesEachWayOfCrossingFolders) {
  EXPECT_EQ(harness_issue({"studies/choice/tradeoff.cpp", "shared/by_scene.hpp"}), "");
  EXPECT_EQ(harness_issue({"studies/choice/advice.cpp", "choice/advice_rule.hpp"}), "");
  EXPECT_EQ(harness_issue({"studies/choice/tradeoff.cpp", "report_util.hpp"}), "");
  EXPECT_EQ(harness_issue({"studies/choice/tradeoff.cpp", "scenes/validate.hpp"}), "");
  EXPECT_EQ(harness_issue({"studies/publish/documents.cpp", "choice/advice_rule.hpp"}), "");
  EXPECT_EQ(harness_issue({"cli/advise.cpp", "choice/advice_verify.hpp"}), "");
  EXPECT_NE(harness_issue({"studies/choice/tradeoff.cpp", "agreement/comparison.hpp"}), "");
  EXPECT_NE(harness_issue({"studies/shared/ensemble.cpp", "paper/table1.hpp"}), "");
  EXPECT_NE(harness_issue({"studies/paper/table1.cpp", "publish/verdicts.hpp"}), "");
  EXPECT_NE(harness_issue({"engine/report.cpp", "shared/ensemble.hpp"}), "");
  EXPECT_NE(harness_issue({"studies/table1.cpp", "report_util.hpp"}), "");
  EXPECT_NE(harness_issue({"studies/paper/table1.cpp", "studies/x.hpp"}), "");
}

// No function of the harness runs over 80 lines (a definition starting at column 0, to the
// closing brace at column 0: the project's format puts both there).
std::vector<std::string> long_functions(const fs::path& root, std::size_t limit) {
  std::vector<std::string> out;
  const std::regex opening(R"re(^[A-Za-z_][^;]*\()re");
  for (const auto& e : fs::recursive_directory_iterator(root)) {
    const auto ext = e.path().extension();
    if (ext != ".cpp" && ext != ".hpp") continue;
    std::ifstream in(e.path());
    std::vector<std::string> lines;
    for (std::string line; std::getline(in, line);)
      lines.push_back(line);
    std::optional<std::size_t> candidate, start;
    for (std::size_t i = 0; i < lines.size(); ++i) {
      const std::string& l = lines[i];
      if (!start) {
        const bool declaration_keyword = l.rfind("namespace", 0) == 0 ||
                                         l.rfind("struct", 0) == 0 || l.rfind("class", 0) == 0 ||
                                         l.rfind("enum", 0) == 0 || l.rfind("template", 0) == 0;
        if (!candidate && !declaration_keyword && std::regex_search(l, opening)) candidate = i;
        if (candidate && !l.empty() && l.back() == '{') {
          start = candidate;
          candidate.reset();
        } else if (candidate && !l.empty() && l.back() == ';') {
          candidate.reset();
        }
      } else if (!l.empty() && l[0] == '}') {
        if (i - *start + 1 > limit)
          out.push_back(fs::relative(e.path(), root).generic_string() + ":" +
                        std::to_string(*start + 1) + " (" + std::to_string(i - *start + 1) +
                        " lines)");
        start.reset();
      }
    }
  }
  return out;
}

TEST(Layout, NoFunctionOfTheHarnessRunsOverEightyLines) {
  const auto found = long_functions(fs::path(MPMSTAB_SOURCE_DIR) / "experiments", 80);
  EXPECT_TRUE(found.empty()) << ::testing::PrintToString(found);
  // The check sees long functions: the harness has some over 40 lines.
  EXPECT_FALSE(long_functions(fs::path(MPMSTAB_SOURCE_DIR) / "experiments", 40).empty());
}

}  // namespace
}  // namespace mpmstab
