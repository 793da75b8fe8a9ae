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

}  // namespace
}  // namespace mpmstab
