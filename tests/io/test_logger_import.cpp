// A logger's CSV -> a measured run (io/logger_import): delimiters and decimal separators
// detected, columns found by name or mapped by --map and a mapping file, units converted, units
// that do not fit their values refused with the fix named, metadata defaulted with a warning,
// and the result read back by the measured run's own reader. The logger files are written here.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <functional>
#include <numbers>
#include <sstream>

#include "io/import_mapping.hpp"
#include "io/import_plausibility.hpp"
#include "io/input_error.hpp"
#include "io/logger_import.hpp"
#include "io/measured_run.hpp"
#include "io/measurement_csv.hpp"
#include "tests/support/test_directory.hpp"

namespace {

using shudder::io::import_logger;
using shudder::io::ImportSpec;
using shudder::io::InputError;
using testing::HasSubstr;
using testing::ThrowsMessage;

// A 10 s ramp at 100 Hz in the thesis' range, in SI: speed 1 -> 100 rpm, 20 kN, torque 100 ->
// 90 N m, disc 60 -> 70 degC, sump 60 degC.
double time_s(int i) { return 0.01 * i; }
double speed_rpm(int i) { return 1.0 + 0.099 * i; }
double force_N(int) { return 20000.0; }
double torque_Nm(int i) { return 100.0 - 0.01 * i; }
double temp_C(int i) { return 60.0 + 0.01 * i; }
constexpr int kRows = 1001;

struct LoggedColumn {
  std::string name;
  std::function<double(int)> value;  // in the column's logged unit
};

class LoggerImport : public shudder::test::TestDirectory {
 protected:
  LoggerImport() : TestDirectory("logger_import") {}

  // Writes a logger file; `decimal_comma` prints ',' as the decimal separator.
  std::string logger(const std::string& name, const std::vector<LoggedColumn>& cols, char delimiter,
                     bool decimal_comma = false, const std::string& preamble = "") {
    std::ostringstream os;
    os << preamble;
    for (std::size_t c = 0; c < cols.size(); ++c) os << (c ? std::string(1, delimiter) : "") << cols[c].name;
    os << "\r\n";
    for (int i = 0; i < kRows; ++i) {
      for (std::size_t c = 0; c < cols.size(); ++c) {
        std::ostringstream v;
        v.precision(10);
        v << cols[c].value(i);
        std::string s = v.str();
        if (decimal_comma)
          for (char& ch : s)
            if (ch == '.') ch = ',';
        os << (c ? std::string(1, delimiter) : "") << s;
      }
      os << "\r\n";
    }
    std::ofstream(path(name), std::ios::binary) << os.str();
    return path(name);
  }

  static void expect_thesis_ramp(const shudder::io::MeasuredRun& run) {
    ASSERT_EQ(run.rows(), static_cast<std::size_t>(kRows));
    // Tolerance: the logger prints 10 significant digits (5e-10 relative at worst, e.g. a speed
    // in rad/s), the conversions add 1e-16: 1e-9 of the value.
    const auto near = [](double got, double want) { return std::abs(got - want) <= 1e-9 * std::abs(want) + 1e-12; };
    for (int i : {0, 1, 500, kRows - 1}) {
      EXPECT_TRUE(near(run.required("time_s")[i], time_s(i))) << i << " " << run.required("time_s")[i];
      EXPECT_TRUE(near(run.required("speed_rpm")[i], speed_rpm(i))) << i << " " << run.required("speed_rpm")[i];
      EXPECT_TRUE(near(run.required("normal_force_N")[i], force_N(i))) << i << " " << run.required("normal_force_N")[i];
      EXPECT_TRUE(near(run.required("torque_Nm")[i], torque_Nm(i))) << i << " " << run.required("torque_Nm")[i];
      EXPECT_TRUE(near(run.required("temp_C")[i], temp_C(i))) << i << " " << run.required("temp_C")[i];
    }
  }
};

TEST_F(LoggerImport, SemicolonDecimalCommaMillisecondsAndKilonewtonsByName) {
  const auto file = logger("log.csv",
                           {{"time_ms", [](int i) { return 1e3 * time_s(i); }},
                            {"speed_rpm", speed_rpm},
                            {"torque_Nm", torque_Nm},
                            {"temp_C", temp_C},
                            {"force_kN", [](int i) { return force_N(i) / 1e3; }}},
                           ';', true);
  const auto r = import_logger(file, {});
  EXPECT_EQ(r.delimiter, ';');
  EXPECT_EQ(r.decimal, ',');
  expect_thesis_ramp(r.run);
  // The measured run's column order, whatever the logger's.
  std::vector<std::string> names;
  for (const auto& c : r.run.columns) names.push_back(c.name);
  EXPECT_EQ(names, (std::vector<std::string>{"time_s", "speed_rpm", "normal_force_N", "torque_Nm", "temp_C"}));
  EXPECT_THAT(r.mapping, testing::Contains("force_kN -> normal_force_N (kN, from its name)"));
}

TEST_F(LoggerImport, CommaSecondsNewtonsAndMetadataDefaultsWithAWarning) {
  const auto file = logger("log.csv",
                           {{"time_s", time_s},
                            {"speed_rpm", speed_rpm},
                            {"torque_Nm", torque_Nm},
                            {"temp_C", temp_C},
                            {"force_N", force_N}},
                           ',');
  const auto r = import_logger(file, {});
  EXPECT_EQ(r.delimiter, ',');
  EXPECT_EQ(r.decimal, '.');
  expect_thesis_ramp(r.run);
  EXPECT_EQ(r.run.meta("format"), "shudder-measurement/1");
  EXPECT_EQ(r.run.meta("rig"), "lsctr");
  EXPECT_EQ(r.run.meta("oil_flow_ml_min"), "200");
  EXPECT_EQ(r.run.meta("temp_sensor"), "separator_thermocouple r_mm=48 z_mm=0.5");
  ASSERT_EQ(r.warnings.size(), 1u);
  EXPECT_THAT(r.warnings[0], HasSubstr("metadata not given, written with the defaults rig=lsctr"));
  // Written and read back by the measured run's strict reader: the same values (6 digits).
  shudder::io::write_measured_run_csv(path("run.csv"), r.run);
  const auto back = shudder::io::read_measured_run(path("run.csv"));
  ASSERT_EQ(back.rows(), r.run.rows());
  for (std::size_t c = 0; c < back.columns.size(); ++c)
    for (std::size_t i = 0; i < back.rows(); ++i)
      EXPECT_NEAR(back.columns[c].values[i], r.run.columns[c].values[i],
                  1e-5 * std::abs(r.run.columns[c].values[i]) + 1e-9);
}

TEST_F(LoggerImport, TabRadiansKelvinExtraColumnsAndExplicitMaps) {
  const double rpm_per_rad_s = 60.0 / (2.0 * std::numbers::pi);
  const auto file = logger("log.txt",
                           {{"pressure_bar", [](int) { return 3.5; }},
                            {"Moment", [](int i) { return torque_Nm(i) / 1e3; }},
                            {"omega [rad/s]", [&](int i) { return speed_rpm(i) / rpm_per_rad_s; }},
                            {"t", time_s},
                            {"Fn", [](int i) { return force_N(i) / 1e3; }},
                            {"disc_K", [](int i) { return temp_C(i) + 273.15; }},
                            {"oil_temp_C", [](int) { return 60.0; }}},
                           '\t', false, "# logger v2.1, bench 3\n# operator: someone\n");
  ImportSpec spec;
  for (const char* m : {"Moment=torque_Nm:kN m", "t=time_s", "Fn=normal_force_N:kN", "disc_K=temp_C:K"})
    spec.maps.push_back(shudder::io::parse_map_option(m));
  const auto r = import_logger(file, spec);
  EXPECT_EQ(r.delimiter, '\t');
  expect_thesis_ramp(r.run);
  ASSERT_NE(r.run.column("sump_temp_C"), nullptr);  // found by name
  EXPECT_DOUBLE_EQ((*r.run.column("sump_temp_C"))[3], 60.0);
  EXPECT_EQ(r.ignored, (std::vector<std::string>{"pressure_bar"}));
  EXPECT_EQ(r.run.meta("operator"), "someone");  // the logger's own '# key: value' lines are kept
}

// A column whose name is a quantity without a unit ("n", a cycle counter here) does not compete
// with one whose name gives the unit; two that give units are ambiguous.
TEST_F(LoggerImport, ANameWithAUnitWinsOverOneWithout) {
  const auto file = logger("log.csv",
                           {{"time_s", time_s},
                            {"n", [](int i) { return double(i); }},
                            {"speed_rpm", speed_rpm},
                            {"torque_Nm", torque_Nm},
                            {"temp_C", temp_C},
                            {"force_N", force_N}},
                           ',');
  const auto r = import_logger(file, {});
  expect_thesis_ramp(r.run);
  EXPECT_EQ(r.ignored, (std::vector<std::string>{"n"}));
  const auto two = logger("two.csv",
                          {{"time_s", time_s},
                           {"speed_rad_s", speed_rpm},
                           {"speed_rpm", speed_rpm},
                           {"torque_Nm", torque_Nm},
                           {"temp_C", temp_C},
                           {"force_N", force_N}},
                          ',');
  EXPECT_THAT([&] { import_logger(two, {}); },
              ThrowsMessage<InputError>(
                  AllOf(HasSubstr("both look like speed_rpm"), HasSubstr("--map COLUMN=speed_rpm:UNIT"))));
}

TEST_F(LoggerImport, MappingFileGivesColumnsMetadataAndDialect) {
  const auto file = logger(
      "log.csv",
      {{"A", [](int i) { return 1e3 * time_s(i); }}, {"B", speed_rpm}, {"C", force_N}, {"D", torque_Nm}, {"E", temp_C}},
      ';', true);
  std::ofstream(path("rig3.toml")) << "# bench 3's logger\ndelimiter = \";\"\ndecimal = \",\"\n"
                                      "[columns]\nA = \"time_s:ms\"\nB = \"speed_rpm:rpm\"\nC = \"normal_force_N:N\"\n"
                                      "D = \"torque_Nm\"\nE = \"temp_C:degC\"\n"
                                      "[metadata]\nrig = \"lsctr\"\noil_flow_ml_min = 150\n"
                                      "temp_sensor = \"separator_thermocouple r_mm=47 z_mm=0.5\"\n";
  ImportSpec spec;
  shudder::io::read_import_mapping(path("rig3.toml"), spec);
  const auto r = import_logger(file, spec);
  expect_thesis_ramp(r.run);
  EXPECT_EQ(r.run.meta("oil_flow_ml_min"), "150");
  EXPECT_TRUE(r.warnings.empty()) << r.warnings.front();
  // The command line wins over the file: B given as rad/s now (and 1 -> 100 rad/s is plausible).
  ImportSpec over;
  over.maps.push_back(shudder::io::parse_map_option("B=speed_rpm:rad/s"));
  shudder::io::read_import_mapping(path("rig3.toml"), over);
  const auto r2 = import_logger(file, over);
  EXPECT_NEAR(r2.run.required("speed_rpm")[0], 60.0 / (2.0 * std::numbers::pi), 1e-9);
}

TEST_F(LoggerImport, UnitsThatDoNotFitTheValuesNameTheColumnAndTheFix) {
  // kN logged under a name that says N.
  const auto kn = logger("kn.csv",
                         {{"time_s", time_s},
                          {"speed_rpm", speed_rpm},
                          {"torque_Nm", torque_Nm},
                          {"temp_C", temp_C},
                          {"force_N", [](int i) { return force_N(i) / 1e3; }}},
                         ',');
  EXPECT_THAT(
      [&] { import_logger(kn, {}); },
      ThrowsMessage<InputError>(AllOf(HasSubstr("kn.csv"), HasSubstr("column 'force_N'"), HasSubstr("look like kN"),
                                      HasSubstr("--map force_N=normal_force_N:kN"))));
  // A 10 s ramp at 100 Hz logged in ms under a name that says s.
  const auto ms = logger("ms.csv",
                         {{"time_s", [](int i) { return 1e3 * time_s(i) * 10; }},
                          {"speed_rpm", speed_rpm},
                          {"torque_Nm", torque_Nm},
                          {"temp_C", temp_C},
                          {"force_N", force_N}},
                         ',');
  EXPECT_THAT([&] { import_logger(ms, {}); },
              ThrowsMessage<InputError>(
                  AllOf(HasSubstr("column 'time_s'"), HasSubstr("look like ms"), HasSubstr("--map time_s=time_s:ms"))));
  // Kelvin under a name that says degC.
  const auto k = logger("k.csv",
                        {{"time_s", time_s},
                         {"speed_rpm", speed_rpm},
                         {"torque_Nm", torque_Nm},
                         {"temp_C", [](int i) { return temp_C(i) + 273.15; }},
                         {"force_N", force_N}},
                        ',');
  EXPECT_THAT([&] { import_logger(k, {}); },
              ThrowsMessage<InputError>(
                  AllOf(HasSubstr("column 'temp_C'"), HasSubstr("look like K"), HasSubstr("--map temp_C=temp_C:K"))));
  // Seconds under a name that says ms: a rate of 100 kHz and more.
  const auto s = logger("s.csv",
                        {{"time_ms", [](int i) { return time_s(i) / 100; }},
                         {"speed_rpm", speed_rpm},
                         {"torque_Nm", torque_Nm},
                         {"temp_C", temp_C},
                         {"force_N", force_N}},
                        ',');
  EXPECT_THAT([&] { import_logger(s, {}); }, ThrowsMessage<InputError>(HasSubstr("look like s, not ms")));
  // --trust-units: the user says the unit is right.
  ImportSpec trust;
  trust.trust_units = true;
  EXPECT_NO_THROW(import_logger(kn, trust));
  // A column name with spaces and brackets: the suggested option is quoted for the shell, so it
  // can be pasted as printed.
  const auto spaced = logger("spaced.csv",
                             {{"time_s", time_s},
                              {"speed_rpm", speed_rpm},
                              {"torque_Nm", torque_Nm},
                              {"temp_C", temp_C},
                              {"Kraft [kN]", [](int i) { return force_N(i) / 1e3; }}},
                             ',');
  ImportSpec named;
  named.maps.push_back(shudder::io::parse_map_option("Kraft [kN]=normal_force_N"));
  EXPECT_THAT([&] { import_logger(spaced, named); },
              ThrowsMessage<InputError>(HasSubstr("give --map 'Kraft [kN]=normal_force_N:kN'")));
}

TEST(MapOptionText, QuotesOnlyWhatTheShellWouldSplitOrExpand) {
  EXPECT_EQ(shudder::io::map_option_text("force_kN", "normal_force_N", "kN"), "--map force_kN=normal_force_N:kN");
  EXPECT_EQ(shudder::io::map_option_text("Zeit [ms]", "time_s", "ms"), "--map 'Zeit [ms]=time_s:ms'");
  EXPECT_EQ(shudder::io::map_option_text("it's", "time_s", "s"), "--map 'it'\\''s=time_s:s'");
}

TEST_F(LoggerImport, BadMapsMissingColumnsAndBadFieldsAreOneLineErrors) {
  const auto file = logger(
      "log.csv",
      {{"time_s", time_s}, {"speed_rpm", speed_rpm}, {"Moment", torque_Nm}, {"temp_C", temp_C}, {"force_N", force_N}},
      ',');
  const auto one_line = [](const std::string& s) { return s.find('\n') == std::string::npos; };
  try {
    import_logger(file, {});
    ADD_FAILURE() << "no error for a missing torque column";
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), AllOf(HasSubstr("no column for torque_Nm"), HasSubstr("'Moment'"),
                                HasSubstr("--map COLUMN=torque_Nm:UNIT (units: N m, kN m)")));
    EXPECT_TRUE(one_line(e.what()));
  }
  EXPECT_THAT([] { shudder::io::parse_map_option("Moment=torque_Nm:lbf ft"); },
              ThrowsMessage<InputError>(AllOf(HasSubstr("unit 'lbf ft'"), HasSubstr("allowed: N m, kN m"))));
  EXPECT_THAT([] { shudder::io::parse_map_option("Moment=torque_N:N m"); },
              ThrowsMessage<InputError>(
                  AllOf(HasSubstr("'torque_N' is not a measured-run column"), HasSubstr("did you mean 'torque_Nm'"))));
  EXPECT_THAT([] { shudder::io::parse_map_option("Moment"); },
              ThrowsMessage<InputError>(HasSubstr("SOURCE=TARGET:UNIT")));
  ImportSpec typo;
  typo.maps.push_back(shudder::io::parse_map_option("Momnet=torque_Nm"));
  EXPECT_THAT([&] { import_logger(file, typo); }, ThrowsMessage<InputError>(HasSubstr("did you mean 'Moment'")));
  // A text field: line and column.
  std::ofstream(path("text.csv")) << "time_s;speed_rpm;torque_Nm;temp_C;force_N\n0;1;2;3;4\n0,1;1;2;n/a;4\n";
  EXPECT_THAT(
      [&] { import_logger(path("text.csv"), {}); },
      ThrowsMessage<InputError>(AllOf(HasSubstr("text.csv:3"), HasSubstr("column 'temp_C': 'n/a' is not a number"))));
  // A column named as a quantity without a unit.
  std::ofstream(path("nounit.csv")) << "time,speed_rpm,torque_Nm,temp_C,force_N\n";
  EXPECT_THAT([&] { import_logger(path("nounit.csv"), {}); }, ThrowsMessage<InputError>(HasSubstr("only 0 data row")));
  const auto no_unit = logger(
      "nounit2.csv",
      {{"time", time_s}, {"speed_rpm", speed_rpm}, {"torque_Nm", torque_Nm}, {"temp_C", temp_C}, {"force_N", force_N}},
      ',');
  EXPECT_THAT([&] { import_logger(no_unit, {}); },
              ThrowsMessage<InputError>(AllOf(HasSubstr("column 'time' looks like time_s"),
                                              HasSubstr("--map time=time_s:UNIT (allowed units: s, ms)"))));
}

TEST_F(LoggerImport, TimeGoingBackAndLargeNegativeForceNameTheLine) {
  std::ostringstream os;
  os << "time_s,speed_rpm,torque_Nm,temp_C,force_N\n";
  for (int i = 0; i < 20; ++i) os << (i == 12 ? 0.05 : 0.01 * i) << ",10,90,60,20000\n";
  std::ofstream(path("back.csv")) << os.str();
  EXPECT_THAT([&] { import_logger(path("back.csv"), {}); },
              ThrowsMessage<InputError>(AllOf(HasSubstr("back.csv:14"), HasSubstr("strictly increasing"))));
  std::ostringstream neg;
  neg << "time_s,speed_rpm,torque_Nm,temp_C,force_N\n";
  for (int i = 0; i < 20; ++i) neg << 0.01 * i << ",10,90,60," << (i < 3 ? -20 : 20000) << "\n";
  std::ofstream(path("offset.csv")) << neg.str();
  const auto r = import_logger(path("offset.csv"), {});  // a load cell's offset at no load: 0 N, warned
  EXPECT_EQ(r.run.required("normal_force_N")[0], 0.0);
  EXPECT_THAT(r.warnings, testing::Contains(HasSubstr("3 slightly negative normal force(s)")));
  std::ostringstream big;
  big << "time_s,speed_rpm,torque_Nm,temp_C,force_N\n";
  for (int i = 0; i < 20; ++i) big << 0.01 * i << ",10,90,60," << (i == 5 ? -5000 : 20000) << "\n";
  std::ofstream(path("negative.csv")) << big.str();
  EXPECT_THAT([&] { import_logger(path("negative.csv"), {}); },
              ThrowsMessage<InputError>(AllOf(HasSubstr("negative.csv:7"), HasSubstr("must be >= 0"))));
}

// A logger's file given where a measured run is read: the reader's refusal points at `import`;
// a measured run with a column in the wrong unit is refused with the import that converts it.
TEST_F(LoggerImport, MeasuredRunReadersPointAtImport) {
  std::ofstream(path("semi.csv"))
      << "# format: shudder-measurement/1\ntime_s;speed_rpm;normal_force_N;torque_Nm;temp_C\n";
  EXPECT_THAT(
      [&] { shudder::io::read_measured_run(path("semi.csv")); },
      ThrowsMessage<InputError>(AllOf(HasSubstr("separated by ';' or tabs"), HasSubstr("shudder import LOG.csv"))));
  std::ofstream(path("noformat.csv")) << "time_s,speed_rpm,normal_force_N,torque_Nm,temp_C\n";
  EXPECT_THAT([&] { shudder::io::read_measured_run(path("noformat.csv")); },
              ThrowsMessage<InputError>(HasSubstr("shudder import LOG.csv -o RUN.csv")));
  std::ostringstream kn;
  kn << "# format: shudder-measurement/1\ntime_s,speed_rpm,normal_force_N,torque_Nm,temp_C\n";
  for (int i = 0; i < 20; ++i) kn << 0.01 * i << ",10,25.3,95,60\n";
  std::ofstream(path("kn.csv")) << kn.str();
  const auto run = shudder::io::read_measured_run(path("kn.csv"));
  EXPECT_THAT([&] { shudder::io::check_measured_run_units(run); },
              ThrowsMessage<InputError>(AllOf(HasSubstr("column 'normal_force_N'"), HasSubstr("look like kN"),
                                              HasSubstr("-o FIXED.csv --map normal_force_N=normal_force_N:kN"))));
  // ... and that import does convert it (its '# key: value' lines kept as metadata).
  ImportSpec fix;
  fix.maps.push_back(shudder::io::parse_map_option("normal_force_N=normal_force_N:kN"));
  const auto fixed = import_logger(path("kn.csv"), fix);
  EXPECT_NEAR(fixed.run.required("normal_force_N")[0], 25300.0, 1e-9);  // 25.3 x 1000 in doubles
  EXPECT_NO_THROW(shudder::io::check_measured_run_units(fixed.run));
}

}  // namespace
