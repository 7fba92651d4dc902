#include "components/network_builder.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>
#include <set>

#include "components/lash_shaft.hpp"
#include "components/one_way_clutch.hpp"
#include "core/nearest_name.hpp"
#include "core/units.hpp"
#include "rig_models/haldex_driveline.hpp"

namespace shudder::components {

namespace {

constexpr double kGravity_m_s2 = 9.80665;

// The wet clutch reads its clamp force as a piecewise-linear schedule (rig_models/drive_cycle.hpp):
// the signal at its knots (a jump becomes a 1 µs ramp) and, for a sine or a product, at 20000
// points over the run besides: a sine of f Hz over D s gets 20000 / (f D) points a period, and at
// 20 a period the chords miss it by at most 1 - cos(pi / 20) = 1.2 % of its amplitude.
rig_models::PiecewiseLinear force_schedule(const Signal& s, double scale_N, double duration_s, bool clamp_at_zero = true) {
  constexpr double kJump_s = 1e-6;
  std::vector<double> t{0.0, duration_s};
  for (double k : s.knots(0.0, duration_s)) {
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
      if (!ground_ok)
        throw NetworkError(component, role + " cannot be \"ground\"; name an inertia or vehicle");
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
                                      (near.empty() ? "" : "; did you mean '" + near + "'?") + " (nodes: " + list + ")");
  }
  void distinct(const std::string& component, int a, int b) const {
    if (a == b)
      throw NetworkError(component, "is joined to itself (both ends on '" +
                                        (a == dynamics::kGround ? std::string(kGroundNode) : out.node_names[a]) +
                                        "'); join two different nodes");
  }
};

// The Haldex coupling: the pack as a wet clutch in its own oil, clamped by its hydraulics
// (rig_models/haldex_coupling_law.hpp); the nodes its control unit reads.
void build_haldex(const ClutchSpec& c, BuiltClutch& bc, const Builder& b, double duration_s) {
  const HaldexSpec& h = c.haldex;
  try {
    const clutch::WetClutchParams pack = pack_params(c);
    bc.wet = std::make_unique<clutch::WetClutch>(pack, c.wet.fluid);
    const rig_models::HaldexHydraulics hydraulics(
        h.hydraulics, pack.sliding_interfaces * h.nominal_friction * bc.wet->mean_radius_m());
    const rig_models::ClutchContact contact(*bc.wet, c.wet.bearing_drag, c.wet.stick_time);
    bc.context = std::make_shared<rig_models::ClutchContext>(
        contact.start_inputs(rig_models::PiecewiseLinear({0.0}, {hydraulics.clamp_force_N(0.0)})));
    bc.command = std::make_shared<rig_models::HaldexCommand>();
    bc.command->setting_bar = h.hydraulics.relief_pressure_bar;
    if (h.valve_pressure_bar) {
      bc.command->setting_schedule_bar = force_schedule(*h.valve_pressure_bar, 1.0, duration_s);
      bc.command->opening = 0.0;  // shut below the setting
    }
    bc.haldex = std::make_shared<const rig_models::HaldexCouplingLaw>(contact, bc.context, hydraulics, bc.command);
  } catch (const std::invalid_argument& e) {
    throw NetworkError(c.name, e.what());
  }
  bc.geometry_factor_m = c.wet.clutch.sliding_interfaces * bc.wet->mean_radius_m();
  bc.front_axle_node = b.node(c.name, "front_axle", h.front_axle, false);
  bc.rear_axle_node = b.node(c.name, "rear_axle", h.rear_axle, false);
}

}  // namespace

clutch::WetClutchParams pack_params(const ClutchSpec& c) {
  clutch::WetClutchParams pack = c.wet.clutch;
  if (c.law != ClutchSpec::Law::kHaldex) return pack;
  rig_models::DrivelineParams oil;
  oil.pack_oil_volume_ml = c.haldex.pack_oil_volume_ml;
  oil.pack_cooling_flow_ml_min = c.haldex.pack_cooling_flow_ml_min;
  clutch::ThermalParams with_pack_oil = pack.thermal;
  rig_models::apply_pack_oil(oil, pack.sliding_interfaces, with_pack_oil);
  if (!c.wet.oil_volume_given) pack.thermal.sump_volume_m3 = with_pack_oil.sump_volume_m3;
  if (!c.wet.oil_flow_given) pack.thermal.supply_flow_m3_s = with_pack_oil.supply_flow_m3_s;
  return pack;
}

double BuiltClutch::scheduled_force_N(double t_s) const { return spec->max_force_N * std::max(spec->force_signal(t_s), 0.0); }

double BuiltClutch::normal_force_N(const dynamics::Sample& s) const {
  return haldex ? haldex->clamp_force_N(s.contact_states.data() + state_index) : scheduled_force_N(s.t_s);
}

std::unique_ptr<BuiltNetwork> build_network(const NetworkSpec& spec) {
  auto built = std::make_unique<BuiltNetwork>();
  BuiltNetwork& out = *built;
  Builder b{spec, out, {}};
  auto& net = out.network;
  const double duration = spec.settings.duration_s;

  // Nodes.
  std::vector<double> speeds, angles;
  for (const auto& i : spec.inertias) {
    if (i.name == kGroundNode) throw NetworkError(i.name, "\"ground\" is the fixed frame; give the inertia another name");
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
  if (out.node_names.empty()) throw NetworkError("", "the network has no inertia; add at least one [network.NAME] with type = \"inertia\"");
  out.initial_speed_rad_s = Eigen::Map<const Eigen::VectorXd>(speeds.data(), static_cast<Eigen::Index>(speeds.size()));
  out.initial_angle_rad = Eigen::Map<const Eigen::VectorXd>(angles.data(), static_cast<Eigen::Index>(angles.size()));

  // Two-node links, for the connectivity check: (a, b) per link.
  std::vector<std::pair<int, int>> links;
  std::set<int> driven_nodes;  // nodes a source, motor, engine or speed source acts on
  std::set<int> fixed_nodes;   // nodes whose speed a gear, differential or speed source ties

  // Clutches and brakes first: contact index = position.
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
                                       std::to_string(duration) + " s), so the clutch can never carry torque; "
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
        bc.wet = std::make_unique<clutch::WetClutch>(c.wet.clutch, c.wet.fluid);
      } catch (const std::invalid_argument& e) {
        throw NetworkError(c.name, e.what());
      }
      const rig_models::ClutchContact contact(*bc.wet, c.wet.bearing_drag, c.wet.stick_time);
      bc.context = std::make_shared<rig_models::ClutchContext>(
          contact.start_inputs(force_schedule(c.force_signal, c.max_force_N, duration)));
      bc.geometry_factor_m = c.wet.clutch.sliding_interfaces * bc.wet->mean_radius_m();
      bc.contact = net.add_contact({c.name, a, bb, std::make_shared<rig_models::ClutchContactLaw>(contact, bc.context)});
    } else {
      build_haldex(c, bc, b, duration);
      bc.contact = net.add_contact({c.name, a, bb, bc.haldex});
    }
    out.clutches.push_back(std::move(bc));
  }
  // A clutch judged on a shaft's torque names a shaft of the network.
  for (const auto& c : spec.clutches) {
    if (c.judged_on.empty()) continue;
    std::vector<std::string> shafts;
    for (const auto& s : spec.shafts) shafts.push_back(s.name);
    if (std::find(shafts.begin(), shafts.end(), c.judged_on) != shafts.end()) continue;
    const std::string near = nearest_key(c.judged_on, shafts);
    std::string list;
    for (const auto& n : shafts) list += (list.empty() ? "" : ", ") + n;
    throw NetworkError(c.name, "judged_on = '" + c.judged_on + "' is no shaft of the network" +
                                   (near.empty() ? "" : "; did you mean '" + near + "'?") +
                                   (list.empty() ? " (it has no shaft)" : " (shafts: " + list + ")"));
  }
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

  for (const auto& s : spec.shafts) {
    const int a = b.node(s.name, "node", s.a, false);
    const int bb = b.node(s.name, "node", s.b, true);
    b.distinct(s.name, a, bb);
    if (!(s.stiffness_Nm_per_rad >= 0) || !(s.damping_Nms_per_rad >= 0) ||
        !(s.stiffness_Nm_per_rad > 0 || s.damping_Nms_per_rad > 0))
      throw NetworkError(s.name, "needs stiffness_Nm_per_rad >= 0 and damping_Nms_per_rad >= 0, not both 0");
    links.emplace_back(a, bb);
    if (s.lash_rad > 0) {
      if (!(s.stiffness_Nm_per_rad > 0)) throw NetworkError(s.name, "a shaft with lash needs stiffness_Nm_per_rad > 0");
      if (bb == dynamics::kGround) throw NetworkError(s.name, "a shaft with lash joins two nodes; ground is not allowed");
      out.lash_elements.push_back(net.add_force_element(
          {s.name, a, bb, 1.0, std::make_shared<LashShaft>(s.stiffness_Nm_per_rad, s.damping_Nms_per_rad, s.lash_rad)}));
    } else {
      net.add_shaft({s.name, a, bb, s.stiffness_Nm_per_rad, s.damping_Nms_per_rad});
    }
  }
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
    if (c == l || c == r || l == r) throw NetworkError(d.name, "carrier, left and right must be three different nodes");
    links.emplace_back(c, l);
    links.emplace_back(c, r);
    fixed_nodes.insert({c, l, r});
    net.add_differential({d.name, c, l, r});
  }
  for (const auto& t : spec.tyres) {
    const int w = b.node(t.name, "wheel", t.wheel, false);
    const int v = b.node(t.name, "vehicle", t.vehicle, false);
    b.distinct(t.name, w, v);
    const auto vit = std::find_if(spec.vehicles.begin(), spec.vehicles.end(), [&](const VehicleSpec& x) { return x.name == t.vehicle; });
    if (vit == spec.vehicles.end()) throw NetworkError(t.name, "vehicle '" + t.vehicle + "' is not a component of type \"vehicle\"");
    std::shared_ptr<const dynamics::ForceLaw> law;
    try {
      law = std::make_shared<rig_models::BrushTyre>(t.params);
    } catch (const std::invalid_argument& e) {
      throw NetworkError(t.name, e.what());
    }
    if (!(t.path_ratio > 0)) throw NetworkError(t.name, "path_ratio must be > 0");
    links.emplace_back(w, v);
    out.tyre_elements.push_back(net.add_force_element({t.name, w, v, t.path_ratio * vit->wheel_radius_m / t.params.radius_m, law}));
  }
  for (std::size_t i = 0; i < spec.vehicles.size(); ++i) {
    const auto& v = spec.vehicles[i];
    const int n = out.vehicle_nodes[i];
    auto road = v.road;
    road.radius_m = v.wheel_radius_m;
    std::shared_ptr<const dynamics::ForceLaw> law;
    try {
      law = std::make_shared<rig_models::RoadLoad>(road);
    } catch (const std::invalid_argument& e) {
      throw NetworkError(v.name, e.what());
    }
    out.road_elements.push_back(net.add_force_element({v.name + ".road_load", n, dynamics::kGround, 1.0, law}));
    if (v.grade_percent != 0.0) {
      const double torque = -v.mass_kg * kGravity_m_s2 * std::sin(std::atan(v.grade_percent / 100.0)) * v.wheel_radius_m;
      out.grade_sources.push_back(net.add_torque_source({v.name + ".grade", n, [torque](double) { return torque; }}));
      driven_nodes.insert(n);
    }
  }

  for (const auto& f : spec.firing_pulsations) {
    const int n = b.node(f.name, "node", f.node, false);
    std::shared_ptr<const dynamics::ForceLaw> law;
    try {
      law = std::make_shared<rig_models::EnginePulsationLaw>(f.params, units::rpm_to_rad_s(f.stall_speed_rpm),
                                                             units::rpm_to_rad_s(f.idle_speed_rpm));
    } catch (const std::invalid_argument& e) {
      throw NetworkError(f.name, e.what());
    }
    out.pulsation_elements.push_back(net.add_force_element({f.name, n, dynamics::kGround, 1.0, law}));
  }

  // Sources.
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
      throw NetworkError(m.name, "needs kp_Nms_per_rad >= 0, ki_Nm_per_rad >= 0 (not both 0) and torque_limit_Nm > 0");
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
    std::shared_ptr<const rig_models::Engine> engine;
    try {
      engine = std::make_shared<const rig_models::Engine>(e.params);
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
  // A drive's torque ripple at its speed reference's revolutions (rig_models/motor_ripple.hpp).
  for (const auto& m : spec.motors) {
    if (m.ripple.amplitude_Nm == 0.0) continue;
    if (!(m.ripple.amplitude_Nm > 0) || !(m.ripple.periods_per_rev > 0))
      throw NetworkError(m.name, "ripple_amplitude_Nm must be >= 0 and ripple_periods_per_rev > 0");
    const rig_models::MotorRippleTorque ripple(m.ripple, force_schedule(m.speed_rpm, 1.0, duration, false));
    out.ripple_sources.push_back(
        net.add_torque_source({m.name + ".ripple", b.node(m.name, "node", m.node, false), [ripple](double t) { return ripple(t); }}));
  }

  // A massless node must have its speed fixed by a gear, a differential or a speed source.
  for (std::size_t i = 0; i < spec.inertias.size(); ++i)
    if (spec.inertias[i].inertia_kg_m2 == 0.0 && !fixed_nodes.count(static_cast<int>(i)))
      throw NetworkError(spec.inertias[i].name,
                         "has no inertia and nothing fixes its speed (no gear, differential or speed source on it); "
                         "give it inertia_kg_m2 > 0");

  // Gears, differentials and speed sources must be independent: a row that adds no rank closes a
  // loop the others already fix.
  {
    const int n = static_cast<int>(out.node_names.size());
    Eigen::MatrixXd g(0, n);
    const auto add_row = [&](const std::string& who, const Eigen::RowVectorXd& row, bool prescribes) {
      Eigen::MatrixXd h(g.rows() + 1, n);
      h << g, row;
      Eigen::FullPivLU<Eigen::MatrixXd> lu(h);
      lu.setThreshold(1e-10);
      if (lu.rank() <= g.rows())
        throw NetworkError(who, "over-constrains the network: the speeds it ties are already fixed by the gears, "
                                "differentials and speed sources before it (a closed loop of gears); remove it or "
                                "replace one gear of the loop by a shaft or a clutch");
      // Gears and differentials alone must leave every node free to turn: a loop whose ratios
      // disagree admits only standstill (a tie-up).
      if (!prescribes) {
        const Eigen::MatrixXd free = lu.kernel();
        for (int i = 0; i < n; ++i)
          if (lu.dimensionOfKernel() == 0 || free.row(i).norm() < 1e-9)
            throw NetworkError(who, "closes a loop of gears whose ratios disagree, which locks '" + out.node_names[i] +
                                        "' at standstill; make the ratios around the loop agree, or replace one gear by "
                                        "a shaft or a clutch");
      }
      g = h;
    };
    for (const auto& gr : net.gears()) {
      Eigen::RowVectorXd r = Eigen::RowVectorXd::Zero(n);
      r[gr.a] += 1.0;
      r[gr.b] -= gr.ratio;
      add_row(gr.name, r, false);
    }
    for (const auto& d : net.differentials()) {
      Eigen::RowVectorXd r = Eigen::RowVectorXd::Zero(n);
      r[d.left] += 1.0;
      r[d.right] += 1.0;
      r[d.carrier] -= 2.0;
      add_row(d.name, r, false);
    }
    for (const auto& s : net.speed_sources()) {
      Eigen::RowVectorXd r = Eigen::RowVectorXd::Zero(n);
      r[s.node] = 1.0;
      add_row(s.name, r, true);
    }
    // The mass left on the free motions must be positive definite (a massless node between gears
    // only, e.g., still needs mass somewhere on its side).
    const Eigen::MatrixXd basis = net.constraint_basis({});
    if (basis.cols() > 0) {
      const Eigen::MatrixXd m = basis.transpose() * net.mass_matrix() * basis;
      const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es(m);
      if (es.eigenvalues().minCoeff() <= 1e-12 * std::max(1.0, es.eigenvalues().maxCoeff())) {
        std::string massless;
        for (const auto& i : spec.inertias)
          if (i.inertia_kg_m2 == 0.0) massless += (massless.empty() ? "" : ", ") + i.name;
        throw NetworkError(massless.empty() ? "" : spec.inertias.front().name,
                           "a part of the network has no inertia (massless nodes: " + massless +
                               "); give one of its nodes inertia_kg_m2 > 0");
      }
    }
  }

  // Every part of the network must be driven or start moving: union-find over the links.
  {
    const int n = static_cast<int>(out.node_names.size());
    std::vector<int> parent(static_cast<std::size_t>(n));
    std::iota(parent.begin(), parent.end(), 0);
    const auto find = [&](int x) {
      while (parent[x] != x) x = parent[x] = parent[parent[x]];
      return x;
    };
    for (const auto& [a, bb] : links)
      if (a >= 0 && bb >= 0) parent[find(a)] = find(bb);
    std::vector<bool> alive(static_cast<std::size_t>(n), false);
    for (int i = 0; i < n; ++i)
      if (driven_nodes.count(i) || out.initial_speed_rad_s[i] != 0.0) alive[find(i)] = true;
    for (int i = 0; i < n; ++i)
      if (!alive[find(i)]) {
        std::vector<std::string> part;
        for (int j = 0; j < n; ++j)
          if (find(j) == find(i)) part.push_back(out.node_names[j]);
        std::string list;
        for (const auto& p : part) list += (list.empty() ? "" : ", ") + p;
        throw NetworkError(out.node_names[i], "its part of the network (" + list +
                                                  ") starts at rest and nothing drives it (no source, motor, engine or "
                                                  "speed source, and no link to one); connect it or give it a speed");
      }
  }

  try {
    net.validate();
  } catch (const std::invalid_argument& e) {
    throw NetworkError("", e.what());
  }
  const auto state_at = net.contact_state_indices();
  for (auto& bc : out.clutches)
    if (bc.haldex) bc.state_index = state_at[static_cast<std::size_t>(bc.contact)];
  return built;
}

}  // namespace shudder::components
