// `shudder compare`: Paper E's fluids A–E ranked as Table 4 orders them (mu1/mu50 at 30 °C:
// A 0.7985 < B < C < D < E 0.8455), a fluid given twice ties with itself, the JSON carries
// every fluid, and a missing fluid file is bad input with nothing written.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

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
}

TEST(CliCompare, MissingFluidIsBadInput) {
  const auto dir = test::scratch_dir("compare_missing");
  const auto r = test::run_cli("compare" + fluid('a') + " nope.toml --json cmp.json", dir);
  test::expect_rejected(r, {"nope.toml", "no such fluid file"});
  EXPECT_FALSE(std::filesystem::exists(dir / "cmp.json"));
}

}  // namespace
