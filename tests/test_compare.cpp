// The comparator: rows by parameters, tolerance rules, explicit special values.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>

#include "compare.hpp"

namespace mpmstab {
namespace {

Row row(std::initializer_list<std::pair<const std::string, std::string>> cells) {
  return Row{std::map<std::string, std::string>(cells)};
}

const std::vector<std::string> kKeys = {"method", "E", "dt"};

Table sample() {
  return Table{{row({{"method", "gimp"},
                     {"E", "4"},
                     {"dt", "1e-3"},
                     {"max_error", "7.562878878566094e-06"},
                     {"crossings", "776"},
                     {"stable", "true"}}),
                row({{"method", "mpm"},
                     {"E", "4"},
                     {"dt", "1e-3"},
                     {"max_error", "0.0039"},
                     {"crossings", "1036"},
                     {"stable", "true"}}),
                row({{"method", "gimp"},
                     {"E", "1000"},
                     {"dt", "1e-3"},
                     {"max_error", "*"},
                     {"crossings", ""},
                     {"stable", "false"}})}};
}

const std::vector<ColumnRule> kExact = {
    {"max_error", 0, 0, false}, {"crossings", 0, 0, false}, {"stable", 0, 0, true}};

TEST(Compare, IdenticalTablesAgreeWhateverTheRowOrder) {
  Table shuffled = sample();
  std::reverse(shuffled.rows.begin(), shuffled.rows.end());
  EXPECT_TRUE(compare_tables(sample(), shuffled, kKeys, kExact).empty());
}

TEST(Compare, KeysMatchAsNumbersAndWithoutCase) {
  Table other = sample();
  other.rows[0].cells["dt"] = "0.001";
  other.rows[0].cells["method"] = "GIMP";
  other.rows[1].cells["E"] = "4.0";
  EXPECT_TRUE(compare_tables(sample(), other, kKeys, kExact).empty());
}

TEST(Compare, CatchesAChangeInTheLastSignificantDigit) {
  Table other = sample();
  other.rows[0].cells["max_error"] = "7.562878878566095e-06";  // one unit in the 16th digit
  const auto m = compare_tables(sample(), other, kKeys, kExact);
  ASSERT_EQ(m.size(), 1u);
  EXPECT_EQ(m[0].kind, MismatchKind::value);
  EXPECT_EQ(m[0].column, "max_error");
  EXPECT_EQ(m[0].cell, "method=gimp E=4 dt=0.001");
  EXPECT_EQ(m[0].expected, "7.562878878566094e-06");
  EXPECT_EQ(m[0].obtained, "7.562878878566095e-06");
  ASSERT_TRUE(m[0].relative_difference);
  EXPECT_GT(*m[0].relative_difference, 0);
  EXPECT_LT(*m[0].relative_difference, 1e-15);

  // Two printed digits, a rule at a quarter of a unit in the last one: 6.8e-6 vs 6.9e-6 fails.
  const ColumnRule two_digits{"x", 0, 0.25 * 0.1 / 9.9, false};
  EXPECT_FALSE(cells_agree(parse_cell("6.8e-6"), parse_cell("6.9e-6"), two_digits));
  EXPECT_TRUE(cells_agree(parse_cell("6.8e-6"), parse_cell("6.8e-6"), two_digits));
}

TEST(Compare, ToleranceRuleIsContinuousNearZero) {
  const ColumnRule rule{"x", 1e-12, 1e-6, false};
  EXPECT_TRUE(cells_agree(parse_cell("0"), parse_cell("1e-13"), rule));
  EXPECT_TRUE(cells_agree(parse_cell("1e-300"), parse_cell("-1e-300"), rule));
  EXPECT_TRUE(cells_agree(parse_cell("-5e-13"), parse_cell("4e-13"), rule));
  EXPECT_FALSE(cells_agree(parse_cell("0"), parse_cell("2e-12"), rule));
  // Moving b away from a: once the rule fails it keeps failing (no jump back at zero).
  for (double a : {0.0, 1e-13, -1e-13, 1.0}) {
    bool failed = false;
    for (int k = 0; k <= 400; ++k) {
      const double b = a + k * (1e-12 + 1e-6 * std::abs(a)) / 100;  // fails near k = 100
      const bool ok = cells_agree(CellValue{CellValue::Kind::number, a, "a"},
                                  CellValue{CellValue::Kind::number, b, "b"}, rule);
      if (failed) {
        EXPECT_FALSE(ok) << a << " " << b;
      }
      failed = failed || !ok;
    }
    EXPECT_TRUE(failed) << a;
  }
}

TEST(Compare, UnstableAgainstANumberIsAVerdictMismatch) {
  Table other = sample();
  other.rows[2].cells["max_error"] = "0.001";
  other.rows[0].cells["max_error"] = "*";
  const auto m = compare_tables(sample(), other, kKeys, kExact);
  ASSERT_EQ(m.size(), 2u);
  EXPECT_EQ(m[0].kind, MismatchKind::verdict);
  EXPECT_EQ(m[1].kind, MismatchKind::verdict);
  // "*" against "*" agrees.
  EXPECT_TRUE(cells_agree(parse_cell("*"), parse_cell("*"), kExact[0]));
}

TEST(Compare, NanAndMissingFollowExplicitRules) {
  const ColumnRule loose{"x", 1e300, 1, false};  // any two numbers agree under this rule
  EXPECT_TRUE(cells_agree(parse_cell("nan"), parse_cell("NaN"), loose));
  EXPECT_FALSE(cells_agree(parse_cell("nan"), parse_cell("1"), loose));
  EXPECT_TRUE(cells_agree(parse_cell(""), parse_cell(""), loose));
  EXPECT_FALSE(cells_agree(parse_cell(""), parse_cell("0"), loose));
  EXPECT_FALSE(cells_agree(parse_cell("*"), parse_cell("nan"), loose));
  EXPECT_FALSE(cells_agree(parse_cell("inf"), parse_cell("1e308"), loose));
  EXPECT_TRUE(cells_agree(parse_cell("inf"), parse_cell("inf"), loose));
  // Unreadable transcriptions are compared as text only when equal.
  EXPECT_TRUE(cells_agree(parse_cell("4.?e-6"), parse_cell("4.?e-6"), loose));
  EXPECT_FALSE(cells_agree(parse_cell("4.?e-6"), parse_cell("4.8e-6"), loose));

  Table other = sample();
  other.rows[1].cells["crossings"] = "";
  const auto m = compare_tables(sample(), other, kKeys, kExact);
  ASSERT_EQ(m.size(), 1u);
  EXPECT_EQ(m[0].kind, MismatchKind::missing_value);
}

TEST(Compare, IntegerColumnsTakeAnAbsoluteAllowance) {
  const ColumnRule crossings{"crossings", 2, 0, false};
  EXPECT_TRUE(cells_agree(parse_cell("776"), parse_cell("778"), crossings));
  EXPECT_FALSE(cells_agree(parse_cell("776"), parse_cell("779"), crossings));
}

TEST(Compare, FactorThreeIsRtolTwoThirds) {
  const ColumnRule factor3{"x", 0, 2.0 / 3.0, false};
  EXPECT_TRUE(cells_agree(parse_cell("1e-5"), parse_cell("3e-5"), factor3));
  EXPECT_TRUE(cells_agree(parse_cell("3e-5"), parse_cell("1e-5"), factor3));
  EXPECT_FALSE(cells_agree(parse_cell("1e-5"), parse_cell("3.01e-5"), factor3));
}

TEST(Compare, MissingExtraAndDuplicateRowsAreNamed) {
  Table other = sample();
  other.rows.erase(other.rows.begin() + 1);
  other.rows.push_back(row({{"method", "mpm"}, {"E", "16"}, {"dt", "1e-3"}}));
  other.rows.push_back(other.rows[0]);
  const auto m = compare_tables(sample(), other, kKeys, kExact);
  std::vector<std::pair<MismatchKind, std::string>> got;
  for (const auto& x : m)
    got.emplace_back(x.kind, x.cell);
  const std::vector<std::pair<MismatchKind, std::string>> want = {
      {MismatchKind::duplicate_row, "method=gimp E=4 dt=0.001"},
      {MismatchKind::missing_row, "method=mpm E=4 dt=0.001"},
      {MismatchKind::extra_row, "method=mpm E=16 dt=0.001"}};
  EXPECT_EQ(got, want);
}

TEST(Compare, TextColumnsCompareExactly) {
  Table other = sample();
  other.rows[0].cells["stable"] = "false";
  const auto m = compare_tables(sample(), other, kKeys, kExact);
  ASSERT_EQ(m.size(), 1u);
  EXPECT_EQ(m[0].kind, MismatchKind::verdict);
  EXPECT_EQ(m[0].tolerance, "exact text");
}

}  // namespace
}  // namespace mpmstab
