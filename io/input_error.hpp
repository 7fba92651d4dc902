#pragma once
// The one error type for bad user input (scenario, fluid, measurement files, CLI values).
// what() is a single line: "FILE:LINE: KEY: what was wrong; what is allowed". The CLI maps it
// to exit code 2. Model code throws std::invalid_argument; io/ catches and rethrows this with
// the file and key attached.

#include <sstream>
#include <stdexcept>
#include <string>

namespace shudder::io {

class InputError : public std::runtime_error {
 public:
  InputError(const std::string& file, long line, const std::string& key, const std::string& message)
      : std::runtime_error(compose(file, line, key, message)) {}
  /// An error composed elsewhere, passed on unchanged (io/isolated_read: from a child process).
  struct Verbatim {};
  InputError(Verbatim, const std::string& what) : std::runtime_error(what) {}

 private:
  static std::string compose(const std::string& file, long line, const std::string& key, const std::string& message) {
    // Built with an ostringstream: GCC 12 flags chained std::string `+` here with a
    // false-positive -Wrestrict at -O3.
    std::ostringstream os;
    os << file;
    if (line > 0) os << ':' << line;
    os << ": ";
    if (!key.empty()) os << "key '" << key << "': ";
    os << message;
    return os.str();
  }
};

}  // namespace shudder::io
