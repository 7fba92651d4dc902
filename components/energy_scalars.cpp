#include "components/energy_scalars.hpp"

#include <algorithm>
#include <cmath>

namespace shudder::components {

std::vector<dynamics::Scalar> heat_account_scalars(const clutch::WetClutch& clutch, const clutch::ThermalState& state) {
  const auto& th = clutch.thermal();
  const double n_if = clutch.params().sliding_interfaces;
  const auto& e = state.energy;
  return {
      {"heat_generated_J", "J", n_if * e.generated_J},
      {"heat_stored_in_discs_J", "J", n_if * (th.stored_energy_J(state) - e.initial_stored_J)},
      {"heat_to_sump_J", "J", n_if * e.to_sump_J},
      {"heat_to_rig_J", "J", n_if * e.to_rig_J},
      {"energy_balance_relative_error", "1",
       e.generated_J > 0 ? std::abs(th.energy_imbalance_J(state)) / e.generated_J : 0.0},
  };
}

double mechanical_energy_relative_error(const dynamics::EnergyAccount& me, MechanicalEnergyScale scale) {
  switch (scale) {
    case MechanicalEnergyScale::kSourceWork:
      return me.source_work_J != 0 ? std::abs(me.imbalance_J()) / std::abs(me.source_work_J) : 0.0;
    case MechanicalEnergyScale::kLargestEnergyInPlay:
      return std::abs(me.imbalance_J()) /
             std::max({std::abs(me.source_work_J), me.initial_kinetic_J + me.initial_elastic_J,
                       me.friction_heat_J + me.damper_loss_J, 1e-300});
  }
  return 0.0;
}

}  // namespace shudder::components
