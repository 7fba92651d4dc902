// `shudder import` end to end: measured runs made by the project's own simulator, rewritten as a
// rig's logger would write them (other names, order, units, delimiter, decimal comma, extra
// columns, no metadata), go through `import` back to the same data and then through
// `characterise` and `diagnose` with no edit by hand; a unit that does not fit is exit 2 with
// one line and nothing written.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "io/fluid_loader.hpp"
#include "io/measured_run.hpp"
#include "tests/support/cli.hpp"
#include "tests/support/ramp_runs.hpp"

namespace {

using namespace shudder;
namespace fs = std::filesystem;
using ::testing::HasSubstr;
using ::testing::Not;

// One logger column: its name, the measured-run column it holds and the factor applied.
struct LoggerColumn {
  std::string name, source;
  double factor = 1.0;
};

// `run` rewritten as a logger file: no metadata, the given columns, delimiter and decimal sign,
// and a constant extra column the import must leave out.
void write_logger(const fs::path& file, const io::MeasuredRun& run, const std::vector<LoggerColumn>& cols,
                  char delimiter, bool decimal_comma) {
  std::ostringstream os;
  os << "cycle_no";
  for (const auto& c : cols) os << delimiter << c.name;
  os << "\n";
  for (std::size_t i = 0; i < run.rows(); ++i) {
    os << 1;
    for (const auto& c : cols) {
      char buf[40];
      std::snprintf(buf, sizeof buf, "%.10g", run.required(c.source)[i] * c.factor);
      std::string s = buf;
      if (decimal_comma)
        for (char& ch : s)
          if (ch == '.') ch = ',';
      os << delimiter << s;
    }
    os << "\n";
  }
  std::ofstream(file) << os.str();
}

const std::vector<LoggerColumn> kMsKnSemicolon = {{"time_ms", "time_s", 1e3},
                                                  {"speed_rpm", "speed_rpm"},
                                                  {"torque_Nm", "torque_Nm"},
                                                  {"temp_C", "temp_C"},
                                                  {"force_kN", "normal_force_N", 1e-3}};
const std::vector<LoggerColumn> kSecondsNewtonsComma = {{"time_s", "time_s"},
                                                        {"speed_rpm", "speed_rpm"},
                                                        {"torque_Nm", "torque_Nm"},
                                                        {"temp_C", "temp_C"},
                                                        {"force_N", "normal_force_N"}};

// The logged columns of two measured runs agree value by value. Tolerance: both hold 6
// significant digits of the same number (the import's conversion ms -> s and kN -> N rounds at
// 1e-16 before printing), so a difference is at most one unit in the 6th digit, 1e-5 relative,
// and occurs only where the conversion's rounding lands on a printing boundary.
void expect_same_logged_columns(const fs::path& a, const fs::path& b) {
  const auto ra = io::read_measured_run(a.string()), rb = io::read_measured_run(b.string());
  ASSERT_EQ(ra.rows(), rb.rows());
  for (const char* col : {"time_s", "speed_rpm", "normal_force_N", "torque_Nm", "temp_C"}) {
    const auto& x = ra.required(col);
    const auto& y = rb.required(col);
    for (std::size_t i = 0; i < x.size(); ++i)
      ASSERT_NEAR(x[i], y[i], 1e-5 * std::abs(x[i]) + 1e-9) << col << " row " << i << " of " << b;
  }
}

// mu of two fluid files' laws at points inside the ramps' data.
void expect_same_law(const fs::path& a, const fs::path& b, double tolerance) {
  const clutch::Fluid fa = io::load_fluid(a.string()), fb = io::load_fluid(b.string());
  for (double v_mm_s : {10.0, 50.0, 200.0, 450.0})
    for (double T : {45.0, 60.0, 75.0}) {
      const double ma = fa.friction->mu(v_mm_s, T, 20000.0), mb = fb.friction->mu(v_mm_s, T, 20000.0);
      EXPECT_NEAR(ma, mb, tolerance * ma) << v_mm_s << " mm/s, " << T << " degC";
    }
}

TEST(CliImport, LoggerRampsThroughImportAndCharacterise) {
  const auto dir = test::scratch_dir("cli_import_characterise");
  const clutch::Fluid fluid = io::load_fluid(SHUDDER_SOURCE_DIR "/scenarios/fluids/lsc_fluid_c.toml");
  std::string originals, imported;
  unsigned seed = 1;
  for (double t0 : {40.0, 60.0, 80.0}) {
    clutch::WetClutchParams p;
    p.start_temp_C = p.sump_start_temp_C = t0;
    rig_models::PrescribedSlipSettings s;
    const auto cycle = test::paper_d_cycle(20000.0);
    s.duration_s = cycle.slip_speed_rpm.times_s().back();
    s.thermal_step_s = 0.02;
    s.sample_rate_Hz = 50.0;
    const auto rec = rig_models::run_prescribed_slip(clutch::WetClutch(p, fluid), cycle, s);
    io::MeasurementOptions mo;
    mo.noise = true;
    mo.seed = seed;
    const std::string name = "run" + std::to_string(seed);
    io::write_measurement((dir / (name + ".csv")).string(), rec, mo);
    // Alternate two logger dialects: ms, kN, ';' and decimal comma; s, N and ','.
    const bool ms_kn = seed % 2 == 1;
    write_logger(dir / (name + ".log"), io::read_measured_run((dir / (name + ".csv")).string()),
                 ms_kn ? kMsKnSemicolon : kSecondsNewtonsComma, ms_kn ? ';' : ',', ms_kn);
    const auto r = test::run_cli("import " + name + ".log -o " + name + "_imported.csv", dir);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_THAT(r.out, HasSubstr(ms_kn ? "(semicolon-separated, decimal comma)" : "(comma-separated, decimal point)"));
    EXPECT_THAT(r.out, HasSubstr("not written: cycle_no"));
    EXPECT_THAT(r.err, HasSubstr("shudder: warning: " + name + ".log: metadata not given"));
    // The same rows the simulator wrote.
    expect_same_logged_columns(dir / (name + ".csv"), dir / (name + "_imported.csv"));
    originals += " " + name + ".csv";
    imported += " " + name + "_imported.csv";
    ++seed;
  }
  const std::string args = " --nu40-cSt 35 --nu100-cSt 6.7 --radius uniform_pressure";
  const auto a = test::run_cli("characterise" + originals + " -o a.toml --json a.json" + args, dir);
  const auto b = test::run_cli("characterise" + imported + " -o b.toml --json b.json" + args, dir);
  ASSERT_EQ(a.exit_code, 0) << a.err;
  ASSERT_EQ(b.exit_code, 0) << b.err;
  EXPECT_THAT(b.out, HasSubstr("6 ramps used (3 up, 3 down)"));
  // The fitted law: the same from the same rows. Tolerance 1e-4 of mu: the two read the same
  // samples at 6 significant digits, differing only where an imported value rounds the other way.
  expect_same_law(dir / "a.toml", dir / "b.toml", 1e-4);
  // The ms/kN logger files straight into characterise with --map: the law of their imports.
  const std::string lin = args + " --compensation linear";
  const auto c = test::run_cli("characterise run1_imported.csv run3_imported.csv -o c.toml" + lin, dir);
  const auto d = test::run_cli(
      "characterise run1.log run3.log -o d.toml --map time_ms=time_s:ms "
      "--map force_kN=normal_force_N:kN" +
          lin,
      dir);
  ASSERT_EQ(c.exit_code, 0) << c.err;
  ASSERT_EQ(d.exit_code, 0) << d.err;
  EXPECT_THAT(d.err, HasSubstr("shudder: warning: run1.log: metadata not given"));
  // The same law as from the imported files. Tolerance 1e-3 of mu: read directly the values keep
  // the logger's 10 digits instead of the imported file's 6, which moves a ramp's window by a
  // sample here and there (measured: the mean load differs by 0.03 N in 20 kN).
  expect_same_law(dir / "c.toml", dir / "d.toml", 1e-3);
}

TEST(CliImport, LoggerRunThroughImportAndDiagnose) {
  const auto dir = test::scratch_dir("cli_import_diagnose");
  test::write_file(dir / "hidden.toml", test::shipped_scenario_text("diagnosis_probe.toml") +
                                            "\n[effects.bearing_drag]\nenabled = true\nequivalent_mu = 0.005\n");
  const auto run =
      test::run_cli("run hidden.toml -o hidden.h5 --measurement a.csv --sample-rate 100 --noise --seed 3", dir);
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const io::MeasuredRun measured = io::read_measured_run((dir / "a.csv").string());
  write_logger(dir / "a.log", measured, kMsKnSemicolon, ';', true);
  // The rig's metadata given on the command line, as a user who knows them would.
  const auto imp =
      test::run_cli("import a.log -o a_imported.csv --meta 'temp_sensor=" + *measured.meta("temp_sensor") +
                        "' --meta oil_flow_ml_min=" + *measured.meta("oil_flow_ml_min") + " --meta rig=lsctr",
                    dir);
  ASSERT_EQ(imp.exit_code, 0) << imp.err;
  EXPECT_EQ(imp.err, "");  // nothing defaulted, nothing to warn about
  test::write_file(dir / "model.toml", test::shipped_scenario_text("diagnosis_probe.toml") +
                                           "\n[effects.torque_sensor_offset]\nenabled = true\noffset_Nm = 0.0\n");
  const auto direct = test::run_cli("diagnose model.toml a.csv --jobs 2", dir);
  const auto via_import = test::run_cli("diagnose model.toml a_imported.csv --jobs 2", dir);
  ASSERT_EQ(direct.exit_code, 0) << direct.err;
  ASSERT_EQ(via_import.exit_code, 0) << via_import.err;
  EXPECT_THAT(via_import.out, HasSubstr("Missing effects: bearing_drag"));
  // The logger file itself, with its mapping on the diagnose command line.
  const auto direct_log = test::run_cli(
      "diagnose model.toml a.log --jobs 2 --map time_ms=time_s:ms "
      "--map force_kN=normal_force_N:kN --map temp_C=temp_C",
      dir);
  ASSERT_EQ(direct_log.exit_code, 0) << direct_log.err;
  EXPECT_THAT(direct_log.err, HasSubstr("a.log: metadata not given, written with the defaults"));
}

TEST(CliImport, UnitThatDoesNotFitIsOneLineAndNothingWritten) {
  const auto dir = test::scratch_dir("cli_import_bad_unit");
  std::ostringstream os;
  os << "time_s;speed_rpm;torque_Nm;temp_C;force_N\n";  // force logged in kN under a name in N
  for (int i = 0; i < 100; ++i) os << "0," << (i < 10 ? "0" : "") << i << ";" << 1 + i << ";95;60;25,3\n";
  test::write_file(dir / "log.csv", os.str());
  const auto r = test::run_cli("import log.csv -o run.csv", dir);
  test::expect_rejected(r, {"log.csv", "column 'force_N'", "look like kN", "--map force_N=normal_force_N:kN"});
  EXPECT_FALSE(fs::exists(dir / "run.csv"));
  const auto fixed = test::run_cli("import log.csv -o run.csv --map force_N=normal_force_N:kN", dir);
  EXPECT_EQ(fixed.exit_code, 0) << fixed.err;
  const auto bad_map = test::run_cli("import log.csv -o run.csv --map force_N=normal_force_N:lbf", dir);
  test::expect_rejected(bad_map, {"--map force_N=normal_force_N:lbf", "unit 'lbf'", "allowed: N, kN"});
  test::write_file(dir / "map.toml", "[columns]\nforce_N = \"normal_force:kN\"\n");
  test::expect_rejected(test::run_cli("import log.csv -o run2.csv --mapping map.toml", dir),
                        {"map.toml:2", "columns.force_N", "did you mean 'normal_force_N'"});
  EXPECT_FALSE(fs::exists(dir / "run2.csv"));
}

TEST(CliImport, CharacteriseAndDiagnoseTakeTrustUnitsAsImportDoes) {
  // A force logged in N that really is small (a light-load rig): refused as kN-looking unless the
  // user says the units are right. With --trust-units the runs get past the unit check and fail,
  // if at all, for what the data are (here: too few rows for a ramp), never for the unit.
  const auto dir = test::scratch_dir("cli_trust_units");
  std::ostringstream os;
  os << "time_s,speed_rpm,torque_Nm,temp_C,force_N\n";
  for (int i = 0; i < 100; ++i) os << 0.01 * i << "," << 1 + i << ",0.1,60,25.3\n";
  test::write_file(dir / "log.csv", os.str());
  const std::string map = " --map force_N=normal_force_N", fluid = " --nu40-cSt 35 --nu100-cSt 6.7";
  const auto refused = test::run_cli("characterise log.csv -o f.toml" + fluid + map, dir);
  test::expect_rejected(refused, {"log.csv", "column 'force_N'", "look like kN", "--trust-units"});
  const auto trusted = test::run_cli("characterise log.csv -o f.toml --trust-units" + fluid + map, dir);
  EXPECT_NE(trusted.exit_code, 0);  // 100 rows of one speed ramp are not a friction law
  EXPECT_THAT(trusted.err, Not(HasSubstr("look like")));
  const auto diagnosed = test::run_cli(
      "diagnose " + test::source_path("scenarios/paper_g_case2_15kN.toml") + " log.csv --trust-units" + map, dir);
  EXPECT_THAT(diagnosed.err, Not(HasSubstr("look like")));
  test::expect_rejected(
      test::run_cli("diagnose " + test::source_path("scenarios/paper_g_case2_15kN.toml") + " log.csv" + map, dir),
      {"log.csv", "look like kN"});
}

}  // namespace
