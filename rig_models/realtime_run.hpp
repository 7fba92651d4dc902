#pragma once
// `shudder run X.toml --fixed-step H`: a scenario run through the real-time steppers
// (docs/realtime.md), recorded like the adaptive run so the same HDF5, summary and plots apply.
//
//   prescribed slip  rig_models::RealtimeCoupling, inputs Δω(t_k), F(t_k) held over each step
//                    (what an FMU master gives it: the FMU test compares against this)
//   rig, driveline   the adaptive run's own network, right-hand side and multi-rate thermal
//                    coupling in dynamics::Simulation's fixed-step mode (RK4 at H; stick and
//                    slip handled at the step ends)
//
// Samples are taken every round(1 / (rate · H)) steps, which must be a whole number; the
// duration (and for the network kinds the thermal step) must be a whole number of steps. The
// prescribed-slip element's thermal channels hold the latched thermal result.

#include "rig_models/model.hpp"
#include "rig_models/realtime_clutch.hpp"

namespace shudder::rig_models {

dynamics::Recording run_fixed_step(const PrescribedSlipModel& model, const clutch::WetClutch& clutch, double step_s);
dynamics::Recording run_fixed_step(const RigModel& model, const clutch::WetClutch& clutch, double step_s);
dynamics::Recording run_fixed_step(const DrivelineModel& model, const clutch::WetClutch& clutch, double step_s);

}  // namespace shudder::rig_models
