// Measured rig run reader (CSV and HDF5) and HDF5 writer. Checked: what write_measurement_csv
// writes reads back to its printed precision; the HDF5 form reads back exactly; the reader picks
// the form by the file's signature, not its name; optional columns and unknown metadata are
// kept in file order; and each rejection rule fails with the file, the place (CSV line; HDF5
// dataset/attribute and row index) and the reason in the message.
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "io/hdf5_run.hpp"
#include "io/input_error.hpp"
#include "io/measured_run.hpp"
#include "io/measurement_csv.hpp"
#include "tests/support/test_directory.hpp"

namespace fs = std::filesystem;
using shudder::dynamics::Recording;
using shudder::io::InputError;
using shudder::io::MeasuredRun;
using shudder::io::MeasurementOptions;
using shudder::io::read_measured_run;
using shudder::io::read_measured_run_csv;
using shudder::io::read_measured_run_hdf5;
using shudder::io::write_measured_run_hdf5;
using testing::AllOf;
using testing::HasSubstr;
using testing::ThrowsMessage;

namespace {

class MeasuredRunTest : public shudder::test::TestDirectory {
 protected:
  MeasuredRunTest() : TestDirectory("mrun") {}

  // Writes `text` byte for byte to `name` and returns the path.
  std::string file(const std::string& name, const std::string& text) const {
    std::ofstream(path(name), std::ios::binary) << text;
    return path(name);
  }

  // Reading the CSV `text` fails at `line` for `reason`; the message names the file too.
  void expect_csv_rejected(const std::string& text, long line, const std::string& reason) const {
    const std::string p = file("bad.csv", text);
    EXPECT_THAT([&] { read_measured_run_csv(p); },
                ThrowsMessage<InputError>(AllOf(HasSubstr(p + ":" + std::to_string(line) + ": "), HasSubstr(reason))));
  }

  // Reading the HDF5 `run` (written without checks) fails naming `key` and `reason`.
  void expect_hdf5_rejected(const MeasuredRun& run, const std::string& key, const std::string& reason,
                            const std::vector<std::pair<std::string, double>>& numbers = {}) {
    const std::string p = path("bad.h5");
    shudder::io::detail::write_measured_run_hdf5_unchecked(p, run, numbers);
    EXPECT_THAT([&] { read_measured_run(p); },
                ThrowsMessage<InputError>(AllOf(HasSubstr(p + ": key '" + key + "'"), HasSubstr(reason))));
  }
};

// The docs/formats/measured_run.md example with `n` rows; `meta` and `header` replace the defaults.
const std::string format_line = "# format: shudder-measurement/1\n";
const std::string header_line = "time_s,speed_rpm,normal_force_N,torque_Nm,temp_C,sump_temp_C\n";

std::string rows(std::size_t n, std::size_t first = 0) {
  std::string out;
  for (std::size_t k = first; k < first + n; ++k) {
    char time[32];
    std::snprintf(time, sizeof time, "%.3f", 0.001 * static_cast<double>(k));
    out += std::string(time) + ",1.000,25300,98." + std::to_string(k % 10) + ",77.02,77.00\n";
  }
  return out;
}

std::string example(std::size_t n = 12) {
  return format_line + "# rig: lsctr\n" + "# fluid: lsc-fluid-c\n" + header_line + rows(n);
}

// 1 s at 1 kHz of a simulated LSCTR run: ramps plus a non-sensor signal the writer leaves out.
Recording ramp_recording() {
  Recording rec;
  for (const char* name :
       {"time_s", "speed_rpm", "normal_force_N", "torque_Nm", "temp_C", "sump_temp_C", "ir_temp_C", "clutch_torque_Nm"})
    rec.add_signal(name, "");
  for (std::size_t k = 0; k <= 1000; ++k) {
    const double t = static_cast<double>(k) / 1000.0;
    const double row[] = {
        t,   100.0 * t, 25300.0 + 3.0 * std::sin(40.0 * t), 10.0 + 50.0 * t, 77.0 + 2.0 * t, 77.0, 78.0 + std::cos(t),
        -1.0};
    for (std::size_t c = 0; c < rec.signals.size(); ++c) rec.signals[c].values.push_back(row[c]);
  }
  return rec;
}

MeasurementOptions noisy() {
  MeasurementOptions opt;
  opt.fluid = "lsc-fluid-c";
  opt.noise = true;
  opt.seed = 42;
  return opt;
}

std::vector<std::string> names(const MeasuredRun& run) {
  std::vector<std::string> out;
  for (const auto& c : run.columns) out.push_back(c.name);
  return out;
}

// A valid run in memory (the docs/formats/measured_run.md columns, 12 rows) for HDF5 tests to break.
MeasuredRun valid_run() {
  MeasuredRun run;
  run.metadata = {{"format", "shudder-measurement/1"}, {"rig", "lsctr"}};
  for (const char* name : {"time_s", "speed_rpm", "normal_force_N", "torque_Nm", "temp_C"})
    run.columns.push_back({name, shudder::io::measured_run_units(name), {}});
  for (std::size_t k = 0; k < 12; ++k) {
    const double row[] = {0.001 * static_cast<double>(k), 1.0, 25300.0, 98.4, 77.02};
    for (std::size_t c = 0; c < 5; ++c) run.columns[c].values.push_back(row[c]);
  }
  return run;
}

void expect_same(const MeasuredRun& a, const MeasuredRun& b) {
  EXPECT_EQ(a.metadata, b.metadata);
  ASSERT_EQ(a.columns.size(), b.columns.size());
  for (std::size_t c = 0; c < a.columns.size(); ++c) {
    EXPECT_EQ(a.columns[c].name, b.columns[c].name);
    EXPECT_EQ(a.columns[c].units, b.columns[c].units) << a.columns[c].name;
    EXPECT_EQ(a.columns[c].values, b.columns[c].values) << a.columns[c].name;
  }
}

}  // namespace

// ---- reading what is valid --------------------------------------------------------------------

TEST_F(MeasuredRunTest, ReadsTheFormatsExample) {
  const std::string p = file("run.csv", example());
  const MeasuredRun run = read_measured_run(p);
  EXPECT_EQ(run.path, p);
  EXPECT_EQ(run.rows(), 12u);
  EXPECT_EQ(names(run),
            (std::vector<std::string>{"time_s", "speed_rpm", "normal_force_N", "torque_Nm", "temp_C", "sump_temp_C"}));
  EXPECT_EQ(run.meta("format"), "shudder-measurement/1");
  EXPECT_EQ(run.meta("fluid"), "lsc-fluid-c");
  EXPECT_EQ(run.meta("absent"), std::nullopt);
  EXPECT_DOUBLE_EQ(run.duration_s(), 0.011);
  EXPECT_EQ(run.required("normal_force_N").front(), 25300.0);
  EXPECT_EQ(run.required("torque_Nm")[3], 98.3);
  EXPECT_EQ(run.column("ir_temp_C"), nullptr);
  EXPECT_EQ(run.columns[3].units, "N m");
  EXPECT_EQ(run.columns[4].units, "degC");
  EXPECT_THROW(MeasuredRun{}.required("time_s"), std::logic_error);
}

TEST_F(MeasuredRunTest, WindowsLineEndingsAndTrailingBlankLinesAccepted) {
  std::string text = example() + "\n  \n\n";
  for (std::size_t pos = 0; (pos = text.find('\n', pos)) != std::string::npos; pos += 2) text.replace(pos, 1, "\r\n");
  const MeasuredRun run = read_measured_run(file("run.csv", text));
  EXPECT_EQ(run.rows(), 12u);
  EXPECT_EQ(run.meta("rig"), "lsctr");  // no '\r' left in values
  EXPECT_EQ(run.columns.back().name, "sump_temp_C");
  EXPECT_EQ(run.columns.back().values.back(), 77.0);
}

TEST_F(MeasuredRunTest, OptionalAndUnknownColumnsKeptInFileOrder) {
  std::string text = format_line +
                     "time_s,strain_ue,speed_rpm,normal_force_N,torque_Nm,temp_C,"
                     "sump_temp_C,ir_temp_C\n";
  for (int k = 0; k < 10; ++k) text += std::to_string(k) + ",-" + std::to_string(k) + ".5,1,0,98,77,76,79.5\n";
  const MeasuredRun run = read_measured_run(file("run.csv", text));
  EXPECT_EQ(names(run), (std::vector<std::string>{"time_s", "strain_ue", "speed_rpm", "normal_force_N", "torque_Nm",
                                                  "temp_C", "sump_temp_C", "ir_temp_C"}));
  ASSERT_NE(run.column("strain_ue"), nullptr);
  EXPECT_EQ(run.column("strain_ue")->at(3), -3.5);
  EXPECT_EQ(run.columns[1].units, "");
  EXPECT_EQ(run.column("ir_temp_C")->at(9), 79.5);
  EXPECT_EQ(run.column("sump_temp_C")->at(0), 76.0);
  EXPECT_EQ(run.duration_s(), 9.0);
}

TEST_F(MeasuredRunTest, UnknownMetadataKeptInFileOrder) {
  const std::string text = "# operator: A. N. Other\n" + format_line +
                           "# oil_flow_ml_min: 200\n# note: run 3: after: re-shim\n# empty:\n" + header_line + rows(10);
  const MeasuredRun run = read_measured_run(file("run.csv", text));
  const std::vector<std::pair<std::string, std::string>> expected = {
      {"operator", "A. N. Other"},
      {"format", "shudder-measurement/1"},
      {"oil_flow_ml_min", "200"},
      {"note", "run 3: after: re-shim"},  // split at the first ':' only
      {"empty", ""}};
  EXPECT_EQ(run.metadata, expected);
}

// What write_measurement_csv prints reads back as the in-memory run to the printed precision:
// 6 significant digits, time to its printed decimals.
TEST_F(MeasuredRunTest, CsvWrittenBySimulationReadsBackToPrintedPrecision) {
  const std::string p = path("sim.csv");
  shudder::io::write_measurement_csv(p, ramp_recording(), noisy());
  const MeasuredRun exact = shudder::io::make_measurement(p, ramp_recording(), noisy());
  const MeasuredRun run = read_measured_run(p);
  EXPECT_EQ(run.metadata, exact.metadata);
  EXPECT_EQ(run.meta("seed"), "42");
  ASSERT_EQ(names(run), names(exact));
  EXPECT_EQ(names(run).back(), "ir_temp_C");
  ASSERT_EQ(run.rows(), 1001u);
  for (std::size_t c = 0; c < run.columns.size(); ++c) {
    EXPECT_EQ(run.columns[c].units, exact.columns[c].units);
    for (std::size_t i = 0; i < run.rows(); ++i) {
      const double want = exact.columns[c].values[i], got = run.columns[c].values[i];
      const double tolerance = c == 0 ? 0.5e-3 : 0.5e-5 * std::abs(want) + 1e-300;
      ASSERT_LE(std::abs(got - want), tolerance) << run.columns[c].name << " row " << i;
    }
  }
}

TEST_F(MeasuredRunTest, Hdf5WriteReadIsExact) {
  MeasuredRun written = shudder::io::make_measurement("x", ramp_recording(), noisy());
  written.columns.push_back({"strain_ue", "", std::vector<double>(written.rows(), 1.0 / 3.0)});
  written.metadata.emplace_back("operator", "A. N. Other, ümlaut");
  const std::string p = path("run.h5");
  write_measured_run_hdf5(p, written);
  EXPECT_FALSE(fs::exists(p + ".tmp"));
  const MeasuredRun run = read_measured_run_hdf5(p);
  EXPECT_EQ(run.path, p);
  expect_same(run, written);
  // And a CSV's content survives the trip through HDF5 unchanged.
  const MeasuredRun csv = read_measured_run(file("run.csv", example()));
  write_measured_run_hdf5(path("csv.h5"), csv);
  expect_same(read_measured_run(path("csv.h5")), csv);
}

TEST_F(MeasuredRunTest, WriteMeasurementPicksHdf5ByExtension) {
  const Recording rec = ramp_recording();
  shudder::io::write_measurement(path("m.H5"), rec, noisy());
  shudder::io::write_measurement(path("m.hdf5"), rec, noisy());
  shudder::io::write_measurement(path("m.csv"), rec, noisy());
  const MeasuredRun exact = shudder::io::make_measurement("x", rec, noisy());
  expect_same(read_measured_run_hdf5(path("m.H5")), exact);
  expect_same(read_measured_run_hdf5(path("m.hdf5")), exact);
  EXPECT_EQ(read_measured_run_csv(path("m.csv")).metadata, exact.metadata);
}

// The form comes from the first bytes, whatever the name says.
TEST_F(MeasuredRunTest, DispatchesOnTheHdf5Signature) {
  const MeasuredRun csv_run = read_measured_run(file("run.csv", example()));
  write_measured_run_hdf5(path("really_hdf5.csv"), csv_run);
  const std::string csv_named_h5 = file("really_csv.h5", example());
  expect_same(read_measured_run(path("really_hdf5.csv")), csv_run);
  expect_same(read_measured_run(csv_named_h5), csv_run);
  // A text file that only starts like the signature is read as CSV (and rejected as such).
  const std::string p = file("almost.h5", "\x89HDF\r\n" + example());
  EXPECT_THAT([&] { read_measured_run(p); }, ThrowsMessage<InputError>(HasSubstr(p + ":1: ")));
}

TEST_F(MeasuredRunTest, Hdf5ReadLeaksNoIdentifiers) {
  write_measured_run_hdf5(path("run.h5"), valid_run());
  const long before = shudder::io::detail::open_hdf5_identifiers();
  read_measured_run(path("run.h5"));
  MeasuredRun bad = valid_run();
  bad.columns[2].values[5] = -1.0;
  shudder::io::detail::write_measured_run_hdf5_unchecked(path("bad.h5"), bad);
  EXPECT_THROW(read_measured_run(path("bad.h5")), InputError);
  EXPECT_EQ(shudder::io::detail::open_hdf5_identifiers(), before);
}

// ---- CSV rejections: one rule each -----------------------------------------------------------

TEST_F(MeasuredRunTest, RejectsMissingFile) {
  const std::string p = path("absent.csv");
  EXPECT_THAT([&] { read_measured_run(p); }, ThrowsMessage<InputError>(AllOf(HasSubstr(p), HasSubstr("no such file"))));
}

TEST_F(MeasuredRunTest, RejectsMissingFormat) {
  expect_csv_rejected("# rig: lsctr\n" + header_line + rows(12), 2,
                      "no '# format: shudder-measurement/1' metadata line before the header");
}

TEST_F(MeasuredRunTest, RejectsOtherFormat) {
  expect_csv_rejected("# rig: lsctr\n# format: shudder-measurement/2\n" + header_line + rows(12), 2,
                      "format is 'shudder-measurement/2'; the only format read is "
                      "'shudder-measurement/1'");
}

TEST_F(MeasuredRunTest, RejectsMetadataLineWithoutColon) {
  expect_csv_rejected(format_line + "# rig lsctr\n" + header_line + rows(12), 2, "malformed metadata line (no ':')");
}

TEST_F(MeasuredRunTest, RejectsDuplicateMetadataKey) {
  expect_csv_rejected(format_line + "# rig: a\n# rig: b\n" + header_line + rows(12), 3,
                      "duplicate metadata key (first on line 2)");
}

TEST_F(MeasuredRunTest, RejectsEmptyFile) {
  expect_csv_rejected("", 1, "file is empty");
  expect_csv_rejected("\r\n\n", 1, "file is empty (or only blank lines)");
}

TEST_F(MeasuredRunTest, RejectsMetadataWithoutHeader) {
  expect_csv_rejected(format_line + "# rig: lsctr\n", 2, "no header line");
}

TEST_F(MeasuredRunTest, RejectsDuplicateColumn) {
  expect_csv_rejected(format_line + "time_s,speed_rpm,normal_force_N,torque_Nm,temp_C,speed_rpm\n" + rows(12), 2,
                      "duplicate column name (header fields 2 and 6)");
}

TEST_F(MeasuredRunTest, RejectsMissingRequiredColumns) {
  const std::string p = file("bad.csv", format_line + "time_s,speed_rpm,normal_force_N,sump_temp_C\n0,1,2,3\n");
  EXPECT_THAT([&] { read_measured_run(p); },
              ThrowsMessage<InputError>(AllOf(HasSubstr(p + ":2: "),
                                              HasSubstr("missing required column(s) 'torque_Nm', 'temp_C'"),
                                              HasSubstr("found 'time_s', 'speed_rpm', 'normal_force_N', "
                                                        "'sump_temp_C'"))));
}

TEST_F(MeasuredRunTest, RejectsRowWithWrongFieldCount) {
  expect_csv_rejected(example(4) + "0.004,1.000,25300,98.4,77.02\n" + rows(8, 5), 9,
                      "row has 5 field(s) but the header (line 4) has 6 columns");
}

TEST_F(MeasuredRunTest, RejectsNonNumber) {
  expect_csv_rejected(example(5) + "0.005,1.000,25300,98.4,77.0x,77.00\n" + rows(8, 6), 10,
                      "key 'temp_C': '77.0x' is not a number");
  expect_csv_rejected(example(5) + "0.005,1.000,25300,98.4,1,2;5\n", 10, "'2;5' is not a number");
  expect_csv_rejected(example(5) + "0.005,1.000, 25300,98.4,1,2\n", 10, "' 25300' is not a number");
  expect_csv_rejected(example(5) + "0.005,1.000,25300,98.4,1,2\r3\n", 10, "is not a number");
}

TEST_F(MeasuredRunTest, RejectsEmptyField) {
  expect_csv_rejected(example(5) + "0.005,1.000,25300,,77.0,77.00\n" + rows(8, 6), 10, "key 'torque_Nm': empty field");
}

TEST_F(MeasuredRunTest, RejectsNanAndInf) {
  expect_csv_rejected(example(5) + "0.005,nan,25300,98.4,77.0,77.00\n" + rows(8, 6), 10,
                      "key 'speed_rpm': value is NaN");
  expect_csv_rejected(example(5) + "0.005,1,25300,-inf,77.0,77.00\n" + rows(8, 6), 10,
                      "key 'torque_Nm': value is infinite");
  expect_csv_rejected(example(5) + "0.005,1,25300,1e999,77.0,77.00\n" + rows(8, 6), 10, "out of the range of a double");
}

TEST_F(MeasuredRunTest, RejectsTimeNotStrictlyIncreasing) {
  expect_csv_rejected(example(5) + "0.004,1,25300,98.4,77.0,77.00\n" + rows(8, 6), 10,
                      "key 'time_s': time_s 0.004 s is not after 0.004 s at line 9; time_s must "
                      "be strictly increasing");
  expect_csv_rejected(example(5) + "0.002,1,25300,98.4,77.0,77.00\n" + rows(8, 6), 10,
                      "time_s 0.002 s is not after 0.004 s at line 9");
}

TEST_F(MeasuredRunTest, RejectsFewerThanTenRows) {
  expect_csv_rejected(example(9) + "\n", 13, "only 9 data row(s); a measured run needs at least 10");
  expect_csv_rejected(format_line + header_line, 2, "only 0 data row(s)");
}

TEST_F(MeasuredRunTest, RejectsNegativeNormalForce) {
  expect_csv_rejected(example(5) + "0.005,1,-0.5,98.4,77.0,77.00\n" + rows(8, 6), 10,
                      "key 'normal_force_N': negative normal force -0.5 N; normal_force_N must "
                      "be >= 0");
}

TEST_F(MeasuredRunTest, RejectsHashLineAfterHeader) {
  expect_csv_rejected(example(5) + "# late: metadata\n" + rows(8, 5), 10,
                      "'#' line after the header; metadata lines must all come before");
}

TEST_F(MeasuredRunTest, RejectsBlankLineInsideData) {
  expect_csv_rejected(example(5) + "\r\n" + rows(8, 5), 10, "blank line inside the data (the next row is on line 11)");
}

TEST_F(MeasuredRunTest, RejectsBlankLineBeforeHeader) {
  expect_csv_rejected(format_line + "\n" + header_line + rows(12), 2, "blank line before the header");
}

TEST_F(MeasuredRunTest, RejectsEmptyOrSpacedColumnName) {
  expect_csv_rejected(format_line + "time_s,,speed_rpm\n" + rows(12), 2, "header field 2 is empty");
  expect_csv_rejected(format_line + "time_s, speed_rpm\n" + rows(12), 2, "leading or trailing spaces");
}

// ---- HDF5 rejections -------------------------------------------------------------------------

TEST_F(MeasuredRunTest, Hdf5RejectsMissingMeasurementGroup) {
  // A simulation output file is HDF5 but not a measured run.
  Recording rec = ramp_recording();
  const std::string p = path("sim.h5");
  shudder::io::write_run_hdf5(p, rec, "");
  EXPECT_THAT([&] { read_measured_run(p); }, ThrowsMessage<InputError>(AllOf(HasSubstr(p + ": key '/measurement'"),
                                                                             HasSubstr("no /measurement group"))));
}

TEST_F(MeasuredRunTest, Hdf5RejectsMissingOrOtherFormat) {
  MeasuredRun run = valid_run();
  run.metadata.erase(run.metadata.begin());
  expect_hdf5_rejected(run, "/measurement@format", "no 'format' attribute on /measurement");
  run.metadata.emplace_back("format", "csv");
  expect_hdf5_rejected(run, "/measurement@format", "format is 'csv'; the only format read is 'shudder-measurement/1'");
}

TEST_F(MeasuredRunTest, Hdf5RejectsNonStringMetadata) {
  expect_hdf5_rejected(valid_run(), "/measurement@oil_flow_ml_min", "metadata attribute is not a string",
                       {{"oil_flow_ml_min", 200.0}});
}

TEST_F(MeasuredRunTest, Hdf5RejectsDatasetsOfDifferentLengths) {
  MeasuredRun run = valid_run();
  run.columns[3].values.pop_back();
  expect_hdf5_rejected(run, "/measurement/torque_Nm",
                       "has 11 values but 'time_s' has 12; all columns must have the same length");
}

TEST_F(MeasuredRunTest, Hdf5RejectsMissingRequiredColumn) {
  MeasuredRun run = valid_run();
  run.columns.erase(run.columns.begin() + 4);
  expect_hdf5_rejected(run, "/measurement", "missing required column(s) 'temp_C'");
}

// Row rules name the dataset and the row index.
TEST_F(MeasuredRunTest, Hdf5RejectsBadValuesByRowIndex) {
  MeasuredRun nan = valid_run();
  nan.columns[1].values[7] = std::numeric_limits<double>::quiet_NaN();
  expect_hdf5_rejected(nan, "/measurement/speed_rpm", "row index 7: value is NaN");
  MeasuredRun back = valid_run();
  back.columns[0].values[4] = back.columns[0].values[3];
  expect_hdf5_rejected(back, "/measurement/time_s", "row index 4: time_s 0.003 s is not after 0.003 s at row index 3");
  MeasuredRun negative = valid_run();
  negative.columns[2].values[11] = -1.0;
  expect_hdf5_rejected(negative, "/measurement/normal_force_N", "row index 11: negative normal force -1 N");
  MeasuredRun short_run = valid_run();
  for (auto& c : short_run.columns) c.values.resize(9);
  expect_hdf5_rejected(short_run, "/measurement/time_s", "only 9 data row(s)");
}

TEST_F(MeasuredRunTest, Hdf5WriterRefusesWhatTheReaderRejects) {
  MeasuredRun run = valid_run();
  run.columns[2].values[0] = -1.0;
  const std::string p = path("out.h5");
  EXPECT_THAT([&] { write_measured_run_hdf5(p, run); },
              ThrowsMessage<InputError>(
                  AllOf(HasSubstr(p + ": key '/measurement/normal_force_N'"), HasSubstr("not written: row index 0"))));
  MeasuredRun slash = valid_run();
  slash.columns.push_back({"a/b", "", std::vector<double>(12, 0.0)});
  EXPECT_THAT([&] { write_measured_run_hdf5(p, slash); }, ThrowsMessage<InputError>(HasSubstr("contain no '/'")));
  MeasuredRun twice = valid_run();
  twice.metadata.emplace_back("rig", "other");
  EXPECT_THAT([&] { write_measured_run_hdf5(p, twice); },
              ThrowsMessage<InputError>(HasSubstr("duplicate metadata key")));
  EXPECT_FALSE(fs::exists(p));
  EXPECT_FALSE(fs::exists(p + ".tmp"));
}

namespace {

// Fuzzing finding (fuzz/fuzz_measured_hdf5, docs/fuzzing.md): a damaged dataspace claiming 2^53
// rows made the reader allocate 64 PiB (old behaviour: std::bad_alloc, which the CLI reports as
// a numerical failure, or an abort under ASan) instead of rejecting the file. The file here is
// a valid 7777-row run whose dataspaces (dimension and maximum, little-endian uint64) are
// patched to 2^53.
TEST(MeasuredRunFuzzRegression, Hdf5DatasetClaimingMoreRowsThanTheFileCanHoldIsRejected) {
  const auto path =
      (std::filesystem::temp_directory_path() / ("shudder_fuzz_rows_" + std::to_string(::getpid()) + ".h5")).string();
  MeasuredRun run;
  run.metadata = {{"format", "shudder-measurement/1"}};
  for (const char* name : {"time_s", "speed_rpm", "normal_force_N", "torque_Nm", "temp_C"})
    run.columns.push_back({name, shudder::io::measured_run_units(name), {}});
  for (std::size_t k = 0; k < 7777; ++k) {
    const double row[] = {0.001 * static_cast<double>(k), 1.0, 25300.0, 98.4, 77.02};
    for (std::size_t c = 0; c < 5; ++c) run.columns[c].values.push_back(row[c]);
  }
  shudder::io::write_measured_run_hdf5(path, run);
  std::string bytes;
  {
    std::ifstream in(path, std::ios::binary);
    bytes.assign(std::istreambuf_iterator<char>(in), {});
  }
  const auto le64 = [](std::uint64_t v) {
    std::string s(8, '\0');
    for (int i = 0; i < 8; ++i) s[static_cast<std::size_t>(i)] = static_cast<char>((v >> (8 * i)) & 0xff);
    return s;
  };
  const std::string from = le64(7777), to = le64(std::uint64_t{1} << 53);
  int patched = 0;
  for (auto at = bytes.find(from); at != std::string::npos; at = bytes.find(from, at + 8), ++patched)
    bytes.replace(at, 8, to);
  ASSERT_GE(patched, 1);
  {
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out << bytes;
  }
  EXPECT_THAT([&] { shudder::io::read_measured_run_hdf5(path); },
              ThrowsMessage<InputError>(HasSubstr("claims 9007199254740992 rows")));
  std::filesystem::remove(path);
}

// Fuzzing finding (fuzz/fuzz_measured_hdf5): a damaged datatype message claiming
// numbers of 2^30 bytes made libhdf5 allocate a conversion buffer of that size inside H5Dread
// (an out-of-memory abort under the fuzzer; old behaviour in a plain build: the 1 GiB buffer
// was allocated and cleared, 9.3 s on a shared machine, before the read failed with "addr
// overflow"; the file is 9 kB). The file is a valid
// run whose float64 datatype messages (size field 8 followed by the IEEE double's bit layout:
// offset 0, precision 64, exponent at 52 of 11 bits, mantissa at 0 of 52 bits, bias 1023) are
// patched to claim 2^30-byte numbers.
TEST(MeasuredRunFuzzRegression, Hdf5DatasetTypeClaimingHugeNumbersIsRejected) {
  const auto path =
      (std::filesystem::temp_directory_path() / ("shudder_fuzz_type_" + std::to_string(::getpid()) + ".h5")).string();
  MeasuredRun run;
  run.metadata = {{"format", "shudder-measurement/1"}};
  for (const char* name : {"time_s", "speed_rpm", "normal_force_N", "torque_Nm", "temp_C"})
    run.columns.push_back({name, shudder::io::measured_run_units(name), {}});
  for (std::size_t k = 0; k < 20; ++k) {
    const double row[] = {0.01 * static_cast<double>(k), 1.0, 15000.0, 80.0, 60.0};
    for (std::size_t c = 0; c < 5; ++c) run.columns[c].values.push_back(row[c]);
  }
  shudder::io::write_measured_run_hdf5(path, run);
  std::string bytes;
  {
    std::ifstream in(path, std::ios::binary);
    bytes.assign(std::istreambuf_iterator<char>(in), {});
  }
  const std::string layout("\x00\x00\x40\x00\x34\x0b\x00\x34\xff\x03\x00\x00", 12);
  const std::string from = std::string("\x08\x00\x00\x00", 4) + layout;
  const std::string to = std::string("\x00\x00\x00\x40", 4) + layout;
  int patched = 0;
  for (auto at = bytes.find(from); at != std::string::npos; at = bytes.find(from, at + 1), ++patched)
    bytes.replace(at, from.size(), to);
  ASSERT_GE(patched, 1);
  {
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out << bytes;
  }
  EXPECT_THAT([&] { shudder::io::read_measured_run_hdf5(path); },
              ThrowsMessage<InputError>(HasSubstr("dataset's type claims 1073741824-byte numbers")));
  std::filesystem::remove(path);
}

}  // namespace
