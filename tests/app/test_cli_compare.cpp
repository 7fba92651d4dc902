// `shudder compare`: Paper E's fluids A–E ranked as Table 4 orders them (mu1/mu50 at 30 °C:
// A 0.7985 < B < C < D < E 0.8455), a fluid given twice ties with itself, the JSON carries
// every fluid, and a missing fluid file is bad input with nothing written.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <map>

#include "tests/support/cli.hpp"
#include "tests/support/json.hpp"

namespace {

using namespace shudder;

// Built with append: GCC 12 flags chained std::string `+` here with a false-positive -Wrestrict.
std::string fluid(char c) {
  std::string rel = "scenarios/fluids/paper_e_fluid_";
  rel.push_back(c);
  rel.append(".toml");
  std::string out = " ";
  out.append(test::source_path(rel));
  return out;
}

TEST(CliCompare, RanksPaperEFluidsAsTable4AndTiesAFluidWithItself) {
  const auto dir = test::scratch_dir("compare_paper_e");
  const auto r = test::run_cli("compare" + fluid('e') + fluid('c') + fluid('a') + fluid('d') + fluid('b') + fluid('c') +
                                   " --temps 30 --json cmp.json",
                               dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = test::parse(test::slurp(dir / "cmp.json"));
  EXPECT_EQ(j["format"].str(), "shudder-compare/1");
  std::map<std::string, double> rank;
  for (const auto& f : j["fluids"].items) rank[f["name"].str()] = f["rank"].number;
  EXPECT_EQ(rank["paper-e-fluid-a"], 1);
  EXPECT_EQ(rank["paper-e-fluid-b"], 2);
  EXPECT_EQ(rank["paper-e-fluid-c"], 3);
  EXPECT_EQ(rank["paper-e-fluid-d"], 5);  // C is given twice: places 3 and 4 tie
  EXPECT_EQ(rank["paper-e-fluid-e"], 6);
  EXPECT_EQ(j["fluids"].items.size(), 6u);
  EXPECT_THAT(r.out, ::testing::HasSubstr("paper-e-fluid-c / paper-e-fluid-c: tie"));
  EXPECT_THAT(r.out, ::testing::HasSubstr("paper-e-fluid-a / paper-e-fluid-b: largest mu1/mu50"));
  // The direction of good is stated, and a column equal for every fluid (the breakaway ratio,
  // 1 in every Paper E file: not measured there) is named once instead of printed five times.
  EXPECT_THAT(r.out, ::testing::HasSubstr("(lower is better)"));
  EXPECT_THAT(r.out, ::testing::HasSubstr("Ranking, best first:"));
  EXPECT_THAT(r.out, ::testing::HasSubstr("The same for every fluid, so left out of the table: breakaway 1.000"));
}

// The clutch-mode margin depends on the fluid: it is taken where the law has data (outside, the
// law is held, its slope is zero and the margin is the bar's own damping, -6.28 1/s on the 100 Hz
// bar for every fluid).
TEST(CliCompare, ClutchMarginDependsOnTheFluid) {
  const auto dir = test::scratch_dir("compare_margin");
  const auto r = test::run_cli("compare" + fluid('a') + fluid('e') + " --json cmp.json", dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = test::parse(test::slurp(dir / "cmp.json"));
  const double a = j["fluids"].items[0]["largest_margin_per_s"].number;
  const double e = j["fluids"].items[1]["largest_margin_per_s"].number;
  EXPECT_LT(a, 0.0);  // both stable (Paper E: no shudder)
  EXPECT_LT(e, 0.0);
  EXPECT_GT(std::abs(a - e), 0.01) << a << " " << e;  // differ beyond the JSON's 10 digits' noise
  EXPECT_THAT(r.out, ::testing::Not(::testing::HasSubstr("-6.28/s")));
}

TEST(CliCompare, MissingFluidIsBadInput) {
  const auto dir = test::scratch_dir("compare_missing");
  const auto r = test::run_cli("compare" + fluid('a') + " nope.toml --json cmp.json", dir);
  test::expect_rejected(r, {"nope.toml", "no such fluid file"});
  EXPECT_FALSE(std::filesystem::exists(dir / "cmp.json"));
}

}  // namespace
