// Temp-file-then-rename; see atomic_file.hpp. POSIX (fsync, rename).
#include "io/atomic_file.hpp"

#include <dirent.h>
#include <fcntl.h>
#include <sys/stat.h>
#include <signal.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <charconv>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <string_view>

#include "io/input_error.hpp"

namespace shudder::io {

std::string temp_path_for(const std::string& path) {
  static std::atomic<unsigned long> writes{0};
  return path + ".tmp." + std::to_string(::getpid()) + "." + std::to_string(writes++);
}

namespace {

// True if `rest` is "<pid>.<n>" (digits only) and no process `pid` runs (kill(pid, 0) fails
// with ESRCH; EPERM means it runs under another user, so it is not ours to judge).
bool names_a_dead_writer(std::string_view rest) {
  const std::size_t dot = rest.find('.');
  if (dot == std::string_view::npos || dot == 0 || dot + 1 == rest.size()) return false;
  long pid = 0;
  const auto [end, err] = std::from_chars(rest.data(), rest.data() + dot, pid);
  if (err != std::errc() || end != rest.data() + dot || pid <= 0) return false;
  for (char c : rest.substr(dot + 1))
    if (c < '0' || c > '9') return false;
  return ::kill(static_cast<pid_t>(pid), 0) != 0 && errno == ESRCH;
}

}  // namespace

void remove_stale_temp_files(const std::string& path) noexcept {
  // A plain readdir with the prefix compared on d_name: the output directory may hold thousands
  // of other files (a shared /tmp: 5,000), and a std::filesystem iteration built a path (two
  // allocations and a parse) for every one of them, ≈ 1.3 ms CPU of a 12 ms run there
  // (docs/performance.md). Only the few names that match are stat()ed and removed.
  const std::size_t slash = path.rfind('/');
  const std::string dir = slash == std::string::npos ? "." : slash == 0 ? "/" : path.substr(0, slash);
  const std::string prefix = path.substr(slash == std::string::npos ? 0 : slash + 1) + ".tmp";
  if (prefix == ".tmp") return;
  DIR* d = ::opendir(dir.c_str());
  if (!d) return;
  const int dir_fd = ::dirfd(d);
  while (const dirent* e = ::readdir(d)) {
    if (std::strncmp(e->d_name, prefix.c_str(), prefix.size()) != 0) continue;
    const std::string_view rest = std::string_view(e->d_name).substr(prefix.size());
    if (!(rest.empty() || (rest.front() == '.' && names_a_dead_writer(rest.substr(1))))) continue;
    // Regular files only (following a symbolic link, as std::filesystem's is_regular_file did);
    // the link itself is what unlinkat removes.
    struct stat st {};
    if (::fstatat(dir_fd, e->d_name, &st, 0) == 0 && S_ISREG(st.st_mode)) ::unlinkat(dir_fd, e->d_name, 0);
  }
  ::closedir(d);
}

void discard_temp_file(const std::string& tmp) noexcept { std::remove(tmp.c_str()); }

bool output_fsync_requested() {
  const char* value = std::getenv("SHUDDER_FSYNC");
  const std::string v = value ? value : "";
  if (v.empty() || v == "0") return false;
  if (v == "1") return true;
  throw InputError(
      "environment", 0, "SHUDDER_FSYNC",
      "'" + v + "' is not 0 or 1; 1 flushes every output file to disk before its rename, " + "0 or unset does not");
}

void commit_temp_file(const std::string& tmp, const std::string& path) {
  bool flush = false;
  try {
    flush = output_fsync_requested();
  } catch (...) {
    discard_temp_file(tmp);
    throw;
  }
  const auto fail = [&](const char* step) {
    const int err = errno;
    discard_temp_file(tmp);
    throw InputError(path, 0, "",
                     std::string("cannot ") + step + " temporary file '" + tmp + "': " + std::strerror(err) +
                         "; check the directory is writable and " + "the target is not a directory");
  };
  if (flush) {
    // Data on disk before the rename, so an OS crash cannot leave a short file at `path`.
    const int fd = ::open(tmp.c_str(), O_RDONLY);
    if (fd < 0) fail("open");
    const int synced = ::fsync(fd);
    ::close(fd);
    if (synced != 0) fail("flush");
  }
  if (std::rename(tmp.c_str(), path.c_str()) != 0) fail("rename");
}

void write_text_file_atomically(const std::string& path, const std::string& text) {
  remove_stale_temp_files(path);
  const std::string tmp = temp_path_for(path);
  {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    if (!out) throw InputError(path, 0, "", "cannot create '" + tmp + "'; check the directory exists and is writable");
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
