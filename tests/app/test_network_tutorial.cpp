// docs/network_tutorial.md as a test: every `toml` block is written to the file its first comment
// line names, every line of every `sh` block is run (with `shudder` the CLI under test) from a
// directory holding scenarios/fluids/, in the page's order. A command may fail only where the page
// says so (`|| echo`); the runs' outputs must exist.
#include <gtest/gtest.h>

#include <filesystem>
#include <regex>
#include <sstream>
#include <string>

#include "tests/support/cli.hpp"

namespace shudder {
namespace {

namespace fs = std::filesystem;

TEST(NetworkTutorial, EveryCommandRuns) {
  const std::string page = test::slurp(test::source_path("docs/network_tutorial.md"));
  const auto dir = test::scratch_dir("network_tutorial");
  fs::create_directories(dir / "scenarios");
  fs::copy(test::source_path("scenarios/fluids"), dir / "scenarios" / "fluids");
  std::istringstream in(page);
  std::string line, block_kind, block;
  int files = 0, commands = 0;
  while (std::getline(in, line)) {
    if (block_kind.empty()) {
      if (line.rfind("```", 0) == 0 && line.size() > 3) {
        block_kind = line.substr(3);
        block.clear();
      }
      continue;
    }
    if (line != "```") {
      block += line + "\n";
      continue;
    }
    if (block_kind == "toml") {
      const auto nl = block.find('\n');
      ASSERT_EQ(block.rfind("# ", 0), 0u) << "a toml block starts with '# FILE': " << block;
      const std::string name = block.substr(2, nl - 2);
      fs::create_directories((dir / name).parent_path());
      test::write_file(dir / name, block.substr(nl + 1));
      ++files;
    } else if (block_kind == "sh") {
      std::istringstream cmds(block);
      std::string cmd;
      while (std::getline(cmds, cmd)) {
        if (cmd.empty()) continue;
        const std::string shell =
            std::regex_replace(cmd, std::regex("(^|[|;&] *)shudder "), "$1'" + std::string(SHUDDER_CLI) + "' ");
        const int status = std::system(("cd '" + dir.string() + "' && " + shell + " > /dev/null 2>&1").c_str());
        EXPECT_EQ(status, 0) << cmd;
        ++commands;
      }
    }
    block_kind.clear();
  }
  EXPECT_GE(files, 2);
  EXPECT_GE(commands, 5);
  for (const char* out : {"my_drivetrain/step1.h5", "my_drivetrain/bench.h5", "my_drivetrain/bars.h5"})
    EXPECT_TRUE(fs::exists(dir / out)) << out;
  EXPECT_FALSE(fs::exists(dir / "my_drivetrain/typo.h5")) << "the misspelt node must stop the run";
}

}  // namespace
}  // namespace shudder
