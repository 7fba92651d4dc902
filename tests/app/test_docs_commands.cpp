// Every command the README and docs/ show in a ```sh block runs as written. The convention
// (docs/commands.md, "Commands in the docs"): a fenced block marked `sh` is run by this test; a
// `text` block or an indented one is shown, not run (output, placeholders such as RUN.csv, or a
// command too long for the tests, with the reason beside it). Each page's blocks run in order,
// each block as one `/bin/sh -e` script, from a scratch directory that holds `build` (the build
// tree under test), `scenarios`, `python` and `tools` (the sources), with `shudder` on PATH.
// docs/network_tutorial.md writes its own files first and has its own test
// (test_network_tutorial.cpp).
#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "tests/support/cli.hpp"

namespace shudder {
namespace {

namespace fs = std::filesystem;

struct ShBlock {
  int line = 0;  // of the opening fence
  std::string text;
};

// The fenced blocks marked `sh`; a fence may be indented (inside a list item), and that
// indentation is taken off its lines.
std::vector<ShBlock> sh_blocks(const std::string& page) {
  std::vector<ShBlock> out;
  std::istringstream in(page);
  std::string line, kind;
  std::size_t indent = 0;
  ShBlock block;
  for (int n = 1; std::getline(in, line); ++n) {
    const std::size_t first = std::min(line.find_first_not_of(' '), line.size());
    const bool fence = line.compare(first, 3, "```") == 0;
    if (kind.empty()) {
      if (fence) {
        kind = line.size() > first + 3 ? line.substr(first + 3) : "plain";
        indent = first;
        block = {n, ""};
      }
      continue;
    }
    if (fence) {
      if (kind == "sh") out.push_back(block);
      kind.clear();
      continue;
    }
    block.text += line.substr(std::min(indent, first)) + "\n";
  }
  return out;
}

// README.md and every page under docs/ (but the tutorial, tested on its own) that has an sh
// block, sorted.
std::vector<std::string> pages() {
  std::vector<std::string> out;
  for (const auto& e : fs::recursive_directory_iterator(test::source_path("docs")))
    if (e.path().extension() == ".md" && e.path().filename() != "network_tutorial.md")
      out.push_back(fs::relative(e.path(), test::source_path("")).string());
  std::sort(out.begin(), out.end());
  out.insert(out.begin(), "README.md");
  std::erase_if(out, [](const std::string& page) { return sh_blocks(test::slurp(test::source_path(page))).empty(); });
  return out;
}

class DocsCommands : public testing::TestWithParam<std::string> {};

TEST_P(DocsCommands, RunAsWritten) {
  const std::string page = GetParam();
  const auto blocks = sh_blocks(test::slurp(test::source_path(page)));
  std::string stem = page;
  for (char& c : stem)
    if (c == '/' || c == '.') c = '_';
  const auto dir = test::scratch_dir("docs_" + stem);
  const fs::path build = fs::path(SHUDDER_CLI).parent_path().parent_path();
  fs::create_directory_symlink(build, dir / "build");
  for (const char* src : {"scenarios", "python", "tools"})
    fs::create_directory_symlink(test::source_path(src), dir / src);
  const auto start = std::chrono::steady_clock::now();
  for (const auto& b : blocks) {
    const fs::path script = dir / ("block_" + std::to_string(b.line) + ".sh");
    std::ofstream(script) << "PATH=\"$PWD/build/app:$PATH\"\n" << b.text;
    const fs::path err = dir / "stderr.txt";
    const std::string cmd =
        "cd '" + dir.string() + "' && /bin/sh -e '" + script.string() + "' > stdout.txt 2> '" + err.string() + "'";
    const int status = std::system(cmd.c_str());
    EXPECT_EQ(status, 0) << page << ":" << b.line << ": the block\n" << b.text << "failed:\n" << test::slurp(err);
  }
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  RecordProperty("seconds", std::to_string(seconds));
  // All pages together take about 70 s on a loaded 2-core machine (docs/commands.md's ~40 s of
  // it); a page past 90 s means a command too long for the docs test: mark it `text` with the
  // reason beside it.
  EXPECT_LT(seconds, 90.0) << page << "'s commands took " << seconds << " s";
}

INSTANTIATE_TEST_SUITE_P(Pages, DocsCommands, testing::ValuesIn(pages()), [](const auto& info) {
  std::string name = info.param;
  for (char& c : name)
    if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
  return name;
});

// The pages a user starts from keep run blocks: converting a page's blocks to `text` wholesale
// would pass the test above silently.
TEST(DocsCommandsConvention, ReadmeAndCommandsPageRunTheirCommands) {
  for (const char* page : {"README.md", "docs/commands.md", "docs/formats/import_mapping.md"})
    EXPECT_FALSE(sh_blocks(test::slurp(test::source_path(page))).empty()) << page << " has no sh block";
}

// That every page a page or a message names exists is tests/app/test_docs_links.cpp.

}  // namespace
}  // namespace shudder
