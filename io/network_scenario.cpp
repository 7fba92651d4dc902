#include "io/network_scenario.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <optional>
#include <numbers>
#include <sstream>

#include "components/network_builder.hpp"
#include "core/nearest_name.hpp"
#include "core/units.hpp"
#include "io/input_error.hpp"
#include "io/scenario.hpp"
#include "io/toml_reader.hpp"

namespace shudder::io {

namespace {

using components::Signal;

const std::vector<std::string> kComponentTypes = {"inertia",   "shaft",         "gear",         "differential",
                                                   "clutch",    "brake",         "freewheel",    "torque_source",
                                                   "speed_source", "motor",      "engine",       "vehicle",
                                                   "tyre"};
const std::vector<std::string> kSignalKinds = {"constant", "table", "step", "sine", "pulse", "ramp", "product"};
constexpr double kGravity_m_s2 = 9.80665;

std::string list(const std::vector<std::string>& v) {
  std::string s;
  for (const auto& x : v) s += (s.empty() ? "" : ", ") + x;
  return s;
}

std::string read_text(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path, 0, "", "cannot open the file for reading");
  std::ostringstream os;
  os << in.rdbuf();
  return os.str();
}

std::string one_of(TomlTable& t, const std::string& key, const std::vector<std::string>& allowed) {
  const std::string v = t.string(key);
  if (std::find(allowed.begin(), allowed.end(), v) != allowed.end()) return v;
  const std::string near = nearest_key(v, allowed);
  t.fail(key, "'" + v + "' is not allowed" + (near.empty() ? "" : "; did you mean '" + near + "'?") +
                  " (allowed: " + list(allowed) + ")");
}

Signal read_signal_table(TomlTable& t) {
  const std::string kind = one_of(t, "kind", kSignalKinds);
  Signal s = Signal::constant(0.0);
  if (kind == "constant") {
    s = Signal::constant(t.number("value"));
  } else if (kind == "table") {
    const auto times = t.numbers("time_s", Range::non_negative(), 1);
    const auto values = t.numbers("value", {}, 1);
    if (values.size() != times.size())
      t.fail("value", "has " + std::to_string(values.size()) + " values but time_s has " + std::to_string(times.size()));
    for (std::size_t i = 1; i < times.size(); ++i)
      if (!(times[i] > times[i - 1])) t.fail("time_s", "must be strictly increasing");
    const std::string interp = t.choice_or("interpolation", "linear", {"linear", "step"});
    s = Signal::table(times, values, interp == "linear");
  } else if (kind == "step") {
    s = Signal::step(t.number("time_s", Range::non_negative()), t.number_or("before", 0.0), t.number("after"));
  } else if (kind == "sine") {
    s = Signal::sine(t.number_or("offset", 0.0), t.number("amplitude"), t.number("frequency_Hz", Range::positive()),
                     t.number_or("phase_deg", 0.0) * std::numbers::pi / 180.0, t.number_or("start_s", 0.0, Range::non_negative()));
  } else if (kind == "pulse") {
    const double period = t.number("period_s", Range::positive());
    const double width = t.number("width_s", Range::positive());
    if (width > period) t.fail("width_s", "must not exceed period_s");
    s = Signal::pulse(t.number_or("low", 0.0), t.number("high"), period, width, t.number_or("start_s", 0.0, Range::non_negative()));
  } else if (kind == "ramp") {
    s = Signal::ramp(t.number_or("from", 0.0), t.number("to"), t.number_or("start_s", 0.0, Range::non_negative()),
                     t.number("duration_s", Range::non_negative()));
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
    if (!fallback) c.number(key);  // reports the missing key
    c.mark_read(key);
    return *fallback;
  }
  if (c.is_table(key)) {
    auto t = c.table(key);
    return read_signal_table(t);
  }
  return Signal::constant(c.number(key));
}

// Plain friction: μ, peak ratio and the geometry factor (components/plain_friction.hpp).
components::PlainFrictionParams read_plain(TomlTable& c) {
  components::PlainFrictionParams p;
  const bool table = c.has("mu_table"), constant = c.has("mu");
  if (table == constant) c.fail(constant ? "mu_table" : "mu", "give exactly one of mu (a constant) or mu_table");
  if (constant) {
    p.slip_rpm = {0.0};
    p.mu = {c.number("mu", Range::positive())};
  } else {
    auto t = c.table("mu_table");
    p.slip_rpm = t.numbers("slip_rpm", Range::non_negative(), 1);
    p.mu = t.numbers("mu", Range::positive(), 1);
    if (p.mu.size() != p.slip_rpm.size())
      t.fail("mu", "has " + std::to_string(p.mu.size()) + " values but slip_rpm has " + std::to_string(p.slip_rpm.size()));
    for (std::size_t i = 1; i < p.slip_rpm.size(); ++i)
      if (!(p.slip_rpm[i] > p.slip_rpm[i - 1])) t.fail("slip_rpm", "must be strictly increasing");
    t.finish();
  }
  p.peak_ratio = c.number_or("peak_ratio", 1.0, Range::closed(1.0, 10.0));
  const bool by_factor = c.has("geometry_factor_m"), by_mean = c.has("mean_radius_m"),
             by_annulus = c.has("inner_radius_m") || c.has("outer_radius_m");
  if (by_factor + by_mean + by_annulus != 1)
    c.fail(by_factor ? "geometry_factor_m" : "mean_radius_m",
           "give exactly one geometry: geometry_factor_m, or mean_radius_m with interfaces, or inner_radius_m and "
           "outer_radius_m with interfaces");
  if (by_factor) {
    p.geometry_factor_m = c.number("geometry_factor_m", Range::positive());
  } else {
    const double n = static_cast<double>(c.integer_or("interfaces", 1, 1, 64));
    if (by_mean) {
      p.geometry_factor_m = n * c.number("mean_radius_m", Range::positive());
    } else {
      const double ri = c.number("inner_radius_m", Range::positive()), ro = c.number("outer_radius_m", Range::positive());
      if (!(ro > ri)) c.fail("outer_radius_m", "must exceed inner_radius_m");
      p.geometry_factor_m = n * (2.0 / 3.0) * (ro * ro * ro - ri * ri * ri) / (ro * ro - ri * ri);  // uniform pressure
    }
  }
  return p;
}

void read_component(TomlTable& c, const std::string& name, const std::string& path, NetworkScenario& sc) {
  auto& spec = sc.spec;
  const std::string type = one_of(c, "type", kComponentTypes);
  const auto node = [&](const std::string& key) { return c.string(key); };
  if (type == "inertia") {
    spec.inertias.push_back({name, c.number("inertia_kg_m2", Range::non_negative()),
                             units::rpm_to_rad_s(c.number_or("speed_rpm", 0.0))});
  } else if (type == "shaft") {
    components::ShaftSpec s{name, node("from"), node("to"), c.number_or("stiffness_Nm_per_rad", 0.0, Range::non_negative()),
                            c.number_or("damping_Nms_per_rad", 0.0, Range::non_negative()),
                            c.number_or("lash_deg", 0.0, Range::closed(0.0, 360.0)) * std::numbers::pi / 180.0};
    if (s.stiffness_Nm_per_rad == 0 && s.damping_Nms_per_rad == 0)
      c.fail("stiffness_Nm_per_rad", "a shaft needs stiffness_Nm_per_rad > 0 or damping_Nms_per_rad > 0");
    spec.shafts.push_back(s);
  } else if (type == "gear") {
    const double ratio = c.number("ratio");
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
    k.max_force_N = c.number("max_force_N", Range::positive());
    k.force_signal = read_signal(c, "normal_force", Signal::constant(1.0));
    const std::string law = c.choice_or("law", "plain", {"plain", "wet"});
    if (law == "plain") {
      k.law = components::ClutchSpec::Law::kPlain;
      k.plain = read_plain(c);
    } else {
      k.law = components::ClutchSpec::Law::kWet;
      k.wet = read_wet_pack(c, path, sc.warnings);
      sc.fluid_paths.push_back(k.wet.fluid_path);
      sc.fluid_texts += "# file: " + k.wet.fluid_path + " (clutch " + name + ")\n" + k.wet.fluid_text + "\n";
    }
    spec.clutches.push_back(std::move(k));
  } else if (type == "freewheel") {
    spec.freewheels.push_back({name, node("driving"), node("driven"), c.number_or("drag_Nm", 0.0, Range::non_negative())});
  } else if (type == "torque_source") {
    spec.torque_sources.push_back({name, node("node"), read_signal(c, "torque_Nm", std::nullopt)});
  } else if (type == "speed_source") {
    spec.speed_sources.push_back({name, node("node"), read_signal(c, "speed_rpm", std::nullopt)});
  } else if (type == "motor") {
    spec.motors.push_back({name, node("node"), read_signal(c, "speed_rpm", std::nullopt),
                           c.number("kp_Nms_per_rad", Range::non_negative()), c.number("ki_Nm_per_rad", Range::non_negative()),
                           c.number("torque_limit_Nm", Range::positive())});
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
      p.full_load_torque_Nm = rig_models::PiecewiseLinear(n, tq);
      fl->finish();
    }
    p.idle_speed_rpm = c.number_or("idle_speed_rpm", p.idle_speed_rpm, Range::positive());
    p.stall_speed_rpm = c.number_or("stall_speed_rpm", p.stall_speed_rpm, Range::positive());
    if (!(p.idle_speed_rpm > p.stall_speed_rpm)) c.fail("idle_speed_rpm", "must exceed stall_speed_rpm");
    p.idle_governor_gain_Nms_per_rad = c.number_or("idle_governor_gain_Nms_per_rad", p.idle_governor_gain_Nms_per_rad, Range::positive());
    p.loss_torque_idle_Nm = c.number_or("loss_torque_idle_Nm", p.loss_torque_idle_Nm, Range::non_negative());
    p.loss_torque_max_Nm = c.number_or("loss_torque_max_Nm", p.loss_torque_max_Nm, Range::non_negative());
    p.max_speed_rpm = c.number_or("max_speed_rpm", p.max_speed_rpm, Range::positive());
    spec.engines.push_back(std::move(e));
  } else if (type == "vehicle") {
    components::VehicleSpec v;
    v.name = name;
    v.mass_kg = c.number("mass_kg", Range::positive());
    v.wheel_radius_m = c.number("wheel_radius_m", Range::positive());
    v.speed_m_s = c.number_or("speed_km_h", 0.0) / 3.6;
    v.grade_percent = c.number_or("grade_percent", 0.0, Range::closed(-100.0, 100.0));
    const double f_r = c.number_or("rolling_resistance_coefficient", 0.012, Range::closed(0.0, 0.5));
    v.road.rolling_resistance_N = f_r * v.mass_kg * kGravity_m_s2 * std::cos(std::atan(v.grade_percent / 100.0));
    v.road.drag_coefficient_area_m2 = c.number_or("drag_area_m2", v.road.drag_coefficient_area_m2, Range::non_negative());
    v.road.air_density_kg_m3 = c.number_or("air_density_kg_m3", v.road.air_density_kg_m3, Range::positive());
    spec.vehicles.push_back(v);
  } else if (type == "tyre") {
    components::TyreSpec t;
    t.name = name;
    t.wheel = node("wheel");
    t.vehicle = node("vehicle");
    auto& p = t.params;
    p.slip_stiffness_N = c.number_or("slip_stiffness_N", p.slip_stiffness_N, Range::positive());
    p.relaxation_length_m = c.number_or("relaxation_length_m", p.relaxation_length_m, Range::positive());
    p.vertical_load_N = c.number("vertical_load_N", Range::positive());
    p.road_friction = c.number_or("road_friction", p.road_friction, Range::positive());
    p.radius_m = c.number_or("radius_m", std::nan(""), Range::positive());  // default: the vehicle's wheel radius
    spec.tyres.push_back(t);
  }
  c.finish();
}

}  // namespace

std::string scenario_type(const std::string& path) {
  const toml::table doc = TomlTable::parse_text(read_text(path), path);
  if (const auto* head = doc["scenario"].as_table())
    if (const auto* type = (*head)["type"].as_string()) return type->get();
  return "prescribed_slip";
}

NetworkScenario load_network_scenario(const std::string& path) { return load_network_scenario_text(read_text(path), path); }

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
  if (auto solver = root.optional_table("solver")) {
    cfg.thermal_step_s = solver->number_or("thermal_step_ms", cfg.thermal_step_s * 1e3, Range::closed(1e-3, 1e4)) * 1e-3;
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
  // A tyre's radius defaults to its vehicle's wheel radius.
  for (auto& t : sc.spec.tyres)
    if (std::isnan(t.params.radius_m)) {
      for (const auto& v : sc.spec.vehicles)
        if (v.name == t.vehicle) t.params.radius_m = v.wheel_radius_m;
      if (std::isnan(t.params.radius_m)) t.params.radius_m = 0.3;  // the builder names the missing vehicle
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
