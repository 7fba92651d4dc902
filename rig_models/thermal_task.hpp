#pragma once
// The clutch's thermal update off the fixed step (real-time mode, docs/realtime.md).
//
// clutch::ThermalModel::step (backward Euler, sparse LU, re-factorised when the oil flow
// changes) costs tens of microseconds and allocates, more than a 0.1 ms real-time step may
// spend. A worker thread therefore advances the thermal model over one slow step with the heat
// per ring the fast side accumulated, and freezes the friction at the new ring temperatures,
// while the fast side carries on with the previous result. Handover happens at fixed step
// counts: the job posted at the end of slow window j is collected at the end of window j + 1
// and used during window j + 2. The results are therefore deterministic (independent of thread
// timing) at the price of one slow step of extra lag on the held ring temperatures (10 ms at the
// default thermal step, against disc time constants of seconds; the accuracy tests bound it).
//
// The fast side's calls (post, collect) make no system call and take no lock when the worker
// keeps up, which in a paced loop it always does: post() copies the window into buffers sized at
// construction and raises an atomic flag; collect() finds the result's flag raised and swaps the
// latched buffers. No heap allocation either. The worker does not need to be woken for a job: it
// polls the flag every `poll_interval_s` (a quarter of the thermal step in the real-time mode,
// so a job starts at most 2.5 ms after it was posted and finishes long before the 10 ms window
// ends). Waking it from post() would cost the stepping thread a futex system call per window —
// measured 4 µs median, 12 µs worst per handover step at SCHED_FIFO on this VM, the costliest
// kind of step (docs/performance.md). Only when collect() finds the job unfinished (steps run
// back to back, faster than real time: `shudder run --fixed-step`, tests) does it lock, wake the
// worker and wait, and the next post() then wakes the worker at once (as before, a futex call
// that costs nothing that matters off a real-time loop); the result is the same either way, so
// the run stays deterministic.

#include <Eigen/Dense>
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <exception>
#include <mutex>
#include <thread>

#include "clutch/wet_clutch.hpp"

namespace shudder::rig_models {

/// What the fast side reads from one thermal update (latched until the next collect()).
struct ThermalOutputs {
  double time_s = 0.0;            // time of the thermal state these come from
  Eigen::VectorXd ring_temp_C;    // (n_r) interface temperature per ring
  clutch::FrozenFriction frozen;  // friction frozen at ring_temp_C and frozen.load_N
  double thermocouple_C = 0.0;    // separator thermocouple (after its lag, if on)
  double ir_C = 0.0;              // pyrometer spot on the interface
  double sump_C = 0.0;
  double rig_C = 0.0;
  double interface_mean_C = 0.0;  // area-weighted
  double interface_max_C = 0.0;
  double field_max_C = 0.0;
};

class ThermalTask {
 public:
  /// Starts the worker with the clutch's initial thermal state; `force_N` is the clamp force
  /// the first frozen friction is built at; the worker looks for a posted job every
  /// `poll_interval_s` (> 0). `clutch` must outlive the task.
  ThermalTask(const clutch::WetClutch& clutch, double force_N, double poll_interval_s);
  ~ThermalTask();
  ThermalTask(const ThermalTask&) = delete;
  ThermalTask& operator=(const ThermalTask&) = delete;

  /// Hands the worker one slow step ending at `t_end_s`: the heat per ring of one interface
  /// over it (J), its length, the mean slip (sets the oil flow) and the clamp force to freeze
  /// the friction at. The previous job must have been collected.
  void post(const Eigen::VectorXd& ring_heat_J, double dt_s, double t_end_s, double mean_slip_rad_s, double force_N);
  /// Waits for the posted job and makes its result the latched one. Rethrows the worker's
  /// exception (a failed thermal solve) on the caller's thread.
  void collect();
  bool busy() const { return posted_; }
  /// How many collect()/reset() calls found the job unfinished and had to wake the worker and
  /// wait (the slow path, with system calls); in a paced real-time loop this stays 0.
  long waited_collects() const { return waited_; }
  const ThermalOutputs& latest() const { return latched_; }
  /// The thermal state after the last collected job (for the run's energy account); read it
  /// only while no job is out (!busy()).
  const clutch::ThermalState& state() const { return state_; }
  /// Waits for any job, drops it and restarts from the clutch's initial state.
  void reset(double force_N);

 private:
  void work();
  void run_job();
  // Waits until the worker has finished the posted job (the slow path of collect()).
  void wait_for_job();
  void fill(ThermalOutputs& out, double force_N) const;

  const clutch::WetClutch& clutch_;
  clutch::ThermalState state_;
  clutch::ThermalWorkspace workspace_;
  ThermalOutputs latched_, result_;
  // The job (written by the fast side while the worker is idle).
  Eigen::VectorXd heat_W_;
  double dt_s_ = 0.0, t_end_s_ = 0.0, slip_rad_s_ = 0.0, force_N_ = 0.0;
  bool posted_ = false;  // fast side's view: a job is out
  long waited_ = 0;
  bool wake_on_post_ = false;  // the last wait for a job was not free: wake the worker on post()

  // Handover flags: pending_ raised by post() (release) and lowered by the worker when it takes
  // the job; done_ raised by the worker when the result (or error_) is written (release) and
  // lowered by collect(). The job buffers belong to the fast side while !pending_ && !busy
  // worker, the result buffers to the worker between taking a job and raising done_.
  std::atomic<bool> pending_{false}, done_{false};
  std::chrono::nanoseconds poll_;
  std::mutex mutex_;  // guards urgent_, stop_ and the slow-path waits
  std::condition_variable cv_;
  bool urgent_ = false, stop_ = false;
  std::exception_ptr error_;
  std::thread worker_;
};

}  // namespace shudder::rig_models
