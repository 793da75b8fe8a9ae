// CI types README's commands as a newcomer does (.ci/run): in a fresh clone, the set-up block,
// the test block and then `make reproduce`, in that order, and then requires a clean tree. These
// tests read README's blocks and .ci/run and fail when the script no longer runs what README says.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

namespace mpmstab {
namespace {

namespace fs = std::filesystem;

std::string read_source(const std::string& relative) {
  std::ifstream in(fs::path(MPMSTAB_SOURCE_DIR) / relative, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

std::string trim(std::string s) {
  const auto first = s.find_first_not_of(" \t");
  if (first == std::string::npos) return {};
  const auto last = s.find_last_not_of(" \t");
  return s.substr(first, last - first + 1);
}

// The commands of the first ```sh block after the line `after` in a Markdown text, each line
// without its comment and split at "&&". Empty when there is no such block.
std::vector<std::string> sh_block_after(const std::string& markdown, const std::string& after) {
  std::vector<std::string> out;
  std::istringstream in(markdown);
  std::string line;
  bool seen = false, inside = false;
  while (std::getline(in, line)) {
    if (!seen) {
      seen = line == after;
      continue;
    }
    if (!inside) {
      inside = line == "```sh";
      continue;
    }
    if (line == "```") break;
    if (const auto hash = line.find('#'); hash != std::string::npos) line.resize(hash);
    std::size_t start = 0;
    while (true) {
      const auto amp = line.find("&&", start);
      const std::string part = trim(line.substr(start, amp - start));
      if (!part.empty()) out.push_back(part);
      if (amp == std::string::npos) break;
      start = amp + 2;
    }
  }
  return out;
}

// The commands .ci/run runs, in order: each line without its comment; a line `step <command>`
// (the script's timer) counts as <command>, without what follows it to catch its output.
std::vector<std::string> ci_commands(const std::string& script) {
  std::vector<std::string> out;
  std::istringstream in(script);
  std::string line;
  while (std::getline(in, line)) {
    line = trim(line);
    if (line.empty() || line.front() == '#') continue;
    if (line.rfind("step ", 0) == 0) {
      line = trim(line.substr(5));
      // What the script does with the output (a redirection, a pipe into tee) is not the
      // command.
      for (const char* tail : {" 2>", " >", " |"})
        if (const auto at = line.find(tail); at != std::string::npos)
          line = trim(line.substr(0, at));
    }
    out.push_back(line);
  }
  return out;
}

// Whether a line of .ci/run does what a README command says. README's clone names no
// repository ("git clone <this repository> mpmstab"): CI clones the commit under test into a
// folder named mpmstab, and goes into it.
bool does(const std::string& ci, const std::string& readme) {
  const auto ends_in_mpmstab = [](const std::string& line) {
    std::string last = line.substr(line.find_last_of(' ') + 1);
    if (!last.empty() && last.back() == '"') last.pop_back();
    return last == "mpmstab" || last.ends_with("/mpmstab");
  };
  if (readme.rfind("git clone ", 0) == 0 && readme.ends_with(" mpmstab"))
    return ci.rfind("git clone ", 0) == 0 && ends_in_mpmstab(ci);
  if (readme == "cd mpmstab") return ci.rfind("cd ", 0) == 0 && ends_in_mpmstab(ci);
  return ci == readme;
}

// What .ci/run fails to do of README's set-up block, then its test block, then `make
// reproduce`, in that order, and the clean-tree check after them. Empty when it does it all.
std::vector<std::string> ci_problems(const std::string& readme, const std::string& script) {
  std::vector<std::string> problems;
  const auto setup = sh_block_after(readme, "## Set-up (fresh Debian machine)");
  const auto tests = sh_block_after(readme, "Run the tests:");
  if (setup.empty()) problems.push_back("README has no set-up block");
  if (tests.empty()) problems.push_back("README has no test block");
  std::vector<std::string> wanted = setup;
  wanted.insert(wanted.end(), tests.begin(), tests.end());
  wanted.push_back("make reproduce");
  const auto ci = ci_commands(script);
  std::size_t at = 0;
  for (const auto& command : wanted) {
    std::size_t i = at;
    while (i < ci.size() && !does(ci[i], command))
      ++i;
    if (i == ci.size()) {
      problems.push_back(".ci/run does not run '" + command + "' (in README's order)");
      continue;
    }
    at = i + 1;
  }
  bool checks_tree = false;
  for (std::size_t i = at; i < ci.size(); ++i)
    checks_tree = checks_tree || ci[i].find("git status --porcelain") != std::string::npos;
  if (!checks_tree)
    problems.push_back(".ci/run does not check git status --porcelain after the commands");
  return problems;
}

std::string joined(const std::vector<std::string>& lines) {
  std::string s;
  for (const auto& l : lines)
    s += l + "\n";
  return s;
}

TEST(Ci, RunsReadmesSetUpTestsAndReproduceInAFreshClone) {
  const std::string readme = read_source("README.md");
  const std::string script = read_source(".ci/run");
  const auto setup = sh_block_after(readme, "## Set-up (fresh Debian machine)");
  ASSERT_GE(setup.size(), 3u) << joined(setup);  // the clone, the cd and make
  EXPECT_EQ(setup.back(), "make");
  const auto problems = ci_problems(readme, script);
  EXPECT_TRUE(problems.empty()) << joined(problems);
}

TEST(Ci, FailsWhenAReadmeCommandChangesWithoutCi) {
  const std::string readme = read_source("README.md");
  const std::string script = read_source(".ci/run");
  ASSERT_TRUE(ci_problems(readme, script).empty());
  const auto changed = [&](const std::string& from, const std::string& to) {
    std::string r = readme;
    const auto at = r.find(from);
    EXPECT_NE(at, std::string::npos) << from;
    if (at != std::string::npos) r.replace(at, from.size(), to);
    return joined(ci_problems(r, script));
  };
  // A test command renamed in README, a set-up step added, the clone's folder renamed.
  EXPECT_NE(changed("make test          #", "make tests         #").find("'make tests'"),
            std::string::npos);
  EXPECT_NE(changed("make               #", "make all && make deps #").find("'make deps'"),
            std::string::npos);
  EXPECT_NE(changed("cd mpmstab", "cd mpm").find("'cd mpm'"), std::string::npos);
  // The script that stops before the test block, or never checks the tree.
  std::string no_cluster = script;
  no_cluster.replace(no_cluster.find("step make test-cluster"), 22, "true");
  EXPECT_NE(joined(ci_problems(readme, no_cluster)).find("'make test-cluster'"), std::string::npos);
  std::string no_status = script;
  for (auto at = no_status.find("git status --porcelain"); at != std::string::npos;
       at = no_status.find("git status --porcelain"))
    no_status.replace(at, 22, "true");
  EXPECT_NE(joined(ci_problems(readme, no_status)).find("git status"), std::string::npos);
}

}  // namespace
}  // namespace mpmstab
