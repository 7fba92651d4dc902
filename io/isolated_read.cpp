#include "io/isolated_read.hpp"

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstring>
#include <filesystem>
#include <stdexcept>

#include "io/input_error.hpp"

namespace shudder::io {

namespace {

// The child's answer: one status byte, then (ok) the run, or (error) the message.
enum class Status : char { kOk = 'R', kInputError = 'I', kOtherError = 'E' };

void put_size(std::string& out, std::uint64_t n) { out.append(reinterpret_cast<const char*>(&n), sizeof n); }
void put_text(std::string& out, const std::string& s) {
  put_size(out, s.size());
  out += s;
}

std::string encode(const MeasuredRun& run) {
  std::string out(1, static_cast<char>(Status::kOk));
  put_size(out, run.metadata.size());
  for (const auto& [key, value] : run.metadata) {
    put_text(out, key);
    put_text(out, value);
  }
  put_size(out, run.columns.size());
  for (const auto& c : run.columns) {
    put_text(out, c.name);
    put_text(out, c.units);
    put_size(out, c.values.size());
    out.append(reinterpret_cast<const char*>(c.values.data()), c.values.size() * sizeof(double));
  }
  return out;
}

class Decoder {
 public:
  explicit Decoder(const std::string& bytes) : bytes_(bytes) {}
  std::uint64_t size() {
    std::uint64_t n = 0;
    take(&n, sizeof n);
    return n;
  }
  std::string text() {
    const std::uint64_t n = size();
    need(n);
    std::string s = bytes_.substr(at_, n);
    at_ += n;
    return s;
  }
  std::vector<double> doubles() {
    const std::uint64_t n = size();
    if (n > (bytes_.size() - at_) / sizeof(double)) throw std::length_error("truncated");
    std::vector<double> v(n);
    take(v.data(), n * sizeof(double));
    return v;
  }
  bool done() const { return at_ == bytes_.size(); }

 private:
  void need(std::uint64_t n) const {
    if (n > bytes_.size() - at_) throw std::length_error("truncated");
  }
  void take(void* dst, std::size_t n) {
    need(n);
    std::memcpy(dst, bytes_.data() + at_, n);
    at_ += n;
  }
  const std::string& bytes_;
  std::size_t at_ = 1;  // after the status byte
};

MeasuredRun decode(const std::string& path, const std::string& bytes) {
  Decoder d(bytes);
  MeasuredRun run;
  run.path = path;
  const std::uint64_t n_meta = d.size();
  for (std::uint64_t i = 0; i < n_meta; ++i) {
    std::string key = d.text();
    run.metadata.emplace_back(std::move(key), d.text());
  }
  const std::uint64_t n_columns = d.size();
  for (std::uint64_t i = 0; i < n_columns; ++i) {
    dynamics::Signal s;
    s.name = d.text();
    s.units = d.text();
    s.values = d.doubles();
    run.columns.push_back(std::move(s));
  }
  if (!d.done()) throw std::length_error("trailing bytes");
  return run;
}

void write_all(int fd, const std::string& bytes) {
  std::size_t at = 0;
  while (at < bytes.size()) {
    const ssize_t n = ::write(fd, bytes.data() + at, bytes.size() - at);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return;  // the parent gave up (time limit): nothing to tell it
    at += static_cast<std::size_t>(n);
  }
}

#if defined(__SANITIZE_ADDRESS__)
constexpr bool kSanitized = true;
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
constexpr bool kSanitized = true;
#else
constexpr bool kSanitized = false;
#endif
#else
constexpr bool kSanitized = false;
#endif

[[noreturn]] void child(int fd, const std::function<MeasuredRun()>& read) {
  // The C library's own last words on a corrupted heap ("free(): invalid size") would make the
  // error two lines; the parent says what happened. A sanitized build keeps them: its reports
  // are what that build is for.
  if (!kSanitized) {
    const int null_fd = ::open("/dev/null", O_WRONLY | O_CLOEXEC);
    if (null_fd >= 0) ::dup2(null_fd, STDERR_FILENO);
  }
  std::string answer;
  try {
    answer = encode(read());
  } catch (const InputError& e) {
    answer = std::string(1, static_cast<char>(Status::kInputError)) + e.what();
  } catch (const std::exception& e) {
    answer = std::string(1, static_cast<char>(Status::kOtherError)) + e.what();
  } catch (...) {
    answer = std::string(1, static_cast<char>(Status::kOtherError)) + "unknown exception";
  }
  write_all(fd, answer);
  ::close(fd);
  ::_exit(0);  // no atexit handlers, no stdio flush: the parent owns those
}

std::string signal_name(int sig) {
  const char* d = ::strsignal(sig);
  return "signal " + std::to_string(sig) + (d ? std::string(", ") + d : std::string());
}

int wait_for(pid_t pid) {
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  return status;
}

constexpr const char* kWhatToDo =
    "the file is damaged (libhdf5 cannot decode it, docs/fuzzing.md); write the run again, or "
    "give it as CSV";

}  // namespace

double isolated_read_time_limit_s(std::uintmax_t file_bytes) { return 30.0 + static_cast<double>(file_bytes) / 10e6; }

MeasuredRun read_measured_run_hdf5_isolated(const std::string& path) {
  std::error_code ec;
  const auto bytes = std::filesystem::file_size(path, ec);
  return detail::run_isolated(path, isolated_read_time_limit_s(ec ? 0 : bytes),
                              [&] { return read_measured_run_hdf5(path); });
}

namespace detail {

MeasuredRun run_isolated(const std::string& path, double time_limit_s, const std::function<MeasuredRun()>& read) {
  int fds[2];
  if (::pipe2(fds, O_CLOEXEC) != 0)
    throw std::runtime_error("cannot create a pipe to read " + path + ": " + std::strerror(errno));
  const pid_t pid = ::fork();
  if (pid < 0) {
    const int err = errno;
    ::close(fds[0]);
    ::close(fds[1]);
    throw std::runtime_error("cannot start a process to read " + path + ": " + std::strerror(err));
  }
  if (pid == 0) {
    ::close(fds[0]);
    child(fds[1], read);
  }
  ::close(fds[1]);

  using clock = std::chrono::steady_clock;
  const auto deadline =
      clock::now() + std::chrono::duration_cast<clock::duration>(std::chrono::duration<double>(time_limit_s));
  std::string answer;
  char buffer[1 << 16];
  bool timed_out = false;
  for (;;) {
    const auto left_ms = std::chrono::duration_cast<std::chrono::milliseconds>(deadline - clock::now()).count();
    if (left_ms <= 0) {
      timed_out = true;
      break;
    }
    pollfd p{fds[0], POLLIN, 0};
    const int ready = ::poll(&p, 1, static_cast<int>(std::min<long long>(left_ms, 1000)));
    if (ready < 0 && errno == EINTR) continue;
    if (ready < 0) {
      const int err = errno;
      ::kill(pid, SIGKILL);
      wait_for(pid);
      ::close(fds[0]);
      throw std::runtime_error("cannot wait for the process reading " + path + ": " + std::strerror(err));
    }
    if (ready == 0) continue;
    const ssize_t n = ::read(fds[0], buffer, sizeof buffer);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) break;  // end of file: the child is done
    answer.append(buffer, static_cast<std::size_t>(n));
  }
  ::close(fds[0]);
  if (timed_out) {
    ::kill(pid, SIGKILL);
    wait_for(pid);
    char limit[32];
    std::snprintf(limit, sizeof limit, "%.3g", time_limit_s);
    throw InputError(path, 0, "",
                     std::string("reading this HDF5 file did not finish within ") + limit +
                         " s (libhdf5 hangs on it; the reader was stopped): " + kWhatToDo);
  }
  const int status = wait_for(pid);
  if (WIFSIGNALED(status))
    throw InputError(path, 0, "",
                     "libhdf5 crashed reading this HDF5 file (" + signal_name(WTERMSIG(status)) + "): " + kWhatToDo);
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0 || answer.empty())
    throw std::runtime_error("the process reading " + path + " ended without an answer (exit status " +
                             std::to_string(WIFEXITED(status) ? WEXITSTATUS(status) : -1) + ")");
  switch (static_cast<Status>(answer.front())) {
    case Status::kOk: try { return decode(path, answer);
      } catch (const std::exception& e) {
        throw std::runtime_error("the process reading " + path + " sent a damaged answer (" + e.what() + ")");
      }
    case Status::kInputError: throw InputError(InputError::Verbatim{}, answer.substr(1));
    case Status::kOtherError: throw std::runtime_error(answer.substr(1));
  }
  throw std::runtime_error("the process reading " + path + " sent an answer of unknown kind");
}

}  // namespace detail

}  // namespace shudder::io
