#pragma once
// Helpers for end-to-end tests that run the `shudder` executable: a scratch directory per test
// and a runner that captures exit code, stdout and stderr.
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <vector>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace shudder::test {

struct CliResult {
  int exit_code = -1;
  std::string out, err;
};

inline std::string slurp(const std::filesystem::path& p) {
  std::ifstream in(p);
  std::ostringstream os;
  os << in.rdbuf();
  return os.str();
}

/// A fresh, empty directory under the system temp dir, unique per name.
inline std::filesystem::path scratch_dir(const std::string& name) {
  // The process id keeps concurrent test runs (two checkouts, CI beside a developer) apart.
  const auto dir = std::filesystem::temp_directory_path() / ("shudder_test_" + name + "_" + std::to_string(::getpid()));
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

/// Runs `shudder ARGS` (ARGS already shell-quoted) from `cwd`.
/// The streams are captured in files of this call's own (process id and call count in the
/// name), never in `cwd`: tests run concurrently from the same directory (the source tree).
inline CliResult run_cli(const std::string& args, const std::filesystem::path& cwd) {
  static int calls = 0;
  const std::string tag = std::to_string(::getpid()) + "_" + std::to_string(++calls);
  const auto capture = std::filesystem::temp_directory_path();
  const auto out = capture / ("shudder_cli_" + tag + ".out"), err = capture / ("shudder_cli_" + tag + ".err");
  const std::string cmd = "cd '" + cwd.string() + "' && '" + std::string(SHUDDER_CLI) + "' " + args + " >'" +
                          out.string() + "' 2>'" + err.string() + "'";
  const int status = std::system(cmd.c_str());
  CliResult r;
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  r.out = slurp(out);
  r.err = slurp(err);
  std::filesystem::remove(out);
  std::filesystem::remove(err);
  return r;
}

inline void write_file(const std::filesystem::path& p, const std::string& text) { std::ofstream(p) << text; }

inline std::string source_path(const std::string& rel) { return std::string(SHUDDER_SOURCE_DIR) + "/" + rel; }

/// `s` with the first `from` replaced by `to`; a missing `from` is a test-setup failure.
inline std::string replace(std::string s, const std::string& from, const std::string& to) {
  const auto pos = s.find(from);
  EXPECT_NE(pos, std::string::npos) << "test setup: '" << from << "' not in the scenario";
  return pos == std::string::npos ? s : s.replace(pos, from.size(), to);
}

/// A shipped scenario's text (`rel` under scenarios/) with its fluid path made absolute, so a
/// copy runs from a scratch directory.
inline std::string shipped_scenario_text(const std::string& rel) {
  return replace(slurp(source_path("scenarios/" + rel)), "fluid = \"fluids/",
                 "fluid = \"" + source_path("scenarios/fluids/"));
}

struct Outcome {
  CliResult r;
  bool output_exists;  // out.h5 or its temporary exists after the run
};

/// Writes `scenario_text` to a fresh scratch dir `dir_name` and runs `shudder run s.toml -o out.h5`.
inline Outcome run_scenario_in(const std::string& dir_name, const std::string& scenario_text) {
  const auto dir = scratch_dir(dir_name);
  write_file(dir / "s.toml", scenario_text);
  Outcome o;
  o.r = run_cli("run s.toml -o out.h5", dir);
  o.output_exists = std::filesystem::exists(dir / "out.h5") || std::filesystem::exists(dir / "out.h5.tmp");
  return o;
}

/// Bad input: exit 2 and ONE stderr line containing every fragment.
inline void expect_rejected(const CliResult& r, const std::vector<std::string>& fragments) {
  EXPECT_EQ(r.exit_code, 2) << r.out << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  for (const auto& f : fragments) EXPECT_THAT(r.err, ::testing::HasSubstr(f));
}

/// Bad input to `shudder run`: as above, and no output file.
inline void expect_rejected(const Outcome& o, const std::vector<std::string>& fragments) {
  expect_rejected(o.r, fragments);
  EXPECT_FALSE(o.output_exists);
}

}  // namespace shudder::test
