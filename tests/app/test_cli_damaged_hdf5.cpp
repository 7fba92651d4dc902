// A damaged HDF5 measured run that crashes Debian's libhdf5 (docs/fuzzing.md) ends `shudder
// characterise` and `shudder diagnose` with exit 2 and one line naming the file, not with a
// segmentation fault (io/isolated_read.hpp). The damage is the fuzz campaign's, reduced by delta
// debugging to one byte and rebuilt here from a run our writer makes: a variable-length string
// attribute of /measurement stores (length, global-heap collection address, object index); the
// index's third byte set to 25 (index + 25·2^16, far past the collection's objects) makes
// libhdf5 1.10.8 read outside the heap collection when the attribute is read (SIGSEGV here).
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <iterator>
#include <string>
#include <vector>

#include "io/measured_run.hpp"
#include "tests/support/cli.hpp"

namespace {

using shudder::io::MeasuredRun;
using shudder::test::run_cli;
using shudder::test::scratch_dir;

std::vector<char> read_bytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// Writes a valid run, then breaks the object index of the last variable-length string that
// refers to the file's global heap collection. Returns false if the file has no such reference.
bool write_damaged_run(const std::string& path) {
  MeasuredRun run;
  run.metadata = {
      {"format", "shudder-measurement/1"}, {"rig", "lsctr"}, {"fluid", "lsc-fluid-c"}, {"oil_flow_ml_min", "200"}};
  for (const char* name : {"time_s", "speed_rpm", "normal_force_N", "torque_Nm", "temp_C"})
    run.columns.push_back({name, shudder::io::measured_run_units(name), {}});
  for (int k = 0; k < 21; ++k) {
    const double row[] = {0.01 * k, 30.0, 15000.0, 60.0 + 0.1 * k, 90.0};
    for (std::size_t c = 0; c < 5; ++c) run.columns[c].values.push_back(row[c]);
  }
  shudder::io::write_measured_run_hdf5(path, run);
  (void)shudder::io::read_measured_run_hdf5(path);  // valid before the damage
  std::vector<char> bytes = read_bytes(path);
  const std::string signature = "GCOL";
  const auto gcol = std::search(bytes.begin(), bytes.end(), signature.begin(), signature.end());
  if (gcol == bytes.end()) return false;
  const std::uint64_t address = static_cast<std::uint64_t>(gcol - bytes.begin());  // little endian below
  char pattern[8];
  std::memcpy(pattern, &address, sizeof pattern);
  std::size_t last = std::string::npos;
  for (std::size_t p = 0; p + 12 <= bytes.size(); ++p) {
    std::uint32_t index = 0;
    std::memcpy(&index, bytes.data() + p + 8, sizeof index);
    if (std::memcmp(bytes.data() + p, pattern, sizeof pattern) == 0 && index > 0 && index < 1000) last = p;
  }
  if (last == std::string::npos) return false;
  bytes[last + 10] = 25;
  std::ofstream(path, std::ios::binary | std::ios::trunc)
      .write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  return true;
}

TEST(CliDamagedHdf5, ALibraryCrashOnADamagedRunIsOneLineAndExitTwo) {
  const auto dir = scratch_dir("damaged_hdf5");
  ASSERT_TRUE(write_damaged_run((dir / "bad.h5").string())) << "no heap reference to damage";
  shudder::test::write_file(dir / "model.toml", shudder::test::shipped_scenario_text("rig_case2_15kN_378Hz.toml"));
  for (const std::string& args : {std::string("characterise bad.h5 -o f.toml --nu40-cSt 35 --nu100-cSt 6.7"),
                                  std::string("diagnose model.toml bad.h5")}) {
    const auto r = run_cli(args, dir);
    // Whatever libhdf5 does with the file (crash here, a clean error in a fixed release), the
    // user gets exit 2 and one line naming the file.
    shudder::test::expect_rejected(r, {"shudder: error: bad.h5: "});
    std::cout << args.substr(0, args.find(' ')) << ": " << r.err;
  }
  std::filesystem::remove_all(dir);
}

}  // namespace
