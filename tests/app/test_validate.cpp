// `shudder validate` and its plot driver (report/gnuplot): the CLI writes a date-free
// validation.md whose targets all pass and which reruns reproduce byte for byte; bad folders
// exit 2; write_plot renders PNG and SVG through gnuplot, reproducibly, and reports a missing
// gnuplot, a bad extension or inconsistent series clearly. Plot tests skip without gnuplot.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <sys/wait.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <stdexcept>
#include <string>

#include "report/gnuplot.hpp"
#include "io/input_error.hpp"

namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;
using ::testing::Not;

struct TempDir {
  fs::path path;
  TempDir() {
    std::string p = (fs::temp_directory_path() / "shudder-validate-test-XXXXXX").string();
    if (!::mkdtemp(p.data())) throw std::runtime_error("mkdtemp failed");
    path = p;
  }
  ~TempDir() {
    std::error_code ec;
    fs::remove_all(path, ec);
  }
};

std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

int run_cli(const std::string& args) {
  const std::string cmd = std::string("'") + SHUDDER_CLI + "' " + args + " >/dev/null 2>&1";
  const int status = std::system(cmd.c_str());
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

bool have_gnuplot() { return std::system("command -v gnuplot >/dev/null 2>&1") == 0; }

shudder::report::Plot sample_plot() {
  shudder::report::Plot p;
  p.title = "test 'quoted' title_with_underscores";
  p.xlabel = "time [s]";
  p.ylabel = "torque [Nm]";
  p.y2label = "temperature [°C]";
  shudder::report::Series torque{"torque [Nm]", {}, {}};
  shudder::report::Series temp{"temp [°C]", {}, {}};
  for (int i = 0; i <= 50; ++i) {
    torque.x.push_back(0.1 * i);
    torque.y.push_back(40 + 0.1 * i * i);
    temp.x.push_back(0.1 * i);
    temp.y.push_back(i == 25 ? NAN : 77 + 0.3 * i);  // a gap
  }
  p.series = {torque};
  p.series_y2 = {temp};
  return p;
}

TEST(Validate, WritesReproducibleDocWhereAllTargetsPass) {
  TempDir dir;
  const std::string args = std::string("validate --scenarios '") + SHUDDER_SOURCE_DIR + "/scenarios' --docs '" +
                           dir.path.string() + "' --no-plots";
  ASSERT_EQ(run_cli(args), 0);
  const std::string first = slurp(dir.path / "validation.md");
  EXPECT_THAT(first, HasSubstr("| case | quantity | target | result | pass |"));
  EXPECT_THAT(first, HasSubstr("./build/app/shudder validate --scenarios scenarios --docs docs"));
  EXPECT_THAT(first, HasSubstr("paper_g_literal"));
  EXPECT_THAT(first, Not(HasSubstr("**NO**")));
  ASSERT_EQ(run_cli(args), 0);
  EXPECT_EQ(slurp(dir.path / "validation.md"), first);
  EXPECT_FALSE(fs::exists(dir.path / "validation.md.tmp"));
}

TEST(Validate, MissingScenarioFolderIsBadInput) {
  TempDir dir;
  EXPECT_EQ(run_cli("validate --scenarios '" + (dir.path / "none").string() + "' --docs '" + dir.path.string() +
                    "' --no-plots"),
            2);
}

TEST(WritePlot, RendersPngAndSvgReproducibly) {
  if (!have_gnuplot()) GTEST_SKIP() << "gnuplot not installed";
  TempDir dir;
  const auto p = sample_plot();
  shudder::report::write_plot((dir.path / "a.png").string(), p);
  shudder::report::write_plot((dir.path / "b.png").string(), p);
  shudder::report::write_plot((dir.path / "a.svg").string(), p);
  const std::string png = slurp(dir.path / "a.png");
  ASSERT_GT(png.size(), 8u);
  EXPECT_EQ(png.substr(1, 3), "PNG");
  EXPECT_EQ(slurp(dir.path / "b.png"), png);
  EXPECT_THAT(slurp(dir.path / "a.svg"), HasSubstr("<svg"));
  EXPECT_FALSE(fs::exists(dir.path / "a.png.tmp"));
}

TEST(WritePlot, RejectsBadRequests) {
  TempDir dir;
  auto p = sample_plot();
  EXPECT_THROW(shudder::report::write_plot((dir.path / "a.jpg").string(), p), shudder::io::InputError);
  p.series[0].y.pop_back();
  EXPECT_THROW(shudder::report::write_plot((dir.path / "a.png").string(), p), std::invalid_argument);
  EXPECT_THROW(shudder::report::write_plot((dir.path / "no_dir" / "a.png").string(), sample_plot()),
               shudder::io::InputError);
}

TEST(WritePlot, MissingGnuplotIsAClearError) {
  TempDir dir;
  const char* old = std::getenv("PATH");
  const std::string saved = old ? old : "";
  ::setenv("PATH", dir.path.c_str(), 1);
  try {
    shudder::report::write_plot((dir.path / "a.png").string(), sample_plot());
    ADD_FAILURE() << "expected an error";
  } catch (const std::runtime_error& e) {
    EXPECT_THAT(e.what(), HasSubstr("gnuplot"));
  }
  ::setenv("PATH", saved.c_str(), 1);
  EXPECT_FALSE(fs::exists(dir.path / "a.png")) << "no image without gnuplot";
  EXPECT_FALSE(fs::exists(dir.path / "a.png.tmp"));
}

// A failing gnuplot is reported by its own cause, without our script. The stand-in
// prints what gnuplot 5 prints for a script error (the echoed script line, a caret, then
// `"FILE" line N: MESSAGE`) and exits 1. The old message appended the log's tail, so it held the
// script text `plot 'data.txt' using 1:2` and the caret line.
TEST(WritePlot, GnuplotFailureIsReportedByItsCauseWithoutTheScript) {
  TempDir dir;
  const fs::path fake = dir.path / "gnuplot";
  {
    std::ofstream out(fake);
    out << "#!/bin/sh\n"
           "echo \"\"\n"
           "echo \"plot 'data.txt' using 1:2 with lines\"\n"
           "echo \"                       ^\"\n"
           "echo \"\\\"$1\\\" line 12: warning: Skipping data file with no valid points\"\n"
           "echo \"\\\"$1\\\" line 14: undefined variable: foo\"\n"
           "exit 1\n";
  }
  fs::permissions(fake, fs::perms::owner_all);
  const char* old = std::getenv("PATH");
  const std::string saved = old ? old : "";
  ::setenv("PATH", dir.path.c_str(), 1);
  const std::string out = (dir.path / "a.png").string();
  std::string message;
  try {
    shudder::report::write_plot(out, sample_plot());
  } catch (const std::runtime_error& e) {
    message = e.what();
  }
  ::setenv("PATH", saved.c_str(), 1);
  EXPECT_EQ(message, "gnuplot could not draw " + out + ": undefined variable: foo");
  EXPECT_FALSE(fs::exists(out));
}

}  // namespace
