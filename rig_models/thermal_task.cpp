#include "rig_models/thermal_task.hpp"

#include <stdexcept>

namespace shudder::rig_models {

ThermalTask::ThermalTask(const clutch::WetClutch& clutch, double force_N)
    : clutch_(clutch),
      state_(clutch.initial_state()),
      workspace_(clutch.thermal()),
      heat_W_(Eigen::VectorXd::Zero(clutch.thermal().radial_cells())) {
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
  {
    std::lock_guard lock(mutex_);
    heat_W_ = ring_heat_J / dt_s;  // same size: no allocation
    dt_s_ = dt_s;
    t_end_s_ = t_end_s;
    slip_rad_s_ = mean_slip_rad_s;
    force_N_ = force_N;
    pending_ = true;
    done_ = false;
  }
  posted_ = true;
  cv_.notify_all();
}

void ThermalTask::collect() {
  if (!posted_) return;
  std::unique_lock lock(mutex_);
  cv_.wait(lock, [this] { return done_; });
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
    std::unique_lock lock(mutex_);
    cv_.wait(lock, [this] { return done_; });
    posted_ = false;
    error_ = nullptr;
  }
  // The workspace keeps its factorisation: it depends on the step and the oil flow only.
  state_ = clutch_.initial_state();
  fill(latched_, force_N);
}

void ThermalTask::work() {
  std::unique_lock lock(mutex_);
  for (;;) {
    cv_.wait(lock, [this] { return pending_ || stop_; });
    if (stop_) return;
    pending_ = false;
    try {
      clutch_.thermal().step(state_, workspace_, dt_s_, heat_W_, slip_rad_s_);
      state_.time_s = t_end_s_;  // exact window end, free of accumulated round-off
      fill(result_, force_N_);
    } catch (...) {
      error_ = std::current_exception();
    }
    done_ = true;
    cv_.notify_all();
  }
}

}  // namespace shudder::rig_models
