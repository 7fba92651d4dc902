#include "components/network_run.hpp"

#include <algorithm>
#include <cmath>
#include <deque>

#include "components/clutch_prediction.hpp"
#include "components/network_builder.hpp"
#include "components/network_channels.hpp"
#include "components/network_stepper.hpp"
#include "rig_models/energy_scalars.hpp"
#include "rig_models/friction_range_block.hpp"

namespace shudder::components {

NetworkRun run_network(const NetworkSpec& spec) {
  const auto& cfg = spec.settings;
  NetworkStepper stepper(spec, cfg.duration_s);
  BuiltNetwork* built = &stepper.built();
  const dynamics::Simulation& sim = stepper.simulation();
  const std::vector<clutch::ThermalState>& thermal = stepper.thermal();
  const std::vector<int>& wet_index = stepper.wet_index();

  std::deque<std::string> names;  // the channel names the recorder's channels view
  std::vector<NetworkChannel> channels = network_channels(spec, *built, wet_index, names);
  NetworkRun run;
  dynamics::Recording& rec = run.recording;
  NetworkRecorder recorder(rec, std::move(channels));
  // States kept every kSnapshotInterval_s (or every sample, if sparser) for the predictions.
  constexpr double kSnapshotInterval_s = 5e-3;
  std::vector<dynamics::Sample> snapshots;
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
      [&](const rig_models::SlowStep& step) {
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
  // Each wet clutch's heat account (rig_models/energy_scalars.hpp) under its name; the run's
  // energy_balance_relative_error is the worst of them, so the energy guard judges every clutch.
  double worst_thermal = 0.0;
  for (std::size_t c = 0, w = 0; c < built->clutches.size(); ++c) {
    const std::string& cn = built->clutches[c].name();
    rec.scalars.push_back({cn + ".friction_work_J", "J", sim.friction_work_J(built->clutches[c].contact)});
    if (built->clutches[c].wet) {
      rec.scalars.push_back({cn + ".peak_interface_temp_C", "degC", peak_C[w]});
      for (auto sc : rig_models::heat_account_scalars(*built->clutches[c].wet, thermal[w])) {
        if (sc.name == "energy_balance_relative_error")
          worst_thermal = std::isfinite(sc.value) ? std::max(worst_thermal, std::abs(sc.value)) : sc.value;
        sc.name = cn + "." + sc.name;
        rec.scalars.push_back(sc);
      }
      ++w;
    }
  }
  if (!wet.empty()) rec.scalars.push_back({"energy_balance_relative_error", "1", worst_thermal});

  // Verdicts, each on its clutch's loaded window (components/clutch_judgement.hpp).
  for (const BuiltClutch& bc : built->clutches)
    run.verdicts.push_back(judge_clutch(rec, bc.name(),
                                        (bc.spec->judged_on.empty() ? bc.name() : bc.spec->judged_on) + ".torque_Nm",
                                        cfg.sample_rate_Hz));
  for (std::size_t c = 0; c < run.verdicts.size(); ++c)
    if (run.verdicts[c].judged)
      run.verdicts[c].verdict.prediction = predict_clutch(*built, c, run.verdicts[c].verdict.window, snapshots);
  run.worst = worst_verdict(run.verdicts);
  add_verdict_blocks(rec, run.verdicts, run.worst,
                     built->clutches.empty() ? "the network has no clutch to judge"
                                             : (run.verdicts.empty() ? "" : run.verdicts.front().reason));
  // Per wet clutch: its friction data range block, and in its verdict block (and the run's, for
  // the clutch it names) the share of the run its law was used outside its data: a verdict
  // reached there is an extrapolation of the law.
  for (std::size_t c = 0; c < built->clutches.size(); ++c) {
    const BuiltClutch& bc = built->clutches[c];
    if (!bc.wet) continue;
    auto range = rig_models::friction_range_block(stepper.data_ranges()[static_cast<std::size_t>(wet_index[c])]);
    const auto* f = range.find_scalar("fraction_outside");
    const double outside = f ? f->value : std::nan("");
    range.name = std::string(rig_models::kFrictionRangeBlock) + "." + bc.name();
    rec.blocks.push_back(std::move(range));
    for (auto& b : rec.blocks) {
      const bool of_this_clutch =
          b.name == "verdict." + bc.name() || (b.name == "verdict" && static_cast<int>(c) == run.worst);
      const auto* verdict = b.find_text("verdict");
      if (of_this_clutch && verdict && verdict->value != "not_judged")
        b.scalars.push_back({"outside_data_fraction", "1", outside});
    }
  }
  return run;
}

}  // namespace shudder::components
