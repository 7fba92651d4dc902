#pragma once
// Distributed sweeps: `mpirun -np N shudder sweep SCENARIO --set ... -o OUT.h5 --mpi`.
// Rank 0 does everything the threaded sweep does (validates every case, lists the unfinished
// ones from OUT.h5.parts/ so a rerun resumes, assembles OUT.h5) and is the only process that
// writes: it hands case indices out one at a time to whichever rank asks next (dynamic, since
// cases differ in cost), runs cases itself on a second thread, and stores the part file every
// other rank sends back. A worker rank runs its case into a node-local temporary part
// (run_case, the threaded sweep's own code), sends the file's bytes and deletes it, so only the
// inputs need to be readable on every node. Each rank runs one case at a time (one rank per core).
#include <cstddef>
#include <functional>
#include <string>
#include <vector>

namespace shudder::app::mpi {

/// `shudder` itself is built without MPI, so that the commands that do not use it (every one but
/// `sweep --mpi`) do not load libmpi and its five companions at start-up (≈ 0.5 ms of every
/// process; docs/performance.md); the same program linked with MPI is `shudder-mpi`, installed
/// beside it. In `shudder`, this replaces the process (execv: same process id, environment and
/// arguments, so mpirun's and srun's rank setup carries over) with `shudder-mpi` from the
/// directory of the running executable, when that file exists. In `shudder-mpi` it does nothing.
/// If it returns, Session() refuses --mpi as an input error.
void relaunch_with_mpi(char** argv);

/// MPI for the life of one `sweep --mpi` (MPI_Init_thread .. MPI_Finalize). Rank 0 (the
/// coordinator) stops, on destruction, every worker it has not stopped yet, so that an input
/// error on rank 0 ends the whole job instead of leaving workers waiting.
/// Throws io::InputError (key --mpi) in a program built without MPI.
class Session {
 public:
  Session();
  ~Session();
  Session(const Session&) = delete;
  Session& operator=(const Session&) = delete;
  bool coordinator() const { return rank_ == 0; }
  int ranks() const { return ranks_; }

 private:
  friend struct Dispatcher;
  int rank_ = 0;
  int ranks_ = 1;
  std::vector<bool> stopped_;  // coordinator: workers already told to stop
};

/// Runs one case: the scenario text into the part file at the path (the threaded sweep's
/// run_case). What it throws stops the sweep (a part that cannot be written, memory).
using CaseRunner = std::function<void(const std::string& text, const std::string& part_path)>;

/// Worker ranks: runs the cases rank 0 hands out until told to stop.
void serve_cases(Session& session, const CaseRunner& run);

/// What escaped run for some case (as the threaded sweep reports it).
struct CasesOutcome {
  std::string first_error;                  // "case K: what"; empty if none
  bool out_of_memory = false;               // some case ran out of memory
  std::vector<std::size_t> cases_per_rank;  // how many cases each rank ran (the hand-out's balance)
};

/// Rank 0: runs the cases `todo` (indices into texts/part_paths) on every rank; on_progress
/// (may be empty) is called on the calling thread with the number finished, about every 200 ms.
CasesOutcome run_cases(Session& session, const std::vector<std::size_t>& todo, const std::vector<std::string>& texts,
                       const std::vector<std::string>& part_paths, const CaseRunner& run,
                       const std::function<void(std::size_t)>& on_progress);

}  // namespace shudder::app::mpi
