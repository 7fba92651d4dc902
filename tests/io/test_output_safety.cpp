// File safety of the writers: outputs that would replace inputs or each other,
// missing output directories, the size limit, stale temporaries of killed writers, and
// compressed datasets. Each test says what the old code did.
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "io/atomic_file.hpp"
#include "io/hdf5_run.hpp"
#include "io/input_error.hpp"
#include "io/output_safety.hpp"
#include "tests/support/test_directory.hpp"

namespace fs = std::filesystem;
using shudder::io::InputError;
using shudder::io::RolePath;
using ::testing::AllOf;
using ::testing::HasSubstr;
using ::testing::ThrowsMessage;

namespace {

class OutputSafety : public shudder::test::TestDirectory {
 protected:
  OutputSafety() : TestDirectory("outsafe") {}
  void touch(const std::string& name) const { std::ofstream(dir_ / name) << "x"; }
};

// A pid no process can have: above the kernel's pid_max.
long dead_pid() {
  long pid_max = 4194304;
  std::ifstream("/proc/sys/kernel/pid_max") >> pid_max;
  return pid_max + 1;
}

// 100,000 samples of smooth signals: what a run records, highly compressible.
shudder::dynamics::Recording smooth_recording() {
  shudder::dynamics::Recording rec;
  std::vector<double> t(100000), x(100000);
  for (std::size_t i = 0; i < t.size(); ++i) {
    t[i] = 1e-4 * static_cast<double>(i);
    x[i] = 100.0 + 5.0 * std::sin(2.0 * 3.14159 * 10.0 * t[i]);
  }
  rec.signals = {{"time_s", "s", t}, {"torque_Nm", "N m", x}};
  return rec;
}

}  // namespace

TEST_F(OutputSafety, OutputEqualToAnInputIsRefusedNamingBoth) {
  // Old code: `run X.toml -o X.toml` replaced the scenario with the run file.
  touch("s.toml");
  const std::string other_spelling = (dir_ / "sub" / ".." / "s.toml").string();
  fs::create_directories(dir_ / "sub");
  EXPECT_THAT(
      [&] {
        shudder::io::require_distinct_paths({{"scenario", path("s.toml")}}, {{"-o", other_spelling}});
      },
      ThrowsMessage<InputError>(
          AllOf(HasSubstr(other_spelling), HasSubstr("output -o is the scenario '" + path("s.toml") + "'"))));
}

TEST_F(OutputSafety, TwoOutputsWithTheSameNameAreRefusedEvenIfTheFileDoesNotExistYet) {
  // Old code: `--measurement same.h5 -o same.h5` left only /measurement.
  EXPECT_THAT(
      [&] {
        shudder::io::require_distinct_paths(
            {}, {{"-o", path("same.h5")}, {"--measurement", (dir_ / "." / "same.h5").string()}});
      },
      ThrowsMessage<InputError>(HasSubstr("output --measurement is also the output -o '" + path("same.h5") + "'")));
  EXPECT_NO_THROW(shudder::io::require_distinct_paths({{"scenario", path("s.toml")}},
                                                      {{"-o", path("a.h5")}, {"--measurement", path("b.csv")}}));
}

TEST_F(OutputSafety, MissingOutputDirectoryIsRefused) {
  EXPECT_THAT([&] { shudder::io::require_output_directory(path("nope/s.h5")); },
              ThrowsMessage<InputError>(HasSubstr("directory '" + path("nope") + "' does not exist")));
  EXPECT_NO_THROW(shudder::io::require_output_directory(path("s.h5")));
  // A directory output named with a trailing slash (`--report report/`) needs only its parent.
  EXPECT_NO_THROW(shudder::io::require_output_directory(path("report/")));
  EXPECT_THROW(shudder::io::require_output_directory(path("nope/report/")), InputError);
  EXPECT_FALSE(fs::exists(dir_ / "nope"));
}

TEST_F(OutputSafety, SizeAboveTheLimitIsRefusedUnlessForced) {
  // 3.6e9 bytes: a rig run at sample_rate_Hz = 1e6.
  EXPECT_THAT([&] { shudder::io::require_output_size(path("o.h5"), 3'600'000'000ULL, "why", false); },
              ThrowsMessage<InputError>(AllOf(
                  HasSubstr("estimated output size 3.60 GB (why) exceeds the limit of 2 GB"), HasSubstr("--force"))));
  EXPECT_NO_THROW(shudder::io::require_output_size(path("o.h5"), 3'600'000'000ULL, "why", true));
  EXPECT_NO_THROW(shudder::io::require_output_size(path("o.h5"), 2'000'000'000ULL, "why", false));
}

TEST_F(OutputSafety, StaleTemporariesOfTheSameOutputAreRemovedOnTheNextWrite) {
  // Old code: the temporary of a killed writer stayed beside the output for ever (and, named
  // `out.h5.tmp` for every writer, two concurrent writers of one output shared it).
  const std::string dead = std::to_string(dead_pid());
  const std::string live = std::to_string(::getpid());
  touch("run.h5.tmp");                      // the old fixed name: ours, stale
  touch("run.h5.tmp." + dead + ".0");       // a killed writer's
  touch("run.h5.tmp." + live + ".999999");  // a live writer's (this process): kept
  touch("other.h5.tmp." + dead + ".0");     // another output's: kept
  touch("run.h5.tmp.notes");                // not our pattern: kept
  shudder::io::write_run_hdf5(path("run.h5"), smooth_recording(), "scenario");
  EXPECT_TRUE(fs::exists(dir_ / "run.h5"));
  EXPECT_FALSE(fs::exists(dir_ / "run.h5.tmp"));
  EXPECT_FALSE(fs::exists(dir_ / ("run.h5.tmp." + dead + ".0")));
  EXPECT_TRUE(fs::exists(dir_ / ("run.h5.tmp." + live + ".999999")));
  EXPECT_TRUE(fs::exists(dir_ / ("other.h5.tmp." + dead + ".0")));
  EXPECT_TRUE(fs::exists(dir_ / "run.h5.tmp.notes"));
}

TEST_F(OutputSafety, StaleScanRemovesOnlyRegularFilesAndLinksNotTheirTargetsNorDirectories) {
  // The scan reads the directory itself (readdir, names compared as bytes): a directory named
  // like a stale temporary is not a file and stays; a symbolic link to a regular file is
  // judged by its target (as std::filesystem's is_regular_file did) and the link, not the
  // target, is removed; a name that only starts like the prefix ("run.h5.tmpx") stays; a
  // crowd of unrelated names around them changes nothing.
  const std::string dead = std::to_string(dead_pid());
  fs::create_directory(dir_ / ("run.h5.tmp." + dead + ".1"));
  touch("target.bin");
  fs::create_symlink(dir_ / "target.bin", dir_ / ("run.h5.tmp." + dead + ".2"));
  touch("run.h5.tmpx");
  touch("run.h5.tmp." + dead + ".3");
  for (int k = 0; k < 300; ++k) touch("crowd_" + std::to_string(k));
  shudder::io::remove_stale_temp_files(path("run.h5"));
  EXPECT_TRUE(fs::is_directory(dir_ / ("run.h5.tmp." + dead + ".1")));
  EXPECT_FALSE(fs::exists(fs::symlink_status(dir_ / ("run.h5.tmp." + dead + ".2"))));
  EXPECT_TRUE(fs::exists(dir_ / "target.bin"));
  EXPECT_TRUE(fs::exists(dir_ / "run.h5.tmpx"));
  EXPECT_FALSE(fs::exists(dir_ / ("run.h5.tmp." + dead + ".3")));
  EXPECT_TRUE(fs::exists(dir_ / "crowd_299"));
  // A path without a directory part scans the working directory; a path naming a directory
  // (trailing slash) has no temporaries and touches nothing.
  const fs::path cwd = fs::current_path();
  fs::current_path(dir_);
  touch("bare.h5.tmp");
  shudder::io::remove_stale_temp_files("bare.h5");
  fs::current_path(cwd);
  EXPECT_FALSE(fs::exists(dir_ / "bare.h5.tmp"));
  touch(".tmp");
  shudder::io::remove_stale_temp_files(dir_.string() + "/");
  EXPECT_TRUE(fs::exists(dir_ / ".tmp"));
}

TEST_F(OutputSafety, TemporaryNamesAreUniquePerWrite) {
  // Old code: always `path + ".tmp"`.
  const std::string a = shudder::io::temp_path_for("x.h5"), b = shudder::io::temp_path_for("x.h5");
  EXPECT_NE(a, b);
  EXPECT_THAT(a, HasSubstr("x.h5.tmp." + std::to_string(::getpid()) + "."));
}

TEST_F(OutputSafety, RunDatasetsAreCompressedAndReadBackBitIdentical) {
  // Old code: contiguous datasets, 2 x 100,000 x 8 = 1.6 MB on disk. Deflated, the smooth
  // signals take well under half of that (the time axis alone shuffles to near nothing).
  const auto rec = smooth_recording();
  shudder::io::write_run_hdf5(path("run.h5"), rec, "scenario");
  EXPECT_LT(fs::file_size(dir_ / "run.h5"), 800000u);
  const auto back = shudder::io::read_run_hdf5(path("run.h5"));
  ASSERT_EQ(back.signals.size(), 2u);
  for (std::size_t k = 0; k < 2; ++k) EXPECT_EQ(back.signals[k].values, rec.signals[k].values);
}
