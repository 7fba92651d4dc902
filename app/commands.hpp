#pragma once
// Subcommands of the `shudder` CLI. Each returns the process exit code:
// 0 success, 2 bad input (io::InputError), 1 numerical or internal failure.

#include <optional>
#include <string>

namespace shudder::app {

struct RunOptions {
  std::string scenario;
  std::string output;                  // HDF5 path; default "<scenario name>.h5"
  std::string measurement;             // measured-run CSV path; empty = none
  double measurement_rate_Hz = 0.0;    // 0 = the recording's rate
  bool noise = false;
  unsigned seed = 1;
  bool profile = false;
};
int run_command(const RunOptions& options);

struct ModesOptions {
  std::string scenario;
};
int modes_command(const ModesOptions& options);

struct ValidateOptions {
  std::string scenarios_dir = "scenarios";
  std::string docs_dir = "docs";
  bool plots = true;
};
int validate_command(const ValidateOptions& options);

}  // namespace shudder::app
