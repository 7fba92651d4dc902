// The index.html of report directories, end to end: `run`, `sweep` and `compare --report DIR`
// write a page that names the scenario, states the verdict, holds the summary and tables, shows
// every plot of the directory and links the data files; a headless chromium loads it and every
// image must load and no script error or failed resource may occur. The browser check is shown
// to fail on a page with a missing image and a script error, and text from input is escaped.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "report/html_page.hpp"
#include "tests/support/browser.hpp"
#include "tests/support/cli.hpp"
#include "tests/support/short_scenarios.hpp"

using namespace shudder;
using namespace shudder::test;
using ::testing::ElementsAre;
using ::testing::HasSubstr;
using ::testing::IsEmpty;
using ::testing::Not;
namespace fs = std::filesystem;

namespace {

bool have_gnuplot() { return std::system("command -v gnuplot >/dev/null 2>&1") == 0; }

int png_files(const fs::path& dir) {
  int n = 0;
  for (const auto& e : fs::directory_iterator(dir)) n += e.path().extension() == ".png";
  return n;
}

/// The page loads in chromium with every image drawn and nothing failing.
void expect_clean_in_browser(const fs::path& page, int images) {
  const std::string exe = chromium_executable();
  if (exe.empty()) GTEST_SKIP() << kChromiumMissing;  // the page's content was checked before
  const BrowserCheck c = check_in_browser(page, exe);
  ASSERT_TRUE(c.ran) << "the check script did not report; chromium's stderr:\n" << c.log << "\nDOM:\n" << c.dom;
  EXPECT_EQ(c.images, images) << page;
  EXPECT_THAT(c.broken, IsEmpty()) << page;
  EXPECT_THAT(c.errors, IsEmpty()) << page;
}

fs::path rig_report(const std::string& name) {
  const auto dir = scratch_dir(name);
  write_file(dir / "rig.toml", short_rig_scenario());
  const auto r = run_cli("run rig.toml -o rig.h5 --report rep", dir);
  EXPECT_EQ(r.exit_code, 0) << r.err;
  return dir;
}

}  // namespace

TEST(ReportIndex, HtmlEscapeAndUrlPathLeaveNoMarkupAndNameTheFile) {
  EXPECT_EQ(report::html_escape("a<b>&\"c'd"), "a&lt;b&gt;&amp;&quot;c&#39;d");
  EXPECT_EQ(report::html_escape("line\nnext\ttab\x01\x7f"), "line\nnext\ttab");
  EXPECT_EQ(report::url_path("../runs/rig run#1?.h5"), "../runs/rig%20run%231%3F.h5");
  EXPECT_EQ(report::url_path("mu_v_30C.png"), "mu_v_30C.png");
  EXPECT_EQ(report::url_path("100%.h5"), "100%25.h5");
}

TEST(ReportIndex, RunPageStatesTheVerdictAndShowsEveryPlotInABrowser) {
  if (!have_gnuplot()) GTEST_SKIP() << "gnuplot not installed";
  const auto dir = rig_report("report_index_rig");
  const fs::path page = dir / "rep" / "index.html";
  ASSERT_TRUE(fs::exists(page));
  const std::string html = slurp(page);
  EXPECT_THAT(html, HasSubstr("<title>shudder run: rig_shudder_negative_slope</title>"));
  EXPECT_THAT(html, HasSubstr("<p class=\"verdict shudder\" id=\"verdict\">Shudder: friction-induced vibration at "));
  EXPECT_THAT(html, HasSubstr("Scenario  rig_shudder_negative_slope (rig)"));  // the summary
  EXPECT_THAT(html, HasSubstr("<td>frequency_Hz</td>"));                       // the verdict table
  for (const char* f : {"torque.png", "temperature.png", "spectrum.png", "spectrogram.png", "stability_map.png"})
    EXPECT_THAT(html, HasSubstr(std::string("<img src=\"") + f + "\"")) << f;
  EXPECT_THAT(html, HasSubstr("<a href=\"../rig.h5\">rig.h5</a>"));
  EXPECT_THAT(html, HasSubstr("<a href=\"verdict.json\">verdict.json</a>"));
  EXPECT_THAT(html, Not(HasSubstr("browser_check")));
  EXPECT_THAT(dead_links(page), IsEmpty());
  expect_clean_in_browser(page, 5);
}

// The check would pass a page that never ran it, or one whose broken parts it cannot see,
// without this: a missing image and a script error must both be reported.
TEST(ReportIndex, BrowserCheckReportsAMissingImageAndAScriptError) {
  if (!have_gnuplot()) GTEST_SKIP() << "gnuplot not installed";
  const std::string exe = chromium_executable();
  if (exe.empty()) GTEST_SKIP() << kChromiumMissing;
  const auto dir = rig_report("report_index_broken");
  const fs::path page = dir / "rep" / "index.html";
  fs::remove(dir / "rep" / "spectrum.png");
  write_file(page, replace(slurp(page), "</body>", "<script>no_such_function();</script>\n</body>"));
  const BrowserCheck c = check_in_browser(page, exe);
  ASSERT_TRUE(c.ran) << c.log;
  EXPECT_EQ(c.images, 5);
  EXPECT_THAT(c.broken, ElementsAre("spectrum.png"));
  EXPECT_THAT(c.errors, testing::Contains(HasSubstr("spectrum.png")));
  EXPECT_THAT(c.errors, testing::Contains(HasSubstr("no_such_function")));
  EXPECT_THAT(dead_links(page), testing::Contains("spectrum.png"));
}

TEST(ReportIndex, TextFromTheScenarioIsEscaped) {
  const auto dir = scratch_dir("report_index_escape");
  write_file(dir / "rig.toml", replace(short_rig_scenario(), "name = \"rig_shudder_negative_slope\"",
                                       "name = \"neg<script>alert('x')</script>&co\""));
  const auto r = run_cli("run rig.toml -o rig.h5 --report rep", dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string html = slurp(dir / "rep" / "index.html");
  EXPECT_THAT(html, HasSubstr("<h1>shudder run: neg&lt;script&gt;alert(&#39;x&#39;)&lt;/script&gt;&amp;co</h1>"));
  EXPECT_THAT(html, Not(HasSubstr("<script>")));
}

TEST(ReportIndex, SweepPageHoldsTheCasesTableAndItsPlot) {
  if (!have_gnuplot()) GTEST_SKIP() << "gnuplot not installed";
  const auto dir = scratch_dir("report_index_sweep");
  write_file(dir / "s.toml", short_rig_scenario());
  const auto r =
      run_cli("sweep s.toml --set rig.torsion_bar.natural_frequency_Hz=200,300 --jobs 2 -o sw.h5 --report rep", dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_THAT(r.out, HasSubstr("Report: rep (3 files)"));  // summary.txt, sweep.png, index.html
  const fs::path page = dir / "rep" / "index.html";
  const std::string html = slurp(page);
  EXPECT_THAT(html, HasSubstr("<h1>shudder sweep: rig_shudder_negative_slope</h1>"));
  EXPECT_THAT(html, HasSubstr("<th>rig.torsion_bar.natural_frequency_Hz</th><th>predicted_stable</th>"));
  EXPECT_THAT(html, HasSubstr("<th>simulated_frequency_Hz [Hz]</th>"));
  EXPECT_THAT(html, HasSubstr("<tr><td>200</td>"));
  EXPECT_THAT(html, HasSubstr("<tr><td>300</td>"));
  EXPECT_THAT(html, HasSubstr("<td>vibration</td>"));
  EXPECT_THAT(html, HasSubstr("<a href=\"../sw.h5\">sw.h5</a>"));
  EXPECT_THAT(dead_links(page), IsEmpty());
  expect_clean_in_browser(page, 1);
}

TEST(ReportIndex, ComparePageShowsOneFigurePerTemperature) {
  if (!have_gnuplot()) GTEST_SKIP() << "gnuplot not installed";
  const auto dir = scratch_dir("report_index_compare");
  const auto r =
      run_cli("compare " + source_path("scenarios/fluids/paper_e_fluid_a.toml") + " " +
                  source_path("scenarios/fluids/paper_e_fluid_e.toml") + " --temps 30,60 --json cmp.json --report rep",
              dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const fs::path page = dir / "rep" / "index.html";
  const std::string html = slurp(page);
  EXPECT_THAT(html, HasSubstr("<h1>shudder compare</h1>"));
  EXPECT_THAT(html, HasSubstr("paper-e-fluid-a"));
  EXPECT_THAT(html, HasSubstr("<a href=\"../cmp.json\">cmp.json</a>"));
  EXPECT_EQ(png_files(dir / "rep"), 2);
  EXPECT_THAT(dead_links(page), IsEmpty());
  expect_clean_in_browser(page, 2);
}
