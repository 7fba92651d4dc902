#include "fuzz/temp_input.hpp"

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <stdexcept>

namespace shudder::fuzz {

namespace {

// Where the inputs go: /dev/shm (tmpfs, memory only) where it exists, else $TMPDIR. A file on
// disk cost ~40 % of every execution in the kernel and most of its wall time: ext4 starts
// writing a truncated-and-rewritten file back when it is closed (perf on fuzz_fluid,
// docs/fuzzing.md). An anonymous memfd behind /proc/self/fd/N would leave nothing behind, but
// libhdf5 resolves that link to "/memfd:... (deleted)" and cannot open it.
std::filesystem::path input_directory() {
  std::error_code ec;
  if (std::filesystem::is_directory("/dev/shm", ec)) return "/dev/shm";
  return std::filesystem::temp_directory_path();
}

// Paths created so far (one per suffix), removed when the fuzzer exits normally.
struct TempFiles {
  std::map<std::string, std::string> by_suffix;
  ~TempFiles() {
    std::error_code ec;
    for (const auto& [suffix, path] : by_suffix) std::filesystem::remove(path, ec);
  }
};
TempFiles& temp_files() {
  static TempFiles files;
  return files;
}

}  // namespace

std::string write_temp_input(const std::uint8_t* data, std::size_t size, const std::string& suffix) {
  auto& files = temp_files().by_suffix;
  auto it = files.find(suffix);
  if (it == files.end()) {
    const std::string name = "shudder_fuzz_" + std::to_string(::getpid()) + suffix;
    it = files.emplace(suffix, (input_directory() / name).string()).first;
  }
  std::ofstream out(it->second, std::ios::binary | std::ios::trunc);
  out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  if (!out) throw std::runtime_error("fuzz: cannot write " + it->second);
  return it->second;
}

}  // namespace shudder::fuzz
