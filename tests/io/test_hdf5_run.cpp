// Run output through HDF5: a small synthetic Recording (signals, thermal snapshots, scalars and
// a 2-D map) written and read back must come back bit-for-bit (doubles are stored as IEEE float64, no conversion);
// failed writes must leave neither the target nor the temporary file; reading rejects what is not a run file; no HDF5
// identifier leaks.
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <cctype>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string_view>

#include "io/hdf5_run.hpp"
#include "io/input_error.hpp"
#include "tests/support/test_directory.hpp"

namespace fs = std::filesystem;
using shudder::dynamics::Recording;
using shudder::io::InputError;
using testing::HasSubstr;

namespace {

class Hdf5Run : public shudder::test::TestDirectory {
 protected:
  Hdf5Run() : TestDirectory("hdf5") {}
};

// Values chosen to catch any lossy conversion: 1/3, -0, a subnormal, the largest double.
Recording sample_recording() {
  Recording rec;
  rec.add_signal("speed_rpm", "rpm").values = {1.0, 1.0 / 3.0, -0.0, 100.0};
  rec.add_signal("time_s", "s").values = {0.0, 1e-3, 2e-3, 3e-3};
  rec.add_signal("torque_Nm", "N m").values = {98.4, std::numeric_limits<double>::denorm_min(),
                                               std::numeric_limits<double>::max(), -7.25};
  rec.grid_r_m = {0.040, 0.046, 0.052};  // (n_r = 3)
  rec.grid_z_m = {0.0005, 0.0015};       // (n_z = 2)
  for (int k = 0; k < 2; ++k) {
    Eigen::MatrixXd t(2, 3);  // (n_z x n_r), every entry distinct to catch transposition
    for (int i = 0; i < 2; ++i)
      for (int j = 0; j < 3; ++j) t(i, j) = 20.0 + 100.0 * k + 10.0 * i + j + 0.125;
    rec.snapshots.push_back({0.5 * k, t});
  }
  rec.scalars = {{"torque_at_10s_Nm", "N m", 101.5}, {"peak_temp_C", "degC", 1.0 / 7.0}};
  // A (3 x 2) map with two layers, entries distinct to catch transposition, a NaN hole.
  shudder::dynamics::Map2D map;
  map.name = "stability_map";
  map.description = "test map";
  map.x_name = "speeds_rpm";
  map.x_units = "rpm";
  map.x = {1.0, 2.0, 3.0};
  map.y_name = "temps_C";
  map.y_units = "degC";
  map.y = {40.0, 1.0 / 3.0 + 50.0};
  Eigen::MatrixXd margin(3, 2), freq(3, 2);
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 2; ++j) margin(i, j) = 10.0 * i + j - 0.5, freq(i, j) = 378.0 + i + 0.1 * j;
  margin(2, 1) = std::numeric_limits<double>::quiet_NaN();
  map.layers = {{"margin_per_s", "1/s", margin}, {"frequency_Hz", "Hz", freq}};
  map.scalars = {{"normal_force_N", "N", 15000.0}};
  rec.maps.push_back(map);
  return rec;
}

}  // namespace

TEST_F(Hdf5Run, RoundTripIsExact) {
  const Recording rec = sample_recording();
  const std::string scenario = "[run]\nname = \"case 1\"  # 77 °C\n";
  shudder::io::write_run_hdf5(path("run.h5"), rec, scenario);
  const Recording back = shudder::io::read_run_hdf5(path("run.h5"));

  // Signals: time_s moved first, otherwise file (= write) order; values and units exact.
  ASSERT_EQ(back.signals.size(), 3u);
  EXPECT_EQ(back.signals[0].name, "time_s");
  EXPECT_EQ(back.signals[1].name, "speed_rpm");
  EXPECT_EQ(back.signals[2].name, "torque_Nm");
  for (const auto& s : back.signals) {
    const auto* orig = rec.find(s.name);
    ASSERT_NE(orig, nullptr);
    EXPECT_EQ(s.units, orig->units) << s.name;
    EXPECT_EQ(s.values, orig->values) << s.name;
  }
  EXPECT_TRUE(std::signbit(back.find("speed_rpm")->values[2]));  // -0 stays -0

  // Thermal grid and snapshots.
  EXPECT_EQ(back.grid_r_m, rec.grid_r_m);
  EXPECT_EQ(back.grid_z_m, rec.grid_z_m);
  ASSERT_EQ(back.snapshots.size(), 2u);
  for (std::size_t k = 0; k < 2; ++k) {
    EXPECT_EQ(back.snapshots[k].time_s, rec.snapshots[k].time_s);
    EXPECT_TRUE(back.snapshots[k].temp_C == rec.snapshots[k].temp_C) << back.snapshots[k].temp_C;
  }

  // Scalars in order, with units.
  ASSERT_EQ(back.scalars.size(), 2u);
  for (std::size_t k = 0; k < 2; ++k) {
    EXPECT_EQ(back.scalars[k].name, rec.scalars[k].name);
    EXPECT_EQ(back.scalars[k].units, rec.scalars[k].units);
    EXPECT_EQ(back.scalars[k].value, rec.scalars[k].value);
  }

  // Maps under /analysis/<name>: axes, layers (n_x x n_y, NaN kept) and scalars exact.
  ASSERT_EQ(back.maps.size(), 1u);
  const auto& m = back.maps[0];
  const auto& om = rec.maps[0];
  EXPECT_EQ(m.name, "stability_map");
  EXPECT_EQ(m.description, om.description);
  EXPECT_EQ(m.x_name, om.x_name);
  EXPECT_EQ(m.x_units, om.x_units);
  EXPECT_EQ(m.x, om.x);
  EXPECT_EQ(m.y_name, om.y_name);
  EXPECT_EQ(m.y_units, om.y_units);
  EXPECT_EQ(m.y, om.y);
  ASSERT_EQ(m.layers.size(), 2u);
  for (std::size_t k = 0; k < 2; ++k) {
    EXPECT_EQ(m.layers[k].name, om.layers[k].name);
    EXPECT_EQ(m.layers[k].units, om.layers[k].units);
    ASSERT_EQ(m.layers[k].values.rows(), 3);
    ASSERT_EQ(m.layers[k].values.cols(), 2);
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 2; ++j) {
        const double a = m.layers[k].values(i, j), b = om.layers[k].values(i, j);
        if (std::isnan(b))
          EXPECT_TRUE(std::isnan(a)) << k << " " << i << " " << j;
        else
          EXPECT_EQ(a, b) << k << " " << i << " " << j;
      }
  }
  ASSERT_NE(m.find_scalar("normal_force_N"), nullptr);
  EXPECT_EQ(m.find_scalar("normal_force_N")->value, 15000.0);
  EXPECT_EQ(m.find_scalar("normal_force_N")->units, "N");
  EXPECT_EQ(back.find_map("stability_map"), &back.maps[0]);

  // Root attributes; no temporary left behind.
  EXPECT_EQ(shudder::io::read_run_attribute(path("run.h5"), "scenario"), scenario);
  EXPECT_EQ(shudder::io::read_run_attribute(path("run.h5"), "shudder_version"), SHUDDER_VERSION);
  // created_utc: ISO 8601 "YYYY-MM-DDThh:mm:ssZ" (std::regex avoided: GCC 12 false positives).
  const std::string created = shudder::io::read_run_attribute(path("run.h5"), "created_utc");
  ASSERT_EQ(created.size(), 20u) << created;
  for (std::size_t i = 0; i < created.size(); ++i) {
    const char expected = std::string_view("0000-00-00T00:00:00Z")[i];
    if (expected == '0')
      EXPECT_TRUE(std::isdigit(static_cast<unsigned char>(created[i]))) << created;
    else
      EXPECT_EQ(created[i], expected) << created;
  }
  EXPECT_FALSE(fs::exists(path("run.h5.tmp")));
}

TEST_F(Hdf5Run, OmitsThermalAndSummaryWhenEmpty) {
  Recording rec;
  rec.add_signal("time_s", "s").values = {0.0, 0.5};
  shudder::io::write_run_hdf5(path("run.h5"), rec, "");
  const Recording back = shudder::io::read_run_hdf5(path("run.h5"));
  ASSERT_EQ(back.signals.size(), 1u);
  EXPECT_EQ(back.signals[0].values, rec.signals[0].values);
  EXPECT_TRUE(back.grid_r_m.empty() && back.grid_z_m.empty());
  EXPECT_TRUE(back.snapshots.empty());
  EXPECT_TRUE(back.scalars.empty());
  EXPECT_TRUE(back.maps.empty());
}

TEST_F(Hdf5Run, UnequalSignalLengthsLeaveNoFile) {
  Recording rec = sample_recording();
  rec.signals[2].values.pop_back();
  try {
    shudder::io::write_run_hdf5(path("run.h5"), rec, "");
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr("torque_Nm"));
    EXPECT_THAT(e.what(), HasSubstr("same length"));
  }
  EXPECT_FALSE(fs::exists(path("run.h5")));
  EXPECT_FALSE(fs::exists(path("run.h5.tmp")));
}

TEST_F(Hdf5Run, SnapshotShapeMustMatchGrid) {
  Recording rec = sample_recording();
  rec.grid_r_m.push_back(0.058);
  EXPECT_THAT([&] { shudder::io::write_run_hdf5(path("run.h5"), rec, ""); },
              testing::ThrowsMessage<InputError>(HasSubstr("does not match grid")));
  EXPECT_FALSE(fs::exists(path("run.h5")));
}

TEST_F(Hdf5Run, MapLayersMustMatchTheGridAndNamesMustBeFree) {
  Recording rec = sample_recording();
  rec.maps[0].layers[1].values.resize(2, 3);  // transposed
  EXPECT_THAT([&] { shudder::io::write_run_hdf5(path("run.h5"), rec, ""); },
              testing::ThrowsMessage<InputError>(HasSubstr("layer is 2 x 3 but the grid is 3 (speeds_rpm) x 2")));
  rec = sample_recording();
  rec.maps[0].name = "summary";
  EXPECT_THAT([&] { shudder::io::write_run_hdf5(path("run.h5"), rec, ""); },
              testing::ThrowsMessage<InputError>(HasSubstr("taken by the summary scalars")));
  rec = sample_recording();
  rec.maps[0].layers[1].name = "temps_C";
  EXPECT_THAT([&] { shudder::io::write_run_hdf5(path("run.h5"), rec, ""); },
              testing::ThrowsMessage<InputError>(HasSubstr("duplicate dataset name 'temps_C'")));
  EXPECT_FALSE(fs::exists(path("run.h5")));
}

TEST_F(Hdf5Run, MissingDirectoryLeavesNoFile) {
  const std::string target = path("no_such_dir/run.h5");
  EXPECT_THAT([&] { shudder::io::write_run_hdf5(target, sample_recording(), ""); },
              testing::ThrowsMessage<InputError>(HasSubstr("cannot write run file")));
  EXPECT_FALSE(fs::exists(target));
  EXPECT_FALSE(fs::exists(target + ".tmp"));
}

// The whole file is written, then the rename fails (the target is a directory): the complete
// temporary must still be removed.
TEST_F(Hdf5Run, FailedRenameRemovesTemporary) {
  fs::create_directory(path("run.h5"));
  EXPECT_THAT([&] { shudder::io::write_run_hdf5(path("run.h5"), sample_recording(), ""); },
              testing::ThrowsMessage<InputError>(HasSubstr("rename")));
  EXPECT_TRUE(fs::is_directory(path("run.h5")));
  EXPECT_FALSE(fs::exists(path("run.h5.tmp")));
}

TEST_F(Hdf5Run, FailedWriteKeepsPreviousFile) {
  Recording good;
  good.add_signal("time_s", "s").values = {0.0, 1.0};
  shudder::io::write_run_hdf5(path("run.h5"), good, "first");
  Recording bad = sample_recording();
  bad.signals[0].values.clear();
  EXPECT_THROW(shudder::io::write_run_hdf5(path("run.h5"), bad, "second"), InputError);
  EXPECT_EQ(shudder::io::read_run_attribute(path("run.h5"), "scenario"), "first");
  EXPECT_EQ(shudder::io::read_run_hdf5(path("run.h5")).signals[0].values, good.signals[0].values);
}

TEST_F(Hdf5Run, ReaderRejectsMissingAndNonHdf5Files) {
  EXPECT_THAT([&] { shudder::io::read_run_hdf5(path("absent.h5")); },
              testing::ThrowsMessage<InputError>(HasSubstr("absent.h5: cannot read run file: no such file")));
  std::ofstream(path("text.h5")) << "time_s,torque_Nm\n0,1\n";
  EXPECT_THAT([&] { shudder::io::read_run_hdf5(path("text.h5")); },
              testing::ThrowsMessage<InputError>(HasSubstr("not an HDF5 file")));
}

TEST_F(Hdf5Run, NoHdf5IdentifiersLeak) {
  // Warm up: the library registers its predefined types and property lists on first use.
  shudder::io::write_run_hdf5(path("run.h5"), sample_recording(), "x");
  (void)shudder::io::read_run_hdf5(path("run.h5"));
  const long before = shudder::io::detail::open_hdf5_identifiers();

  // Successful and failing writes and reads.
  shudder::io::write_run_hdf5(path("run.h5"), sample_recording(), "x");
  (void)shudder::io::read_run_hdf5(path("run.h5"));
  (void)shudder::io::read_run_attribute(path("run.h5"), "scenario");
  EXPECT_THROW(shudder::io::write_run_hdf5(path("missing/run.h5"), sample_recording(), ""), InputError);
  fs::create_directory(path("dir.h5"));
  EXPECT_THROW(shudder::io::write_run_hdf5(path("dir.h5"), sample_recording(), ""), InputError);
  std::ofstream(path("text.h5")) << "not hdf5\n";
  EXPECT_THROW(shudder::io::read_run_hdf5(path("text.h5")), InputError);

  EXPECT_EQ(shudder::io::detail::open_hdf5_identifiers(), before);
}
