#include "components/haldex_coupling_law.hpp"

#include <cmath>
#include <stdexcept>
#include <utility>

namespace shudder::components {

HaldexCouplingLaw::HaldexCouplingLaw(ClutchContact pack, std::shared_ptr<ClutchContext> pack_context,
                                     HaldexHydraulics hydraulics, std::shared_ptr<HaldexCommand> command,
                                     double start_pressure_bar)
    : pack_(pack),
      context_(std::move(pack_context)),
      hydraulics_(std::move(hydraulics)),
      command_(std::move(command)),
      start_pressure_bar_(start_pressure_bar) {
  if (!context_ || !command_) throw std::invalid_argument("Haldex coupling: needs a pack context and a command");
  if (!(start_pressure_bar_ >= 0.0)) throw std::invalid_argument("Haldex coupling: start pressure must be >= 0 bar");
}

double HaldexCouplingLaw::kinetic_torque_Nm(double abs_slip, double t, const double* z) const {
  return pack_.kinetic_torque_at_force_Nm(*context_, abs_slip, t, clamp_force_N(z));
}

double HaldexCouplingLaw::static_capacity_Nm(double t, double stick_time, const double* z) const {
  return pack_.static_capacity_at_force_Nm(*context_, t, stick_time, clamp_force_N(z));
}

double HaldexCouplingLaw::kinetic_torque_slope_Nms(double abs_slip, double t, const double* z) const {
  return pack_.kinetic_torque_slope_at_force_Nms(*context_, abs_slip, t, clamp_force_N(z));
}

void HaldexCouplingLaw::channel_heat_W(double abs_slip, double t, const double* z, double* out) const {
  pack_.channel_heat_at_force_W(*context_, abs_slip, t, clamp_force_N(z), out);
}

void HaldexCouplingLaw::state_rates(double slip, double t, const double* z, double* dzdt) const {
  const HaldexCommand& cmd = *command_;
  dzdt[kPressure] =
      hydraulics_.pressure_rate_bar_s(z[kPressure], std::abs(slip), z[kOpening], cmd.setting_at_bar(t), cmd.leak_scale);
  dzdt[kOpening] = (cmd.opening - z[kOpening]) / (1e-3 * hydraulics_.params().valve_time_constant_ms);
}

void HaldexCouplingLaw::initial_states(double* z) const {
  z[kPressure] = start_pressure_bar_;
  z[kOpening] = command_->opening;
}

}  // namespace shudder::components
