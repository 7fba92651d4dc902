// Recording -> measured-run CSV (docs/formats/measured_run.md). Checked: metadata and header exactly as the
// format's example; linear-ramp resampling exact at the new times; noise off = the recorded
// values; noise reproducible per seed and of the stated size; bad options and recordings
// rejected with nothing left on disk.
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "io/input_error.hpp"
#include "io/measurement_csv.hpp"
#include "tests/support/test_directory.hpp"

namespace fs = std::filesystem;
using shudder::dynamics::Recording;
using shudder::io::InputError;
using shudder::io::MeasurementOptions;
using shudder::io::write_measurement_csv;
using testing::HasSubstr;
using testing::ThrowsMessage;

namespace {

class MeasurementCsv : public shudder::test::TestDirectory {
 protected:
  MeasurementCsv() : TestDirectory("csv") {}
};

// A written file split into metadata lines, header and numeric rows.
struct Csv {
  std::vector<std::string> meta, header;
  std::vector<std::vector<double>> rows;
  std::vector<double> column(const std::string& name) const {
    const auto c = static_cast<std::size_t>(std::find(header.begin(), header.end(), name) - header.begin());
    std::vector<double> out;
    for (const auto& r : rows) out.push_back(r.at(c));
    return out;
  }
};

std::string slurp(const std::string& file) {
  std::ifstream in(file, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

Csv parse(const std::string& file) {
  Csv csv;
  std::istringstream in(slurp(file));
  std::string line;
  while (std::getline(in, line)) {
    std::vector<std::string> fields;
    std::stringstream ls(line);
    for (std::string f; std::getline(ls, f, ',');) fields.push_back(f);
    if (line.starts_with("#") && csv.header.empty()) {
      csv.meta.push_back(line);
    } else if (csv.header.empty()) {
      csv.header = fields;
    } else {
      std::vector<double> row;
      for (const auto& f : fields) {
        double v = NAN;
        const auto res = std::from_chars(f.data(), f.data() + f.size(), v);
        EXPECT_EQ(res.ptr, f.data() + f.size()) << "not a number: " << f;
        row.push_back(v);
      }
      csv.rows.push_back(row);
    }
  }
  return csv;
}

// 1 s at 1 kHz of ramps whose values at multiples of 4 ms are short decimals (so "%.6g" prints
// them exactly): speed = 100 t rpm, torque = 10 + 50 t Nm, temp = 77 + 2 t degC.
Recording ramp_recording(std::size_t n = 1001, double rate_Hz = 1000.0) {
  Recording rec;
  for (const char* name : {"time_s", "speed_rpm", "normal_force_N", "torque_Nm", "temp_C", "sump_temp_C",
                           "clutch_torque_Nm" /* not a sensor: not written */})
    rec.add_signal(name, "");
  for (std::size_t k = 0; k < n; ++k) {
    const double t = static_cast<double>(k) / rate_Hz;
    const double row[] = {t, 100.0 * t, 25300.0, 10.0 + 50.0 * t, 77.0 + 2.0 * t, 77.0, -1.0};
    for (std::size_t c = 0; c < rec.signals.size(); ++c) rec.signals[c].values.push_back(row[c]);
  }
  return rec;
}

MeasurementOptions lsc_fluid_c() {
  MeasurementOptions opt;
  opt.fluid = "lsc-fluid-c";
  return opt;
}

}  // namespace

TEST_F(MeasurementCsv, MetadataAndHeaderAsInFormats) {
  write_measurement_csv(path("run.csv"), ramp_recording(), lsc_fluid_c());
  const Csv csv = parse(path("run.csv"));
  // The first five lines are docs/formats/measured_run.md's example verbatim; then this writer's additions.
  EXPECT_THAT(csv.meta, testing::ElementsAre("# format: shudder-measurement/1", "# rig: lsctr", "# fluid: lsc-fluid-c",
                                             "# temp_sensor: separator_thermocouple r_mm=48 z_mm=0.5",
                                             "# oil_flow_ml_min: 200", "# sample_rate_Hz: 1000", "# noise: off"));
  EXPECT_THAT(csv.header,
              testing::ElementsAre("time_s", "speed_rpm", "normal_force_N", "torque_Nm", "temp_C", "sump_temp_C"));
  // First data row as text: time with 3 decimals at 1 kHz, values "%.6g".
  EXPECT_THAT(slurp(path("run.csv")), HasSubstr("\n0.000,0,25300,10,77,77\n0.001,0.1,25300,10.05,77.002,77\n"));
  EXPECT_FALSE(fs::exists(path("run.csv.tmp")));
}

TEST_F(MeasurementCsv, NoiseMetadataNamesTheSeed) {
  MeasurementOptions opt = lsc_fluid_c();
  opt.noise = true;
  opt.seed = 42;
  write_measurement_csv(path("run.csv"), ramp_recording(), opt);
  const Csv csv = parse(path("run.csv"));
  EXPECT_THAT(csv.meta, testing::IsSupersetOf({"# noise: on", "# seed: 42"}));
}

TEST_F(MeasurementCsv, OwnRateWithoutNoiseWritesRecordedValues) {
  const Recording rec = ramp_recording();
  write_measurement_csv(path("run.csv"), rec, lsc_fluid_c());
  const Csv csv = parse(path("run.csv"));
  ASSERT_EQ(csv.rows.size(), 1001u);
  for (const auto& name : csv.header) {
    const std::vector<double> written = csv.column(name), recorded = rec.find(name)->values;
    ASSERT_EQ(written.size(), recorded.size());
    // Recorded values are short decimals, so the 6 significant digits written hold them exactly
    // (up to the last bit of the decimal -> binary conversion).
    for (std::size_t k = 0; k < written.size(); ++k)
      ASSERT_NEAR(written[k], recorded[k], 1e-12 * std::max(1.0, std::abs(recorded[k]))) << name << " row " << k;
  }
}

// Linear interpolation reproduces a straight line exactly, so at 250 Hz (t = 4 ms k) every
// value is the ramp's value; at 300 Hz the times are not short decimals and the check is to the
// 6 significant digits written.
TEST_F(MeasurementCsv, ResamplesLinearRampExactly) {
  MeasurementOptions opt = lsc_fluid_c();
  opt.sample_rate_Hz = 250.0;
  write_measurement_csv(path("run.csv"), ramp_recording(), opt);
  Csv csv = parse(path("run.csv"));
  ASSERT_EQ(csv.rows.size(), 251u);  // 0 .. 1 s inclusive
  for (std::size_t k = 0; k < csv.rows.size(); ++k) {
    const double t = 0.004 * static_cast<double>(k);
    EXPECT_DOUBLE_EQ(csv.column("time_s")[k], t);
    EXPECT_DOUBLE_EQ(csv.column("speed_rpm")[k], 100.0 * t);
    EXPECT_DOUBLE_EQ(csv.column("torque_Nm")[k], 10.0 + 50.0 * t);
    EXPECT_DOUBLE_EQ(csv.column("temp_C")[k], 77.0 + 2.0 * t);
    EXPECT_EQ(csv.column("normal_force_N")[k], 25300.0);
  }
  EXPECT_THAT(csv.meta, testing::Contains("# sample_rate_Hz: 250"));

  opt.sample_rate_Hz = 300.0;
  write_measurement_csv(path("run.csv"), ramp_recording(), opt);
  csv = parse(path("run.csv"));
  ASSERT_EQ(csv.rows.size(), 301u);
  for (std::size_t k = 0; k < csv.rows.size(); ++k) {
    const double t = static_cast<double>(k) / 300.0;
    // Time is written to 1 % of the step (5 decimals at 300 Hz), values to 6 significant digits.
    EXPECT_NEAR(csv.column("time_s")[k], t, 0.01 / 300.0);
    EXPECT_NEAR(csv.column("torque_Nm")[k], 10.0 + 50.0 * t, 1e-5 * (10.0 + 50.0 * t));
  }
}

// At 1 MHz the time column needs 6 decimals; printed times must stay strictly increasing.
TEST_F(MeasurementCsv, TimesStayStrictlyIncreasingAtOneMegahertz) {
  MeasurementOptions opt;
  opt.sample_rate_Hz = 1e6;
  write_measurement_csv(path("run.csv"), ramp_recording(11, 1e4), opt);  // 1 ms long
  const std::vector<double> t = parse(path("run.csv")).column("time_s");
  ASSERT_EQ(t.size(), 1001u);
  for (std::size_t k = 1; k < t.size(); ++k) {
    ASSERT_GT(t[k], t[k - 1]) << "row " << k;
    ASSERT_NEAR(t[k], 1e-6 * static_cast<double>(k), 1e-8);
  }
}

TEST_F(MeasurementCsv, SameSeedSameFileOtherSeedDiffers) {
  MeasurementOptions opt = lsc_fluid_c();
  opt.noise = true;
  opt.seed = 7;
  write_measurement_csv(path("a.csv"), ramp_recording(), opt);
  write_measurement_csv(path("b.csv"), ramp_recording(), opt);
  opt.seed = 8;
  write_measurement_csv(path("c.csv"), ramp_recording(), opt);
  EXPECT_EQ(slurp(path("a.csv")), slurp(path("b.csv")));
  const Csv a = parse(path("a.csv")), c = parse(path("c.csv"));
  EXPECT_NE(a.column("torque_Nm"), c.column("torque_Nm"));
}

// Noise sigma = half the stated accuracy: torque 1.25 / 2 = 0.625 Nm, force 37.5 N,
// thermocouple 0.335 degC, speed 0.005 rpm. Over N = 20001 samples the sample standard
// deviation has a relative standard error of about 1 / sqrt(2 N) = 0.5 %, so 3 % (6 standard
// errors) cannot fail by chance; the mean is checked to 5 standard errors, sigma / sqrt(N).
// The "%.6g" rounding (at most ~1 % of sigma here) adds < 0.01 % to the variance.
TEST_F(MeasurementCsv, NoiseHasHalfTheStatedAccuracyAsSigma) {
  using A = shudder::io::SensorAccuracy;
  MeasurementOptions opt = lsc_fluid_c();
  opt.noise = true;
  opt.seed = 2024;
  Recording rec = ramp_recording(20001);  // 20 s at 1 kHz
  // Speed within the rig's 0-125 rpm: at 2000 rpm "%.6g" keeps only 0.01 rpm, which would add
  // rounding noise comparable to the 0.005 rpm sigma.
  for (double& v : rec.signals[1].values) v /= 20.0;
  write_measurement_csv(path("run.csv"), rec, opt);
  const Csv csv = parse(path("run.csv"));
  ASSERT_EQ(csv.rows.size(), 20001u);
  const struct {
    const char* name;
    double sigma;
  } expected[] = {{"torque_Nm", 0.625},
                  {"normal_force_N", A::normal_force_N / 2},
                  {"temp_C", A::thermocouple_C / 2},
                  {"sump_temp_C", A::thermocouple_C / 2},
                  {"speed_rpm", A::speed_rpm / 2}};
  for (const auto& [name, sigma] : expected) {
    const std::vector<double> noisy = csv.column(name), clean = rec.find(name)->values;
    double sum = 0.0, sum_sq = 0.0;
    for (std::size_t k = 0; k < noisy.size(); ++k) sum += noisy[k] - clean[k];
    const double n = static_cast<double>(noisy.size()), mean = sum / n;
    for (std::size_t k = 0; k < noisy.size(); ++k) sum_sq += std::pow(noisy[k] - clean[k] - mean, 2);
    const double std_dev = std::sqrt(sum_sq / (n - 1));
    EXPECT_NEAR(std_dev, sigma, 0.03 * sigma) << name;
    EXPECT_NEAR(mean, 0.0, 5.0 * sigma / std::sqrt(n)) << name;
  }
  EXPECT_DOUBLE_EQ(A::torque_Nm, 1.25);
  EXPECT_DOUBLE_EQ(A::normal_force_N, 75.0);
}

TEST_F(MeasurementCsv, NoisyNormalForceNeverNegative) {
  Recording rec = ramp_recording();
  for (double& f : rec.signals[2].values) f = 0.0;  // unloaded
  MeasurementOptions opt;
  opt.noise = true;
  write_measurement_csv(path("run.csv"), rec, opt);
  for (double f : parse(path("run.csv")).column("normal_force_N")) ASSERT_GE(f, 0.0);
}

TEST_F(MeasurementCsv, RejectsBadRatesAndLeavesNoFile) {
  for (double rate : {-1.0, 2e6, std::nan("")}) {
    MeasurementOptions opt;
    opt.sample_rate_Hz = rate;
    EXPECT_THAT([&] { write_measurement_csv(path("run.csv"), ramp_recording(), opt); },
                ThrowsMessage<InputError>(HasSubstr("key 'sample_rate_Hz'")))
        << rate;
  }
  EXPECT_FALSE(fs::exists(path("run.csv")));
}

TEST_F(MeasurementCsv, RejectsMissingSignalTooFewRowsAndNonFinite) {
  Recording no_temp = ramp_recording();
  no_temp.signals.erase(no_temp.signals.begin() + 4);
  EXPECT_THAT([&] { write_measurement_csv(path("run.csv"), no_temp, {}); },
              ThrowsMessage<InputError>(HasSubstr("key 'temp_C': recording has no such signal")));

  MeasurementOptions slow;
  slow.sample_rate_Hz = 5.0;  // 1 s -> 6 rows
  EXPECT_THAT([&] { write_measurement_csv(path("run.csv"), ramp_recording(), slow); },
              ThrowsMessage<InputError>(HasSubstr("at least 10")));

  Recording nan = ramp_recording();
  nan.signals[3].values[500] = NAN;
  EXPECT_THAT([&] { write_measurement_csv(path("run.csv"), nan, {}); },
              ThrowsMessage<InputError>(HasSubstr("key 'torque_Nm': non-finite value at t = 0.5")));

  EXPECT_FALSE(fs::exists(path("run.csv")));
  EXPECT_FALSE(fs::exists(path("run.csv.tmp")));
}

TEST_F(MeasurementCsv, UnwritableTargetLeavesNoFile) {
  const std::string target = path("no_such_dir/run.csv");
  EXPECT_THAT([&] { write_measurement_csv(target, ramp_recording(), {}); },
              ThrowsMessage<InputError>(HasSubstr("check the directory exists")));
  EXPECT_FALSE(fs::exists(target + ".tmp"));

  fs::create_directory(path("dir.csv"));  // written completely, then the rename fails
  EXPECT_THAT([&] { write_measurement_csv(path("dir.csv"), ramp_recording(), {}); },
              ThrowsMessage<InputError>(HasSubstr("rename")));
  EXPECT_FALSE(fs::exists(path("dir.csv.tmp")));
}
