#include "io/network_scenario.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <optional>
#include <numbers>

#include "components/network_builder.hpp"
#include "core/nearest_name.hpp"
#include "core/units.hpp"
#include "io/haldex_tables.hpp"
#include "io/input_error.hpp"
#include "io/network_components.hpp"
#include "io/scenario.hpp"
#include "io/toml_reader.hpp"

namespace shudder::io {

namespace {

using components::Signal;

constexpr double kGravity_m_s2 = 9.80665;

std::string list(const std::vector<std::string>& v) {
  std::string s;
  for (const auto& x : v) s += (s.empty() ? "" : ", ") + x;
  return s;
}

std::string one_of(TomlTable& t, const std::string& key, const std::vector<std::string>& allowed) {
  const std::string v = t.string(key);
  if (std::find(allowed.begin(), allowed.end(), v) != allowed.end()) return v;
  const std::string near = nearest_key(v, allowed);
  t.fail(key, "'" + v + "' is not allowed" + (near.empty() ? "" : "; did you mean '" + near + "'?") +
                  " (allowed: " + list(allowed) + ")");
}

Signal read_signal_table(TomlTable& t) {
  // A table without `kind` is a constant (so a sweep can set NAME.normal_force.value alone).
  const std::string kind = t.has("kind") ? one_of(t, "kind", signal_kinds()) : std::string("constant");
  const ComponentDecl& d = signal_decl(kind);
  const auto num = [&](const std::string& key) { return read_number(t, d, key); };
  Signal s = Signal::constant(0.0);
  if (kind == "constant") {
    s = Signal::constant(num("value"));
  } else if (kind == "table") {
    const auto times = t.numbers("time_s", Range::non_negative(), 1);
    const auto values = t.numbers("value", {}, 1);
    if (values.size() != times.size())
      t.fail("value",
             "has " + std::to_string(values.size()) + " values but time_s has " + std::to_string(times.size()));
    for (std::size_t i = 1; i < times.size(); ++i)
      if (!(times[i] > times[i - 1])) t.fail("time_s", "must be strictly increasing");
    const auto& interp = d.key("interpolation").choices;
    s = Signal::table(times, values, t.choice_or("interpolation", interp.front(), interp) == "linear");
  } else if (kind == "step") {
    s = Signal::step(num("time_s"), num("before"), num("after"));
  } else if (kind == "sine") {
    s = Signal::sine(num("offset"), num("amplitude"), num("frequency_Hz"), num("phase_deg") * std::numbers::pi / 180.0,
                     num("start_s"));
  } else if (kind == "pulse") {
    const double period = num("period_s"), width = num("width_s");
    if (width > period) t.fail("width_s", "must not exceed period_s");
    s = Signal::pulse(num("low"), num("high"), period, width, num("start_s"));
  } else if (kind == "ramp") {
    s = Signal::ramp(num("from"), num("to"), num("start_s"), num("duration_s"));
  } else {  // product
    auto factors = t.table_array("factors");
    if (factors.size() < 2) t.fail("factors", "a product needs at least two factor signals");
    s = read_signal_table(factors[0]);
    for (std::size_t i = 1; i < factors.size(); ++i) s = Signal::product(s, read_signal_table(factors[i]));
  }
  t.finish();
  return s;
}

/// `key` as a signal table, or a plain number meaning a constant; `fallback` when absent.
Signal read_signal(TomlTable& c, const std::string& key, std::optional<Signal> fallback) {
  if (!c.has(key)) {
    if (!fallback)
      c.fail(key, "missing; give a signal: a number, or a table with kind = one of " + list(signal_kinds()));
    c.mark_read(key);
    return *fallback;
  }
  if (c.is_table(key)) {
    auto t = c.table(key);
    return read_signal_table(t);
  }
  return Signal::constant(c.number(key));
}

// Plain friction: mu, peak ratio and the geometry factor (components/plain_friction.hpp).
components::PlainFrictionParams read_plain(TomlTable& c, const ComponentDecl& d) {
  const auto num = [&](const std::string& key) { return read_number(c, d, key); };
  components::PlainFrictionParams p;
  const bool table = c.has("mu_table"), constant = c.has("mu");
  if (table == constant) c.fail(constant ? "mu_table" : "mu", "give exactly one of mu (a constant) or mu_table");
  if (constant) {
    p.slip_rpm = {0.0};
    p.mu = {num("mu")};
  } else {
    auto t = c.table("mu_table");
    p.slip_rpm = t.numbers("slip_rpm", Range::non_negative(), 1);
    p.mu = t.numbers("mu", Range::positive(), 1);
    if (p.mu.size() != p.slip_rpm.size())
      t.fail("mu",
             "has " + std::to_string(p.mu.size()) + " values but slip_rpm has " + std::to_string(p.slip_rpm.size()));
    for (std::size_t i = 1; i < p.slip_rpm.size(); ++i)
      if (!(p.slip_rpm[i] > p.slip_rpm[i - 1])) t.fail("slip_rpm", "must be strictly increasing");
    t.finish();
  }
  p.peak_ratio = num("peak_ratio");
  const bool by_factor = c.has("geometry_factor_m"), by_mean = c.has("mean_radius_m"),
             by_annulus = c.has("inner_radius_m") || c.has("outer_radius_m");
  if (by_factor + by_mean + by_annulus != 1)
    c.fail(by_factor ? "geometry_factor_m" : "mean_radius_m",
           "give exactly one geometry: geometry_factor_m, or mean_radius_m with interfaces, or inner_radius_m and "
           "outer_radius_m with interfaces");
  if (by_factor) {
    p.geometry_factor_m = num("geometry_factor_m");
  } else {
    const double n = num("interfaces");
    if (by_mean) {
      p.geometry_factor_m = n * num("mean_radius_m");
    } else {
      const double ri = num("inner_radius_m"), ro = num("outer_radius_m");
      if (!(ro > ri)) c.fail("outer_radius_m", "must exceed inner_radius_m");
      p.geometry_factor_m = n * (2.0 / 3.0) * (ro * ro * ro - ri * ri * ri) / (ro * ro - ri * ri);  // uniform pressure
    }
  }
  return p;
}

void read_component(TomlTable& c, const std::string& name, const std::string& path, NetworkScenario& sc) {
  auto& spec = sc.spec;
  const std::string type = one_of(c, "type", component_types());
  const ComponentDecl& d = component_decl(type);
  const auto num = [&](const std::string& key) { return read_number(c, d, key); };
  const auto node = [&](const std::string& key) {
    d.key(key);  // declared
    return c.string(key);
  };
  if (type == "inertia") {
    spec.inertias.push_back({name, num("inertia_kg_m2"), units::rpm_to_rad_s(num("speed_rpm")),
                             num("angle_deg") * std::numbers::pi / 180.0});
  } else if (type == "shaft") {
    components::ShaftSpec s{name,
                            node("from"),
                            node("to"),
                            num("stiffness_Nm_per_rad"),
                            num("damping_Nms_per_rad"),
                            num("lash_deg") * std::numbers::pi / 180.0};
    if (s.stiffness_Nm_per_rad == 0 && s.damping_Nms_per_rad == 0)
      c.fail("stiffness_Nm_per_rad", "a shaft needs stiffness_Nm_per_rad > 0 or damping_Nms_per_rad > 0");
    spec.shafts.push_back(s);
  } else if (type == "gear") {
    const double ratio = num("ratio");
    if (ratio == 0.0) c.fail("ratio", "must not be 0 (speed of input = ratio x speed of output)");
    spec.gears.push_back({name, node("input"), node("output"), ratio});
  } else if (type == "differential") {
    spec.differentials.push_back({name, node("carrier"), node("left"), node("right")});
  } else if (type == "clutch" || type == "brake") {
    components::ClutchSpec k;
    k.name = name;
    if (type == "clutch") {
      k.a = node("from");
      k.b = node("to");
    } else {
      k.a = node("node");
      k.b = components::kGroundNode;
    }
    k.max_force_N = num("max_force_N");
    if (gives(c, d.key("judged_on").key)) k.judged_on = c.string("judged_on");
    k.force_signal = read_signal(c, "normal_force", Signal::constant(1.0));
    const auto& laws = d.key("law").choices;
    const std::string law = c.choice_or("law", laws.front(), laws);
    if (law == "plain") {
      k.law = components::ClutchSpec::Law::kPlain;
      k.plain = read_plain(c, d);
      for (const char* wet_only : {"clutch", "effects"})
        if (c.has(wet_only)) c.fail(wet_only, "belongs to law = \"wet\"; a plain clutch takes mu or mu_table");
    } else {
      k.law = components::ClutchSpec::Law::kWet;
      for (const char* plain_only : {"mu", "mu_table", "peak_ratio", "geometry_factor_m", "mean_radius_m",
                                     "inner_radius_m", "outer_radius_m", "interfaces"})
        if (c.has(plain_only))
          c.fail(plain_only,
                 "belongs to law = \"plain\"; a wet clutch's friction comes from its fluid and its "
                 "geometry from its [clutch] table");
      k.wet = read_wet_pack(c, path, sc.warnings);
      sc.fluid_paths.push_back(k.wet.fluid_path);
      sc.fluid_texts += "# file: " + k.wet.fluid_path + " (clutch " + name + ")\n" + k.wet.fluid_text + "\n";
    }
    spec.clutches.push_back(std::move(k));
  } else if (type == "haldex_coupling") {
    components::ClutchSpec k;
    k.name = name;
    k.law = components::ClutchSpec::Law::kHaldex;
    k.a = node("from");
    k.b = node("to");
    auto& h = k.haldex;
    h.front_axle = node("front_axle");
    h.rear_axle = node("rear_axle");
    h.front_path_ratio = num("front_path_ratio");
    h.rear_path_ratio = num("rear_path_ratio");
    h.wheel_radius_m = gives(c, "wheel_radius_m") ? num("wheel_radius_m") : std::nan("");  // default: the vehicle's
    if (!gives(c, "wheel_radius_m")) c.mark_read("wheel_radius_m");
    h.pedal = read_signal(c, "pedal", Signal::constant(0.0));
    if (c.has("valve_opening")) h.valve_opening = read_signal(c, "valve_opening", std::nullopt);
    if (c.has("valve_pressure_bar")) h.valve_pressure_bar = read_signal(c, "valve_pressure_bar", std::nullopt);
    if (h.valve_opening && h.valve_pressure_bar)
      c.fail("valve_pressure_bar",
             "valve_opening is given too; give one raw valve schedule, or neither (the control unit)");
    h.nominal_friction = num("nominal_friction");
    h.pack_oil_volume_ml = num("pack_oil_volume_ml");
    h.pack_cooling_flow_ml_min = num("pack_cooling_flow_ml_min");
    if (auto t = c.optional_table("hydraulics")) read_haldex_hydraulics(*t, h.hydraulics);
    if (c.has("controller") && (h.valve_opening || h.valve_pressure_bar))
      c.fail("controller", "is given with a raw valve schedule; give either the schedule or the controller");
    if (auto t = c.optional_table("controller")) read_haldex_controller(*t, h.controller);
    const double duration = sc.spec.settings.duration_s;
    if (h.valve_opening &&
        (h.valve_opening->min_over(0.0, duration) < 0 || h.valve_opening->max_over(0.0, duration) > 1))
      c.fail("valve_opening", "must stay within [0, 1] (0 shut, 1 open) over the run");
    if (h.valve_pressure_bar && (h.valve_pressure_bar->min_over(0.0, duration) < 0 ||
                                 h.valve_pressure_bar->max_over(0.0, duration) > h.hydraulics.relief_pressure_bar))
      c.fail("valve_pressure_bar", "must stay within [0, relief_pressure_bar = " +
                                       std::to_string(h.hydraulics.relief_pressure_bar) + " bar] over the run");
    if (gives(c, d.key("judged_on").key)) k.judged_on = c.string("judged_on");
    k.wet = read_wet_pack(c, path, sc.warnings);
    sc.fluid_paths.push_back(k.wet.fluid_path);
    sc.fluid_texts += "# file: " + k.wet.fluid_path + " (coupling " + name + ")\n" + k.wet.fluid_text + "\n";
    spec.clutches.push_back(std::move(k));
  } else if (type == "firing_pulsation") {
    components::FiringPulsationSpec f;
    f.name = name;
    f.node = node("node");
    f.params.amplitude_Nm = num("amplitude_Nm");
    f.params.cylinders = static_cast<int>(num("cylinders"));
    f.stall_speed_rpm = num("stall_speed_rpm");
    f.idle_speed_rpm = num("idle_speed_rpm");
    if (!(f.idle_speed_rpm > f.stall_speed_rpm)) c.fail("idle_speed_rpm", "must exceed stall_speed_rpm");
    spec.firing_pulsations.push_back(f);
  } else if (type == "freewheel") {
    spec.freewheels.push_back({name, node("driving"), node("driven"), num("drag_Nm")});
  } else if (type == "torque_source") {
    spec.torque_sources.push_back({name, node("node"), read_signal(c, "torque_Nm", std::nullopt)});
  } else if (type == "speed_source") {
    spec.speed_sources.push_back({name, node("node"), read_signal(c, "speed_rpm", std::nullopt)});
  } else if (type == "motor") {
    spec.motors.push_back({name,
                           node("node"),
                           read_signal(c, "speed_rpm", std::nullopt),
                           num("kp_Nms_per_rad"),
                           num("ki_Nm_per_rad"),
                           num("torque_limit_Nm"),
                           num("start_torque_Nm"),
                           {num("ripple_amplitude_Nm"), num("ripple_periods_per_rev")}});
    if (spec.motors.back().start_torque_Nm != 0 && spec.motors.back().ki_Nm_per_rad == 0)
      c.fail("start_torque_Nm", "needs ki_Nm_per_rad > 0: the integrator holds the start torque");
    if (spec.motors.back().kp_Nms_per_rad == 0 && spec.motors.back().ki_Nm_per_rad == 0)
      c.fail("kp_Nms_per_rad", "a speed loop needs kp_Nms_per_rad > 0 or ki_Nm_per_rad > 0");
  } else if (type == "engine") {
    components::EngineSpec e;
    e.name = name;
    e.node = node("node");
    e.throttle = read_signal(c, "throttle", std::nullopt);
    auto& p = e.params;
    if (auto fl = c.optional_table("full_load")) {
      const auto n = fl->numbers("speed_rpm", Range::non_negative(), 2);
      const auto tq = fl->numbers("torque_Nm", Range::non_negative(), 2);
      if (n.size() != tq.size()) fl->fail("torque_Nm", "needs one value per speed_rpm");
      for (std::size_t i = 1; i < n.size(); ++i)
        if (!(n[i] > n[i - 1])) fl->fail("speed_rpm", "must be strictly increasing");
      p.full_load_torque_Nm = components::PiecewiseLinear(n, tq);
      fl->finish();
    }
    p.idle_speed_rpm = num("idle_speed_rpm");
    p.stall_speed_rpm = num("stall_speed_rpm");
    if (!(p.idle_speed_rpm > p.stall_speed_rpm)) c.fail("idle_speed_rpm", "must exceed stall_speed_rpm");
    p.idle_governor_gain_Nms_per_rad = num("idle_governor_gain_Nms_per_rad");
    p.loss_torque_idle_Nm = num("loss_torque_idle_Nm");
    p.loss_torque_max_Nm = num("loss_torque_max_Nm");
    p.max_speed_rpm = num("max_speed_rpm");
    spec.engines.push_back(std::move(e));
  } else if (type == "vehicle") {
    components::VehicleSpec v;
    v.name = name;
    v.mass_kg = num("mass_kg");
    v.wheel_radius_m = num("wheel_radius_m");
    v.speed_m_s = num("speed_km_h") / 3.6;
    v.grade_percent = num("grade_percent");
    const double f_r = num("rolling_resistance_coefficient");
    v.road.rolling_resistance_N = f_r * v.mass_kg * kGravity_m_s2 * std::cos(std::atan(v.grade_percent / 100.0));
    v.road.drag_coefficient_area_m2 = num("drag_area_m2");
    v.road.air_density_kg_m3 = num("air_density_kg_m3");
    v.cg_height_m = num("cg_height_m");
    if (gives(c, "wheelbase_m"))
      v.wheelbase_m = num("wheelbase_m");
    else
      c.mark_read("wheelbase_m");
    if (gives(c, "front_axle_load_share"))
      v.front_axle_load_share = num("front_axle_load_share");
    else
      c.mark_read("front_axle_load_share");
    spec.vehicles.push_back(v);
  } else if (type == "tyre") {
    components::TyreSpec t;
    t.name = name;
    t.wheel = node("wheel");
    t.vehicle = node("vehicle");
    auto& p = t.params;
    const auto& axles = d.key("axle").choices;
    const std::string axle = c.choice_or("axle", axles.front(), axles);
    t.axle = axle == "front"  ? components::TyreSpec::Axle::kFront
             : axle == "rear" ? components::TyreSpec::Axle::kRear
                              : components::TyreSpec::Axle::kNone;
    if (t.axle == components::TyreSpec::Axle::kNone) {
      if (!gives(c, "vertical_load_N"))
        c.fail("vertical_load_N", "is required for a tyre without an axle (or name its axle = \"front\" or \"rear\")");
      p.vertical_load_N = num("vertical_load_N");
    } else {
      if (gives(c, "vertical_load_N"))
        c.fail(
            "vertical_load_N",
            "is not for a tyre on an axle: it takes its load from the vehicle (give one of vertical_load_N and axle)");
      c.mark_read("vertical_load_N");
    }
    if (gives(c, "slip_stiffness_N") && gives(c, "slip_stiffness_per_load"))
      c.fail("slip_stiffness_per_load",
             "is an alternative to slip_stiffness_N; give one (C_kappa / F_z, or an absolute C_kappa)");
    if (gives(c, "slip_stiffness_N"))
      p.slip_stiffness_N = num("slip_stiffness_N");
    else
      c.mark_read("slip_stiffness_N");
    if (gives(c, "slip_stiffness_per_load"))
      p.slip_stiffness_per_load = num("slip_stiffness_per_load");
    else
      c.mark_read("slip_stiffness_per_load");
    p.relaxation_length_m = num("relaxation_length_m");
    p.road_friction = num("road_friction");
    p.radius_m = gives(c, "radius_m") ? num("radius_m") : std::nan("");  // default: the vehicle's wheel radius
    if (!gives(c, "radius_m")) c.mark_read("radius_m");
    t.path_ratio = num("path_ratio");
    spec.tyres.push_back(t);
  }
  c.finish();
}

}  // namespace

std::string scenario_type(const std::string& path) { return scenario_type_of_text(read_scenario_text(path), path); }

std::string scenario_type_of_text(const std::string& text, const std::string& path) {
  const toml::table doc = TomlTable::parse_text(text, path);
  if (const auto* head = doc["scenario"].as_table())
    if (const auto* type = (*head)["type"].as_string()) return type->get();
  return "prescribed_slip";
}

NetworkScenario load_network_scenario(const std::string& path) {
  return load_network_scenario_text(read_scenario_text(path), path);
}

NetworkScenario load_network_scenario_text(const std::string& text, const std::string& path) {
  NetworkScenario sc;
  sc.path = path;
  sc.text = text;
  const toml::table doc = TomlTable::parse_text(text, path);
  TomlTable root(doc, path, "");
  auto& cfg = sc.spec.settings;
  {
    auto head = root.table("scenario");
    sc.name = head.string_or("name", std::filesystem::path(path).stem().string());
    head.choice_or("type", "network", {"network"});
    sc.description = head.string_or("description", "");
    cfg.duration_s = head.number("duration_s", Range::closed(1e-3, 1e5));
    head.finish();
  }
  // Rings of every wet pack's thermal grid (as a scenario's [solver] radial_cells): the friction
  // of each right-hand side and the thermal solve cost in proportion to them.
  std::optional<int> radial_cells;
  if (auto solver = root.optional_table("solver")) {
    if (solver->has("radial_cells")) radial_cells = static_cast<int>(solver->integer_or("radial_cells", 20, 2, 2000));
    cfg.thermal_step_s =
        solver->number_or("thermal_step_ms", cfg.thermal_step_s * 1e3, Range::closed(1e-3, 1e4)) * 1e-3;
    auto& integ = cfg.integrator;
    integ.abs_tol = solver->number_or("abs_tol", integ.abs_tol, Range::closed(1e-15, 1e-2));
    integ.rel_tol = solver->number_or("rel_tol", integ.rel_tol, Range::closed(1e-15, 1e-2));
    integ.max_step_s = solver->number_or("max_step_ms", integ.max_step_s * 1e3, Range::closed(1e-6, 1e3)) * 1e-3;
    solver->finish();
  }
  if (auto out = root.optional_table("output")) {
    cfg.sample_rate_Hz = out->number_or("sample_rate_Hz", cfg.sample_rate_Hz, Range::closed(1e-3, 1e6));
    out->finish();
  }
  auto net = root.table("network");
  const auto names = net.subtable_keys();
  for (const auto& name : names) {
    auto c = net.table(name);
    read_component(c, name, path, sc);
  }
  net.finish();
  root.finish();
  if (radial_cells)
    for (auto& k : sc.spec.clutches)
      if (k.law != components::ClutchSpec::Law::kPlain) k.wet.clutch.thermal.radial_cells = *radial_cells;
  // A tyre's radius defaults to its vehicle's wheel radius.
  for (auto& t : sc.spec.tyres)
    if (std::isnan(t.params.radius_m)) {
      for (const auto& v : sc.spec.vehicles)
        if (v.name == t.vehicle) t.params.radius_m = v.wheel_radius_m;
      if (std::isnan(t.params.radius_m)) t.params.radius_m = 0.3;  // the builder names the missing vehicle
    }

  // A coupling's wheel radius defaults to the network's one vehicle's.
  for (auto& k : sc.spec.clutches) {
    if (k.law != components::ClutchSpec::Law::kHaldex || !std::isnan(k.haldex.wheel_radius_m)) continue;
    if (sc.spec.vehicles.size() != 1) {
      const auto* n = doc["network"][k.name].node();
      throw InputError(path, n ? static_cast<long>(n->source().begin.line) : 0, "network." + k.name + ".wheel_radius_m",
                       "missing; the network has " + std::to_string(sc.spec.vehicles.size()) +
                           " vehicles to take it from: give the rolling radius the control unit maps axle speed with");
    }
    k.haldex.wheel_radius_m = sc.spec.vehicles.front().wheel_radius_m;
  }

  // Build once: a bad network is an input error at the component's line.
  try {
    components::build_network(sc.spec);
  } catch (const components::NetworkError& e) {
    long line = 0;
    std::string key = "network";
    if (!e.component().empty()) {
      key += "." + e.component();
      if (const auto* n = doc["network"][e.component()].node()) line = static_cast<long>(n->source().begin.line);
    }
    std::string msg = e.what();
    const std::string prefix = "component '" + e.component() + "': ";
    if (msg.rfind(prefix, 0) == 0) msg = msg.substr(prefix.size());
    throw InputError(path, line, key, msg);
  }
  return sc;
}

}  // namespace shudder::io
