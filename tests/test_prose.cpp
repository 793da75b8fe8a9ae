// The prose of every report types no number by hand. Each number a report prints comes
// from its records, its spec or a named constant the computation itself uses (the agreement
// factor, the edge search's scan and tolerance, the bands of the extremes study ...), so that
// a changed rule changes its sentence. This test reads the string literals of the study sources
// and refuses a digit outside the paper's names ("Table 1", "eq. (108)"), an identifier
// ("table1", "fig2_variants"), a printf conversion ("%.3g") or a claim's "{placeholder}".
#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <string_view>
#include <vector>

#include "claims.hpp"

namespace mpmstab {
namespace {

struct Literal {
  int line = 0;
  std::string text;
};

// The string literals of C++ source, comments and character literals skipped. Raw strings are
// returned whole; escapes are kept as written.
std::vector<Literal> string_literals(const std::string& src) {
  std::vector<Literal> out;
  int line = 1;
  for (std::size_t i = 0; i < src.size(); ++i) {
    const char c = src[i];
    if (c == '\n') {
      ++line;
    } else if (c == '/' && i + 1 < src.size() && src[i + 1] == '/') {
      while (i < src.size() && src[i] != '\n')
        ++i;
      --i;
    } else if (c == '/' && i + 1 < src.size() && src[i + 1] == '*') {
      const std::size_t end = src.find("*/", i + 2);
      for (std::size_t k = i; k < end && k < src.size(); ++k)
        line += src[k] == '\n';
      i = end == std::string::npos ? src.size() : end + 1;
    } else if (c == '\'') {
      // A digit separator (1'000) is preceded by a digit; a character literal is not.
      if (i > 0 && std::isalnum(static_cast<unsigned char>(src[i - 1]))) continue;
      for (++i; i < src.size() && src[i] != '\''; ++i)
        if (src[i] == '\\') ++i;
    } else if (c == '"') {
      Literal lit{line, {}};
      for (++i; i < src.size() && src[i] != '"'; ++i) {
        if (src[i] == '\\') lit.text += src[i++];
        lit.text += src[i];
      }
      out.push_back(lit);
    }
  }
  return out;
}

// The digits of `text` that are typed by hand: hand_typed_digits() (claims.hpp) with the
// identifiers and printf conversions of code also allowed.
std::string typed_digits(const std::string& text) {
  std::string kept;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    const bool digit = c >= '0' && c <= '9';
    if (c == '%') {  // a printf conversion: %.3g, %016llx, %zu
      std::size_t k = i + 1;
      while (k < text.size() &&
             std::string_view("0123456789.-+#lhz").find(text[k]) != std::string_view::npos)
        ++k;
      i = k;
      continue;
    }
    if (digit && !kept.empty() &&
        (std::isalpha(static_cast<unsigned char>(kept.back())) || kept.back() == '_')) {
      // part of an identifier: table1, fig2_variants, errors_within
      while (i + 1 < text.size() && text[i + 1] >= '0' && text[i + 1] <= '9')
        ++i;
      kept += 'x';
      continue;
    }
    kept += c;
  }
  return hand_typed_digits(kept);
}

// Every study's source, and the engine's writers of reports that are not studies (the
// performance report and the index).
std::vector<std::filesystem::path> study_sources() {
  std::vector<std::filesystem::path> files;
  const auto root = std::filesystem::path(MPMSTAB_SOURCE_DIR) / "experiments";
  for (const auto& e : std::filesystem::recursive_directory_iterator(root / "studies"))
    if (e.path().extension() == ".cpp") files.push_back(e.path());
  files.push_back(root / "engine" / "performance.cpp");
  files.push_back(root / "engine" / "report.cpp");
  std::sort(files.begin(), files.end());
  return files;
}

// Phrases that generalise or compare beyond what a sentence's rows can show ("holds for a run of
// any length", "above every scheme's limit", "the smooth regime", "is safe"): a study states such
// a thing only as a claim with its predicate, whose template is not prose of this kind, and a
// spec description says what an experiment runs, never what it found. The phrases found in
// `text`, lower-cased.
const std::vector<std::string> kUnsupported = {
    "any length", "any run length", "smooth regime", "is safe", "are safe", "above every",
    "below every", "in either code", "falls below", "always holds", "never fails",
    // A cause is stated only as a claim that holds, never in a report's prose.
    "its source is", "their source is", "is caused by", "are caused by", "is due to", "are due to",
    "stems from"};
std::vector<std::string> unsupported_phrases(std::string text) {
  std::transform(text.begin(), text.end(), text.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  std::vector<std::string> found;
  for (const auto& p : kUnsupported)
    if (text.find(p) != std::string::npos) found.push_back(p);
  return found;
}

// The spec descriptions and variant descriptions of every experiment, and the documents'
// generated blocks' sources (the studies) are scanned; the documents' hand-written text is
// checked for the same phrases.
std::vector<std::pair<std::string, std::string>> descriptions() {
  std::vector<std::pair<std::string, std::string>> out;
  const auto root = std::filesystem::path(MPMSTAB_SOURCE_DIR);
  for (const auto& e : std::filesystem::directory_iterator(root / "experiments")) {
    if (e.path().extension() != ".json") continue;
    std::ifstream in(e.path());
    std::stringstream ss;
    ss << in.rdbuf();
    out.emplace_back(e.path().filename().string(), ss.str());
  }
  for (const char* doc : {"README.md", "docs/theory.md", "docs/studies.md", "docs/engineering.md",
                          "docs/architecture.md"}) {
    std::ifstream in(root / doc);
    std::stringstream ss;
    ss << in.rdbuf();
    out.emplace_back(doc, ss.str());
  }
  return out;
}

TEST(Prose, UnsupportedGeneralisationsAreFoundWhereverTheyArePlanted) {
  EXPECT_EQ(unsupported_phrases("An edge at or below the limit holds for a run of Any Length"),
            std::vector<std::string>{"any length"});
  EXPECT_EQ(unsupported_phrases("C = 1.6, above every scheme's spectral limit"),
            std::vector<std::string>{"above every"});
  EXPECT_TRUE(unsupported_phrases("the largest C below which every run survives").empty());
  EXPECT_EQ(unsupported_phrases("Its source is FLIP's re-projection"),
            std::vector<std::string>{"its source is"});
}

TEST(Prose, NoStudySpecOrDocumentGeneralisesBeyondItsRows) {
  for (const auto& file : study_sources()) {
    std::ifstream in(file);
    std::stringstream ss;
    ss << in.rdbuf();
    for (const auto& lit : string_literals(ss.str()))
      EXPECT_TRUE(unsupported_phrases(lit.text).empty())
          << file.filename().string() << ':' << lit.line << ": \"" << lit.text << '"';
  }
  for (const auto& [name, text] : descriptions())
    EXPECT_TRUE(unsupported_phrases(text).empty())
        << name << ": " << unsupported_phrases(text).front();
}

TEST(Prose, TheScannerFindsWhatItShould) {
  const auto lits = string_literals("a = 'x'; // \"1\"\n/* \"2\" */ f(\"a 3\", \"b\\\"4\");");
  ASSERT_EQ(lits.size(), 2u);
  EXPECT_EQ(lits[0].line, 2);
  EXPECT_EQ(typed_digits(lits[0].text), "3");
  EXPECT_EQ(typed_digits(lits[1].text), "4");
  EXPECT_EQ(typed_digits("see table1 and fig2_variants, %.3g, {n} of Table 1"), "");
  EXPECT_EQ(typed_digits("within a factor 3"), "3");
  EXPECT_EQ(typed_digits("from h/(16c) to 4h/c"), "164");
}

TEST(Prose, StudiesTypeNoNumberByHand) {
  int literals = 0;
  for (const auto& file : study_sources()) {
    std::ifstream in(file);
    std::stringstream ss;
    ss << in.rdbuf();
    for (const auto& lit : string_literals(ss.str())) {
      ++literals;
      EXPECT_EQ(typed_digits(lit.text), "")
          << file.filename().string() << ':' << lit.line << ": \"" << lit.text << '"';
    }
  }
  EXPECT_GT(literals, 1000);
}

}  // namespace
}  // namespace mpmstab
