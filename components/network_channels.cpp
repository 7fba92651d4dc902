#include "components/network_channels.hpp"

#include <cmath>

#include "core/units.hpp"

namespace shudder::components {

std::vector<NetworkChannel> network_channels(const NetworkSpec& spec, const BuiltNetwork& built,
                                             const std::vector<int>& wet_index, std::deque<std::string>& names) {
  const auto& net = built.network;
  const int n = net.nodes();
  const auto name = [&](const std::string& component, const char* quantity) -> std::string_view {
    names.push_back(component + "." + quantity);
    return names.back();
  };
  using dynamics::Sample;
  std::vector<NetworkChannel> ch;
  ch.push_back(NetworkRecorder::sampled(dynamics::signal_names::kTime, "s", [](const Sample& s) { return s.t_s; }));
  for (int i = 0; i < n; ++i)
    ch.push_back(NetworkRecorder::sampled(name(built.node_names[i], "speed_rpm"), "rpm",
                                          [i](const Sample& s) { return units::rad_s_to_rpm(s.omega_rad_s[i]); }));
  for (std::size_t v = 0; v < spec.vehicles.size(); ++v) {
    const int node = built.vehicle_nodes[v];
    const double r = spec.vehicles[v].wheel_radius_m;
    ch.push_back(NetworkRecorder::sampled(name(spec.vehicles[v].name, "speed_km_h"), "km/h",
                                          [node, r](const Sample& s) { return s.omega_rad_s[node] * r * 3.6; }));
  }
  for (std::size_t k = 0; k < net.shafts().size(); ++k)
    ch.push_back(NetworkRecorder::sampled(name(net.shafts()[k].name, "torque_Nm"), "N m", [k](const Sample& s) {
      return s.shaft_torque_Nm[static_cast<Eigen::Index>(k)];
    }));
  for (int e : built.lash_elements)
    ch.push_back(NetworkRecorder::sampled(name(net.force_elements()[e].name, "torque_Nm"), "N m",
                                          [e](const Sample& s) { return s.element_torque_Nm[e]; }));
  for (std::size_t c = 0; c < built.clutches.size(); ++c) {
    const BuiltClutch& bc = built.clutches[c];
    const int k = bc.contact;
    const std::string& cn = bc.name();
    ch.push_back(NetworkRecorder::sampled(name(cn, "torque_Nm"), "N m",
                                          [k](const Sample& s) { return s.contact_torque_Nm[k]; }));
    ch.push_back(NetworkRecorder::sampled(
        name(cn, "slip_rpm"), "rpm", [k](const Sample& s) { return units::rad_s_to_rpm(s.contact_slip_rad_s[k]); }));
    ch.push_back(NetworkRecorder::sampled(name(cn, "stuck"), "1", [k](const Sample& s) {
      return static_cast<double>(s.modes[static_cast<std::size_t>(k)] == dynamics::ContactMode::kStuck);
    }));
    ch.push_back(NetworkRecorder::sampled(name(cn, "normal_force_N"), "N",
                                          [&bc](const Sample& s) { return bc.normal_force_N(s); }));
    ch.push_back(NetworkRecorder::sampled(name(cn, "friction_coefficient"), "1", [&bc, k](const Sample& s) {
      const double f = bc.normal_force_N(s);
      return f > 0 ? std::abs(s.contact_torque_Nm[k]) / (bc.geometry_factor_m * f) : 0.0;
    }));
    if (bc.haldex) {
      const int z = bc.state_index;
      ch.push_back(NetworkRecorder::sampled(name(cn, "pressure_bar"), "bar", [z](const Sample& s) {
        return s.contact_states[z + components::HaldexCouplingLaw::kPressure];
      }));
      ch.push_back(NetworkRecorder::sampled(name(cn, "valve_opening"), "1", [z](const Sample& s) {
        return s.contact_states[z + components::HaldexCouplingLaw::kOpening];
      }));
    }
    if (bc.wet) {
      const int w = wet_index[c];
      const auto& th = bc.wet->thermal();
      ch.push_back(NetworkRecorder::interpolated(
          name(cn, "interface_mean_temp_C"), "degC",
          [&th, w](const NetworkSlow& st) { return th.mean_interface_temp_C((*st)[w]); }));
      ch.push_back(NetworkRecorder::interpolated(
          name(cn, "interface_max_temp_C"), "degC",
          [&th, w](const NetworkSlow& st) { return th.interface_temps_C((*st)[w]).maxCoeff(); }));
      ch.push_back(NetworkRecorder::interpolated(name(cn, "temp_C"), "degC",
                                                 [w](const NetworkSlow& st) { return (*st)[w].sensor_temp_C; }));
    }
  }
  for (std::size_t f = 0; f < built.freewheel_contacts.size(); ++f) {
    const int k = built.freewheel_contacts[f];
    ch.push_back(NetworkRecorder::sampled(name(spec.freewheels[f].name, "torque_Nm"), "N m",
                                          [k](const Sample& s) { return s.contact_torque_Nm[k]; }));
    ch.push_back(NetworkRecorder::sampled(name(spec.freewheels[f].name, "locked"), "1", [k](const Sample& s) {
      return static_cast<double>(s.modes[static_cast<std::size_t>(k)] == dynamics::ContactMode::kStuck);
    }));
  }
  for (std::size_t k = 0; k < net.torque_sources().size(); ++k) {
    const auto& src = net.torque_sources()[k];
    ch.push_back(NetworkRecorder::sampled(name(src.name, "torque_Nm"), "N m", [&src](const Sample& s) {
      const double w = s.omega_rad_s[src.node];
      return src.torque_at_speed_Nm ? src.torque_at_speed_Nm(s.t_s, w) : src.torque_Nm(s.t_s);
    }));
  }
  for (std::size_t m = 0; m < net.motors().size(); ++m)
    ch.push_back(NetworkRecorder::sampled(name(net.motors()[m].name, "torque_Nm"), "N m", [m](const Sample& s) {
      return s.motor_torque_Nm[static_cast<Eigen::Index>(m)];
    }));
  for (std::size_t t = 0; t < spec.tyres.size(); ++t) {
    const int e = built.tyre_elements[t];
    const double r = spec.tyres[t].params.radius_m;
    ch.push_back(NetworkRecorder::sampled(name(spec.tyres[t].name, "force_N"), "N",
                                          [e, r](const Sample& s) { return s.element_torque_Nm[e] / r; }));
  }

  return ch;
}

}  // namespace shudder::components
