// Claims (experiments/engine/claims.hpp): the conclusions of a report as data. Their templates
// type no number by hand and their numbers come from values.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>

#include "claims.hpp"
#include "result_json.hpp"
#include "run/run.hpp"
#include "spec.hpp"

namespace mpmstab {
namespace {

using ojson = nlohmann::ordered_json;

TEST(Claims, RenderSubstitutesEveryValueAndRefusesAMissingOne) {
  Claim c = claim("x", "{a} of {b} runs fail", "{a} fail");
  c.count("a", 3).count("b", 4);
  EXPECT_EQ(render_statement(c), "3 of 4 runs fail");
  Claim missing = claim("y", "{a} of {b}");
  missing.count("a", 1);
  EXPECT_THROW(render_statement(missing), std::logic_error);
}

TEST(Claims, HandTypedDigitsAreFoundOutsidePlaceholdersAndNames) {
  EXPECT_EQ(hand_typed_digits("every run above {limit} fails"), "");
  EXPECT_EQ(hand_typed_digits("eq. (108) lies below Table 1's {x}"), "");
  EXPECT_EQ(hand_typed_digits("every run above 0.756 fails"), "0756");
  EXPECT_EQ(hand_typed_digits("in 10 of {n}"), "10");
}

TEST(Claims, AClaimThatDoesNotHoldIsPrintedAsNotHolding) {
  Claim c = claim("z", "{n} runs", "");
  c.count("n", 2);
  c.holds = false;
  const std::string md = claims_markdown({c});
  EXPECT_NE(md.find("does not hold"), std::string::npos);
  EXPECT_NE(claims_csv({c}, "").find("z,no,"), std::string::npos);
}

TEST(Claims, AClaimOverNoCaseIsVacuousAndOneOverTooFewIsNotCountedAsHolding) {
  // "Every run of the set passes", decided over 0, 2 and 3 runs that all pass, and over 2 runs
  // of which one fails (a counterexample refutes at any size), as the studies declare such a
  // claim (Claim::every).
  auto every = [](long long runs, long long passing) {
    Claim c = claim("every", "Every run passes", "{passing} of {runs}");
    c.every("passing", passing, "runs", runs);
    return c;
  };
  const Claim three = every(3, 3);
  ASSERT_EQ(three.values.size(), 2u);
  EXPECT_EQ(three.values[0], (std::pair<std::string, std::string>("passing", "3")));
  EXPECT_EQ(three.values[1], (std::pair<std::string, std::string>("runs", "3")));
  EXPECT_EQ(three.support, 3);
  EXPECT_EQ(every(0, 0).status(), Claim::Status::vacuous);
  EXPECT_EQ(every(2, 2).status(), Claim::Status::too_few);
  EXPECT_EQ(every(3, 3).status(), Claim::Status::holds);
  EXPECT_EQ(every(2, 1).status(), Claim::Status::fails);
  EXPECT_EQ(every(0, 0).status(), Claim::Status::vacuous);
  const std::string md = claims_markdown({every(0, 0), every(2, 2), every(3, 3)});
  EXPECT_NE(md.find("**vacuous (0 cases)**"), std::string::npos) << md;
  EXPECT_NE(md.find("**too few cases (2; at least 3 to say every)**"), std::string::npos) << md;
  EXPECT_NE(md.find(" 1 of 3 hold."), std::string::npos) << md;  // only the one over 3 runs
  const std::string csv = claims_csv({every(0, 0), every(2, 2), every(3, 3)}, "");
  EXPECT_NE(csv.find("every,vacuous,"), std::string::npos) << csv;
  EXPECT_NE(csv.find("every,too-few,"), std::string::npos) << csv;
  EXPECT_NE(csv.find("every,yes,"), std::string::npos) << csv;
  const auto json = claims_json({every(0, 0)});
  EXPECT_FALSE(json[0]["holds"].get<bool>());
  EXPECT_EQ(json[0]["status"], "vacuous");
  // A claim of another form (no support given) keeps holds as its predicate says.
  Claim other = claim("other", "A fitted order is near two", "");
  other.holds = true;
  EXPECT_EQ(other.status(), Claim::Status::holds);
}

// Every committed report's claims: no template types a number by hand, and the stored text is
// the template with its values.
TEST(Claims, CommittedReportsTypeNoNumberByHand) {
  const std::filesystem::path results = std::filesystem::path(MPMSTAB_SOURCE_DIR) / "results";
  int claims = 0;
  for (const auto& entry : std::filesystem::directory_iterator(results)) {
    if (entry.path().extension() != ".json") continue;
    std::ifstream in(entry.path());
    const ojson doc = ojson::parse(in, nullptr, false);
    if (doc.is_discarded() || !doc.is_object() || !doc.contains("claims")) continue;
    for (const auto& c : doc["claims"]) {
      ++claims;
      const std::string t = c["template"].get<std::string>();
      EXPECT_EQ(hand_typed_digits(t), "") << entry.path() << ": " << t;
      EXPECT_EQ(hand_typed_digits(c["evidence_template"].get<std::string>()), "")
          << entry.path() << ": " << c["evidence_template"];
      Claim back = claim(c["id"], t);
      for (const auto& [k, v] : c["values"].items())
        back.value(k, v.get<std::string>());
      EXPECT_EQ(render_statement(back), c["statement"].get<std::string>());
      // Where its rows lie (Claim::on): a conclusion says which amplitudes, lengths and grids
      // it was measured on.
      EXPECT_FALSE(c.value("measured_on", std::string()).empty())
          << entry.path() << ": " << c["id"];
    }
  }
  EXPECT_GT(claims, 0);
}

}  // namespace
}  // namespace mpmstab
