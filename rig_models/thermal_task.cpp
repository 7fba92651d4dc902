#include "rig_models/thermal_task.hpp"

#include <stdexcept>

#ifdef __linux__
#include <sys/prctl.h>
#endif

namespace shudder::rig_models {

ThermalTask::ThermalTask(const clutch::WetClutch& clutch, double force_N, double poll_interval_s)
    : clutch_(clutch),
      state_(clutch.initial_state()),
      workspace_(clutch.thermal()),
      heat_W_(Eigen::VectorXd::Zero(clutch.thermal().radial_cells())),
      poll_(std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::duration<double>(poll_interval_s))) {
  if (!(poll_interval_s > 0.0) || poll_.count() < 1)
    throw std::invalid_argument("thermal task: the poll interval must be > 0");
  fill(latched_, force_N);
  result_ = latched_;
  worker_ = std::thread([this] { work(); });
}

ThermalTask::~ThermalTask() {
  {
    std::lock_guard lock(mutex_);
    stop_ = true;
  }
  cv_.notify_all();
  worker_.join();
}

void ThermalTask::fill(ThermalOutputs& out, double force_N) const {
  const auto& th = clutch_.thermal();
  out.time_s = state_.time_s;
  out.ring_temp_C = th.interface_temps_C(state_);
  out.frozen = clutch_.freeze(out.ring_temp_C, force_N);
  out.thermocouple_C = state_.sensor_temp_C;
  out.ir_C = th.ir_C(state_);
  out.sump_C = state_.sump_temp_C;
  out.rig_C = state_.rig_temp_C;
  out.interface_mean_C = th.mean_interface_temp_C(state_);
  out.interface_max_C = out.ring_temp_C.maxCoeff();
  out.field_max_C = th.max_temp_C(state_);
}

void ThermalTask::post(const Eigen::VectorXd& ring_heat_J, double dt_s, double t_end_s, double mean_slip_rad_s,
                       double force_N) {
  if (posted_) throw std::logic_error("thermal task: the previous job was not collected");
  // The worker is idle (the previous job was collected): the job buffers are ours.
  heat_W_ = ring_heat_J / dt_s;  // same size: no allocation
  dt_s_ = dt_s;
  t_end_s_ = t_end_s;
  slip_rad_s_ = mean_slip_rad_s;
  force_N_ = force_N;
  posted_ = true;
  pending_.store(true, std::memory_order_release);  // no wake-up: the worker polls
  if (wake_on_post_) {
    // The last collect() had to wait: the steps run faster than real time, where a system call
    // costs nothing that matters and starting the job at once saves the next wait.
    std::lock_guard lock(mutex_);
    urgent_ = true;
    cv_.notify_all();
  }
}

void ThermalTask::wait_for_job() {
  wake_on_post_ = !done_.load(std::memory_order_acquire);
  if (!wake_on_post_) return;  // the worker kept up: no lock, no system call
  ++waited_;
  std::unique_lock lock(mutex_);
  urgent_ = true;
  cv_.notify_all();
  cv_.wait(lock, [this] { return done_.load(std::memory_order_acquire); });
  urgent_ = false;
}

void ThermalTask::collect() {
  if (!posted_) return;
  wait_for_job();
  done_.store(false, std::memory_order_relaxed);
  posted_ = false;
  if (error_) {
    std::exception_ptr e = error_;
    error_ = nullptr;
    std::rethrow_exception(e);
  }
  std::swap(latched_, result_);  // swaps buffers, no allocation
}

void ThermalTask::reset(double force_N) {
  if (posted_) {
    wait_for_job();
    done_.store(false, std::memory_order_relaxed);
    posted_ = false;
    error_ = nullptr;
  }
  // The workspace keeps its factorisation: it depends on the step and the oil flow only.
  state_ = clutch_.initial_state();
  fill(latched_, force_N);
}

void ThermalTask::run_job() {
  try {
    clutch_.thermal().step(state_, workspace_, dt_s_, heat_W_, slip_rad_s_);
    state_.time_s = t_end_s_;  // exact window end, free of accumulated round-off
    fill(result_, force_N_);
  } catch (...) {
    error_ = std::current_exception();
  }
}

void ThermalTask::work() {
#ifdef __linux__
  prctl(PR_SET_TIMERSLACK, 1UL);  // wake at the poll time itself, not up to 50 µs later
#endif
  using clock = std::chrono::steady_clock;
  std::unique_lock lock(mutex_);
  for (;;) {
    // Sleep until the next whole multiple of the poll interval on the monotonic clock (so the
    // polls keep a fixed phase that a real-time loop can release its steps away from:
    // docs/realtime.md), or less when collect() is waiting for a posted job.
    const auto now = clock::now().time_since_epoch();
    const clock::time_point next{(now / poll_ + 1) * poll_};
    cv_.wait_until(lock, next, [this] { return stop_ || (urgent_ && pending_.load(std::memory_order_acquire)); });
    if (stop_) return;
    if (!pending_.load(std::memory_order_acquire)) continue;
    pending_.store(false, std::memory_order_relaxed);
    lock.unlock();
    run_job();
    lock.lock();
    done_.store(true, std::memory_order_release);
    cv_.notify_all();  // a collect() on the slow path waits for this
  }
}

}  // namespace shudder::rig_models
