#pragma once
// Checks made before a command writes anything:
//   * no output may be one of the command's inputs, nor another of its outputs (a run with
//     `-o X.toml` used to replace its own scenario; `--measurement same.h5 -o same.h5` left
//     only /measurement). Paths are compared canonically (symlinks, `..`, relative spellings),
//     with std::filesystem::weakly_canonical for files that do not exist yet.
//   * an output's directory must exist: nothing creates parent directories silently.
//   * an output larger than a stated limit is refused before simulating unless forced.
// Every refusal is an io::InputError (exit 2) naming the paths or the figures.

#include <cstdint>
#include <string>
#include <vector>

namespace shudder::io {

/// A file a command reads or writes, with the role it plays in messages ("scenario",
/// "fluid file", "-o", "--measurement").
struct RolePath {
  std::string role;
  std::string path;
};

/// InputError naming both paths if an output equals an input or another output.
void require_distinct_paths(const std::vector<RolePath>& inputs, const std::vector<RolePath>& outputs);

/// InputError if the directory that would hold `path` does not exist or is not a directory.
void require_output_directory(const std::string& path);

/// Largest output written without --force: 2 GB (2e9 bytes). The README's sweep writes ~20 MB
/// and the longest shipped run ~5 MB, so only a mistaken rate or duration reaches it; a file
/// that size also takes memory of the same order while it is recorded.
constexpr std::uint64_t kMaxOutputBytesWithoutForce = 2'000'000'000ULL;

/// InputError naming the estimate, the limit and --force if `estimated_bytes` exceeds
/// kMaxOutputBytesWithoutForce and `force` is false. `what` says what was estimated.
void require_output_size(const std::string& path, std::uint64_t estimated_bytes, const std::string& what, bool force);

}  // namespace shudder::io
