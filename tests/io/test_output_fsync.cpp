// Output durability choice (io/atomic_file.hpp): the fsync before an output's rename is off by
// default and SHUDDER_FSYNC=1 turns it on; a value other than 0/1 is bad input that leaves no
// file behind. (Whether the kernel really flushed cannot be observed here; that both paths
// still produce the complete file can.)
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <optional>
#include <sstream>
#include <string>

#include "io/atomic_file.hpp"
#include "io/input_error.hpp"

namespace fs = std::filesystem;
using shudder::io::InputError;
using ::testing::AllOf;
using ::testing::HasSubstr;

namespace {

class OutputFsync : public testing::Test {
 protected:
  void SetUp() override {
    if (const char* v = std::getenv("SHUDDER_FSYNC")) saved_ = v;
    dir_ = fs::temp_directory_path() / ("shudder_fsync_" + std::to_string(::getpid()));
    fs::create_directories(dir_);
  }
  void TearDown() override {
    if (saved_)
      ::setenv("SHUDDER_FSYNC", saved_->c_str(), 1);
    else
      ::unsetenv("SHUDDER_FSYNC");
    fs::remove_all(dir_);
  }
  static std::string read(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
  }
  std::optional<std::string> saved_;
  fs::path dir_;
};

TEST_F(OutputFsync, OffUnlessTheEnvironmentAsksForIt) {
  ::unsetenv("SHUDDER_FSYNC");
  EXPECT_FALSE(shudder::io::output_fsync_requested());
  ::setenv("SHUDDER_FSYNC", "", 1);
  EXPECT_FALSE(shudder::io::output_fsync_requested());
  ::setenv("SHUDDER_FSYNC", "0", 1);
  EXPECT_FALSE(shudder::io::output_fsync_requested());
  ::setenv("SHUDDER_FSYNC", "1", 1);
  EXPECT_TRUE(shudder::io::output_fsync_requested());
}

TEST_F(OutputFsync, BothChoicesWriteTheCompleteFileAndNoTemporary) {
  for (const char* choice : {"0", "1"}) {
    ::setenv("SHUDDER_FSYNC", choice, 1);
    const fs::path out = dir_ / (std::string("out_") + choice + ".txt");
    const std::string text(100000, choice[0]);
    shudder::io::write_text_file_atomically(out.string(), text);
    EXPECT_EQ(read(out), text) << "SHUDDER_FSYNC=" << choice;
    EXPECT_EQ(std::distance(fs::directory_iterator(dir_), fs::directory_iterator{}),
              choice[0] == '0' ? 1 : 2);  // the outputs only, no .tmp.* left
  }
}

TEST_F(OutputFsync, AnotherValueIsBadInputAndLeavesNoFile) {
  ::setenv("SHUDDER_FSYNC", "yes", 1);
  const fs::path out = dir_ / "out.txt";
  EXPECT_THAT(
      [&] { shudder::io::write_text_file_atomically(out.string(), "x"); },
      ::testing::ThrowsMessage<InputError>(
          AllOf(HasSubstr("environment: key 'SHUDDER_FSYNC': 'yes' is not 0 or 1"), HasSubstr("0 or unset does not"))));
  EXPECT_TRUE(fs::is_empty(dir_));  // neither the output nor its temporary
}

}  // namespace
