// Distributed sweeps on MPI (mpi_sweep.hpp). Built with MPI when SHUDDER_HAS_MPI is defined
// (into `shudder-mpi`, with cmake -DSHUDDER_MPI=ON, the default); otherwise (`shudder`) `--mpi`
// hands the process over to `shudder-mpi` beside it, or is refused as an input error.
#include "app/mpi_sweep.hpp"

#include "io/input_error.hpp"

#ifdef SHUDDER_HAS_MPI

#include <mpi.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <climits>
#include <cstdint>
#include <exception>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <mutex>
#include <new>
#include <stdexcept>
#include <thread>

#include "io/atomic_file.hpp"

namespace shudder::app::mpi {

namespace {

namespace fs = std::filesystem;

// Message tags. Worker -> rank 0: kReady (first request), kResult {case, status} followed by
// kBytes (the part file, or the error message). Rank 0 -> worker: kTask {case} followed by
// kBytes (the case's scenario text), or kTask {-1}: stop. MPI keeps the order of messages
// between two ranks, so a kResult is always followed by its own kBytes.
constexpr int kReady = 1, kResult = 2, kBytes = 3, kTask = 4;
// A case's outcome as sent back.
enum Status : std::int64_t { kPartWritten = 0, kFailed = 1, kOutOfMemory = 2 };

void check(int rc, const char* call) {
  if (rc != MPI_SUCCESS) throw std::runtime_error(std::string("MPI: ") + call + " failed");
}

void send_bytes(const std::string& bytes, int to) {
  if (bytes.size() > static_cast<std::size_t>(INT_MAX)) throw std::runtime_error("MPI: message above 2 GB");
  check(MPI_Send(bytes.data(), static_cast<int>(bytes.size()), MPI_BYTE, to, kBytes, MPI_COMM_WORLD), "MPI_Send");
}

std::string receive_bytes(int from) {
  MPI_Status st;
  check(MPI_Probe(from, kBytes, MPI_COMM_WORLD, &st), "MPI_Probe");
  int n = 0;
  MPI_Get_count(&st, MPI_BYTE, &n);
  std::string bytes(static_cast<std::size_t>(n), '\0');
  check(MPI_Recv(bytes.data(), n, MPI_BYTE, from, kBytes, MPI_COMM_WORLD, MPI_STATUS_IGNORE), "MPI_Recv");
  return bytes;
}

std::string read_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error("cannot read the part " + path);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// Runs case k as the threaded sweep does: what escapes `run` is the case's status and message.
Status run_guarded(const CaseRunner& run, std::size_t k, const std::string& text, const std::string& part,
                   std::string& message) {
  try {
    run(text, part);
    return kPartWritten;
  } catch (const std::bad_alloc&) {
    return kOutOfMemory;
  } catch (const std::exception& e) {
    message = "case " + std::to_string(k) + ": " + e.what();
    return kFailed;
  }
}

}  // namespace

// Rank 0's side of the protocol: answers requests, stores returned parts.
struct Dispatcher {
  Session& s;
  void stop(int worker) {
    const std::int64_t none = -1;
    check(MPI_Send(&none, 1, MPI_INT64_T, worker, kTask, MPI_COMM_WORLD), "MPI_Send");
    s.stopped_[static_cast<std::size_t>(worker)] = true;
  }
  int workers_running() const {
    int n = 0;
    for (std::size_t r = 1; r < s.stopped_.size(); ++r) n += s.stopped_[r] ? 0 : 1;
    return n;
  }
};

void relaunch_with_mpi(char**) {}

Session::Session() {
  int provided = 0;
  // Only the main thread calls MPI (rank 0 runs its own cases on a second thread).
  check(MPI_Init_thread(nullptr, nullptr, MPI_THREAD_FUNNELED, &provided), "MPI_Init_thread");
  MPI_Comm_rank(MPI_COMM_WORLD, &rank_);
  MPI_Comm_size(MPI_COMM_WORLD, &ranks_);
  stopped_.assign(static_cast<std::size_t>(ranks_), false);
}

Session::~Session() {
  // Rank 0 leaving early (an input error, a failed write): every worker still waiting for a
  // task, or sending a result nobody will store, is told to stop.
  if (coordinator()) {
    Dispatcher d{*this};
    while (d.workers_running() > 0) {
      MPI_Status st;
      if (MPI_Probe(MPI_ANY_SOURCE, MPI_ANY_TAG, MPI_COMM_WORLD, &st) != MPI_SUCCESS) break;
      if (st.MPI_TAG == kResult) {
        std::int64_t head[2];
        MPI_Recv(head, 2, MPI_INT64_T, st.MPI_SOURCE, kResult, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
        try {
          receive_bytes(st.MPI_SOURCE);
        } catch (const std::exception&) {
        }
      } else {
        MPI_Recv(nullptr, 0, MPI_BYTE, st.MPI_SOURCE, st.MPI_TAG, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
      }
      try {
        d.stop(st.MPI_SOURCE);
      } catch (const std::exception&) {
        break;
      }
    }
  }
  MPI_Finalize();
}

void serve_cases(Session& session, const CaseRunner& run) {
  (void)session;
  check(MPI_Send(nullptr, 0, MPI_BYTE, 0, kReady, MPI_COMM_WORLD), "MPI_Send");
  for (;;) {
    std::int64_t k = -1;
    check(MPI_Recv(&k, 1, MPI_INT64_T, 0, kTask, MPI_COMM_WORLD, MPI_STATUS_IGNORE), "MPI_Recv");
    if (k < 0) return;
    const std::string text = receive_bytes(0);
    // A node-local scratch part: only rank 0 writes into the output's directory.
    const fs::path part =
        fs::temp_directory_path() / ("shudder_mpi_" + std::to_string(getpid()) + "_" + std::to_string(k) + ".h5");
    std::string payload;
    Status status = run_guarded(run, static_cast<std::size_t>(k), text, part.string(), payload);
    if (status == kPartWritten) {
      try {
        payload = read_file(part.string());
      } catch (const std::exception& e) {
        status = kFailed;
        payload = "case " + std::to_string(k) + ": " + e.what();
      }
    }
    std::error_code ignored;
    fs::remove(part, ignored);
    const std::int64_t head[2] = {k, status};
    check(MPI_Send(head, 2, MPI_INT64_T, 0, kResult, MPI_COMM_WORLD), "MPI_Send");
    send_bytes(payload, 0);
  }
}

CasesOutcome run_cases(Session& session, const std::vector<std::size_t>& todo, const std::vector<std::string>& texts,
                       const std::vector<std::string>& part_paths, const CaseRunner& run,
                       const std::function<void(std::size_t)>& on_progress) {
  Dispatcher d{session};
  std::atomic<std::size_t> next{0}, done{0};
  std::mutex outcome_mutex;
  CasesOutcome outcome;
  outcome.cases_per_rank.assign(static_cast<std::size_t>(session.ranks()), 0);
  const auto record = [&](Status status, std::string message) {
    const std::lock_guard lock(outcome_mutex);
    if (status == kOutOfMemory) outcome.out_of_memory = true;
    if (status == kFailed && outcome.first_error.empty()) outcome.first_error = std::move(message);
  };
  // Hands worker `w` the next case, or tells it to stop when none is left.
  const auto dispatch = [&](int w) {
    const std::size_t i = next++;
    if (i >= todo.size()) return d.stop(w);
    const auto k = static_cast<std::int64_t>(todo[i]);
    check(MPI_Send(&k, 1, MPI_INT64_T, w, kTask, MPI_COMM_WORLD), "MPI_Send");
    send_bytes(texts[todo[i]], w);
  };

  // Rank 0's own cases, from the same queue.
  std::thread local([&] {
    for (std::size_t i; (i = next++) < todo.size();) {
      std::string message;
      const std::size_t k = todo[i];
      const Status status = run_guarded(run, k, texts[k], part_paths[k], message);
      if (status != kPartWritten) record(status, std::move(message));
      {
        const std::lock_guard lock(outcome_mutex);
        ++outcome.cases_per_rank[0];
      }
      ++done;
    }
  });
  // The main thread polls rather than blocks: a blocking receive spins a core in OpenMPI, which
  // the local cases need. A result waits at most ~1 ms for its answer.
  auto last_progress = std::chrono::steady_clock::now();
  std::exception_ptr error;
  try {
    while (d.workers_running() > 0 || done < todo.size()) {
      int flag = 0;
      MPI_Status st;
      check(MPI_Iprobe(MPI_ANY_SOURCE, MPI_ANY_TAG, MPI_COMM_WORLD, &flag, &st), "MPI_Iprobe");
      if (flag && st.MPI_TAG == kReady) {
        check(MPI_Recv(nullptr, 0, MPI_BYTE, st.MPI_SOURCE, kReady, MPI_COMM_WORLD, MPI_STATUS_IGNORE), "MPI_Recv");
        dispatch(st.MPI_SOURCE);
      } else if (flag && st.MPI_TAG == kResult) {
        std::int64_t head[2];
        check(MPI_Recv(head, 2, MPI_INT64_T, st.MPI_SOURCE, kResult, MPI_COMM_WORLD, MPI_STATUS_IGNORE), "MPI_Recv");
        std::string payload = receive_bytes(st.MPI_SOURCE);
        const auto k = static_cast<std::size_t>(head[0]);
        const auto status = static_cast<Status>(head[1]);
        if (status == kPartWritten) {
          io::write_text_file_atomically(part_paths.at(k), payload);
        } else {
          record(status, std::move(payload));
        }
        {
          const std::lock_guard lock(outcome_mutex);
          ++outcome.cases_per_rank.at(static_cast<std::size_t>(st.MPI_SOURCE));
        }
        ++done;
        dispatch(st.MPI_SOURCE);
      } else if (flag) {
        throw std::runtime_error("MPI: unexpected message tag " + std::to_string(st.MPI_TAG));
      } else {
        std::this_thread::sleep_for(std::chrono::milliseconds(1));
      }
      const auto now = std::chrono::steady_clock::now();
      if (on_progress && now - last_progress > std::chrono::milliseconds(200)) {
        on_progress(done);
        last_progress = now;
      }
    }
  } catch (...) {
    error = std::current_exception();
    next = todo.size();  // the local thread takes no new case
  }
  local.join();
  if (error) std::rethrow_exception(error);
  if (on_progress) on_progress(done);
  return outcome;
}

}  // namespace shudder::app::mpi

#else  // built without MPI

#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <system_error>

namespace shudder::app::mpi {

namespace {
[[noreturn]] void no_mpi() {
  throw io::InputError("--mpi", 0, "",
                       "this shudder has no MPI and found no shudder-mpi beside it; build it with "
                       "cmake -DSHUDDER_MPI=ON (needs libopenmpi-dev; docs/mpi.md) or drop --mpi to "
                       "sweep on threads");
}
}  // namespace

void relaunch_with_mpi(char** argv) {
  // Once only: a `shudder-mpi` that is itself built without MPI (a copy of shudder) must refuse,
  // not hand over to itself forever.
  if (std::getenv("SHUDDER_MPI_HANDED_OVER") != nullptr) return;
  std::error_code ec;
  const std::filesystem::path self = std::filesystem::read_symlink("/proc/self/exe", ec);
  if (ec) return;
  const std::string mpi_build = (self.parent_path() / "shudder-mpi").string();
  if (::access(mpi_build.c_str(), X_OK) != 0) return;
  ::setenv("SHUDDER_MPI_HANDED_OVER", "1", 1);
  ::execv(mpi_build.c_str(), argv);  // returns only on failure: then refused as without MPI
  ::unsetenv("SHUDDER_MPI_HANDED_OVER");
}

// Session() refuses, so nothing below is ever reached in this build.
Session::Session() { no_mpi(); }
Session::~Session() = default;
void serve_cases(Session&, const CaseRunner&) { no_mpi(); }
CasesOutcome run_cases(Session&, const std::vector<std::size_t>&, const std::vector<std::string>&,
                       const std::vector<std::string>&, const CaseRunner&, const std::function<void(std::size_t)>&) {
  no_mpi();
}

}  // namespace shudder::app::mpi

#endif
