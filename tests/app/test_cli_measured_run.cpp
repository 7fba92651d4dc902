// `shudder run SCENARIO --measurement FILE` through the real CLI: a `.h5` name gets the measured
// run's HDF5 form, which the strict reader accepts and which holds the same run as the CSV the
// same command writes for a `.csv` name (CSV values to its 6 printed digits).
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <string>

#include "io/measured_run.hpp"
#include "tests/support/cli.hpp"

using namespace shudder::test;
using shudder::io::MeasuredRun;
using shudder::io::read_measured_run;
using ::testing::HasSubstr;

TEST(CliMeasuredRun, RunWritesReadableHdf5MeasurementForH5Name) {
  const auto dir = scratch_dir("measured_run_h5");
  // Appended, not `"'" + ...`: GCC 12 -O3 reports a false -Wrestrict for that.
  std::string scenario = "'";
  scenario += source_path("scenarios/paper_g_case1_10kN.toml");
  scenario += "'";
  const auto h5 = run_cli("run " + scenario + " -o out.h5 --measurement m.h5", dir);
  ASSERT_EQ(h5.exit_code, 0) << h5.err;
  EXPECT_THAT(h5.out, HasSubstr("m.h5"));
  const auto csv = run_cli("run " + scenario + " -o out2.h5 --measurement m.csv", dir);
  ASSERT_EQ(csv.exit_code, 0) << csv.err;
  EXPECT_FALSE(std::filesystem::exists(dir / "m.h5.tmp"));

  // The .h5 file really is HDF5 (signature), whatever the reader would make of its name.
  EXPECT_EQ(slurp(dir / "m.h5").substr(0, 4), "\x89HDF");
  const MeasuredRun run = read_measured_run((dir / "m.h5").string());
  const MeasuredRun text = read_measured_run((dir / "m.csv").string());
  EXPECT_EQ(run.meta("format"), "shudder-measurement/1");
  EXPECT_EQ(run.meta("noise"), "off");
  EXPECT_EQ(run.metadata, text.metadata);
  ASSERT_EQ(run.columns.size(), text.columns.size());
  ASSERT_EQ(run.rows(), text.rows());
  EXPECT_GE(run.rows(), 1000u);  // 10 s at the scenario's 100 Hz
  EXPECT_NEAR(run.duration_s(), 10.0, 1e-9);
  for (std::size_t c = 0; c < run.columns.size(); ++c) {
    EXPECT_EQ(run.columns[c].name, text.columns[c].name);
    EXPECT_EQ(run.columns[c].units, text.columns[c].units);
    for (std::size_t i = 0; i < run.rows(); ++i) {
      const double exact = run.columns[c].values[i], printed = text.columns[c].values[i];
      ASSERT_LE(std::abs(exact - printed), 0.5e-5 * std::abs(exact) + (c == 0 ? 0.5e-3 : 0.0))
          << run.columns[c].name << " row " << i;
    }
  }
  // The force the scenario prescribes, the slip ramp's ends.
  EXPECT_NEAR(run.required("normal_force_N")[run.rows() / 2], 10400.0, 1e-6);
  EXPECT_NEAR(run.required("speed_rpm").front(), 1.0, 1e-6);
  EXPECT_NEAR(run.required("speed_rpm").back(), 100.0, 1e-6);
}
