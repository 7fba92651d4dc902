#include "io/output_safety.hpp"

#include <cstdio>
#include <filesystem>
#include <system_error>

#include "io/input_error.hpp"

namespace shudder::io {

namespace fs = std::filesystem;

namespace {

// The path a file is or would be at: canonical where it exists, resolved as far as it does
// otherwise (weakly_canonical), so "out.h5", "./out.h5" and "dir/../out.h5" compare equal.
fs::path resolved(const std::string& path) {
  std::error_code ec;
  fs::path p = fs::weakly_canonical(fs::absolute(path, ec), ec);
  return ec ? fs::absolute(path).lexically_normal() : p;
}

}  // namespace

void require_distinct_paths(const std::vector<RolePath>& inputs, const std::vector<RolePath>& outputs) {
  for (std::size_t o = 0; o < outputs.size(); ++o) {
    const fs::path out = resolved(outputs[o].path);
    for (const auto& in : inputs)
      if (resolved(in.path) == out)
        throw InputError(outputs[o].path, 0, "",
                         "output " + outputs[o].role + " is the " + in.role + " '" + in.path +
                             "' this command reads; writing it would destroy the input: choose another output name");
    for (std::size_t k = 0; k < o; ++k)
      if (resolved(outputs[k].path) == out)
        throw InputError(outputs[o].path, 0, "",
                         "output " + outputs[o].role + " is also the output " + outputs[k].role + " '" +
                             outputs[k].path + "'; one would overwrite the other: give them different names");
  }
}

void require_output_directory(const std::string& path) {
  // "report/" names the directory report: drop the empty last element before going up.
  fs::path target = fs::absolute(path);
  if (!target.has_filename()) target = target.parent_path();
  const fs::path parent = target.parent_path();
  std::error_code ec;
  if (!fs::is_directory(parent, ec))
    throw InputError(path, 0, "",
                     "directory '" + parent.string() +
                         "' does not exist; create it first (shudder "
                         "does not create directories for its outputs)");
}

void require_output_size(const std::string& path, std::uint64_t estimated_bytes, const std::string& what, bool force) {
  if (force || estimated_bytes <= kMaxOutputBytesWithoutForce) return;
  char msg[512];
  std::snprintf(msg, sizeof msg,
                "estimated output size %.2f GB (%s) exceeds the limit of %.0f GB; lower the sample rate "
                "or the duration, or pass --force to write it anyway",
                static_cast<double>(estimated_bytes) / 1e9, what.c_str(),
                static_cast<double>(kMaxOutputBytesWithoutForce) / 1e9);
  throw InputError(path, 0, "", msg);
}

}  // namespace shudder::io
