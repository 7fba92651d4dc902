#include "components/network_run.hpp"

#include <algorithm>
#include <cmath>
#include <deque>
#include <limits>
#include <span>
#include <utility>

#include "components/network_builder.hpp"
#include "components/transient_oscillation.hpp"
#include "core/units.hpp"
#include "rig_models/channel_recorder.hpp"
#include "rig_models/energy_scalars.hpp"
#include "rig_models/multirate_clutch.hpp"

namespace shudder::components {

namespace {

using Slow = const std::vector<clutch::ThermalState>*;
using Recorder = rig_models::ChannelRecorder<dynamics::Sample, Slow>;

// Every signal's jumps over the run, for the stepper's restarts.
std::vector<double> input_breaks(const NetworkSpec& spec) {
  const double d = spec.settings.duration_s;
  std::vector<double> t;
  const auto add = [&](const Signal& s) {
    const auto k = s.knots(0.0, d);
    t.insert(t.end(), k.begin(), k.end());
  };
  for (const auto& c : spec.clutches) add(c.force_signal);
  for (const auto& s : spec.torque_sources) add(s.torque_Nm);
  for (const auto& s : spec.speed_sources) add(s.speed_rpm);
  for (const auto& m : spec.motors) add(m.speed_rpm);
  for (const auto& e : spec.engines) add(e.throttle);
  std::sort(t.begin(), t.end());
  t.erase(std::unique(t.begin(), t.end()), t.end());
  return t;
}

const dynamics::Signal& signal(const dynamics::Recording& rec, const std::string& name) {
  const auto* s = rec.find(name);
  if (!s) throw std::logic_error("network run: channel " + name + " missing");
  return *s;
}

// The part of the record a clutch is judged on: from its first loaded sample (normal force > 0)
// to its last sample slipping under load. The lock-up that ends an engagement, and the time the
// clutch stays open or locked after it, are not judged: a single lock-up is no stick-slip.
std::pair<std::size_t, std::size_t> loaded_window(const std::vector<double>& stuck, const std::vector<double>& force) {
  std::size_t i0 = 0;
  while (i0 < force.size() && !(force[i0] > 0)) ++i0;
  std::size_t i1 = force.size();
  while (i1 > i0 && !(force[i1 - 1] > 0 && stuck[i1 - 1] < 0.5)) --i1;
  return {i0, i1};
}

// A verdict needs the oscillation to repeat (components/transient_oscillation.hpp): stick-slip at
// least two stick onsets in the window; a vibration kMinJudgedCycles cycles whose swings pass
// half the verdict's threshold, and an amplitude over the window's last two periods at least half
// the largest period's (a ringing that dies out is the drivetrain answering a step, not judder). One transient (a force ramp's corner) reads as none, its
// amplitude and peak frequency kept, as the detector's own rule for a record without oscillation.
void confirm_repeated(const rig_models::RecordingDetection& d, analysis::ShudderResult& r) {
  if (r.verdict == analysis::Verdict::kNone || !(r.frequency_Hz > 0)) return;
  if (r.verdict == analysis::Verdict::kStickSlip && stick_onsets(d.input.stuck) >= 2) return;
  const int swings = oscillation_swings(d.input.time_s, d.input.torque_Nm, r.frequency_Hz, 0.5 * r.threshold_Nm);
  const auto periods = period_amplitudes_from_end(d.input.time_s, d.input.torque_Nm, r.frequency_Hz);
  const bool sustained = periods.size() >= 2 &&
                         0.5 * (periods[0] + periods[1]) >= 0.5 * *std::max_element(periods.begin(), periods.end());
  if (r.verdict == analysis::Verdict::kVibration && swings >= static_cast<int>(2 * kMinJudgedCycles) && sustained) return;
  constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
  r.verdict = analysis::Verdict::kNone;
  r.frequency_Hz = r.onset_time_s = r.growth_rate_per_s = r.growth_acceleration_per_s2 = kNaN;
  r.at_onset = {kNaN, kNaN, kNaN, kNaN};
}

}  // namespace

int verdict_rank(const analysis::ShudderResult& r) {
  switch (r.verdict) {
    case analysis::Verdict::kNone: return 0;
    case analysis::Verdict::kVibration: return 1;
    case analysis::Verdict::kStickSlip: return 2;
  }
  return 0;
}

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

  dynamics::Simulation sim(net, cfg.integrator);
  const int n = net.nodes();
  sim.initialize(0.0, Eigen::VectorXd::Zero(n), built->initial_speed_rad_s,
                 Eigen::VectorXd::Zero(static_cast<Eigen::Index>(net.motors().size())));

  // Channels, in the order of the components' kinds (network_spec.hpp).
  std::deque<std::string> names;  // the recorder's names live here
  const auto name = [&](const std::string& component, const char* quantity) -> std::string_view {
    names.push_back(component + "." + quantity);
    return names.back();
  };
  using dynamics::Sample;
  std::vector<Recorder::Channel> ch;
  ch.push_back(Recorder::sampled(dynamics::signal_names::kTime, "s", [](const Sample& s) { return s.t_s; }));
  for (int i = 0; i < n; ++i)
    ch.push_back(Recorder::sampled(name(built->node_names[i], "speed_rpm"), "rpm",
                                   [i](const Sample& s) { return units::rad_s_to_rpm(s.omega_rad_s[i]); }));
  for (std::size_t v = 0; v < spec.vehicles.size(); ++v) {
    const int node = built->vehicle_nodes[v];
    const double r = spec.vehicles[v].wheel_radius_m;
    ch.push_back(Recorder::sampled(name(spec.vehicles[v].name, "speed_km_h"), "km/h",
                                   [node, r](const Sample& s) { return s.omega_rad_s[node] * r * 3.6; }));
  }
  for (std::size_t k = 0; k < net.shafts().size(); ++k)
    ch.push_back(Recorder::sampled(name(net.shafts()[k].name, "torque_Nm"), "N m",
                                   [k](const Sample& s) { return s.shaft_torque_Nm[static_cast<Eigen::Index>(k)]; }));
  for (int e : built->lash_elements)
    ch.push_back(Recorder::sampled(name(net.force_elements()[e].name, "torque_Nm"), "N m",
                                   [e](const Sample& s) { return s.element_torque_Nm[e]; }));
  for (std::size_t c = 0; c < built->clutches.size(); ++c) {
    const BuiltClutch& bc = built->clutches[c];
    const int k = bc.contact;
    const std::string& cn = bc.name();
    ch.push_back(Recorder::sampled(name(cn, "torque_Nm"), "N m", [k](const Sample& s) { return s.contact_torque_Nm[k]; }));
    ch.push_back(Recorder::sampled(name(cn, "slip_rpm"), "rpm",
                                   [k](const Sample& s) { return units::rad_s_to_rpm(s.contact_slip_rad_s[k]); }));
    ch.push_back(Recorder::sampled(name(cn, "stuck"), "1", [k](const Sample& s) {
      return static_cast<double>(s.modes[static_cast<std::size_t>(k)] == dynamics::ContactMode::kStuck);
    }));
    ch.push_back(Recorder::sampled(name(cn, "normal_force_N"), "N", [&bc](const Sample& s) { return bc.normal_force_N(s.t_s); }));
    ch.push_back(Recorder::sampled(name(cn, "friction_coefficient"), "1", [&bc, k](const Sample& s) {
      const double f = bc.normal_force_N(s.t_s);
      return f > 0 ? std::abs(s.contact_torque_Nm[k]) / (bc.geometry_factor_m * f) : 0.0;
    }));
    if (bc.wet) {
      const int w = wet_index[c];
      const auto& th = bc.wet->thermal();
      ch.push_back(Recorder::interpolated(name(cn, "interface_mean_temp_C"), "degC",
                                          [&th, w](const Slow& st) { return th.mean_interface_temp_C((*st)[w]); }));
      ch.push_back(Recorder::interpolated(name(cn, "interface_max_temp_C"), "degC",
                                          [&th, w](const Slow& st) { return th.interface_temps_C((*st)[w]).maxCoeff(); }));
      ch.push_back(Recorder::interpolated(name(cn, "temp_C"), "degC",
                                          [w](const Slow& st) { return (*st)[w].sensor_temp_C; }));
    }
  }
  for (std::size_t f = 0; f < built->freewheel_contacts.size(); ++f) {
    const int k = built->freewheel_contacts[f];
    ch.push_back(Recorder::sampled(name(spec.freewheels[f].name, "torque_Nm"), "N m",
                                   [k](const Sample& s) { return s.contact_torque_Nm[k]; }));
    ch.push_back(Recorder::sampled(name(spec.freewheels[f].name, "locked"), "1", [k](const Sample& s) {
      return static_cast<double>(s.modes[static_cast<std::size_t>(k)] == dynamics::ContactMode::kStuck);
    }));
  }
  for (std::size_t k = 0; k < net.torque_sources().size(); ++k) {
    const auto& src = net.torque_sources()[k];
    ch.push_back(Recorder::sampled(name(src.name, "torque_Nm"), "N m", [&src](const Sample& s) {
      const double w = s.omega_rad_s[src.node];
      return src.torque_at_speed_Nm ? src.torque_at_speed_Nm(s.t_s, w) : src.torque_Nm(s.t_s);
    }));
  }
  for (std::size_t m = 0; m < net.motors().size(); ++m)
    ch.push_back(Recorder::sampled(name(net.motors()[m].name, "torque_Nm"), "N m",
                                   [m](const Sample& s) { return s.motor_torque_Nm[static_cast<Eigen::Index>(m)]; }));
  for (std::size_t t = 0; t < spec.tyres.size(); ++t) {
    const int e = built->tyre_elements[t];
    const double r = spec.tyres[t].params.radius_m;
    ch.push_back(Recorder::sampled(name(spec.tyres[t].name, "force_N"), "N",
                                   [e, r](const Sample& s) { return s.element_torque_Nm[e] / r; }));
  }

  NetworkRun run;
  dynamics::Recording& rec = run.recording;
  Recorder recorder(rec, std::move(ch));
  recorder.sample(sim.sample());
  const Slow slow = &thermal;
  recorder.start(slow);

  std::vector<rig_models::MultirateClutch> wet;
  for (std::size_t c = 0; c < built->clutches.size(); ++c)
    if (built->clutches[c].wet)
      wet.push_back({built->clutches[c].context.get(), built->clutches[c].wet.get(), &thermal[static_cast<std::size_t>(wet_index[c])],
                     built->clutches[c].contact, nullptr});
  std::vector<double> peak_C;
  for (std::size_t c = 0; c < built->clutches.size(); ++c)
    if (built->clutches[c].wet) peak_C.push_back(built->clutches[c].wet->thermal().interface_temps_C(thermal[peak_C.size()]).maxCoeff());
  const double slow_step = wet.empty() ? cfg.duration_s : cfg.thermal_step_s;
  rig_models::run_multirate(
      sim, wet, cfg.duration_s, slow_step, cfg.sample_rate_Hz, [&](const Sample& s) { recorder.sample(s); },
      [&](const rig_models::SlowStep& step) {
        for (std::size_t w = 0; w < wet.size(); ++w)
          peak_C[w] = std::max(peak_C[w], wet[w].clutch->thermal().interface_temps_C(thermal[w]).maxCoeff());
        recorder.step(slow, step.ta_s, step.tb_s);
      },
      input_breaks(spec));

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

  // Verdicts, each on its clutch's loaded window (header).
  const auto& time = signal(rec, std::string(dynamics::signal_names::kTime));
  for (const BuiltClutch& bc : built->clutches) {
    ClutchVerdict cv;
    cv.clutch = bc.name();
    const std::string torque = bc.name() + ".torque_Nm", slip = bc.name() + ".slip_rpm";
    const auto& stuck = signal(rec, bc.name() + ".stuck").values;
    const auto& force = signal(rec, bc.name() + ".normal_force_N").values;
    const auto window = loaded_window(stuck, force);
    const std::size_t i0 = window.first, i1 = window.second;  // plain names: lambdas below capture them
    const double span_s = i1 > i0 ? time.values[i1 - 1] - time.values[i0] : 0.0;
    if (i1 - i0 < kMinJudgedSamples) {
      cv.reason = i1 > i0 ? "it slips under load for only " + std::to_string(span_s) + " s (" +
                                std::to_string(i1 - i0) + " samples; at least " + std::to_string(kMinJudgedSamples) +
                                " are judged)"
                          : "it never slips under load";
    } else {
      rig_models::RecordingDetection d;
      d.torque_signal = torque;
      d.slip_signal = slip;
      const auto part = [&](const std::vector<double>& v) { return std::span<const double>(v).subspan(i0, i1 - i0); };
      d.input.time_s = part(time.values);
      d.input.torque_Nm = part(signal(rec, torque).values);
      d.input.slip_rpm = part(signal(rec, slip).values);
      d.input.stuck = part(stuck);
      d.input.normal_force_N = part(force);
      if (const auto* s = rec.find(bc.name() + ".interface_mean_temp_C")) d.input.interface_temp_C = part(s->values);
      d.settings.onset_definition = analysis::OnsetDefinition::kThresholdCrossing;
      d.settings.min_frequency_Hz = std::max(kNetworkMinFrequency_Hz, kMinJudgedCycles / span_s);
      if (d.settings.min_frequency_Hz >= 0.5 * cfg.sample_rate_Hz / 2) {
        cv.reason = "its loaded slip (" + std::to_string(span_s) + " s) is too short to hold " +
                    std::to_string(static_cast<int>(kMinJudgedCycles)) + " cycles below the sampling's Nyquist rate";
      } else {
        d.settings.max_frequency_Hz = std::min(d.settings.max_frequency_Hz, 0.4 * cfg.sample_rate_Hz);
        try {
          cv.verdict = rig_models::judge_detection(d);
          cv.judged = true;
          confirm_repeated(d, cv.verdict.judged);
          cv.verdict.prediction = rig_models::Prediction::none("a network's linear prediction is not made per clutch yet");
        } catch (const std::invalid_argument& err) {
          cv.reason = err.what();
        }
      }
    }
    if (cv.judged) {
      auto block = rig_models::verdict_block(cv.verdict);
      block.name = "verdict." + bc.name();
      block.description = "clutch " + bc.name() + ": " + block.description;
      rec.blocks.push_back(std::move(block));
    } else {
      auto block = rig_models::not_judged_block(cv.reason);
      block.name = "verdict." + bc.name();
      rec.blocks.push_back(std::move(block));
    }
    run.verdicts.push_back(std::move(cv));
  }
  for (std::size_t i = 0; i < run.verdicts.size(); ++i) {
    const auto& v = run.verdicts[i];
    if (!v.judged) continue;
    if (run.worst < 0) {
      run.worst = static_cast<int>(i);
      continue;
    }
    const auto& w = run.verdicts[static_cast<std::size_t>(run.worst)].verdict.judged;
    const int rv = verdict_rank(v.verdict.judged), rw = verdict_rank(w);
    if (rv > rw || (rv == rw && rv > 0 && v.verdict.judged.amplitude_Nm > w.amplitude_Nm)) run.worst = static_cast<int>(i);
  }
  if (run.worst >= 0) {
    auto block = rig_models::verdict_block(run.verdicts[static_cast<std::size_t>(run.worst)].verdict);
    block.texts.push_back({"clutch", run.verdicts[static_cast<std::size_t>(run.worst)].clutch});
    block.description = "the run's verdict: the worst of its clutches' verdicts (text `clutch` names it)";
    rec.blocks.push_back(std::move(block));
  } else {
    auto block = rig_models::not_judged_block(built->clutches.empty() ? "the network has no clutch to judge"
                                                                      : run.verdicts.front().reason);
    rec.blocks.push_back(std::move(block));
  }
  return run;
}

}  // namespace shudder::components
