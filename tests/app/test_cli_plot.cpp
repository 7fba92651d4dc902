// `shudder plot` and the --report directories end to end, from runs made here: a short rig run
// that shudders (the negative-slope case, 0.8 s), a short prescribed-slip run (Paper G Case 1,
// 3 s) and a two-case sweep. Every --what draws a real PNG (signature bytes) and SVG through
// gnuplot with the scenario's name in the title; plots the file cannot support exit 2 naming
// what is missing; reports hold the summary and the key plots. The stability map stored by
// `shudder run` is checked against the run itself: the run's operating point (30 rpm, 60 °C)
// lies in its unstable region, at the bar's frequency.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <regex>

#include "io/hdf5_run.hpp"
#include "report/plots.hpp"
#include "tests/support/cli.hpp"
#include "tests/support/short_scenarios.hpp"

using namespace shudder;
using namespace shudder::test;
using ::testing::HasSubstr;
using ::testing::Not;
namespace fs = std::filesystem;

namespace {

bool have_gnuplot() { return std::system("command -v gnuplot >/dev/null 2>&1") == 0; }

void expect_png(const fs::path& p) {
  ASSERT_TRUE(fs::exists(p)) << p;
  const std::string bytes = slurp(p);
  ASSERT_GT(bytes.size(), 1000u) << p;
  EXPECT_EQ(bytes.substr(0, 8), std::string("\x89PNG\r\n\x1a\n", 8)) << p;
}

std::string expect_svg(const fs::path& p) {
  EXPECT_TRUE(fs::exists(p)) << p;
  const std::string text = slurp(p);
  EXPECT_THAT(text, HasSubstr("<svg")) << p;
  return text;
}

// A scratch directory `name` holding a fresh run of `scenario` as `h5` (one per test: CTest may
// run tests in parallel processes).
fs::path run_in(const std::string& name, const std::string& scenario, const std::string& h5) {
  const auto d = scratch_dir(name);
  write_file(d / "scenario.toml", scenario);
  const auto r = run_cli("run scenario.toml -o " + h5, d);
  EXPECT_EQ(r.exit_code, 0) << r.err;
  return d;
}

// A shipped network file run into DIR/STEM.h5 and its spectrum plotted to DIR/STEM.svg: the
// run's summary and the plot's SVG text (empty, with the failure recorded, if a command fails).
struct RunAndPlot {
  std::string summary, svg;
};
RunAndPlot network_spectrum(const fs::path& dir, const std::string& network, const std::string& stem) {
  const auto run =
      run_cli("run " + source_path("scenarios/networks/" + network + ".toml") + " -o " + stem + ".h5", dir);
  EXPECT_EQ(run.exit_code, 0) << run.err;
  const auto plot = run_cli("plot " + stem + ".h5 --what spectrum -o " + stem + ".svg", dir);
  EXPECT_EQ(plot.exit_code, 0) << plot.err;
  return {run.out, run.exit_code == 0 && plot.exit_code == 0 ? slurp(dir / (stem + ".svg")) : std::string()};
}

// A network summary's none verdict: its largest oscillation's amplitude and frequency.
const std::regex kNoneVerdict("Verdict: none \\(largest oscillation ([0-9.]+) N m at ([0-9.]+) Hz\\)");

}  // namespace

TEST(CliPlot, RigRunStoresAStabilityMapThatPlacesTheRunInItsUnstableRegion) {
  const auto dir = run_in("plot_map", short_rig_scenario(), "rig.h5");
  const auto rec = io::read_run_hdf5((dir / "rig.h5").string());
  const auto* m = rec.find_map("stability_map");
  ASSERT_NE(m, nullptr);
  // Grid: 60 slip speeds 1 .. 125 rpm, 50 temperatures start - 20 .. start + 80 = 40 .. 140 °C.
  ASSERT_EQ(m->x.size(), 60u);
  ASSERT_EQ(m->y.size(), 50u);
  EXPECT_DOUBLE_EQ(m->x.front(), 1.0);
  EXPECT_DOUBLE_EQ(m->x.back(), 125.0);
  EXPECT_DOUBLE_EQ(m->y.front(), 40.0);
  EXPECT_DOUBLE_EQ(m->y.back(), 140.0);
  EXPECT_EQ(m->x_units, "rpm");
  EXPECT_EQ(m->y_units, "degC");
  ASSERT_NE(m->find_scalar("normal_force_N"), nullptr);
  EXPECT_DOUBLE_EQ(m->find_scalar("normal_force_N")->value, 15000.0);
  const auto* margin = m->find("margin_per_s");
  const auto* freq = m->find("frequency_Hz");
  ASSERT_NE(margin, nullptr);
  ASSERT_NE(freq, nullptr);
  // The grid point nearest the run's operating point (30 rpm, 60 °C): unstable (the fluid's
  // slope, -1.5 N m s/rad, beats the bar's +0.95 N m s/rad, scenario comment) at the bar's
  // 378 Hz.
  long i = 0, j = 0;
  for (long k = 0; k < 60; ++k)
    if (std::abs(m->x[k] - 30.0) < std::abs(m->x[i] - 30.0)) i = k;
  for (long k = 0; k < 50; ++k)
    if (std::abs(m->y[k] - 60.0) < std::abs(m->y[j] - 60.0)) j = k;
  EXPECT_GT(margin->values(i, j), 0.0);
  EXPECT_NEAR(freq->values(i, j), 378.0, 0.01 * 378.0);
}

TEST(CliPlot, EveryRunPlotOfARigRunDrawsPngAndSvgTitledWithTheScenario) {
  if (!have_gnuplot()) GTEST_SKIP() << "gnuplot not installed";
  const auto dir = run_in("plot_rig", short_rig_scenario(), "rig.h5");
  for (const char* what : {"torque", "temperature", "spectrum", "spectrogram", "stability_map"}) {
    for (const char* ext : {".png", ".svg"}) {
      const std::string out = std::string(what) + ext;
      const auto r = run_cli(std::string("plot rig.h5 --what ") + what + " -o " + out, dir);
      ASSERT_EQ(r.exit_code, 0) << what << ext << "\n" << r.err;
      EXPECT_THAT(r.out, HasSubstr("Plot: " + out));
      if (std::string(ext) == ".png") {
        expect_png(dir / out);
      } else {
        const std::string svg = expect_svg(dir / out);
        EXPECT_THAT(svg, HasSubstr("rig_shudder_negative_slope: ")) << what;
      }
      EXPECT_FALSE(fs::exists(dir / (out + ".tmp")));
    }
  }
  // The spectrum names what the detector found; the spectrogram its colour scale in dB.
  EXPECT_THAT(slurp(dir / "spectrum.svg"), HasSubstr("friction-induced vibration at 37"));
  EXPECT_THAT(slurp(dir / "spectrogram.svg"), HasSubstr("dB re 1 (N m)²/Hz"));
  // The spectrogram names its channel and a frame length one can read.
  EXPECT_THAT(slurp(dir / "spectrogram.svg"),
              testing::ContainsRegex("spectrogram of torque_Nm \\(frames of [0-9.]+ ms = "));
  // The oscillating run's torque: slip in its own panel, onset and end details.
  const std::string torque = slurp(dir / "torque.svg");
  for (const char* text : {"slip_rpm [rpm]", "onset detail (onset ", "end detail (", "8 periods of 37"})
    EXPECT_THAT(torque, HasSubstr(text)) << text;
  // The spectrum's fundamental over the oscillating part is the detector's window: it lies
  // closer to the detector's half peak-to-peak than the whole record's, which averages in the
  // quiet start, and not above it (the half peak-to-peak also holds the harmonics).
  const std::string spectrum = slurp(dir / "spectrum.svg");
  std::smatch m, d;
  ASSERT_TRUE(
      std::regex_search(spectrum, m, std::regex("fundamental ([0-9.]+) N m \\(whole record: ([0-9.]+) N m\\)")));
  ASSERT_TRUE(std::regex_search(spectrum, d, std::regex("detector amplitude ([0-9.]+) N m \\(half peak-to-peak\\)")));
  const double part = std::stod(m[1].str()), whole = std::stod(m[2].str()), detector = std::stod(d[1].str());
  EXPECT_LT(whole, part);
  EXPECT_LE(part, 1.02 * detector);
  EXPECT_LT(std::abs(detector - part), std::abs(detector - whole));
  // The thermometers are told apart in the legend.
  EXPECT_THAT(slurp(dir / "temperature.svg"), HasSubstr("ir_temp_C: IR pyrometer (dashed, triangles); within "));
  EXPECT_THAT(slurp(dir / "stability_map.svg"), HasSubstr("stable | unstable boundary"));
}

TEST(CliPlot, PrescribedSlipRunPlotsTimeHistoriesButHasNoStabilityMap) {
  if (!have_gnuplot()) GTEST_SKIP() << "gnuplot not installed";
  const auto dir = run_in("plot_prescribed", short_prescribed_scenario(), "pg.h5");
  for (const char* what : {"torque", "temperature", "spectrum", "spectrogram"}) {
    const auto r = run_cli(std::string("plot pg.h5 --what ") + what + " -o " + what + ".png", dir);
    ASSERT_EQ(r.exit_code, 0) << what << "\n" << r.err;
    expect_png(dir / (std::string(what) + ".png"));
  }
  // No shudder: the speed below the torque, no detail panels.
  ASSERT_EQ(run_cli("plot pg.h5 --what torque -o torque.svg", dir).exit_code, 0);
  const std::string torque = slurp(dir / "torque.svg");
  EXPECT_THAT(torque, HasSubstr("speed_rpm [rpm]"));
  EXPECT_THAT(torque, Not(HasSubstr("onset detail")));
  const auto r = run_cli("plot pg.h5 --what stability_map -o map.png", dir);
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.err, HasSubstr("pg.h5: no /analysis/stability_map: it is written for rig scenarios"));
  EXPECT_FALSE(fs::exists(dir / "map.png"));
  EXPECT_FALSE(fs::exists(dir / "map.png.tmp"));
}

TEST(CliPlot, SweepPlotDrawsPngAndSvgAndFileKindsAreNotMixedUp) {
  if (!have_gnuplot()) GTEST_SKIP() << "gnuplot not installed";
  const auto dir = scratch_dir("plot_sweep");
  write_file(dir / "s.toml", short_rig_scenario());
  auto r = run_cli("sweep s.toml --set rig.torsion_bar.natural_frequency_Hz=200,300 --jobs 2 --quiet -o sw.h5", dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  r = run_cli("plot sw.h5 --what sweep -o sweep.png", dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  expect_png(dir / "sweep.png");
  r = run_cli("plot sw.h5 --what sweep -o sweep.svg", dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string svg = expect_svg(dir / "sweep.svg");
  EXPECT_THAT(svg, HasSubstr("rig_shudder_negative_slope: sweep of "
                             "rig.torsion_bar.natural_frequency_Hz (2 cases)"));
  EXPECT_THAT(svg, HasSubstr("predicted frequency"));
  EXPECT_THAT(svg, HasSubstr("simulated: vibration"));
  // Frequency and margin each in a panel of their own, each with its own zero: no right axis.
  EXPECT_THAT(svg, HasSubstr("frequency: predicted (linearised) and simulated (detector)"));
  EXPECT_THAT(svg, HasSubstr("predicted margin (> 0: unstable), marked with each case's simulated verdict"));
  EXPECT_THAT(svg, Not(HasSubstr("right axis")));

  // A sweep file has no run signals; a run file has no /cases table.
  r = run_cli("plot sw.h5 --what torque -o t.png", dir);
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.err, HasSubstr("sw.h5: no /signals: a sweep file; use --what sweep"));
  write_file(dir / "rig.toml", short_rig_scenario());
  ASSERT_EQ(run_cli("run rig.toml -o rig.h5", dir).exit_code, 0);
  r = run_cli("plot rig.h5 --what sweep -o s.png", dir);
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.err, HasSubstr("rig.h5: no /cases table: a run file"));
  EXPECT_FALSE(fs::exists(dir / "t.png"));
  EXPECT_FALSE(fs::exists(dir / "s.png"));
}

// A network run's plots mark the verdict the run reached on its judged clutch (its loaded window,
// its band from 2 Hz), not another peak a generic look at the record finds. The Haldex car's
// take-up judders at 44.5 Hz: the label gives the verdict's frequency and the detector's
// amplitude. On its low-mu hill the start rings the 1.83 Hz shuffle, which dies away (none):
// the mark names that 1.83 Hz ringing, where the generic band (from 5 Hz) would mark a 4.8 Hz
// side peak.
TEST(CliPlot, NetworkSpectrumMarksTheRunsVerdict) {
  if (!have_gnuplot()) GTEST_SKIP() << "gnuplot not installed";
  const auto dir = scratch_dir("plot_network_verdict");
  const auto judder = network_spectrum(dir, "haldex_car_takeup_judder", "takeup");
  std::smatch v;
  ASSERT_TRUE(
      std::regex_search(judder.summary, v, std::regex("Verdict: vibration at ([0-9.]+) Hz, amplitude ([0-9.]+) N m")))
      << judder.summary;
  std::smatch s;
  ASSERT_TRUE(std::regex_search(judder.svg, s, std::regex("friction-induced vibration at ([0-9.]+) Hz"))) << judder.svg;
  EXPECT_NEAR(std::stod(s[1]), std::stod(v[1]), 0.05);  // the label's one decimal
  ASSERT_TRUE(std::regex_search(judder.svg, s, std::regex("detector amplitude ([0-9.]+) N m")));
  EXPECT_NEAR(std::stod(s[1]), std::stod(v[2]), 0.05);  // both printed to three digits

  const auto hill = network_spectrum(dir, "haldex_car_low_mu_uphill", "hill");
  ASSERT_TRUE(std::regex_search(hill.summary, v, kNoneVerdict)) << hill.summary;
  ASSERT_TRUE(std::regex_search(hill.svg, s, std::regex("largest oscillation ([0-9.]+) N m at ([0-9.]+) Hz")));
  EXPECT_EQ(s[2].str(), v[2].str());
  EXPECT_LT(std::stod(s[2]), 5.0);
}

// A run that reads none: the spectrum's mark names the detector's strongest oscillation, the
// figures the summary prints, not the whole record's spectral peak nearby (which, for a network
// clutch judged over its loaded window, can lie a bin or more away).
TEST(CliPlot, NetworkSpectrumOfANoneVerdictNamesTheDetectorsFigures) {
  if (!have_gnuplot()) GTEST_SKIP() << "gnuplot not installed";
  const auto dir = scratch_dir("plot_network_none");
  const auto chain = network_spectrum(dir, "four_inertia_chain", "chain");
  std::smatch v;
  ASSERT_TRUE(std::regex_search(chain.summary, v, kNoneVerdict)) << chain.summary;
  std::smatch s;
  ASSERT_TRUE(
      std::regex_search(chain.svg, s, std::regex("no shudder: largest oscillation ([0-9.]+) N m at ([0-9.]+) Hz")))
      << chain.svg;
  EXPECT_EQ(s[1].str(), v[1].str());  // both printed to three digits
  EXPECT_EQ(s[2].str(), v[2].str());
  // The chain's clutches ring well above the threshold as they lock, once each: a transient,
  // which the summary's none already says and the label must not call "under the threshold".
  ASSERT_TRUE(std::regex_search(chain.svg, s,
                                std::regex("above the threshold ([0-9.]+) N m but not sustained \\(a transient\\)")));
  EXPECT_GT(std::stod(v[1]), std::stod(s[1]));
  EXPECT_THAT(chain.svg, Not(HasSubstr("under the threshold")));
  // Prescribed slip at constant speed rings far below the threshold.
  const auto quiet = run_in("plot_prescribed_none", short_prescribed_scenario(), "pg.h5");
  ASSERT_EQ(run_cli("plot pg.h5 --what spectrum -o pg.svg", quiet).exit_code, 0);
  const std::string quiet_svg = slurp(quiet / "pg.svg");
  EXPECT_THAT(quiet_svg, HasSubstr("under the threshold"));
  EXPECT_THAT(quiet_svg, Not(HasSubstr("not sustained")));
}

TEST(CliPlot, BadRequestsExitTwoNamingTheProblem) {
  const auto dir = run_in("plot_bad", short_rig_scenario(), "rig.h5");
  struct Case {
    std::string args, fragment;
  };
  for (const auto& c :
       std::vector<Case>{{"plot rig.h5 --what torqeu -o x.png", "--what"},
                         {"plot absent.h5 --what torque -o x.png", "absent.h5: cannot read run file: no such file"},
                         {"plot rig.h5 --what torque -o x.jpg", "unsupported plot format '.jpg'"},
                         {"plot rig.h5 --what torque -o no_dir/x.png", "cannot write plot"},
                         {"plot rig.h5 --what torque", "--output"}}) {
    const auto r = run_cli(c.args, dir);
    EXPECT_EQ(r.exit_code, 2) << c.args << "\n" << r.err;
    EXPECT_THAT(r.err, HasSubstr(c.fragment)) << c.args;
  }
  EXPECT_FALSE(fs::exists(dir / "x.png"));
  EXPECT_FALSE(fs::exists(dir / "x.jpg"));
}

TEST(CliPlot, RunReportHoldsTheSummaryAndTheKeyPlots) {
  if (!have_gnuplot()) GTEST_SKIP() << "gnuplot not installed";
  // Rig run: summary plus five plots.
  const auto dir = scratch_dir("plot_report_rig");
  write_file(dir / "rig.toml", short_rig_scenario());
  auto r = run_cli("run rig.toml -o rig.h5 --report rep", dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_THAT(r.out, HasSubstr("Report: rep (8 files)"));  // summary.txt, verdict.json, five plots, index.html
  EXPECT_TRUE(fs::exists(dir / "rep" / "verdict.json"));
  const std::string summary = slurp(dir / "rep" / "summary.txt");
  EXPECT_THAT(summary, HasSubstr("Scenario  rig_shudder_negative_slope (rig)"));
  EXPECT_THAT(summary, HasSubstr("Output: rig.h5"));
  EXPECT_EQ(r.out.substr(0, summary.size()), summary) << "summary.txt is the printed summary";
  for (const char* f : {"torque.png", "temperature.png", "spectrum.png", "spectrogram.png", "stability_map.png"})
    expect_png(dir / "rep" / f);

  // Prescribed-slip run: no spectrogram, no stability map.
  const auto pdir = scratch_dir("plot_report_prescribed");
  write_file(pdir / "pg.toml", short_prescribed_scenario());
  r = run_cli("run pg.toml -o pg.h5 --report rep", pdir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  for (const char* f : {"summary.txt", "torque.png", "temperature.png", "spectrum.png"})
    EXPECT_TRUE(fs::exists(pdir / "rep" / f)) << f;
  EXPECT_FALSE(fs::exists(pdir / "rep" / "spectrogram.png"));
  EXPECT_FALSE(fs::exists(pdir / "rep" / "stability_map.png"));
}

// A gnuplot that fails (here a stand-in that exits 1) costs the run report its plots, not the
// report: summary.txt and verdict.json are written, each plot is listed as skipped with gnuplot's
// cause, exit 0 -- as the characterisation, comparison and diagnosis reports already did. Before,
// the first plot's failure ended the report ("shudder: report failed") after the summary.
TEST(CliPlot, RunReportSkipsPlotsWhenGnuplotFails) {
  const auto dir = scratch_dir("plot_report_gnuplot_fails");
  const auto bin = dir / "fakebin";
  fs::create_directories(bin);
  write_file(bin / "gnuplot", "#!/bin/sh\necho \"\\\"$1\\\" line 3: cannot open output\"\nexit 1\n");
  fs::permissions(bin / "gnuplot", fs::perms::owner_all);
  write_file(dir / "rig.toml", short_rig_scenario());
  const char* old = std::getenv("PATH");
  const std::string saved = old ? old : "";
  ::setenv("PATH", (bin.string() + ":" + saved).c_str(), 1);
  const auto r = run_cli("run rig.toml -o rig.h5 --report rep", dir);
  ::setenv("PATH", saved.c_str(), 1);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_THAT(r.out, HasSubstr("Report: rep (3 files)"));  // summary.txt, verdict.json, index.html
  EXPECT_TRUE(fs::exists(dir / "rep" / "summary.txt"));
  EXPECT_TRUE(fs::exists(dir / "rep" / "verdict.json"));
  EXPECT_THAT(r.err, HasSubstr("shudder: warning: report: torque.png: gnuplot could not draw"));
  EXPECT_THAT(r.err, HasSubstr("cannot open output"));
  EXPECT_THAT(r.err, Not(HasSubstr("report failed")));
  EXPECT_FALSE(fs::exists(dir / "rep" / "torque.png"));
  EXPECT_FALSE(fs::exists(dir / "rep" / "torque.png.tmp"));
}

TEST(CliPlot, SweepReportHoldsTheSummaryAndTheSweepPlot) {
  if (!have_gnuplot()) GTEST_SKIP() << "gnuplot not installed";
  const auto dir = scratch_dir("plot_report_sweep");
  write_file(dir / "s.toml", short_rig_scenario());
  const auto r =
      run_cli("sweep s.toml --set rig.torsion_bar.natural_frequency_Hz=200,300 --jobs 2 -o sw.h5 --report rep", dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string summary = slurp(dir / "rep" / "summary.txt");
  EXPECT_THAT(summary, HasSubstr("Sweep of rig_shudder_negative_slope: 2 cases"));
  EXPECT_THAT(summary, HasSubstr("Simulated: 0 none, 2 vibration, 0 stick-slip"));
  EXPECT_THAT(r.out, HasSubstr(summary));
  expect_png(dir / "rep" / "sweep.png");
}

// The zero contour by marching squares, against closed forms.
TEST(CliPlot, ContourOfALinearAndARadialFieldLiesOnTheExactCurve) {
  std::vector<double> x, y;
  for (int k = 0; k <= 40; ++k) x.push_back(-2.0 + 0.1 * k), y.push_back(-2.0 + 0.1 * k);
  // v = x - 0.55: every contour point at x = 0.55 exactly (linear interpolation is exact).
  Eigen::MatrixXd lin(41, 41), rad(41, 41);
  for (int i = 0; i <= 40; ++i)
    for (int j = 0; j <= 40; ++j) {
      lin(i, j) = x[i] - 0.55;
      rad(i, j) = x[i] * x[i] + y[j] * y[j] - 1.0;
    }
  const report::Series a = report::contour_series(x, y, lin, 0.0, "zero");
  ASSERT_FALSE(a.x.empty());
  std::size_t points = 0;
  for (std::size_t k = 0; k < a.x.size(); ++k) {
    if (std::isnan(a.x[k])) continue;  // breaks between segments
    EXPECT_NEAR(a.x[k], 0.55, 1e-12);
    ++points;
  }
  EXPECT_EQ(points, 2u * 40u);  // one segment per cell row the line crosses
  // v = x² + y² - 1: contour points on the unit circle to the interpolation error of a
  // quadratic over a 0.1 cell, h²/4 / (2 r) ~ 1.3e-3.
  const report::Series c = report::contour_series(x, y, rad, 0.0, "circle");
  for (std::size_t k = 0; k < c.x.size(); ++k) {
    if (std::isnan(c.x[k])) continue;
    EXPECT_NEAR(std::hypot(c.x[k], c.y[k]), 1.0, 2e-3);
  }
  // Nothing crosses 5 on the linear field; a NaN corner removes its cells.
  EXPECT_TRUE(report::contour_series(x, y, lin, 5.0, "none").x.empty());
  lin(25, 3) = std::numeric_limits<double>::quiet_NaN();  // x[25] = 0.5, next to the line
  EXPECT_EQ(report::contour_series(x, y, lin, 0.0, "hole").x.size(), a.x.size() - 2 * 3);
}
