#include "io/network_components.hpp"

#include <limits>
#include <sstream>
#include <stdexcept>

#include "components/network_spec.hpp"
#include "components/engine.hpp"
#include "components/engine_pulsation.hpp"
#include "components/tyre.hpp"

namespace shudder::io {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

KeyDecl number(std::string key, std::string unit, std::optional<double> fallback, Range range, std::string meaning) {
  return {std::move(key), KeyKind::kNumber, std::move(unit), fallback, range, std::move(meaning), "", {}};
}
KeyDecl integer(std::string key, double fallback, double lo, double hi, std::string meaning) {
  return {std::move(key), KeyKind::kInteger, "", fallback, Range::closed(lo, hi), std::move(meaning), "", {}};
}
KeyDecl optional_number(std::string key, std::string unit, Range range, std::string meaning, std::string note) {
  return {std::move(key), KeyKind::kNumber,   std::move(unit), std::nullopt,
          range,          std::move(meaning), std::move(note), {}};
}
KeyDecl node(std::string key, std::string meaning, bool ground = false) {
  return {std::move(key),
          ground ? KeyKind::kNodeOrGround : KeyKind::kNode,
          "",
          std::nullopt,
          {},
          std::move(meaning),
          "",
          {}};
}
KeyDecl signal(std::string key, std::string unit, std::string meaning, std::string note = "") {
  return {std::move(key), KeyKind::kSignal, std::move(unit), std::nullopt, {}, std::move(meaning), std::move(note), {}};
}
KeyDecl choice(std::string key, std::vector<std::string> choices, std::string meaning) {
  return {std::move(key), KeyKind::kChoice, "", std::nullopt, {}, std::move(meaning), "", std::move(choices)};
}
KeyDecl table(std::string key, std::string meaning, std::string note) {
  return {std::move(key), KeyKind::kTable, "", std::nullopt, {}, std::move(meaning), std::move(note), {}};
}

std::vector<KeyDecl> friction_keys() {
  return {
      choice("law", {"plain", "wet"},
             "plain: a friction coefficient (below); wet: the wet clutch with its fluid and thermal model (`clutch`, "
             "`effects`)"),
      number("max_force_N", "N", std::nullopt, Range::positive(), "largest normal force F_max"),
      signal("normal_force", "1", "normalised normal force u(t): F = F_max max(u, 0), open at u <= 0",
             "default 1 (always closed)"),
      optional_number("mu", "1", Range::positive(), "plain: constant friction coefficient", "give `mu` or `mu_table`"),
      table("mu_table",
            "plain: `slip_rpm` (ascending, from >= 0) and `mu` (each > 0): mu linear in slip, held beyond the ends",
            "give `mu` or `mu_table`"),
      number("peak_ratio", "1", 1.0, Range::closed(1.0, 10.0),
             "plain: static (breakaway) over kinetic friction at zero slip"),
      optional_number("geometry_factor_m", "m", Range::positive(), "plain: torque per unit mu F (n r_mean)",
                      "one geometry: this, `mean_radius_m`, or the two radii"),
      optional_number("mean_radius_m", "m", Range::positive(),
                      "plain: mean friction radius; R = interfaces x mean_radius_m", "one geometry"),
      optional_number("inner_radius_m", "m", Range::positive(),
                      "plain: annulus inner radius (with outer_radius_m; uniform pressure)", "one geometry"),
      optional_number("outer_radius_m", "m", Range::positive(), "plain: annulus outer radius", "one geometry"),
      integer("interfaces", 1, 1, 64, "plain: friction interfaces n (with a radius)"),
      table("clutch",
            "wet: the clutch exactly as a scenario's [clutch] (docs/formats/scenario_file.md): `fluid` relative to "
            "this file, `sliding_interfaces`, radii, layers, oil, sensors",
            "required for law = \"wet\""),
      table("effects", "wet: switchable effects exactly as a scenario's [effects] (docs/effects.md)", "optional"),
      {"judged_on",
       KeyKind::kComponent,
       "",
       std::nullopt,
       {},
       "a shaft whose torque the clutch's verdict is judged on (as a rig's torque cell reads its torsion bar)",
       "default: the clutch's own torque",
       {}},
  };
}

std::vector<KeyDecl> haldex_keys() {
  const components::HaldexSpec h;
  return {
      node("from", "input side (from the front axle's power take-off)"),
      node("to", "output side (to the rear axle)"),
      node("front_axle", "node whose speed the control unit reads as the front axle's (its differential's carrier)"),
      node("rear_axle", "node whose speed it reads as the rear axle's"),
      number("front_path_ratio", "1", 1.0, Range::positive(),
             "mean path of the front wheels over the vehicle's in the turn (1 straight): slip the geometry explains"),
      number("rear_path_ratio", "1", 1.0, Range::positive(), "the same for the rear wheels"),
      optional_number("wheel_radius_m", "m", Range::positive(),
                      "rolling radius that maps an axle's speed to the vehicle speed the unit estimates",
                      "default: the network's vehicle's wheel_radius_m (one vehicle)"),
      signal("pedal", "1", "accelerator pedal 0..1 the control unit reads (clamped)", "default 0"),
      signal("valve_opening", "1", "raw throttle-valve opening 0 (shut) .. 1 (open) instead of the control unit",
             "optional"),
      signal("valve_pressure_bar", "bar",
             "raw pressure setting (valve shut below it, 0 .. relief_pressure_bar) instead of the control unit",
             "optional"),
      number("nominal_friction", "1", h.nominal_friction, Range::closed(0.01, 1.0),
             "mu_nom that turns the preload torque into a force"),
      number("pack_oil_volume_ml", "ml", h.pack_oil_volume_ml, Range::positive(),
             "the coupling's own oil, shared by its interfaces (unless the clutch's oil table gives sump_volume_ml)"),
      number("pack_cooling_flow_ml_min", "ml/min", h.pack_cooling_flow_ml_min, Range::non_negative(),
             "its cooling flow, shared likewise (unless supply_flow_ml_min is given)"),
      table("clutch",
            "the disc pack exactly as a scenario's [clutch] (docs/formats/scenario_file.md): `fluid` relative to this "
            "file, `sliding_interfaces`, radii, layers",
            "required"),
      table("effects", "switchable effects exactly as a scenario's [effects] (docs/effects.md)", "optional"),
      table("hydraulics",
            "pump, chamber, throttle and relief valves, piston: the keys of a driveline's [driveline.hydraulics] "
            "(docs/driveline.md)",
            "optional: the Gen I estimates"),
      table("controller",
            "the control unit's thresholds, control period and speed filter: the keys of [driveline.controller] "
            "(docs/driveline.md)",
            "optional: the estimates; not with a raw valve schedule"),
      {"judged_on",
       KeyKind::kComponent,
       "",
       std::nullopt,
       {},
       "a shaft whose torque the coupling's verdict is judged on",
       "default: the coupling's own torque",
       {}},
  };
}

std::vector<ComponentDecl> make_components() {
  const components::EngineParams engine;
  const components::TyreParams tyre;
  std::vector<ComponentDecl> d;
  d.push_back({"inertia",
               "a rigid rotating body: a node of the network",
               {
                   number("inertia_kg_m2", "kg m^2", std::nullopt, Range::non_negative(),
                          "rotational inertia; 0 only where a gear or differential fixes its speed"),
                   number("speed_rpm", "rpm", 0.0, {}, "speed at t = 0"),
                   number("angle_deg", "deg", 0.0, {},
                          "angle at t = 0: a shaft starts twisted by the difference of its ends' angles (e.g. "
                          "preloaded by a steady torque T: angle T / k)"),
               }});
  d.push_back(
      {"shaft",
       "spring-damper between two nodes (or a node and ground), optionally with backlash",
       {
           node("from", "first node"),
           node("to", "second node, or \"ground\"", true),
           number("stiffness_Nm_per_rad", "N m/rad", 0.0, Range::non_negative(), "torsional stiffness k"),
           number("damping_Nms_per_rad", "N m s/rad", 0.0, Range::non_negative(), "damping c (k and c not both 0)"),
           number("lash_deg", "deg", 0.0, Range::closed(0.0, 360.0),
                  "total free play; the spring acts beyond it (needs k > 0 and two nodes)"),
       }});
  d.push_back({"gear",
               "ideal lossless gear pair: speed of input = ratio x speed of output",
               {
                   node("input", "input node"),
                   node("output", "output node"),
                   number("ratio", "1", std::nullopt, {}, "speed ratio input/output, not 0 (negative: reversing)"),
               }});
  d.push_back({"differential",
               "open differential: left + right = 2 carrier speed, equal torque split",
               {
                   node("carrier", "carrier (input) node"),
                   node("left", "left output node"),
                   node("right", "right output node"),
               }});
  ComponentDecl clutch{"clutch",
                       "friction clutch between two nodes",
                       {node("from", "driving-side node"), node("to", "driven-side node, or \"ground\"", true)}};
  for (auto& k : friction_keys()) clutch.keys.push_back(k);
  d.push_back(clutch);
  ComponentDecl brake{"brake", "friction brake: a clutch from a node to ground", {node("node", "braked node")}};
  for (auto& k : friction_keys()) brake.keys.push_back(k);
  d.push_back(brake);
  d.push_back({"freewheel",
               "one-way clutch: locks when driving would turn faster than driven; driven may overrun",
               {
                   node("driving", "driving node"),
                   node("driven", "driven node, or \"ground\" (a backstop)", true),
                   number("drag_Nm", "N m", 0.0, Range::non_negative(), "drag torque while overrunning"),
               }});
  d.push_back({"torque_source",
               "a prescribed torque on a node",
               {
                   node("node", "node it acts on"),
                   signal("torque_Nm", "N m", "torque, positive along the node's positive speed"),
               }});
  d.push_back({"speed_source",
               "a prescribed speed of a node (a kinematic constraint)",
               {
                   node("node", "node it drives"),
                   signal("speed_rpm", "rpm", "speed"),
               }});
  d.push_back(
      {"motor",
       "PI speed loop with a torque limit and anti-windup (dynamics/network.hpp)",
       {
           node("node", "node it drives"),
           signal("speed_rpm", "rpm", "speed set point"),
           number("kp_Nms_per_rad", "N m s/rad", std::nullopt, Range::non_negative(), "proportional gain"),
           number("ki_Nm_per_rad", "N m/rad", std::nullopt, Range::non_negative(),
                  "integral gain (kp and ki not both 0)"),
           number("torque_limit_Nm", "N m", std::nullopt, Range::positive(), "limit on the motor torque (either sign)"),
           number("start_torque_Nm", "N m", 0.0, {},
                  "the integrator's torque at t = 0 (a loop already holding a steady load; needs ki > 0)"),
           number("ripple_amplitude_Nm", "N m", 0.0, Range::non_negative(),
                  "the drive's torque ripple A sin(2 pi N revolutions of the set point) (components/motor_ripple.hpp); "
                  "0: none"),
           number("ripple_periods_per_rev", "1", 576.0, Range::positive(), "N: ripple periods per revolution"),
       }});
  d.push_back(
      {"engine",
       "combustion engine torque from a throttle map, losses and an idle governor (components/engine.hpp)",
       {
           node("node", "crankshaft node"),
           signal("throttle", "1", "throttle 0..1 (clamped)"),
           table("full_load", "`speed_rpm` (ascending) and `torque_Nm`: full-load torque curve",
                 "default: a 2-litre petrol engine's curve (estimate, components/engine.hpp)"),
           number("idle_speed_rpm", "rpm", engine.idle_speed_rpm, Range::positive(),
                  "idle governor's set speed (above stall_speed_rpm)"),
           number("stall_speed_rpm", "rpm", engine.stall_speed_rpm, Range::positive(),
                  "below it the engine cannot fire"),
           number("idle_governor_gain_Nms_per_rad", "N m s/rad", engine.idle_governor_gain_Nms_per_rad,
                  Range::positive(), "governor's proportional gain"),
           number("loss_torque_idle_Nm", "N m", engine.loss_torque_idle_Nm, Range::non_negative(),
                  "friction and pumping losses at idle"),
           number("loss_torque_max_Nm", "N m", engine.loss_torque_max_Nm, Range::non_negative(),
                  "losses at max_speed_rpm"),
           number("max_speed_rpm", "rpm", engine.max_speed_rpm, Range::positive(), "speed of the largest losses"),
       }});
  d.push_back({"vehicle",
               "the car's mass as a node of inertia m r^2 (speed = v / r) with rolling resistance, drag and grade",
               {
                   number("mass_kg", "kg", std::nullopt, Range::positive(), "vehicle mass m"),
                   number("wheel_radius_m", "m", std::nullopt, Range::positive(),
                          "rolling radius r that maps v to the node's speed"),
                   number("speed_km_h", "km/h", 0.0, {}, "speed at t = 0"),
                   number("grade_percent", "%", 0.0, Range::closed(-100.0, 100.0), "road grade, uphill positive"),
                   number("rolling_resistance_coefficient", "1", 0.012, Range::closed(0.0, 0.5),
                          "f_r: rolling resistance f_r m g cos(grade) (Gillespie 1992, ch. 4)"),
                   number("drag_area_m2", "m^2", components::RoadLoadParams{}.drag_coefficient_area_m2,
                          Range::non_negative(), "c_d A"),
                   number("air_density_kg_m3", "kg/m^3", components::RoadLoadParams{}.air_density_kg_m3,
                          Range::positive(), "air density"),
                   number("cg_height_m", "m", 0.0, Range::closed(0.0, 5.0),
                          "h: centre of gravity above the road; its tyres with an `axle` take the load transfer m a h "
                          "/ L (0: static loads only)"),
                   optional_number("wheelbase_m", "m", Range::positive(), "L: front to rear axle",
                                   "required when a tyre names its `axle`"),
                   optional_number("front_axle_load_share", "1", Range::closed(0.05, 0.95),
                                   "the front axle's share of the weight on the level",
                                   "required when a tyre names its `axle`"),
               }});
  d.push_back(
      {"tyre",
       "longitudinal tyre force with slip stiffness, relaxation length, road friction and its axle's load "
       "(components/tyre.hpp)",
       {
           node("wheel", "wheel node"),
           node("vehicle", "the vehicle component it drives"),
           choice("axle", {"none", "front", "rear"},
                  "the vehicle's axle it is on: its static load from the vehicle's weight split, wheelbase and grade, "
                  "shared by that axle's tyres, plus the load transfer (none: `vertical_load_N`, constant)"),
           optional_number("vertical_load_N", "N", Range::positive(), "F_z on the tyre(s), constant",
                           "required with axle = \"none\"; not with an axle"),
           optional_number("slip_stiffness_per_load", "1", Range::positive(),
                           "C_kappa / F_z: the slip stiffness follows the load (Magic Formula dry tarmac B C D = 19, "
                           "components/tyre.hpp)",
                           "default 19 unless `slip_stiffness_N` is given; not both"),
           optional_number("slip_stiffness_N", "N", Range::positive(),
                           "C_kappa per unit slip, absolute (independent of the load)",
                           "default: slip_stiffness_per_load x F_z; not both"),
           number("relaxation_length_m", "m", tyre.relaxation_length_m, Range::positive(),
                  "sigma at the static load (the carcass stiffness C_kappa / sigma is kept as the load changes)"),
           number("road_friction", "1", tyre.road_friction, Range::positive(), "road friction coefficient"),
           optional_number("radius_m", "m", Range::positive(), "rolling radius",
                           "default: the vehicle's wheel_radius_m"),
           number("path_ratio", "1", 1.0, Range::positive(),
                  "the wheel's path over the vehicle's in a steady turn (1 straight; a turn's outer wheels > 1)"),
       }});
  d.push_back({"haldex_coupling",
               "Haldex limited-slip coupling: a wet disc pack clamped by its own pump pressure, the throttle valve set "
               "by a sampled control unit (components/haldex_coupling_law.hpp)",
               haldex_keys()});
  d.push_back({"firing_pulsation",
               "an engine's firing-order torque pulsation on a node, A s(speed) sin(z/2 crank angle) "
               "(components/engine_pulsation.hpp)",
               {
                   node("node", "crankshaft node"),
                   number("amplitude_Nm", "N m", components::EnginePulsation{}.amplitude_Nm, Range::non_negative(),
                          "A: the pulsation that passes the flywheel and damper"),
                   integer("cylinders", components::EnginePulsation{}.cylinders, 1, 16, "z, four-stroke"),
                   number("stall_speed_rpm", "rpm", engine.stall_speed_rpm, Range::positive(), "no firing below it"),
                   number("idle_speed_rpm", "rpm", engine.idle_speed_rpm, Range::positive(),
                          "full pulsation from it (above stall_speed_rpm)"),
               }});
  return d;
}

std::vector<ComponentDecl> make_signals() {
  return {
      {"constant", "y = value", {number("value", "", std::nullopt, {}, "the value")}},
      {"table",
       "points (time_s, value), linear or held between them, end values beyond",
       {
           table("time_s", "times, s, strictly increasing, >= 0", "required (an array)"),
           table("value", "one value per time", "required (an array)"),
           choice("interpolation", {"linear", "step"},
                  "linear: straight lines; step: each value held to the next time"),
       }},
      {"step",
       "before until time_s, after from then on",
       {
           number("time_s", "s", std::nullopt, Range::non_negative(), "step time"),
           number("before", "", 0.0, {}, "value before"),
           number("after", "", std::nullopt, {}, "value after"),
       }},
      {"ramp",
       "from until start_s, linear to `to` over duration_s, then held",
       {
           number("from", "", 0.0, {}, "start value"),
           number("to", "", std::nullopt, {}, "end value"),
           number("start_s", "s", 0.0, Range::non_negative(), "ramp start"),
           number("duration_s", "s", std::nullopt, Range::non_negative(), "ramp duration (0: a step)"),
       }},
      {"sine",
       "offset + amplitude sin(2 pi f (t - start_s) + phase) from start_s, offset before",
       {
           number("offset", "", 0.0, {}, "mean"),
           number("amplitude", "", std::nullopt, {}, "amplitude"),
           number("frequency_Hz", "Hz", std::nullopt, Range::positive(), "frequency"),
           number("phase_deg", "deg", 0.0, {}, "phase at start_s"),
           number("start_s", "s", 0.0, Range::non_negative(), "start time"),
       }},
      {"pulse",
       "square wave: high for width_s of every period_s from start_s, low otherwise",
       {
           number("low", "", 0.0, {}, "low value"),
           number("high", "", std::nullopt, {}, "high value"),
           number("period_s", "s", std::nullopt, Range::positive(), "period"),
           number("width_s", "s", std::nullopt, Range::positive(), "time high per period (<= period_s)"),
           number("start_s", "s", 0.0, Range::non_negative(), "first rising edge"),
       }},
      {"product",
       "the product of two or more signals",
       {table("factors", "array of signal tables", "required, at least two")}},
  };
}

std::string default_text(const KeyDecl& k) {
  if (!k.optional_note.empty()) return k.optional_note;
  switch (k.kind) {
    case KeyKind::kNumber:
    case KeyKind::kInteger: {
      if (!k.fallback) return "required";
      std::ostringstream os;
      os << *k.fallback;
      return os.str();
    }
    case KeyKind::kChoice: return "\"" + k.choices.front() + "\"";
    default: return "required";
  }
}

std::string kind_text(const KeyDecl& k) {
  switch (k.kind) {
    case KeyKind::kNumber: return "number";
    case KeyKind::kInteger: return "integer";
    case KeyKind::kNode: return "node name";
    case KeyKind::kNodeOrGround: return "node name or \"ground\"";
    case KeyKind::kComponent: return "component name";
    case KeyKind::kSignal: return "signal";
    case KeyKind::kChoice: {
      std::string s;
      for (const auto& c : k.choices) s += (s.empty() ? "" : " or ") + ("\"" + c + "\"");
      return s;
    }
    case KeyKind::kTable: return "table/array";
  }
  return "";
}

std::string range_text(const KeyDecl& k) {
  if (k.kind != KeyKind::kNumber && k.kind != KeyKind::kInteger) return "";
  if (k.range.min == -kInf && k.range.max == kInf) return "";
  return k.range.describe();
}

void key_table(std::ostream& os, const ComponentDecl& c) {
  os << "| key | kind | unit | default | allowed | meaning |\n|---|---|---|---|---|---|\n";
  for (const auto& k : c.keys)
    os << "| `" << k.key << "` | " << kind_text(k) << " | " << k.unit << " | " << default_text(k) << " | "
       << range_text(k) << " | " << k.meaning << " |\n";
  os << "\n";
}

}  // namespace

const KeyDecl& ComponentDecl::key(const std::string& name) const {
  for (const auto& k : keys)
    if (k.key == name) return k;
  throw std::logic_error("network component '" + type + "' reads the undeclared key '" + name + "'");
}

const std::vector<ComponentDecl>& network_component_decls() {
  static const std::vector<ComponentDecl> d = make_components();
  return d;
}

const std::vector<ComponentDecl>& signal_kind_decls() {
  static const std::vector<ComponentDecl> d = make_signals();
  return d;
}

const ComponentDecl& component_decl(const std::string& type) {
  for (const auto& c : network_component_decls())
    if (c.type == type) return c;
  throw std::logic_error("no component type " + type);
}

const ComponentDecl& signal_decl(const std::string& kind) {
  for (const auto& c : signal_kind_decls())
    if (c.type == kind) return c;
  throw std::logic_error("no signal kind " + kind);
}

std::vector<std::string> component_types() {
  std::vector<std::string> v;
  for (const auto& c : network_component_decls()) v.push_back(c.type);
  return v;
}

std::vector<std::string> signal_kinds() {
  std::vector<std::string> v;
  for (const auto& c : signal_kind_decls()) v.push_back(c.type);
  return v;
}

double read_number(TomlTable& t, const ComponentDecl& decl, const std::string& key) {
  const KeyDecl& k = decl.key(key);
  if (k.kind == KeyKind::kInteger) {
    const auto lo = static_cast<long>(k.range.min), hi = static_cast<long>(k.range.max);
    return static_cast<double>(k.fallback ? t.integer_or(key, static_cast<long>(*k.fallback), lo, hi)
                                          : t.integer(key, lo, hi));
  }
  if (k.kind != KeyKind::kNumber) throw std::logic_error("key '" + key + "' of '" + decl.type + "' is not a number");
  return k.fallback ? t.number_or(key, *k.fallback, k.range) : t.number(key, k.range);
}

bool gives(const TomlTable& t, const std::string& key) { return t.has(key); }

std::string network_reference_markdown() {
  std::ostringstream os;
  for (const auto& c : network_component_decls()) {
    os << "### `type = \"" << c.type << "\"`: " << c.what << "\n\n";
    key_table(os, c);
  }
  os << "### Signals\n\n";
  os << "A signal is a table with `kind` and the kind's keys (inline, `{ kind = \"ramp\", to = 1, duration_s = 0.5 "
        "}`), "
        "or a plain number for a constant. A table without `kind` is a constant: `{ value = 0.8 }`, which a sweep can "
        "set "
        "as `network.NAME.KEY.value`.\n\n";
  for (const auto& c : signal_kind_decls()) {
    os << "#### `kind = \"" << c.type << "\"`: " << c.what << "\n\n";
    key_table(os, c);
  }
  return os.str();
}

}  // namespace shudder::io
