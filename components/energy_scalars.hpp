#pragma once
// The runs' energy scalars, defined once.
//
// Heat account of the clutch (all sliding interfaces, n_if times one interface's account):
//   heat_generated_J       friction heat generated
//   heat_stored_in_discs_J change of the heat stored in the discs since the start
//   heat_to_sump_J         heat carried to the sump oil
//   heat_to_rig_J          heat conducted into the rig's parts
//   energy_balance_relative_error  |generated − stored − to sump − to rig| / generated (0 if
//                          nothing was generated), from clutch::ThermalModel::energy_imbalance_J.
//
// Mechanical energy account of a torsional run (dynamics::EnergyAccount): the relative error
// |imbalance| / scale, where the scale is chosen per model (MechanicalEnergyScale).

#include <vector>

#include "clutch/wet_clutch.hpp"
#include "dynamics/recording.hpp"
#include "dynamics/simulation.hpp"

namespace shudder::components {

/// The five heat-account scalars above, in that order.
std::vector<dynamics::Scalar> heat_account_scalars(const clutch::WetClutch& clutch, const clutch::ThermalState& state);

/// What the mechanical imbalance is measured against.
enum class MechanicalEnergyScale {
  // |source work| (0 → the error is 0): the rig, whose motor does all the work there is.
  kSourceWork,
  // The largest energy in play: max(|source work|, initial kinetic + elastic, friction heat +
  // damper losses): a coasting car (no engine work) is judged against the kinetic energy it
  // started with or the energy its tyres and coupling took. The driveline.
  kLargestEnergyInPlay,
};

double mechanical_energy_relative_error(const dynamics::EnergyAccount& energy, MechanicalEnergyScale scale);

}  // namespace shudder::components
