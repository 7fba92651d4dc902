// Temp-file-then-rename; see atomic_file.hpp. POSIX (fsync, rename).
#include "io/atomic_file.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fstream>

#include "io/input_error.hpp"

namespace shudder::io {

std::string temp_path_for(const std::string& path) { return path + ".tmp"; }

void discard_temp_file(const std::string& tmp) noexcept { std::remove(tmp.c_str()); }

void commit_temp_file(const std::string& tmp, const std::string& path) {
  const auto fail = [&](const char* step) {
    const int err = errno;
    discard_temp_file(tmp);
    throw InputError(path, 0, "",
                     std::string("cannot ") + step + " temporary file '" + tmp +
                         "': " + std::strerror(err) + "; check the directory is writable and " +
                         "the target is not a directory");
  };
  // Data on disk before the rename, so a crash cannot leave a short file at `path`.
  const int fd = ::open(tmp.c_str(), O_RDONLY);
  if (fd < 0) fail("open");
  const int synced = ::fsync(fd);
  ::close(fd);
  if (synced != 0) fail("flush");
  if (std::rename(tmp.c_str(), path.c_str()) != 0) fail("rename");
}

void write_text_file_atomically(const std::string& path, const std::string& text) {
  const std::string tmp = temp_path_for(path);
  {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    if (!out)
      throw InputError(path, 0, "", "cannot create '" + tmp + "'; check the directory exists and is writable");
    out << text;
    out.close();
    if (out.fail()) {
      discard_temp_file(tmp);
      throw InputError(path, 0, "", "cannot write '" + tmp + "' (disk full?)");
    }
  }
  commit_temp_file(tmp, path);
}

}  // namespace shudder::io
