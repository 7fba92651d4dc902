#include "fmu/network_variables.hpp"

#include <algorithm>
#include <cctype>
#include <deque>
#include <map>
#include <stdexcept>

#include "components/network_channels.hpp"

namespace shudder::fmu {

std::vector<NetworkInput> network_inputs(components::NetworkSpec& spec) {
  std::vector<NetworkInput> in;
  for (auto& c : spec.clutches) {
    if (c.law == components::ClutchSpec::Law::kHaldex) {
      // The control unit's inputs: the pedal it reads and, in place of the unit, a raw valve setting.
      auto& h = c.haldex;
      in.push_back({c.name + ".pedal", "1", "accelerator pedal 0..1 (clamped) the control unit reads", &h.pedal});
      if (h.valve_opening)
        in.push_back({c.name + ".valve_opening_command", "1",
                      "raw throttle valve opening commanded, 0 shut .. 1 open (clamped)", &*h.valve_opening});
      if (h.valve_pressure_bar)
        in.push_back({c.name + ".valve_pressure_bar", "bar", "raw pressure setting (valve shut below it)",
                      &*h.valve_pressure_bar});
      continue;
    }
    in.push_back(
        {c.name + ".normal_force", "1", "normalised normal force u: F = max_force_N max(u, 0)", &c.force_signal});
  }
  for (auto& s : spec.torque_sources)
    in.push_back(
        {s.name + ".torque_Nm", "N.m", "torque on node " + s.node + ", positive along its speed", &s.torque_Nm});
  for (auto& s : spec.speed_sources)
    in.push_back({s.name + ".speed_rpm", "rpm", "speed of node " + s.node, &s.speed_rpm});
  for (auto& m : spec.motors)
    if (m.ripple.amplitude_Nm == 0.0)
      in.push_back({m.name + ".speed_rpm", "rpm", "speed set point of the motor on node " + m.node, &m.speed_rpm});
  for (auto& e : spec.engines)
    in.push_back({e.name + ".throttle", "1", "throttle 0..1 (clamped) of the engine on node " + e.node, &e.throttle});
  return in;
}

std::string fmi_name(const std::string& name) {
  std::string out, part;
  const auto flush = [&] {
    if (part.empty() || std::isdigit(static_cast<unsigned char>(part.front()))) out += '_';
    out += part;
    part.clear();
  };
  for (char ch : name) {
    if (ch == '.') {
      flush();
      out += '.';
    } else {
      part += std::isalnum(static_cast<unsigned char>(ch)) || ch == '_' ? ch : '_';
    }
  }
  flush();
  return out;
}

std::string fmi_unit(const std::string& unit) { return unit == "N m" ? "N.m" : unit; }

DescribedModel network_description(const io::NetworkScenario& sc, double fixed_step_s) {
  DescribedModel m;
  m.model_name = sc.name;
  m.model_identifier = kNetworkModelIdentifier;
  m.description =
      (sc.description.empty() ? "network scenario " + sc.name : sc.description) + " (shudder network, fixed-step RK4)";
  m.naming_convention = "structured";
  m.log_events =
      "what the instance does: instantiation, the scenario and fluids loaded, initialisation, steps that "
      "end with a shorter internal step, reset, termination";
  m.stop_time_s = sc.spec.settings.duration_s;
  m.step_size_s = 1.0 / sc.spec.settings.sample_rate_Hz;

  components::NetworkSpec spec = sc.spec;
  std::map<std::string, std::string> taken;  // FMI name -> the name it came from
  const auto claim = [&](const std::string& from) {
    std::string n = fmi_name(from);
    const auto [it, fresh] = taken.emplace(n, from);
    if (!fresh)
      throw std::invalid_argument("'" + from + "' and '" + it->second + "' both become the FMU variable '" + n +
                                  "'; rename one of the components");
    return n;
  };
  unsigned vr = 0;
  std::vector<std::string> input_names;
  for (const auto& i : network_inputs(spec)) {
    input_names.push_back(i.name);
    m.variables.push_back({vr++, claim(i.name), Type::kReal, Causality::kInput, i.unit, (*i.signal)(0.0), "",
                           i.description + "; replaces the scenario's signal (start: its value at t = 0)"});
  }
  // The outputs: the channels of the built network.
  const components::NetworkStepper stepper(spec, spec.settings.duration_s);
  std::deque<std::string> names;
  const auto channels = components::network_channels(spec, stepper.built(), stepper.wet_index(), names);
  vr = kFirstOutputVr;
  for (const auto& ch : channels) {
    const std::string name(ch.name);
    if (name == dynamics::signal_names::kTime) continue;
    if (std::find(input_names.begin(), input_names.end(), name) != input_names.end()) continue;
    m.variables.push_back({vr++, claim(name), Type::kReal, Causality::kOutput, fmi_unit(std::string(ch.units)), 0.0, "",
                           ch.interpolated ? "recorded channel " + name + " (at the last thermal step's end)"
                                           : "recorded channel " + name});
  }
  m.variables.push_back({kFixedStepVr, "fixed_step_s", Type::kReal, Causality::kParameter, "s", fixed_step_s, "",
                         "internal RK4 step; the thermal step must be a whole multiple of it"});
  return m;
}

}  // namespace shudder::fmu
