// Claims (experiments/engine/claims.hpp): the conclusions of a report as data. Their templates
// type no number by hand, their numbers come from values, and the advice rule's claim fails when
// a recommendation's confirming run misses the target.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>

#include "advice.hpp"
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
  // of which one fails (a counterexample refutes at any size).
  auto every = [](long long runs, long long passing) {
    Claim c = claim("every", "Every run passes", "{passing} of {runs}");
    c.count("passing", passing).count("runs", runs).over(runs);
    c.holds = passing == runs;
    return c;
  };
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
    }
  }
  EXPECT_GT(claims, 0);
}

ojson advice_row(double courant, double limit, double error, const char* outcome = "stable") {
  return {{"courant", courant},
          {"courant_spectral", limit},
          {"max_error_over_time", error},
          {"outcome", outcome},
          {"cells", 50},
          {"jitter", 0.0},
          {"A", 0.015},
          {"T", 1.0}};
}

TEST(Advice, EachPartOfTheRuleDecides) {
  const double target = 1e-4;
  const ojson ok = advice_row(0.4, 0.756, 1e-5);
  EXPECT_TRUE(candidate(ok, target));
  EXPECT_FALSE(candidate(advice_row(0.7, 0.756, 1e-5), target));  // above limit / 1.25
  EXPECT_FALSE(candidate(advice_row(0.4, 0.756, 6e-5), target));  // above target / 2
  EXPECT_FALSE(candidate(advice_row(0.4, 0.756, 1e-5, "too_short"), target));
  // The confirming runs: finer grid, jitter, an amplitude 100 times smaller (its target scaled
  // with it), a run 4 times as long.
  ojson small = advice_row(0.4, 0.756, 1e-7);
  small["A"] = 0.015 / kAdviceRule.amplitude_factor;
  const ojson longer = ok;
  const std::vector<ojson> all_pass = {ok, ok, small, longer};
  EXPECT_TRUE(judge(ok, target, all_pass).recommended());
  // Too few confirming runs confirm nothing.
  EXPECT_FALSE(judge(ok, target, {ok, ok}).recommended());
  // A confirming run that misses the target, or fails, withdraws the recommendation, and the
  // advice claim then does not hold.
  const Advice missed = judge(ok, target, {ok, advice_row(0.4, 0.756, 2e-4), small, longer});
  EXPECT_FALSE(missed.recommended());
  EXPECT_FALSE(recommendations_claim({missed}, target).holds);
  EXPECT_FALSE(judge(ok, target, {advice_row(0.4, 0.756, 1e-5, "unstable"), ok, small, longer})
                   .recommended());
  // The small amplitude is held to the target scaled with A: 1e-5 meets target / 2 unscaled,
  // but not the relative accuracy the setting claims.
  ojson small_missed = small;
  small_missed["max_error_over_time"] = 1e-5;
  EXPECT_FALSE(judge(ok, target, {ok, ok, small_missed, longer}).recommended());
  // The longer run that turns meaningless withdraws it too.
  EXPECT_FALSE(judge(ok, target, {ok, ok, small, advice_row(0.4, 0.756, 0.02, "meaningless")})
                   .recommended());
  EXPECT_TRUE(recommendations_claim({judge(ok, target, all_pass)}, target).holds);
}

TEST(Advice, ConfirmingRunsRefineAtTheSameCourantNumberAndJitter) {
  RunParams p;
  p.cells = 25;
  p.dt = 1e-3;
  const auto runs = confirming_runs(p);
  ASSERT_EQ(runs.size(), kConfirmingRuns);
  EXPECT_EQ(runs[0].cells, 50);
  EXPECT_DOUBLE_EQ(runs[0].dt * runs[0].cells, p.dt * p.cells);
  EXPECT_EQ(runs[1].cells, 25);
  EXPECT_GT(runs[1].layout.jitter, 0);
  EXPECT_EQ(runs[2].A, p.A / kAdviceRule.amplitude_factor);  // the same setting otherwise
  EXPECT_EQ(runs[2].dt, p.dt);
  EXPECT_EQ(runs[3].T, p.T * kAdviceRule.length_factor);
  EXPECT_EQ(runs[3].dt, p.dt);
}

}  // namespace
}  // namespace mpmstab

namespace mpmstab {
namespace {

// Every setting a committed report recommends (results/<name>.json, study.recommended) is rerun
// here with its confirming runs -- the same setting on a grid twice as fine, on a jittered
// layout, at a smaller amplitude and on a longer run -- and each must meet the rule's limit and
// error target (scaled with A): a recommendation that a fresh run contradicts fails the suite,
// whatever the committed report says.
TEST(Advice, CommittedRecommendationsPassTheirConfirmingRunsWhenRerun) {
  const std::filesystem::path results = std::filesystem::path(MPMSTAB_SOURCE_DIR) / "results";
  int rerun = 0;
  for (const char* name : {"methods", "tradeoff"}) {
    std::ifstream in(results / (std::string(name) + ".json"));
    ASSERT_TRUE(in) << name;
    const ojson doc = ojson::parse(in);
    ASSERT_TRUE(doc.contains("study") && doc["study"].contains("recommended")) << name;
    for (const auto& rec : doc["study"]["recommended"]) {
      const double target = rec["target"].get<double>();
      const ojson spec = {{"name", "rerun"},
                          {"title", "rerun"},
                          {"report", "cases"},
                          {"cases", ojson::array({rec["case"]})}};
      const Spec parsed = parse_spec(spec.dump(), "rerun.json");
      ASSERT_EQ(parsed.cases.size(), 1u);
      const RunParams& p = parsed.cases[0].params;
      // The setting itself reproduces its committed numbers.
      const ojson own = to_json(run(p));
      EXPECT_EQ(own["max_error_over_time"], rec["max_error_over_time"]) << rec.dump();
      const double limit = own["courant_spectral"].get<double>();
      for (const RunParams& c : confirming_runs(p)) {
        const ojson row = to_json(run(c));
        EXPECT_TRUE(within_limit(row, limit)) << name << ": " << rec.dump() << " -> " << row.dump();
        EXPECT_TRUE(meets_target(row, target * c.A / p.A))
            << name << ": " << rec.dump() << " -> " << row.dump();
        ++rerun;
      }
    }
  }
  EXPECT_GT(rerun, 0);
}

}  // namespace
}  // namespace mpmstab
