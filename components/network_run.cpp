#include "components/network_run.hpp"

#include <algorithm>
#include <cmath>
#include <deque>

#include "components/network_builder.hpp"
#include "components/network_channels.hpp"
#include "components/energy_scalars.hpp"
#include "components/friction_range_block.hpp"

namespace shudder::components {

NetworkSimulation simulate_network(const NetworkSpec& spec) {
  const auto& cfg = spec.settings;
  NetworkSimulation run;
  run.stepper = std::make_unique<NetworkStepper>(spec, cfg.duration_s);
  NetworkStepper& stepper = *run.stepper;
  BuiltNetwork* built = &stepper.built();
  const dynamics::Simulation& sim = stepper.simulation();
  const std::vector<clutch::ThermalState>& thermal = stepper.thermal();
  const std::vector<int>& wet_index = stepper.wet_index();

  std::deque<std::string> names;  // the channel names the recorder's channels view
  std::vector<NetworkChannel> channels = network_channels(spec, *built, wet_index, names);
  dynamics::Recording& rec = run.recording;
  NetworkRecorder recorder(rec, std::move(channels));
  // States kept every kSnapshotInterval_s (or every sample, if sparser) for the predictions.
  constexpr double kSnapshotInterval_s = 5e-3;
  std::vector<dynamics::Sample>& snapshots = run.snapshots;
  double next_snapshot_s = 0.0;
  const auto keep_snapshot = [&](const dynamics::Sample& s) {
    if (s.t_s < next_snapshot_s - 1e-12) return;
    snapshots.push_back(s);
    next_snapshot_s = s.t_s + kSnapshotInterval_s;
  };
  recorder.sample(sim.sample());
  keep_snapshot(sim.sample());
  const NetworkSlow slow = &thermal;
  recorder.start(slow);

  std::vector<const clutch::WetClutch*> wet;  // in the order of `thermal`
  for (const auto& bc : built->clutches)
    if (bc.wet) wet.push_back(bc.wet.get());
  std::vector<double> peak_C;
  for (std::size_t w = 0; w < wet.size(); ++w)
    peak_C.push_back(wet[w]->thermal().interface_temps_C(thermal[w]).maxCoeff());
  stepper.advance_to(
      cfg.duration_s,
      [&](const dynamics::Sample& s) {
        recorder.sample(s);
        keep_snapshot(s);
      },
      [&](const components::SlowStep& step) {
        for (std::size_t w = 0; w < wet.size(); ++w)
          peak_C[w] = std::max(peak_C[w], wet[w]->thermal().interface_temps_C(thermal[w]).maxCoeff());
        recorder.step(slow, step.ta_s, step.tb_s);
      });

  // Scalars: the energy account, per clutch its heat, per wet clutch its peak temperature.
  const auto e = sim.energy();
  run.energy_imbalance_J = e.imbalance_J();
  run.energy_scale_J = std::max({std::abs(e.source_work_J), e.initial_kinetic_J, e.kinetic_J, e.friction_heat_J, 1e-9});
  rec.scalars = {
      {"source_work_J", "J", e.source_work_J},
      {"kinetic_energy_change_J", "J", e.kinetic_J - e.initial_kinetic_J},
      {"elastic_energy_change_J", "J", e.elastic_J - e.initial_elastic_J},
      {"friction_heat_J", "J", e.friction_heat_J},
      {"damper_loss_J", "J", e.damper_loss_J},
      {"mechanical_energy_relative_error", "1", run.energy_imbalance_J / run.energy_scale_J},
      {"integrator_steps", "1", static_cast<double>(sim.counters().steps)},
      {"stick_events", "1", static_cast<double>(sim.counters().stick_events)},
      {"breakaway_events", "1", static_cast<double>(sim.counters().breakaway_events)},
  };
  if (cfg.integrator.fixed_step_s > 0) rec.scalars.push_back({"fixed_step_s", "s", cfg.integrator.fixed_step_s});
  // Each wet clutch's heat account (components/energy_scalars.hpp) under its name; the run's
  // energy_balance_relative_error is the worst of them, so the energy guard judges every clutch.
  double worst_thermal = 0.0;
  for (std::size_t c = 0, w = 0; c < built->clutches.size(); ++c) {
    const std::string& cn = built->clutches[c].name();
    rec.scalars.push_back({cn + ".friction_work_J", "J", sim.friction_work_J(built->clutches[c].contact)});
    if (built->clutches[c].wet) {
      rec.scalars.push_back({cn + ".peak_interface_temp_C", "degC", peak_C[w]});
      for (auto sc : components::heat_account_scalars(*built->clutches[c].wet, thermal[w])) {
        if (sc.name == "energy_balance_relative_error")
          worst_thermal = std::isfinite(sc.value) ? std::max(worst_thermal, std::abs(sc.value)) : sc.value;
        sc.name = cn + "." + sc.name;
        rec.scalars.push_back(sc);
      }
      ++w;
    }
  }
  if (!wet.empty()) rec.scalars.push_back({"energy_balance_relative_error", "1", worst_thermal});

  // Per wet clutch: its friction data range block (components/friction_range_block.hpp).
  for (std::size_t c = 0; c < built->clutches.size(); ++c) {
    const BuiltClutch& bc = built->clutches[c];
    if (!bc.wet) continue;
    auto range = components::friction_range_block(stepper.data_ranges()[static_cast<std::size_t>(wet_index[c])]);
    range.name = std::string(components::kFrictionRangeBlock) + "." + bc.name();
    rec.blocks.push_back(std::move(range));
  }
  return run;
}

}  // namespace shudder::components
