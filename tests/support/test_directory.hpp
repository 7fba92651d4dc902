#pragma once
// A gtest fixture base for the file-format tests: each test gets a fresh, empty directory
// (temp dir / shudder_PREFIX_PID_TESTNAME) that is removed after it. The process id keeps two
// test runs at once (two checkouts, CI beside a developer) apart, the test name the cases that
// ctest runs in parallel.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <string>
#include <utility>

namespace shudder::test {

class TestDirectory : public testing::Test {
 protected:
  explicit TestDirectory(std::string prefix) : prefix_(std::move(prefix)) {}
  void SetUp() override {
    dir_ = std::filesystem::temp_directory_path() / ("shudder_" + prefix_ + "_" + std::to_string(::getpid()) + "_" +
                                                     testing::UnitTest::GetInstance()->current_test_info()->name());
    std::filesystem::remove_all(dir_);
    std::filesystem::create_directories(dir_);
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }
  /// `name` inside the test's directory.
  std::string path(const std::string& name) const { return (dir_ / name).string(); }
  std::filesystem::path dir_;

 private:
  std::string prefix_;
};

}  // namespace shudder::test
