// `shudder characterise` end to end: simulated Paper D ramp logs (CSV, sensor noise) -> a fluid
// file that `screen` and `run` accept, FIT.json and a report; bad input -> exit 2 with one
// line naming the file and the reason, a fit that gives no plausible law -> exit 1, and in
// every failure nothing written.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "io/fluid_loader.hpp"
#include "tests/support/cli.hpp"
#include "tests/support/json.hpp"
#include "tests/support/ramp_runs.hpp"

namespace {

using namespace shudder;
namespace fs = std::filesystem;

// Paper D cycles of fluid C at 10 and 20 kN from 40, 60 and 80 °C, one CSV each (a.csv ...).
std::string write_runs(const fs::path& dir, const std::string& rig = "lsctr", double t_ramp_s = 10.0) {
  const clutch::Fluid fluid = io::load_fluid(SHUDDER_SOURCE_DIR "/scenarios/fluids/lsc_fluid_c.toml");
  std::string names;
  unsigned seed = 1;
  for (double load : {10000.0, 20000.0})
    for (double t0 : {40.0, 60.0, 80.0}) {
      clutch::WetClutchParams p;
      p.start_temp_C = p.sump_start_temp_C = t0;
      rig_models::PrescribedSlipSettings s;
      const auto cycle = test::paper_d_cycle(load, t_ramp_s);
      s.duration_s = cycle.slip_speed_rpm.times_s().back();
      s.thermal_step_s = 0.02;
      s.sample_rate_Hz = 50.0;
      const auto rec = rig_models::run_prescribed_slip(clutch::WetClutch(p, fluid), cycle, s);
      io::MeasurementOptions mo;
      mo.noise = true;
      mo.seed = seed;
      mo.rig = rig;
      const std::string name = std::string(1, char('a' + seed - 1)) + ".csv";
      io::write_measurement((dir / name).string(), rec, mo);
      names += " " + name;
      ++seed;
    }
  return names;
}

const std::string kFluidArgs = " --nu40-cSt 35 --nu100-cSt 6.7 --radius uniform_pressure";

TEST(CliCharacterise, WritesAFluidThatScreenAndRunAcceptPlusJsonAndReport) {
  const auto dir = test::scratch_dir("characterise_ok");
  const std::string runs = write_runs(dir);
  const auto r =
      test::run_cli("characterise" + runs + " -o fitted.toml --json fit.json --report rep" + kFluidArgs, dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_THAT(r.out, ::testing::HasSubstr("12 ramps used (6 up, 6 down)"));
  const auto json = test::parse(test::slurp(dir / "fit.json"));
  EXPECT_EQ(json["format"].str(), "shudder-characterisation/1");
  // 2 loads x (40, 60, 80 °C and the hot row at the hottest reading, ~100 °C).
  EXPECT_EQ(json["rows"].items.size(), 8u);
  EXPECT_GT(json["hot_row_temp_C"].num(), 83.0);
  EXPECT_EQ(json["ramps_used"].items.size(), 12u);
  EXPECT_TRUE(fs::exists(dir / "rep" / "summary.txt"));
  // Paper D's cycles start at N0 = 1 rpm, never at rest: no breakaway to measure, and it says so.
  EXPECT_FALSE(json["breakaway"]["measured"].boolean);
  EXPECT_EQ(json["breakaway"]["ratio"].num(), 1.0);
  EXPECT_THAT(json["breakaway"]["not_measured"].str(), ::testing::HasSubstr("no run starts an up-ramp from rest"));
  EXPECT_THAT(r.out, ::testing::HasSubstr("breakaway ratio (mu_s / mu_k(v_min), written): 1 — not measured: no run "
                                          "starts an up-ramp from rest"));
  EXPECT_THAT(test::slurp(dir / "fitted.toml"), ::testing::HasSubstr("source = \"not measured: no run starts"));
  // Piecewise compensation: one surface per load, its knots at the rows (40, 60, 80 °C) and on.
  const auto pw = test::run_cli(
      "characterise" + runs + " -o pw.toml --law table --compensation piecewise --json pw.json" + kFluidArgs, dir);
  ASSERT_EQ(pw.exit_code, 0) << pw.err;
  const auto pj = test::parse(test::slurp(dir / "pw.json"));
  EXPECT_EQ(pj["compensation"].str(), "piecewise");
  ASSERT_EQ(pj["piecewise"].items.size(), 2u);  // 10 and 20 kN
  for (const auto& row_temp : pj["temps_C"].items) {
    if (row_temp.num() == pj["hot_row_temp_C"].num()) continue;  // made after the surface, from it
    bool is_knot = false;
    for (const auto& knot : pj["piecewise"].items[0]["temp_knots_C"].items) is_knot |= knot.num() == row_temp.num();
    EXPECT_TRUE(is_knot) << row_temp.num();
  }
  const auto screen = test::run_cli("screen fitted.toml --load-N 15000", dir);
  EXPECT_EQ(screen.exit_code, 0) << screen.err;
  // The same runs as a table law; a Paper G Case 2 run with it.
  const auto t = test::run_cli("characterise" + runs + " -o table.toml --law table" + kFluidArgs, dir);
  ASSERT_EQ(t.exit_code, 0) << t.err;
  test::write_file(
      dir / "case2.toml",
      test::replace(test::shipped_scenario_text("paper_g_case2_15kN.toml"),
                    "fluid = \"" + test::source_path("scenarios/fluids/lsc_fluid_c.toml"), "fluid = \"table.toml"));
  const auto run = test::run_cli("run case2.toml -o case2.h5", dir);
  EXPECT_EQ(run.exit_code, 0) << run.err;
}

void expect_nothing_written(const fs::path& dir) {
  EXPECT_FALSE(fs::exists(dir / "out.toml"));
  EXPECT_FALSE(fs::exists(dir / "fit.json"));
}

TEST(CliCharacterise, RunWithoutARampIsBadInput) {
  const auto dir = test::scratch_dir("characterise_noramp");
  write_runs(dir);
  std::ostringstream flat;
  flat << "# format: shudder-measurement/1\n# rig: lsctr\ntime_s,speed_rpm,normal_force_N,torque_Nm,temp_C\n";
  for (int k = 0; k < 200; ++k) flat << k * 0.01 << ",25,20000,90," << 60 + 0.01 * k << "\n";
  test::write_file(dir / "flat.csv", flat.str());
  const auto r = test::run_cli("characterise a.csv flat.csv -o out.toml --json fit.json" + kFluidArgs, dir);
  test::expect_rejected(r, {"flat.csv", "no speed ramp found"});
  expect_nothing_written(dir);
}

TEST(CliCharacterise, MixedRigsAreBadInput) {
  const auto dir = test::scratch_dir("characterise_rigs");
  write_runs(dir);
  const auto other = test::scratch_dir("characterise_rigs_other");
  write_runs(other, "other_rig");
  fs::copy_file(other / "a.csv", dir / "z.csv");
  const auto r = test::run_cli("characterise a.csv b.csv z.csv -o out.toml --json fit.json" + kFluidArgs, dir);
  test::expect_rejected(r, {"z.csv", "rig", "'other_rig'", "one rig's runs"});
  expect_nothing_written(dir);
}

TEST(CliCharacterise, RowWithTooFewRampsIsBadInput) {
  const auto dir = test::scratch_dir("characterise_few");
  const std::string runs = write_runs(dir);
  const auto r = test::run_cli("characterise" + runs + " -o out.toml --json fit.json --min-ramps 3" + kFluidArgs, dir);
  test::expect_rejected(r, {".csv", "has 2 ramp(s); at least 3 are needed"});
  expect_nothing_written(dir);
}

TEST(CliCharacterise, RequestedTemperatureOutsideEveryRampIsBadInput) {
  const auto dir = test::scratch_dir("characterise_temps");
  const std::string runs = write_runs(dir);
  const auto r = test::run_cli(
      "characterise" + runs + " -o out.toml --json fit.json --law table --row-temps 40,150" + kFluidArgs, dir);
  test::expect_rejected(r, {"requested row temperature 150 °C: no ramp starts within ±3 °C"});
  expect_nothing_written(dir);
}

TEST(CliCharacterise, QuadraticCompensationWithOneTemperatureIsBadInput) {
  const auto dir = test::scratch_dir("characterise_onetemp");
  write_runs(dir);
  const auto r = test::run_cli("characterise a.csv -o out.toml --json fit.json" + kFluidArgs, dir);
  test::expect_rejected(r, {"a.csv", "quadratic compensation at 10 kN", "--compensation linear or none"});
  expect_nothing_written(dir);
  // Piecewise: one ramp's speed and temperature rise together; no second row to separate them.
  const auto p =
      test::run_cli("characterise a.csv -o out.toml --json fit.json --compensation piecewise" + kFluidArgs, dir);
  test::expect_rejected(p, {"a.csv", "piecewise compensation at 10 kN: ramps start at 1 row temperature",
                            "--compensation linear or none"});
  expect_nothing_written(dir);
}

TEST(CliCharacterise, FitWithoutAPlausibleLawIsANumericalFailure) {
  // Torque x 20: mu ~ 2, which the fitted Mäki sets cannot give inside (0, 1].
  const auto dir = test::scratch_dir("characterise_implausible");
  const std::string runs = write_runs(dir);
  for (const char* f : {"a.csv", "b.csv", "c.csv", "d.csv", "e.csv", "f.csv"}) {
    std::istringstream in(test::slurp(dir / f));
    std::ostringstream out;
    std::string line;
    while (std::getline(in, line)) {
      if (line.empty() || line[0] == '#' || line[0] == 't') {
        out << line << "\n";
        continue;
      }
      std::vector<std::string> cells;
      std::istringstream ls(line);
      for (std::string c; std::getline(ls, c, ',');) cells.push_back(c);
      cells[3] = std::to_string(20.0 * std::stod(cells[3]));
      for (std::size_t i = 0; i < cells.size(); ++i) out << (i ? "," : "") << cells[i];
      out << "\n";
    }
    test::write_file(dir / f, out.str());
  }
  const auto r = test::run_cli("characterise" + runs + " -o out.toml --json fit.json" + kFluidArgs, dir);
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_THAT(r.err, ::testing::HasSubstr("outside (0, 1]"));
  expect_nothing_written(dir);
}

// --method inverse: the runs replayed through the clutch and thermal model; the fluid file holds
// the inverse law, FIT.json and the printout both methods side by side.
TEST(CliCharacterise, InverseMethodReportsBothMethods) {
  const auto dir = test::scratch_dir("characterise_inverse");
  const std::string runs = write_runs(dir);
  const auto r =
      test::run_cli("characterise" + runs + " -o inv.toml --json fit.json --method inverse" + kFluidArgs, dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_THAT(r.out, ::testing::HasSubstr("methods: sensor (quadratic compensation"));
  EXPECT_THAT(r.out, ::testing::HasSubstr("replayed torque vs measured (rms): sensor law"));
  const auto json = test::parse(test::slurp(dir / "fit.json"));
  EXPECT_EQ(json["method"].str(), "inverse");
  EXPECT_EQ(json["temperature"].str(), "model_interface_mean");
  const auto& m = json["methods"];
  ASSERT_EQ(m["sensor"]["rows"].items.size(), 8u);  // with the hot rows
  ASSERT_EQ(m["inverse"]["rows"].items.size(), 8u);
  EXPECT_EQ(m["sensor"]["compensation"].str(), "quadratic");
  // On data from the model itself both laws replay the runs at the torque cell's noise (with the
  // hot rows; docs/characterisation.md 2c: 0.665 against 0.658 N m, 1 %): the inverse law is
  // not worse by more than 3 %, twice that. (Without the hot rows the sensor law missed the runs
  // above its top row by 1.5-4.6 sigma and the inverse one by less.)
  EXPECT_LT(m["inverse"]["replayed_torque_rms_Nm"].num(), 1.03 * m["sensor"]["replayed_torque_rms_Nm"].num());
  EXPECT_EQ(m["thermal_calibration"]["temp_rms_C"].items.size(), 2u);
  EXPECT_NO_THROW(io::load_fluid((dir / "inv.toml").string()));
}

TEST(CliCharacterise, InverseMethodThatDoesNotConvergeIsANumericalFailure) {
  // One law update per pass cannot meet the 1e-4 tolerance from the sensor law's start.
  const auto dir = test::scratch_dir("characterise_inverse_nc");
  const std::string runs = write_runs(dir);
  const auto r = test::run_cli(
      "characterise" + runs + " -o out.toml --json fit.json --method inverse --inverse-iterations 1" + kFluidArgs, dir);
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_THAT(r.err, ::testing::HasSubstr("did not converge: after 1 replays"));
  expect_nothing_written(dir);
}

}  // namespace

namespace {

// The friction radius of --radius model (the default) from the runs' metadata: the default clutch
// on the annulus they state, 40-60 mm: its 20 rings of 1 mm (centres 40.5 ... 59.5 mm) give
// sum r_i A_i / sum A_i = sum r_i² / sum r_i = 50.665 mm exactly (the closed form 2/3 (60³ - 40³) /
// (60² - 40²) = 50.667 mm less the midpoint rule's 0.0017 mm). Written with 10 digits.
TEST(CliCharacterise, TheModelRadiusFollowsTheRunsAnnulus) {
  const auto dir = test::scratch_dir("characterise_annulus");
  const std::string runs = write_runs(dir);
  std::istringstream names(runs);
  for (std::string name; names >> name;) {
    std::string text = test::slurp(dir / name);
    text.insert(text.find('\n') + 1, "# inner_radius_mm: 40\n# outer_radius_mm: 60\n");  // after the format line
    test::write_file(dir / name, text);
  }
  const auto r = test::run_cli("characterise" + runs + " -o f.toml --json f.json --nu40-cSt 35 --nu100-cSt 6.7", dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto json = test::parse(test::slurp(dir / "f.json"));
  double r2 = 0.0, r1 = 0.0;
  for (int i = 0; i < 20; ++i) {
    r2 += (40.5 + i) * (40.5 + i);
    r1 += 40.5 + i;
  }
  EXPECT_NEAR(json["radius"]["effective_mm"].num(), r2 / r1, 1e-7);
  EXPECT_EQ(json["radius"]["rule"].str(), "uniform_pressure");
  EXPECT_THAT(r.out, ::testing::HasSubstr("the default clutch on the run's annulus 40-60 mm"));
  // A radius that is not a number: bad input naming the file and the key.
  const std::string first = runs.substr(1, runs.find(' ', 1) - 1);
  std::string text = test::slurp(dir / first);
  const auto at = text.find("# inner_radius_mm: 40");
  ASSERT_NE(at, std::string::npos);
  text.replace(at, 21, "# inner_radius_mm: forty");
  test::write_file(dir / first, text);
  const auto bad = test::run_cli("characterise" + runs + " -o g.toml --nu40-cSt 35 --nu100-cSt 6.7", dir);
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_THAT(bad.err, ::testing::HasSubstr("inner_radius_mm"));
  EXPECT_THAT(bad.err, ::testing::HasSubstr("'forty'"));
}

}  // namespace
