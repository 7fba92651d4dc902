#include "components/network_run.hpp"

#include <algorithm>
#include <cmath>
#include <deque>

#include "components/clutch_prediction.hpp"
#include "components/haldex_control.hpp"
#include "components/network_builder.hpp"
#include "components/network_channels.hpp"
#include "rig_models/energy_scalars.hpp"
#include "rig_models/friction_range_block.hpp"
#include "rig_models/multirate_clutch.hpp"

namespace shudder::components {

namespace {

// Every signal's jumps over the run, for the stepper's restarts.
std::vector<double> input_breaks(const NetworkSpec& spec) {
  const double d = spec.settings.duration_s;
  std::vector<double> t;
  const auto add = [&](const Signal& s) {
    const auto k = s.knots(0.0, d);
    t.insert(t.end(), k.begin(), k.end());
  };
  for (const auto& c : spec.clutches) {
    if (c.law != ClutchSpec::Law::kHaldex) {
      add(c.force_signal);
      continue;
    }
    add(c.haldex.pedal);
    if (c.haldex.valve_opening) add(*c.haldex.valve_opening);
    if (c.haldex.valve_pressure_bar) add(*c.haldex.valve_pressure_bar);
  }
  for (const auto& s : spec.torque_sources) add(s.torque_Nm);
  for (const auto& s : spec.speed_sources) add(s.speed_rpm);
  for (const auto& m : spec.motors) add(m.speed_rpm);
  for (const auto& e : spec.engines) add(e.throttle);
  std::sort(t.begin(), t.end());
  t.erase(std::unique(t.begin(), t.end()), t.end());
  return t;
}

}  // namespace

NetworkRun run_network(const NetworkSpec& spec) {
  const auto built = build_network(spec);
  const auto& net = built->network;
  const auto& cfg = spec.settings;
  if (!(cfg.duration_s > 0) || !(cfg.thermal_step_s > 0) || !(cfg.sample_rate_Hz > 0))
    throw std::invalid_argument("duration, thermal step and sample rate must be > 0");

  std::vector<clutch::ThermalState> thermal;  // one per wet clutch, in clutch order
  std::vector<int> wet_index(built->clutches.size(), -1);
  for (std::size_t c = 0; c < built->clutches.size(); ++c)
    if (built->clutches[c].wet) {
      wet_index[c] = static_cast<int>(thermal.size());
      thermal.push_back(built->clutches[c].wet->initial_state());
    }

  // Each Haldex coupling's control unit, its first command set before the simulation reads the
  // valve's start opening from it.
  std::vector<HaldexControlUnit> units;
  std::vector<std::size_t> unit_wet;  // the unit's coupling's index into `thermal`
  for (std::size_t c = 0; c < built->clutches.size(); ++c)
    if (built->clutches[c].haldex) {
      try {
        units.emplace_back(built->clutches[c]);
      } catch (const std::invalid_argument& e) {
        throw NetworkError(built->clutches[c].name(), e.what());
      }
      unit_wet.push_back(static_cast<std::size_t>(wet_index[c]));
      units.back().start(built->initial_speed_rad_s, thermal[unit_wet.back()]);
    }

  dynamics::Simulation sim(net, cfg.integrator);
  sim.initialize(0.0, built->initial_angle_rad, built->initial_speed_rad_s, built->initial_motor_integral);

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

  // Each wet clutch's tally of its friction law used outside its data (clutch/friction_data_range.hpp).
  std::vector<clutch::FrictionDataRange> ranges;
  ranges.reserve(thermal.size());
  for (const auto& bc : built->clutches)
    if (bc.wet) ranges.emplace_back(*bc.wet->fluid().friction);
  std::vector<rig_models::MultirateClutch> wet;
  for (std::size_t c = 0; c < built->clutches.size(); ++c) {
    const BuiltClutch& bc = built->clutches[c];
    if (!bc.wet) continue;
    const auto w = static_cast<std::size_t>(wet_index[c]);
    wet.push_back({bc.context.get(), bc.wet.get(), &thermal[w], bc.contact, &ranges[w]});
    if (bc.haldex) wet.back().clamp_force_N = [&bc](const dynamics::Sample& s) { return bc.normal_force_N(s); };
  }
  // Restarts: the inputs' jumps and the control units' instants.
  std::vector<double> breaks = input_breaks(spec);
  for (const auto& u : units) {
    const auto t = u.instants(cfg.duration_s);
    breaks.insert(breaks.end(), t.begin(), t.end());
  }
  std::sort(breaks.begin(), breaks.end());
  breaks.erase(std::unique(breaks.begin(), breaks.end()), breaks.end());
  std::vector<double> peak_C;
  for (std::size_t c = 0; c < built->clutches.size(); ++c)
    if (built->clutches[c].wet) peak_C.push_back(built->clutches[c].wet->thermal().interface_temps_C(thermal[peak_C.size()]).maxCoeff());
  const double slow_step = wet.empty() ? cfg.duration_s : cfg.thermal_step_s;
  rig_models::run_multirate(
      sim, wet, cfg.duration_s, slow_step, cfg.sample_rate_Hz,
      [&](const dynamics::Sample& s) {
        recorder.sample(s);
        keep_snapshot(s);
      },
      [&](const rig_models::SlowStep& step) {
        for (std::size_t w = 0; w < wet.size(); ++w)
          peak_C[w] = std::max(peak_C[w], wet[w].clutch->thermal().interface_temps_C(thermal[w]).maxCoeff());
        for (std::size_t u = 0; u < units.size(); ++u) units[u].update_oil(thermal[unit_wet[u]]);
        recorder.step(slow, step.ta_s, step.tb_s);
      },
      breaks,
      units.empty() ? std::function<void(double)>() : [&](double t) {
        const dynamics::Sample s = sim.sample();
        for (auto& u : units) u.at(t, s);
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
    run.verdicts.push_back(judge_clutch(
        rec, bc.name(), (bc.spec->judged_on.empty() ? bc.name() : bc.spec->judged_on) + ".torque_Nm", cfg.sample_rate_Hz));
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
    auto range = rig_models::friction_range_block(ranges[static_cast<std::size_t>(wet_index[c])]);
    const auto* f = range.find_scalar("fraction_outside");
    const double outside = f ? f->value : std::nan("");
    range.name = std::string(rig_models::kFrictionRangeBlock) + "." + bc.name();
    rec.blocks.push_back(std::move(range));
    for (auto& b : rec.blocks) {
      const bool of_this_clutch = b.name == "verdict." + bc.name() || (b.name == "verdict" && static_cast<int>(c) == run.worst);
      const auto* verdict = b.find_text("verdict");
      if (of_this_clutch && verdict && verdict->value != "not_judged")
        b.scalars.push_back({"outside_data_fraction", "1", outside});
    }
  }
  return run;
}

}  // namespace shudder::components
