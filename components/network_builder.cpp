#include "components/network_builder.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>
#include <set>

#include "components/lash_shaft.hpp"
#include "components/network_checks.hpp"
#include "components/one_way_clutch.hpp"
#include "core/nearest_name.hpp"
#include "core/units.hpp"
#include "components/pack_oil.hpp"

namespace shudder::components {

namespace {

constexpr double kGravity_m_s2 = 9.80665;

// The wet clutch reads its clamp force as a piecewise-linear schedule (components/drive_cycle.hpp):
// the signal at its knots (a jump becomes a 1 µs ramp) and, for a sine or a product, at 20000
// points over the run besides: a sine of f Hz over D s gets 20000 / (f D) points a period, and at
// 20 a period the chords miss it by at most 1 - cos(pi / 20) = 1.2 % of its amplitude.
components::PiecewiseLinear force_schedule(const Signal& s, double scale_N, double duration_s,
                                           bool clamp_at_zero = true) {
  constexpr double kJump_s = 1e-6;
  std::vector<double> t{0.0, duration_s};
  for (double k : s.knots(0.0, duration_s)) {
    // A jump gets a point just before it; a corner (a linear table's knot) needs none.
    const double before = s(std::nextafter(k, 0.0)), at = s(k);
    if (std::abs(at - before) > 1e-9 * std::max({1.0, std::abs(at), std::abs(before)}))
      t.push_back(std::max(0.0, k - kJump_s));
    t.push_back(k);
  }
  if (s.kind() == Signal::Kind::kSine || s.kind() == Signal::Kind::kProduct) {
    const int n = 20000;
    for (int i = 1; i < n; ++i) t.push_back(duration_s * i / n);
  }
  std::sort(t.begin(), t.end());
  t.erase(std::unique(t.begin(), t.end(), [](double a, double b) { return b - a < 1e-12; }), t.end());
  std::vector<double> v;
  for (double x : t) v.push_back(scale_N * (clamp_at_zero ? std::max(s(x), 0.0) : s(x)));
  return {t, v};
}

struct Builder {
  const NetworkSpec& spec;
  BuiltNetwork& out;
  std::map<std::string, int> index;

  int node(const std::string& component, const std::string& role, const std::string& name, bool ground_ok) const {
    if (name == kGroundNode) {
      if (!ground_ok) throw NetworkError(component, role + " cannot be \"ground\"; name an inertia or vehicle");
      return dynamics::kGround;
    }
    const auto it = index.find(name);
    if (it != index.end()) return it->second;
    std::vector<std::string> names(out.node_names);
    if (ground_ok) names.push_back(kGroundNode);
    const std::string near = nearest_key(name, names);
    std::string list;
    for (const auto& n : names) list += (list.empty() ? "" : ", ") + n;
    throw NetworkError(component, role + " '" + name + "' is no node of the network" +
                                      (near.empty() ? "" : "; did you mean '" + near + "'?") + " (nodes: " + list +
                                      ")");
  }
  void distinct(const std::string& component, int a, int b) const {
    if (a == b)
      throw NetworkError(component, "is joined to itself (both ends on '" +
                                        (a == dynamics::kGround ? std::string(kGroundNode) : out.node_names[a]) +
                                        "'); join two different nodes");
  }
};

// The Haldex coupling: the pack as a wet clutch in its own oil, clamped by its hydraulics
// (components/haldex_coupling_law.hpp); the nodes its control unit reads.
void build_haldex(const ClutchSpec& c, BuiltClutch& bc, const Builder& b, double duration_s) {
  const HaldexSpec& h = c.haldex;
  try {
    const clutch::WetClutchParams pack = pack_params(c);
    bc.wet = c.wet.prebuilt ? c.wet.prebuilt : std::make_shared<const clutch::WetClutch>(pack, c.wet.fluid);
    const components::HaldexHydraulics hydraulics(
        h.hydraulics, pack.sliding_interfaces * h.nominal_friction * bc.wet->mean_radius_m());
    const components::ClutchContact contact(*bc.wet, c.wet.bearing_drag, c.wet.stick_time);
    bc.context = std::make_shared<components::ClutchContext>(
        contact.start_inputs(components::PiecewiseLinear({0.0}, {hydraulics.clamp_force_N(0.0)})));
    bc.command = std::make_shared<components::HaldexCommand>();
    bc.command->setting_bar = h.hydraulics.relief_pressure_bar;
    if (h.valve_pressure_bar) {
      bc.command->setting_schedule_bar = force_schedule(*h.valve_pressure_bar, 1.0, duration_s);
      bc.command->opening = 0.0;  // shut below the setting
    }
    bc.haldex = std::make_shared<const components::HaldexCouplingLaw>(contact, bc.context, hydraulics, bc.command);
  } catch (const std::invalid_argument& e) {
    throw NetworkError(c.name, e.what());
  }
  bc.geometry_factor_m = c.wet.clutch.sliding_interfaces * bc.wet->mean_radius_m();
  bc.front_axle_node = b.node(c.name, "front_axle", h.front_axle, false);
  bc.rear_axle_node = b.node(c.name, "rear_axle", h.rear_axle, false);
}

// The network put together stage by stage (build_network below), with what the topology checks
// need: the two-node links, the driven nodes and the nodes whose speed a constraint ties.
struct Assembly {
  Assembly(const NetworkSpec& s, BuiltNetwork& o) : spec(s), out(o) {}
  const NetworkSpec& spec;
  BuiltNetwork& out;
  Builder b{spec, out, {}};
  dynamics::TorsionalNetwork& net = out.network;
  const double duration = spec.settings.duration_s;
  Topology topology;

  void add_nodes() {
    std::vector<double> speeds, angles;
    for (const auto& i : spec.inertias) {
      if (i.name == kGroundNode)
        throw NetworkError(i.name, "\"ground\" is the fixed frame; give the inertia another name");
      if (!(i.inertia_kg_m2 >= 0)) throw NetworkError(i.name, "inertia_kg_m2 must be >= 0");
      b.index[i.name] = net.add_inertia({i.name, i.inertia_kg_m2});
      out.node_names.push_back(i.name);
      speeds.push_back(i.speed_rad_s);
      angles.push_back(i.angle_rad);
    }
    for (const auto& v : spec.vehicles) {
      if (!(v.mass_kg > 0) || !(v.wheel_radius_m > 0))
        throw NetworkError(v.name, "mass_kg and wheel_radius_m must be > 0");
      const int n = net.add_inertia({v.name, v.mass_kg * v.wheel_radius_m * v.wheel_radius_m});
      b.index[v.name] = n;
      out.node_names.push_back(v.name);
      out.vehicle_nodes.push_back(n);
      speeds.push_back(v.speed_m_s / v.wheel_radius_m);
      angles.push_back(0.0);
    }
    if (out.node_names.empty())
      throw NetworkError("", "the network has no inertia; add at least one [network.NAME] with type = \"inertia\"");
    out.initial_speed_rad_s =
        Eigen::Map<const Eigen::VectorXd>(speeds.data(), static_cast<Eigen::Index>(speeds.size()));
    out.initial_angle_rad = Eigen::Map<const Eigen::VectorXd>(angles.data(), static_cast<Eigen::Index>(angles.size()));
  }

  // Clutches and brakes first: contact index = position.
  void add_clutches() {
    auto& links = topology.links;
    for (const auto& c : spec.clutches) {
      const int a = b.node(c.name, "node", c.a, false);
      const int bb = b.node(c.name, "node", c.b, true);
      b.distinct(c.name, a, bb);
      links.emplace_back(a, bb);
      if (c.law != ClutchSpec::Law::kHaldex) {
        if (!(c.max_force_N > 0))
          throw NetworkError(c.name, "max_force_N = " + std::to_string(c.max_force_N) +
                                         " can never load the clutch; give the largest normal force in N (> 0)");
        if (!(c.force_signal.max_over(0.0, duration) > 0))
          throw NetworkError(c.name, "its normal_force signal never rises above 0 during the run (0 to " +
                                         std::to_string(duration) +
                                         " s), so the clutch can never carry torque; "
                                         "raise the signal or remove the clutch");
      }
      BuiltClutch bc;
      bc.spec = &c;
      if (c.law == ClutchSpec::Law::kPlain) {
        PlainFrictionParams p = c.plain;
        p.max_force_N = c.max_force_N;
        try {
          bc.plain = std::make_shared<const PlainFrictionLaw>(p, c.force_signal);
        } catch (const std::invalid_argument& e) {
          throw NetworkError(c.name, e.what());
        }
        bc.geometry_factor_m = p.geometry_factor_m;
        bc.contact = net.add_contact({c.name, a, bb, bc.plain});
      } else if (c.law == ClutchSpec::Law::kWet) {
        try {
          bc.wet =
              c.wet.prebuilt ? c.wet.prebuilt : std::make_shared<const clutch::WetClutch>(c.wet.clutch, c.wet.fluid);
        } catch (const std::invalid_argument& e) {
          throw NetworkError(c.name, e.what());
        }
        const components::ClutchContact contact(*bc.wet, c.wet.bearing_drag, c.wet.stick_time);
        bc.context = std::make_shared<components::ClutchContext>(
            contact.start_inputs(force_schedule(c.force_signal, c.max_force_N, duration)));
        bc.geometry_factor_m = c.wet.clutch.sliding_interfaces * bc.wet->mean_radius_m();
        bc.contact =
            net.add_contact({c.name, a, bb, std::make_shared<components::ClutchContactLaw>(contact, bc.context)});
      } else {
        build_haldex(c, bc, b, duration);
        bc.contact = net.add_contact({c.name, a, bb, bc.haldex});
      }
      out.clutches.push_back(std::move(bc));
    }
  }

  void add_freewheels() {
    auto& links = topology.links;
    for (const auto& f : spec.freewheels) {
      const int a = b.node(f.name, "driving", f.driving, false);
      const int bb = b.node(f.name, "driven", f.driven, true);
      b.distinct(f.name, a, bb);
      if (!(f.drag_Nm >= 0)) throw NetworkError(f.name, "drag_Nm must be >= 0");
      const double wb = bb == dynamics::kGround ? 0.0 : out.initial_speed_rad_s[bb];
      if (out.initial_speed_rad_s[a] > wb + 1e-12)
        throw NetworkError(f.name, "starts with '" + f.driving + "' faster than '" + f.driven +
                                       "', which a freewheel cannot allow (it locks that way); start driving no faster "
                                       "than driven");
      links.emplace_back(a, bb);
      out.freewheel_contacts.push_back(net.add_contact({f.name, a, bb, std::make_shared<OneWayClutchLaw>(f.drag_Nm)}));
    }
  }

  void add_shafts() {
    auto& links = topology.links;
    for (const auto& s : spec.shafts) {
      const int a = b.node(s.name, "node", s.a, false);
      const int bb = b.node(s.name, "node", s.b, true);
      b.distinct(s.name, a, bb);
      if (!(s.stiffness_Nm_per_rad >= 0) || !(s.damping_Nms_per_rad >= 0) ||
          !(s.stiffness_Nm_per_rad > 0 || s.damping_Nms_per_rad > 0))
        throw NetworkError(s.name, "needs stiffness_Nm_per_rad >= 0 and damping_Nms_per_rad >= 0, not both 0");
      links.emplace_back(a, bb);
      if (s.lash_rad > 0) {
        if (!(s.stiffness_Nm_per_rad > 0))
          throw NetworkError(s.name, "a shaft with lash needs stiffness_Nm_per_rad > 0");
        if (bb == dynamics::kGround)
          throw NetworkError(s.name, "a shaft with lash joins two nodes; ground is not allowed");
        out.lash_elements.push_back(net.add_force_element(
            {s.name, a, bb, 1.0,
             std::make_shared<LashShaft>(s.stiffness_Nm_per_rad, s.damping_Nms_per_rad, s.lash_rad)}));
      } else {
        net.add_shaft({s.name, a, bb, s.stiffness_Nm_per_rad, s.damping_Nms_per_rad});
      }
    }
  }

  void add_gears_and_differentials() {
    auto& links = topology.links;
    auto& fixed_nodes = topology.fixed_nodes;
    for (const auto& g : spec.gears) {
      const int a = b.node(g.name, "input", g.input, false);
      const int bb = b.node(g.name, "output", g.output, false);
      b.distinct(g.name, a, bb);
      if (!(std::isfinite(g.ratio) && g.ratio != 0.0)) throw NetworkError(g.name, "ratio must be finite and not 0");
      links.emplace_back(a, bb);
      fixed_nodes.insert({a, bb});
      net.add_gear({g.name, a, bb, g.ratio});
    }
    for (const auto& d : spec.differentials) {
      const int c = b.node(d.name, "carrier", d.carrier, false);
      const int l = b.node(d.name, "left", d.left, false);
      const int r = b.node(d.name, "right", d.right, false);
      if (c == l || c == r || l == r)
        throw NetworkError(d.name, "carrier, left and right must be three different nodes");
      links.emplace_back(c, l);
      links.emplace_back(c, r);
      fixed_nodes.insert({c, l, r});
      net.add_differential({d.name, c, l, r});
    }
  }

  // A tyre on an axle: its share of the axle's static load on the grade (the vehicle's weight
  // split, moved rearwards by m g (h/L) sin θ uphill) and the transfer ± m h/(n L) per unit
  // acceleration, n the axle's tyres on that vehicle (components/tyre.hpp).
  components::TyreParams axle_tyre_params(const TyreSpec& t, const VehicleSpec& v) const {
    components::TyreParams p = t.params;
    p.load_transfer.path_ratio = t.path_ratio;
    if (t.axle == TyreSpec::Axle::kNone) return p;
    if (!v.wheelbase_m || !v.front_axle_load_share)
      throw NetworkError(t.name,
                         "names its axle: vehicle '" + v.name + "' needs wheelbase_m and front_axle_load_share");
    const bool front = t.axle == TyreSpec::Axle::kFront;
    const auto on_axle = std::count_if(spec.tyres.begin(), spec.tyres.end(),
                                       [&](const TyreSpec& x) { return x.vehicle == t.vehicle && x.axle == t.axle; });
    const double theta = std::atan(v.grade_percent / 100.0);
    const double weight_N = v.mass_kg * kGravity_m_s2, lever = v.cg_height_m / *v.wheelbase_m;
    const double share = front ? *v.front_axle_load_share : 1.0 - *v.front_axle_load_share;
    const double axle_N = weight_N * (share * std::cos(theta) + (front ? -1.0 : 1.0) * lever * std::sin(theta));
    if (!(axle_N > 0))
      throw NetworkError(
          t.name, "its axle would lift on vehicle '" + v.name + "''s grade (cg_height_m / wheelbase_m too large)");
    const double n = static_cast<double>(on_axle);
    p.vertical_load_N = axle_N / n;
    p.load_transfer.load_per_acceleration_kg = (front ? -1.0 : 1.0) * v.mass_kg * lever / n;
    return p;
  }

  void add_tyres_and_vehicles() {
    auto& links = topology.links;
    auto& driven_nodes = topology.driven_nodes;
    for (const auto& t : spec.tyres) {
      const int w = b.node(t.name, "wheel", t.wheel, false);
      const int v = b.node(t.name, "vehicle", t.vehicle, false);
      b.distinct(t.name, w, v);
      const auto vit = std::find_if(spec.vehicles.begin(), spec.vehicles.end(),
                                    [&](const VehicleSpec& x) { return x.name == t.vehicle; });
      if (vit == spec.vehicles.end())
        throw NetworkError(t.name, "vehicle '" + t.vehicle + "' is not a component of type \"vehicle\"");
      if (!(t.path_ratio > 0)) throw NetworkError(t.name, "path_ratio must be > 0");
      std::shared_ptr<const dynamics::ForceLaw> law;
      try {
        law = std::make_shared<components::BrushTyre>(axle_tyre_params(t, *vit));
      } catch (const std::invalid_argument& e) {
        throw NetworkError(t.name, e.what());
      }
      links.emplace_back(w, v);
      out.tyre_elements.push_back(
          net.add_force_element({t.name, w, v, t.path_ratio * vit->wheel_radius_m / t.params.radius_m, law}));
    }
    for (std::size_t i = 0; i < spec.vehicles.size(); ++i) {
      const auto& v = spec.vehicles[i];
      const int n = out.vehicle_nodes[i];
      auto road = v.road;
      road.radius_m = v.wheel_radius_m;
      std::shared_ptr<const dynamics::ForceLaw> law;
      try {
        law = std::make_shared<components::RoadLoad>(road);
      } catch (const std::invalid_argument& e) {
        throw NetworkError(v.name, e.what());
      }
      out.road_elements.push_back(net.add_force_element({v.name + ".road_load", n, dynamics::kGround, 1.0, law}));
      if (v.grade_percent != 0.0) {
        const double torque =
            -v.mass_kg * kGravity_m_s2 * std::sin(std::atan(v.grade_percent / 100.0)) * v.wheel_radius_m;
        out.grade_sources.push_back(net.add_torque_source({v.name + ".grade", n, [torque](double) { return torque; }}));
        driven_nodes.insert(n);
      }
    }
  }

  void add_firing_pulsations() {
    for (const auto& f : spec.firing_pulsations) {
      const int n = b.node(f.name, "node", f.node, false);
      std::shared_ptr<const dynamics::ForceLaw> law;
      try {
        law = std::make_shared<components::EnginePulsationLaw>(f.params, units::rpm_to_rad_s(f.stall_speed_rpm),
                                                               units::rpm_to_rad_s(f.idle_speed_rpm));
      } catch (const std::invalid_argument& e) {
        throw NetworkError(f.name, e.what());
      }
      out.pulsation_elements.push_back(net.add_force_element({f.name, n, dynamics::kGround, 1.0, law}));
    }
  }

  void add_sources() {
    auto& driven_nodes = topology.driven_nodes;
    auto& fixed_nodes = topology.fixed_nodes;
    std::vector<double> motor_integrals;
    for (const auto& s : spec.torque_sources) {
      const int n = b.node(s.name, "node", s.node, false);
      driven_nodes.insert(n);
      net.add_torque_source({s.name, n, [sig = s.torque_Nm](double t) { return sig(t); }});
    }
    for (const auto& s : spec.speed_sources) {
      const int n = b.node(s.name, "node", s.node, false);
      driven_nodes.insert(n);
      fixed_nodes.insert(n);
      net.add_speed_source({s.name, n, [sig = s.speed_rpm](double t) { return units::rpm_to_rad_s(sig(t)); },
                            [sig = s.speed_rpm](double t) { return units::rpm_to_rad_s(sig.derivative(t)); }});
    }
    for (const auto& m : spec.motors) {
      const int n = b.node(m.name, "node", m.node, false);
      if (!(m.kp_Nms_per_rad >= 0) || !(m.ki_Nm_per_rad >= 0) || !(m.kp_Nms_per_rad + m.ki_Nm_per_rad > 0) ||
          !(m.torque_limit_Nm > 0))
        throw NetworkError(m.name,
                           "needs kp_Nms_per_rad >= 0, ki_Nm_per_rad >= 0 (not both 0) and torque_limit_Nm > 0");
      driven_nodes.insert(n);
      net.add_motor({m.name, n, [sig = m.speed_rpm](double t) { return units::rpm_to_rad_s(sig(t)); }, m.kp_Nms_per_rad,
                     m.ki_Nm_per_rad, m.torque_limit_Nm});
      if (m.start_torque_Nm != 0.0 && !(m.ki_Nm_per_rad > 0))
        throw NetworkError(m.name, "start_torque_Nm needs an integral gain (ki_Nm_per_rad > 0) to hold it");
      motor_integrals.push_back(m.ki_Nm_per_rad > 0 ? m.start_torque_Nm / m.ki_Nm_per_rad : 0.0);
    }
    out.initial_motor_integral =
        Eigen::Map<const Eigen::VectorXd>(motor_integrals.data(), static_cast<Eigen::Index>(motor_integrals.size()));
    for (const auto& e : spec.engines) {
      const int n = b.node(e.name, "node", e.node, false);
      std::shared_ptr<const components::Engine> engine;
      try {
        engine = std::make_shared<const components::Engine>(e.params);
      } catch (const std::invalid_argument& err) {
        throw NetworkError(e.name, err.what());
      }
      driven_nodes.insert(n);
      dynamics::TorqueSource src{e.name, n, [](double) { return 0.0; }};
      src.torque_at_speed_Nm = [engine, throttle = e.throttle](double t, double w) {
        return engine->torque_Nm(w, std::clamp(throttle(t), 0.0, 1.0));
      };
      out.engine_sources.push_back(net.add_torque_source(std::move(src)));
    }
    // A drive's torque ripple at its speed reference's revolutions (components/motor_ripple.hpp).
    for (const auto& m : spec.motors) {
      if (m.ripple.amplitude_Nm == 0.0) continue;
      if (!(m.ripple.amplitude_Nm > 0) || !(m.ripple.periods_per_rev > 0))
        throw NetworkError(m.name, "ripple_amplitude_Nm must be >= 0 and ripple_periods_per_rev > 0");
      const components::MotorRippleTorque ripple(m.ripple, force_schedule(m.speed_rpm, 1.0, duration, false));
      out.ripple_sources.push_back(net.add_torque_source(
          {m.name + ".ripple", b.node(m.name, "node", m.node, false), [ripple](double t) { return ripple(t); }}));
    }
  }

  void finish() {
    try {
      net.validate();
    } catch (const std::invalid_argument& e) {
      throw NetworkError("", e.what());
    }
    const auto state_at = net.contact_state_indices();
    for (auto& bc : out.clutches)
      if (bc.haldex) bc.state_index = state_at[static_cast<std::size_t>(bc.contact)];
  }
};

}  // namespace

clutch::WetClutchParams pack_params(const ClutchSpec& c) {
  clutch::WetClutchParams pack = c.wet.clutch;
  if (c.law != ClutchSpec::Law::kHaldex) return pack;
  clutch::ThermalParams with_pack_oil = pack.thermal;
  apply_pack_oil(c.haldex.pack_oil_volume_ml, c.haldex.pack_cooling_flow_ml_min, pack.sliding_interfaces,
                 with_pack_oil);
  if (!c.wet.oil_volume_given) pack.thermal.sump_volume_m3 = with_pack_oil.sump_volume_m3;
  if (!c.wet.oil_flow_given) pack.thermal.supply_flow_m3_s = with_pack_oil.supply_flow_m3_s;
  return pack;
}

double BuiltClutch::scheduled_force_N(double t_s) const {
  return spec->max_force_N * std::max(spec->force_signal(t_s), 0.0);
}

double BuiltClutch::normal_force_N(const dynamics::Sample& s) const {
  return haldex ? haldex->clamp_force_N(s.contact_states.data() + state_index) : scheduled_force_N(s.t_s);
}

std::unique_ptr<BuiltNetwork> build_network(const NetworkSpec& spec, NetworkChecks checks) {
  auto built = std::make_unique<BuiltNetwork>();
  const bool topology = checks == NetworkChecks::kAll;
  Assembly a(spec, *built);
  a.add_nodes();
  a.add_clutches();
  if (topology) check_judged_on(spec);
  a.add_freewheels();
  a.add_shafts();
  a.add_gears_and_differentials();
  a.add_tyres_and_vehicles();
  a.add_firing_pulsations();
  a.add_sources();
  if (topology) {
    check_massless_nodes(spec, a.topology);
    check_constraints(spec, *built);
    check_connected(*built, a.topology);
  }
  a.finish();
  return built;
}

OwnedNetwork::OwnedNetwork(NetworkSpec spec, NetworkChecks checks)
    : spec_(std::make_unique<const NetworkSpec>(std::move(spec))), built_(build_network(*spec_, checks)) {}

const BuiltClutch& OwnedNetwork::clutch(std::size_t c) const {
  if (c >= built_->clutches.size())
    throw std::invalid_argument("network: clutch " + std::to_string(c) + " asked of a network with " +
                                std::to_string(built_->clutches.size()) + " clutches");
  return built_->clutches[c];
}

ClutchContext& OwnedNetwork::clutch_context(std::size_t c) const {
  const BuiltClutch& b = clutch(c);
  if (!b.context) throw std::invalid_argument("clutch '" + b.name() + "' has no held inputs: it is not a wet clutch");
  return *b.context;
}

HaldexCommand& OwnedNetwork::command(std::size_t c) const {
  const BuiltClutch& b = clutch(c);
  if (!b.command)
    throw std::invalid_argument("clutch '" + b.name() + "' has no valve command: it is not a Haldex coupling");
  return *b.command;
}

}  // namespace shudder::components
