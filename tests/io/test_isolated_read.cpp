// Reading an HDF5 measured run in a child process (io/isolated_read.hpp). Checked: a valid run
// comes back exactly as the in-process reader gives it (values bit for bit, metadata and column
// order, units); the reader's InputError reaches the caller word for word; a child that dies on a
// signal or hangs becomes an InputError naming the file, the signal or the time limit, and what
// to do (exit 2 in the CLI) instead of a crash or a hang; any other exception stays a
// std::runtime_error (a numerical/internal failure, exit 1), not an input error.
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <limits>
#include <new>
#include <string>

#include "io/input_error.hpp"
#include "io/isolated_read.hpp"
#include "io/measured_run.hpp"

namespace fs = std::filesystem;
using shudder::io::InputError;
using shudder::io::MeasuredRun;
using testing::AllOf;
using testing::HasSubstr;
using testing::Not;

namespace {

fs::path scratch() {
  const auto dir = fs::temp_directory_path() / ("shudder_isolated_" + std::to_string(::getpid()) + "_" +
                                                testing::UnitTest::GetInstance()->current_test_info()->name());
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

// 2,000 rows with values no decimal print would keep (the pipe must carry raw doubles), an
// optional column and extra metadata after `format`.
MeasuredRun awkward_run() {
  MeasuredRun run;
  run.metadata = {{"format", "shudder-measurement/1"}, {"rig", "lsctr"}, {"note", "ünïcode, commas"}};
  for (const char* name : {"time_s", "speed_rpm", "normal_force_N", "torque_Nm", "temp_C", "ir_temp_C"})
    run.columns.push_back({name, shudder::io::measured_run_units(name), {}});
  for (std::size_t k = 0; k < 2000; ++k) {
    const double t = 1e-3 * static_cast<double>(k) + 1e-13;
    const double row[] = {t,
                          std::sqrt(2.0) + t,
                          25300.0 / 3.0,
                          std::nextafter(98.4, 1e9) * std::sin(t),
                          77.02 + std::exp(-t),
                          std::numeric_limits<double>::denorm_min()};
    for (std::size_t c = 0; c < 6; ++c) run.columns[c].values.push_back(row[c]);
  }
  return run;
}

MeasuredRun never_returns() {
  for (;;) ::pause();
}

TEST(IsolatedRead, AValidRunComesBackExactlyAsTheInProcessReaderGivesIt) {
  const auto dir = scratch();
  const std::string path = (dir / "run.h5").string();
  shudder::io::write_measured_run_hdf5(path, awkward_run());
  const MeasuredRun here = shudder::io::read_measured_run_hdf5(path);
  const MeasuredRun isolated = shudder::io::read_measured_run_hdf5_isolated(path);
  const MeasuredRun dispatched = shudder::io::read_measured_run(path);
  for (const MeasuredRun* r : {&isolated, &dispatched}) {
    EXPECT_EQ(r->path, path);
    EXPECT_EQ(r->metadata, here.metadata);
    ASSERT_EQ(r->columns.size(), here.columns.size());
    for (std::size_t c = 0; c < here.columns.size(); ++c) {
      EXPECT_EQ(r->columns[c].name, here.columns[c].name);
      EXPECT_EQ(r->columns[c].units, here.columns[c].units);
      EXPECT_EQ(r->columns[c].values, here.columns[c].values) << here.columns[c].name;  // bit for bit
    }
  }
  fs::remove_all(dir);
}

TEST(IsolatedRead, TheReadersInputErrorArrivesWordForWord) {
  const auto dir = scratch();
  const std::string path = (dir / "no_temp.h5").string();
  MeasuredRun run = awkward_run();
  run.columns.erase(run.columns.begin() + 4);  // temp_C, a required column
  shudder::io::detail::write_measured_run_hdf5_unchecked(path, run);
  std::string in_process;
  try {
    (void)shudder::io::read_measured_run_hdf5(path);
  } catch (const InputError& e) {
    in_process = e.what();
  }
  ASSERT_THAT(in_process, HasSubstr("temp_C"));
  try {
    (void)shudder::io::read_measured_run(path);
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()), in_process);
  }
  fs::remove_all(dir);
}

TEST(IsolatedRead, AChildKilledByASignalIsAnInputErrorNamingTheFileAndTheSignal) {
  const auto crash = [] {
    ::signal(SIGSEGV, SIG_DFL);  // as libhdf5's invalid read would end, sanitizers or not
    ::raise(SIGSEGV);
    return MeasuredRun{};
  };
  try {
    (void)shudder::io::detail::run_isolated("damaged.h5", 30.0, crash);
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(),
                AllOf(HasSubstr("damaged.h5: "), HasSubstr("libhdf5 crashed"),
                      HasSubstr("signal " + std::to_string(SIGSEGV)), HasSubstr("as CSV"), Not(HasSubstr("\n"))));
  }
}

TEST(IsolatedRead, AChildThatHangsIsStoppedAtTheTimeLimit) {
  try {
    (void)shudder::io::detail::run_isolated("stuck.h5", 0.3, never_returns);
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(),
                AllOf(HasSubstr("stuck.h5: "), HasSubstr("did not finish within 0.3 s"), HasSubstr("as CSV")));
  }
}

TEST(IsolatedRead, OtherExceptionsStayFailuresOfTheProgramNotOfTheInput) {
  const auto out_of_memory = []() -> MeasuredRun { throw std::bad_alloc(); };
  try {
    (void)shudder::io::detail::run_isolated("big.h5", 30.0, out_of_memory);
    FAIL() << "no error";
  } catch (const InputError&) {
    FAIL() << "an out-of-memory in the reader is not a damaged file";
  } catch (const std::runtime_error& e) {
    EXPECT_THAT(e.what(), HasSubstr("bad_alloc"));
  }
}

TEST(IsolatedRead, TheTimeLimitGrowsWithTheFile) {
  EXPECT_DOUBLE_EQ(shudder::io::isolated_read_time_limit_s(0), 30.0);
  EXPECT_DOUBLE_EQ(shudder::io::isolated_read_time_limit_s(1'000'000'000), 130.0);  // 1 GB: +100 s
}

}  // namespace
