#include "io/scenario.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <system_error>

#include "components/pack_oil.hpp"
#include "core/units.hpp"
#include "io/fluid_loader.hpp"
#include "io/haldex_tables.hpp"
#include "io/toml_reader.hpp"
#include "rig_models/effect_registry.hpp"

namespace shudder::io {

namespace {

namespace fs = std::filesystem;

constexpr double kMaxForce_N = 30000.0;             // rig cylinder maximum (thesis Method)
constexpr double kMaxSlip_rpm = 1000.0;             // beyond any LSC use; friction data end at 100 rpm
const Range kTemp_C = Range::closed(-60.0, 250.0);  // friction matrix spans -40..200 °C

// The scenario as read, before it becomes a typed model: every kind's pieces side by side, so
// that the readers below (and the effects' reader) fill them in the file's order. `type` is the
// file's string, `kind` the same mapped once; load_scenario_text builds the model of that kind.
struct Draft {
  std::string path;
  std::string type;
  ModelKind kind = ModelKind::kPrescribedSlip;
  std::string fluid_path;
  std::string fluid_text;
  clutch::Fluid fluid;
  clutch::WetClutchParams clutch;
  components::DriveCycle cycle;                           // prescribed_slip and rig
  rig_models::PrescribedSlipSettings settings;            // duration, steps, sampling, bearing drag
  rig_models::RigParams rig;                              // rig (stick-time friction: every kind)
  rig_models::DrivelineParams driveline;                  // driveline
  rig_models::DrivelineInputs manoeuvre;                  // driveline
  bool oil_volume_given = false, oil_flow_given = false;  // [clutch.oil]: else the driveline's pack oil
  std::vector<std::string> warnings;
};

ModelKind kind_of_type(const std::string& type) {
  for (ModelKind k : kModelKinds)
    if (model_kind_name(k) == type) return k;
  throw std::logic_error("scenario type '" + type + "' passed the reader's choice but names no model kind");
}

void read_layer(TomlTable& parent, const std::string& key, clutch::Layer& layer) {
  auto t = parent.optional_table(key);
  if (!t) return;
  layer.thickness_m = t->number_or("thickness_mm", layer.thickness_m * 1e3, Range::positive()) * 1e-3;
  layer.density_kg_m3 = t->number_or("density_kg_m3", layer.density_kg_m3, Range::positive());
  layer.specific_heat_J_per_kgK =
      t->number_or("specific_heat_J_per_kgK", layer.specific_heat_J_per_kgK, Range::positive());
  layer.conductivity_W_per_mK = t->number_or("conductivity_W_per_mK", layer.conductivity_W_per_mK, Range::positive());
  layer.cells = static_cast<int>(t->integer_or("cells", layer.cells, 1, 200));
  t->finish();
}

void read_clutch(TomlTable& root, Draft& s) {
  auto c = root.table("clutch");
  auto& p = s.clutch;
  auto& th = p.thermal;
  const std::string fluid = c.string("fluid");
  s.fluid_path = (fs::path(s.path).parent_path() / fluid).string();
  // The non-throwing status: a name the OS refuses (too long, bad component) is bad input too.
  std::error_code status_error;
  const fs::file_status status = fs::status(s.fluid_path, status_error);
  if (!fs::exists(status)) {
    const bool odd = status_error && status_error != std::errc::no_such_file_or_directory;
    const fs::path folder = fs::path(s.path).parent_path();
    const std::string from =
        fs::path(fluid).is_absolute() ? ""
        : folder.empty()              ? "; a relative fluid path is read from the scenario's folder, "
                                        "here the current directory"
                         : "; a relative fluid path is read from the scenario's folder, '" + folder.string() + "'";
    c.fail("fluid",
           "file '" + s.fluid_path + "' does not exist" + (odd ? " (" + status_error.message() + ")" : "") + from);
  }
  if (!fs::is_regular_file(status))
    c.fail("fluid", "'" + s.fluid_path + "' is not a regular file; expected a fluid TOML file");
  // The fluid is parsed from the very text stored in the outputs (reproducibility).
  s.fluid_text = read_scenario_text(s.fluid_path);
  s.fluid = load_fluid_text(s.fluid_text, s.fluid_path);
  p.sliding_interfaces = static_cast<int>(c.integer_or("sliding_interfaces", 1, 1, 64));
  p.start_temp_C = c.number("start_temp_C", kTemp_C);
  p.sump_start_temp_C = c.number_or("sump_start_temp_C", p.start_temp_C, kTemp_C);
  th.inner_radius_m = c.number_or("inner_radius_mm", th.inner_radius_m * 1e3, Range::positive()) * 1e-3;
  th.outer_radius_m = c.number_or("outer_radius_mm", th.outer_radius_m * 1e3, Range::positive()) * 1e-3;
  if (!(th.outer_radius_m > th.inner_radius_m)) c.fail("outer_radius_mm", "must exceed inner_radius_mm");
  read_layer(c, "separator", th.separator);
  read_layer(c, "lining", th.lining);
  read_layer(c, "core", th.core);
  if (auto oil = c.optional_table("oil")) {
    s.oil_volume_given = oil->has("sump_volume_ml");
    s.oil_flow_given = oil->has("supply_flow_ml_min");
    th.oil_density_kg_m3 = oil->number_or("density_kg_m3", th.oil_density_kg_m3, Range::positive());
    th.oil_specific_heat_J_per_kgK =
        oil->number_or("specific_heat_J_per_kgK", th.oil_specific_heat_J_per_kgK, Range::positive());
    // Mean oil film in the interface (Paper G's h_mean = 10 µm). Bounded to [0.01, 1000] µm:
    // below 0.01 µm (a few molecular layers) the film cell's heat capacity vanishes and its
    // conductance r²/h explodes (1e-300 µm gives 5e279 °C); above 1 mm it is no
    // longer a film but a gap as deep as the discs are thick.
    th.film_thickness_m =
        oil->number_or("film_thickness_um", th.film_thickness_m * 1e6, Range::closed(0.01, 1000.0)) * 1e-6;
    th.sump_volume_m3 = oil->number_or("sump_volume_ml", th.sump_volume_m3 * 1e6, Range::positive()) * 1e-6;
    th.supply_flow_m3_s = units::ml_min_to_m3_s(oil->number_or(  // rig pump: 0–1000 ml/min
        "supply_flow_ml_min", units::m3_s_to_ml_min(th.supply_flow_m3_s), Range::closed(0.0, 1000.0)));
    oil->finish();
  }
  if (auto tc = c.optional_table("thermocouple")) {
    th.thermocouple_r_m = tc->number_or("r_mm", th.thermocouple_r_m * 1e3, Range::positive()) * 1e-3;
    th.thermocouple_z_m = tc->number_or("z_mm", th.thermocouple_z_m * 1e3, Range::non_negative()) * 1e-3;
    tc->finish();
  }
  if (auto ir = c.optional_table("ir_pyrometer")) {
    th.ir_r_m = ir->number_or("r_mm", th.ir_r_m * 1e3, Range::positive()) * 1e-3;
    th.ir_spot_diameter_m = ir->number_or("spot_diameter_mm", th.ir_spot_diameter_m * 1e3, Range::positive()) * 1e-3;
    ir->finish();
  }
  const double z_total = th.separator.thickness_m + th.lining.thickness_m + th.core.thickness_m;
  if (th.thermocouple_z_m > z_total) c.fail("thermocouple", "z_mm lies outside the disc stack");
  c.finish();
}

components::PiecewiseLinear read_schedule(TomlTable& drive, const std::string& key, const std::vector<double>& times,
                                          Range range) {
  // A single number means constant; an array must align with time_s.
  if (!drive.is_array(key)) return {{0.0}, {drive.number(key, range)}};
  const auto values = drive.numbers(key, range, 1);
  if (values.size() != times.size())
    drive.fail(key, "has " + std::to_string(values.size()) + " values but time_s has " + std::to_string(times.size()) +
                        "; give one value per time or a single number");
  return {times, values};
}

void read_drive(TomlTable& root, Draft& s) {
  auto d = root.table("drive");
  const auto times = d.numbers("time_s", Range::non_negative(), 1);
  for (std::size_t i = 1; i < times.size(); ++i)
    if (times[i] <= times[i - 1]) d.fail("time_s", "must be strictly increasing");
  s.cycle.slip_speed_rpm = read_schedule(d, "speed_rpm", times, Range::closed(-kMaxSlip_rpm, kMaxSlip_rpm));
  s.cycle.normal_force_N = read_schedule(d, "normal_force_N", times, Range::closed(0.0, kMaxForce_N));
  d.finish();
}

void read_rig(TomlTable& root, Draft& s) {
  auto& r = s.rig;
  // Speeds the motor can hold (thesis: 0.5–125 rpm).
  auto drive_speeds = s.cycle.slip_speed_rpm.values();
  auto rig = root.optional_table("rig");
  if (rig) {
    r.drive_inertia_kg_m2 = rig->number_or("drive_inertia_kg_m2", r.drive_inertia_kg_m2, Range::positive());
    r.housing_inertia_kg_m2 = rig->number_or("housing_inertia_kg_m2", r.housing_inertia_kg_m2, Range::positive());
    r.start_at_rest = rig->choice_or("start", "steady_sliding", {"steady_sliding", "at_rest"}) == "at_rest";
    if (auto bar = rig->optional_table("torsion_bar")) {
      const bool by_f = bar->has("natural_frequency_Hz"), by_k = bar->has("stiffness_Nm_per_rad");
      if (by_f == by_k)
        bar->fail(by_f ? "stiffness_Nm_per_rad" : "natural_frequency_Hz",
                  "give exactly one of natural_frequency_Hz (the bar is derived from it) or stiffness_Nm_per_rad");
      if (by_f) {
        r.bar_natural_frequency_Hz = bar->number("natural_frequency_Hz", Range::closed(1.0, 10000.0));
        if (r.bar_natural_frequency_Hz < 100.0 || r.bar_natural_frequency_Hz > 500.0)
          s.warnings.push_back(
              s.path + ": rig.torsion_bar.natural_frequency_Hz = " + std::to_string(r.bar_natural_frequency_Hz) +
              " Hz lies outside the rig's 100-500 Hz bars (accepted as another bar)");
        bar->mark_read("stiffness_Nm_per_rad");
      } else {
        r.bar_stiffness_Nm_per_rad = bar->number("stiffness_Nm_per_rad", Range::positive());
        bar->mark_read("natural_frequency_Hz");
      }
      r.bar_damping_ratio = bar->number_or("damping_ratio", r.bar_damping_ratio, Range::closed(0.0, 2.0));
      bar->finish();
    }
    if (auto motor = rig->optional_table("motor")) {
      r.speed_loop_bandwidth_Hz =
          motor->number_or("speed_loop_bandwidth_Hz", r.speed_loop_bandwidth_Hz, Range::closed(0.01, 1000.0));
      r.motor_torque_limit_Nm = motor->number_or("torque_limit_Nm", r.motor_torque_limit_Nm, Range::positive());
      // Torque ripple, the seed of friction-induced vibration (components/motor_ripple.hpp).
      // Bounds: up to 10 % of the rated 500 N m (more is a faulty drive, not a ripple); up to
      // 2000 periods/rev (4 kHz at 125 rpm: beyond, the integrator's step is set by the ripple).
      r.motor_ripple.amplitude_Nm =
          motor->number_or("torque_ripple_Nm", r.motor_ripple.amplitude_Nm, Range::closed(0.0, 50.0));
      r.motor_ripple.periods_per_rev =
          motor->number_or("torque_ripple_periods_per_rev", r.motor_ripple.periods_per_rev, Range::closed(1.0, 2000.0));
      motor->finish();
    }
    rig->finish();
  }
  for (double v : drive_speeds)
    if (v < r.min_speed_rpm || v > r.max_speed_rpm) {
      auto drive = root.table("drive");
      drive.mark_read("time_s");
      drive.mark_read("speed_rpm");
      drive.mark_read("normal_force_N");
      drive.fail("speed_rpm",
                 "value " + std::to_string(v) + " rpm is outside the rig motor's range; allowed [0.5, 125] rpm");
    }
}

// type = "driveline": the car of rig_models/haldex_driveline.hpp (every key optional, defaults
// there) and the manoeuvre it drives.
void read_driveline(TomlTable& root, Draft& s) {
  auto& p = s.driveline;
  if (root.has("drive"))
    root.fail("drive",
              "[drive] belongs to prescribed_slip and rig scenarios; a driveline scenario is "
              "driven by [manoeuvre] (time_s, engine_torque_Nm, valve_pressure_bar)");
  bool controller_given = false;
  if (auto d = root.optional_table("driveline")) {
    controller_given = d->has("controller");
    const auto positive = [&](const char* key, double& v) { v = d->number_or(key, v, Range::positive()); };
    positive("engine_inertia_kg_m2", p.engine_inertia_kg_m2);
    positive("gear_ratio", p.gear_ratio);
    positive("final_drive_ratio", p.final_drive_ratio);
    positive("ptu_ratio", p.ptu_ratio);
    positive("rear_diff_ratio", p.rear_diff_ratio);
    positive("halfshaft_stiffness_Nm_per_rad", p.halfshaft_stiffness_Nm_per_rad);
    positive("propshaft_stiffness_Nm_per_rad", p.propshaft_stiffness_Nm_per_rad);
    positive("wheel_inertia_kg_m2", p.wheel_inertia_kg_m2);
    positive("tyre_stiffness_Nm_per_rad", p.tyre_stiffness_Nm_per_rad);
    if (d->has("tyre_slip_stiffness_N") && d->has("tyre_slip_stiffness_per_load"))
      d->fail("tyre_slip_stiffness_per_load",
              "is an alternative to tyre_slip_stiffness_N; give one (C_kappa / F_z, "
              "or an absolute C_kappa per tyre)");
    if (d->has("tyre_slip_stiffness_N"))
      p.tyre_slip_stiffness_N = d->number_or("tyre_slip_stiffness_N", 0.0, Range::positive());
    if (d->has("tyre_slip_stiffness_per_load"))
      p.tyre_slip_stiffness_per_load = d->number_or("tyre_slip_stiffness_per_load", 0.0, Range::closed(1.0, 100.0));
    p.cg_height_m = d->number_or("cg_height_m", p.cg_height_m, Range::closed(0.0, 2.0));
    positive("side_gear_inertia_kg_m2", p.side_gear_inertia_kg_m2);
    positive("wheelbase_m", p.wheelbase_m);
    positive("track_width_m", p.track_width_m);
    p.front_axle_load_share = d->number_or("front_axle_load_share", p.front_axle_load_share, Range::closed(0.05, 0.95));
    p.rolling_resistance_coefficient =
        d->number_or("rolling_resistance_coefficient", p.rolling_resistance_coefficient, Range::closed(0.0, 0.1));
    p.drag_coefficient_area_m2 =
        d->number_or("drag_coefficient_area_m2", p.drag_coefficient_area_m2, Range::closed(0.0, 10.0));
    p.air_density_kg_m3 = d->number_or("air_density_kg_m3", p.air_density_kg_m3, Range::closed(0.0, 2.0));
    positive("vehicle_mass_kg", p.vehicle_mass_kg);
    positive("wheel_radius_m", p.wheel_radius_m);
    positive("coupling_half_inertia_kg_m2", p.coupling_half_inertia_kg_m2);
    p.nominal_friction = d->number_or("nominal_friction", p.nominal_friction, Range::closed(0.01, 1.0));
    // Straight (1) to well past full lock (≈ 1.05); below 1 the rear axle would run ahead,
    // which a car in a turn does not do.
    p.turn_ratio = d->number_or("turn_ratio", p.turn_ratio, Range::closed(1.0, 1.2));
    if (auto e = d->optional_table("engine")) {
      auto& ep = p.engine;
      if (e->has("full_load_speed_rpm") || e->has("full_load_torque_Nm")) {
        const auto speeds = e->numbers("full_load_speed_rpm", Range::non_negative(), 1);
        for (std::size_t i = 1; i < speeds.size(); ++i)
          if (speeds[i] <= speeds[i - 1]) e->fail("full_load_speed_rpm", "must be strictly increasing");
        const auto torques = e->numbers("full_load_torque_Nm", Range::closed(0.0, 2000.0), 1);
        if (torques.size() != speeds.size())
          e->fail("full_load_torque_Nm",
                  "needs one value per full_load_speed_rpm (" + std::to_string(speeds.size()) + ")");
        ep.full_load_torque_Nm = components::PiecewiseLinear(speeds, torques);
      }
      ep.stall_speed_rpm = e->number_or("stall_speed_rpm", ep.stall_speed_rpm, Range::closed(50.0, 2000.0));
      ep.idle_speed_rpm =
          e->number_or("idle_speed_rpm", ep.idle_speed_rpm, Range{ep.stall_speed_rpm, 3000.0, true, false});
      ep.max_speed_rpm =
          e->number_or("max_speed_rpm", ep.max_speed_rpm, Range{ep.idle_speed_rpm, 20000.0, true, false});
      ep.idle_governor_gain_Nms_per_rad =
          e->number_or("idle_governor_gain_Nms_per_rad", ep.idle_governor_gain_Nms_per_rad, Range::closed(0.0, 1000.0));
      ep.loss_torque_idle_Nm = e->number_or("loss_torque_idle_Nm", ep.loss_torque_idle_Nm, Range::closed(0.0, 500.0));
      ep.loss_torque_max_Nm = e->number_or("loss_torque_max_Nm", ep.loss_torque_max_Nm, Range::closed(0.0, 500.0));
      // Firing pulsation, the driveline's seed (components/engine_pulsation.hpp). Up to 100 N m:
      // the undamped 2nd-order gas torque of a car engine; more is not a pulsation. 1–16 cylinders.
      auto& fp = p.engine_pulsation;
      fp.amplitude_Nm = e->number_or("firing_pulsation_Nm", fp.amplitude_Nm, Range::closed(0.0, 100.0));
      fp.cylinders = static_cast<int>(e->integer_or("cylinders", fp.cylinders, 1, 16));
      e->finish();
    }
    p.pack_oil_volume_ml = d->number_or("pack_oil_volume_ml", p.pack_oil_volume_ml, Range{0.0, 1e5, true, false});
    p.pack_cooling_flow_ml_min =
        d->number_or("pack_cooling_flow_ml_min", p.pack_cooling_flow_ml_min, Range::closed(0.0, 1e5));
    if (auto h = d->optional_table("hydraulics")) read_haldex_hydraulics(*h, p.hydraulics);
    if (auto c = d->optional_table("controller")) read_haldex_controller(*c, p.controller);
    d->finish();
  }
  auto m = root.table("manoeuvre");
  const auto times = m.numbers("time_s", Range::non_negative(), 1);
  for (std::size_t i = 1; i < times.size(); ++i)
    if (times[i] <= times[i - 1]) m.fail("time_s", "must be strictly increasing");
  if (m.has("throttle")) {
    // The engine map (components/engine.hpp) instead of a raw torque schedule.
    if (m.has("engine_torque_Nm"))
      m.fail("throttle", "engine_torque_Nm is given too; give either a throttle (the engine map) or a torque schedule");
    s.manoeuvre.throttle = read_schedule(m, "throttle", times, Range::closed(0.0, 1.0));
  } else {
    s.manoeuvre.engine_torque_Nm = read_schedule(m, "engine_torque_Nm", times, Range::closed(-1000.0, 1000.0));
  }
  // The throttle valve: raw schedules (an opening, a pressure setting, or both) instead of the
  // controller model of [driveline.controller]; without them the controller decides.
  const bool raw_valve = m.has("valve_opening") || m.has("valve_pressure_bar");
  if (raw_valve && controller_given)
    m.fail(
        m.has("valve_opening") ? "valve_opening" : "valve_pressure_bar",
        "is a raw valve schedule and [driveline.controller] is given too; give either the schedule or the controller");
  if (m.has("valve_opening"))
    s.manoeuvre.valve_opening = read_schedule(m, "valve_opening", times, Range::closed(0.0, 1.0));
  if (m.has("valve_pressure_bar"))
    // The valve cannot hold more than the relief valve lets through.
    s.manoeuvre.valve_pressure_bar =
        read_schedule(m, "valve_pressure_bar", times, Range::closed(0.0, p.hydraulics.relief_pressure_bar));
  s.manoeuvre.start_speed_km_h = m.number_or("start_speed_km_h", 0.0, Range::closed(0.0, 300.0));
  if (s.manoeuvre.throttle) {
    // No clutch or torque converter is modelled: the engine turns with the wheels, so a mapped
    // engine must start above its stall speed (launches from rest take a torque schedule).
    const double engine_rpm = s.manoeuvre.start_speed_km_h / 3.6 / p.wheel_radius_m * p.gear_ratio *
                              p.final_drive_ratio * 60.0 / (2.0 * 3.14159265358979323846);
    if (engine_rpm <= p.engine.stall_speed_rpm)
      m.fail("start_speed_km_h",
             "puts the engine at " + std::to_string(static_cast<int>(engine_rpm)) +
                 " rpm, at or below its stall speed; a throttle needs the engine above " +
                 std::to_string(static_cast<int>(p.engine.stall_speed_rpm)) +
                 " rpm at the start (no clutch is modelled; launch from rest with engine_torque_Nm)");
  }
  if (m.has("turn_radius_m")) {
    if (p.turn_ratio != 1.0)
      m.fail("turn_radius_m", "[driveline] turn_ratio is given too; give either turn_radius_m or turn_ratio");
    // Geometry: the inner rear wheel must roll forwards, R > track / 2.
    s.manoeuvre.turn_radius_m = m.number_or("turn_radius_m", 0.0, Range{0.5 * p.track_width_m, 1e4, true, false});
  }
  m.finish();
  if (auto road = root.optional_table("road")) {
    // μ per wheel (FL, FR, RL, RR) or one for all; > 0 (ice ≈ 0.1, dry asphalt ≈ 1).
    const auto mu = road->numbers("friction", Range{0.0, 2.0, true, false}, 1);
    if (mu.size() != 1 && mu.size() != 4)
      road->fail("friction", "needs one value or four (FL, FR, RL, RR), got " + std::to_string(mu.size()));
    for (std::size_t w = 0; w < 4; ++w) s.manoeuvre.road_friction[w] = mu[mu.size() == 1 ? 0 : w];
    s.manoeuvre.grade_percent = road->number_or("grade_percent", 0.0, Range::closed(-50.0, 50.0));
    road->finish();
  }
  // The disc pack sits in the coupling's own oil unless [clutch.oil] says otherwise.
  clutch::ThermalParams pack = s.clutch.thermal;
  components::apply_pack_oil(p.pack_oil_volume_ml, p.pack_cooling_flow_ml_min, s.clutch.sliding_interfaces, pack);
  if (!s.oil_volume_given) s.clutch.thermal.sump_volume_m3 = pack.sump_volume_m3;
  if (!s.oil_flow_given) s.clutch.thermal.supply_flow_m3_s = pack.supply_flow_m3_s;
}

// The scenario's structs that effects write into (the registry's EffectTarget).
rig_models::EffectTarget effect_target(Draft& s) {
  return {s.clutch,
          s.settings.bearing_drag,
          s.rig.stick_time,
          s.settings.torque_cell,
          s.settings.load_cell,
          s.settings.friction_drift};
}

Range toml_range(const rig_models::ValueRange& r) { return {r.min, r.max, r.min_exclusive, r.max_exclusive}; }

// `[effects.NAME]` per the registry: `enabled`, then each parameter (read in the key's unit,
// stored in SI), then each choice; an enabled effect inert in this kind of scenario is a warning.
void read_effects(TomlTable& root, Draft& s) {
  auto effects = root.optional_table("effects");
  if (!effects) return;
  for (const auto& name : effects->subtable_keys())
    if (!rig_models::find_effect(name))
      effects->fail(name, "unknown effect; valid effects are: " + rig_models::effect_names_list());
  auto target = effect_target(s);
  for (const auto& effect : rig_models::effect_registry()) {
    auto t = effects->optional_table(effect.name);
    if (!t) continue;
    effect.enabled(target) = t->boolean("enabled");
    for (const auto& p : effect.parameters) {
      double& member = p.member(target);
      member = t->number_or(p.key, member * p.scale.to_key, toml_range(p.range)) * p.scale.to_si;
    }
    for (const auto& c : effect.choices) {
      const std::string chosen = t->choice_or(c.key, c.options.at(c.get(target)), c.options);
      c.set(target,
            static_cast<std::size_t>(std::find(c.options.begin(), c.options.end(), chosen) - c.options.begin()));
    }
    t->finish();
  }
  const ModelKind kind = s.kind;
  for (const auto& effect : rig_models::effect_registry())
    if (const auto why = rig_models::inert_reason(effect, kind); why && effect.enabled(target)) {
      // On a car, a rig-only effect is a mistake in the file, not a harmless no-op.
      if (kind == ModelKind::kDriveline)
        effects->fail(effect.name, "has no effect in a driveline scenario (" + std::string(*why) +
                                       "); disable it or remove the table");
      s.warnings.push_back("effect " + effect.name + " has no effect in a " + std::string(model_kind_name(kind)) +
                           " scenario (" + std::string(*why) + ")");
    }
  effects->finish();
}

}  // namespace

std::string set_scenario_key(const std::string& text, const std::string& path, const std::string& key, double value) {
  toml::table doc = TomlTable::parse_text(text, path);
  // Walk/create the tables of a dotted key ("rig.torsion_bar.natural_frequency_Hz").
  toml::table* table = &doc;
  std::size_t start = 0;
  for (std::size_t dot; (dot = key.find('.', start)) != std::string::npos; start = dot + 1) {
    const std::string part = key.substr(start, dot - start);
    if (!table->contains(part)) table->insert(part, toml::table{});
    table = (*table)[part].as_table();
    if (!table) throw InputError(path, 0, key, "'" + part + "' is not a table; cannot set a value below it");
  }
  const std::string leaf = key.substr(start);
  if (leaf.empty()) throw InputError(path, 0, key, "empty key");
  if (const auto* old = table->get(leaf); old && !old->is_number())
    throw InputError(path, 0, key, "holds a non-number; only numeric keys can be swept");
  // A whole number is written as a TOML integer: integer keys (`solver.radial_cells`,
  // `clutch.sliding_interfaces`) refuse a float, and number keys read an integer exactly.
  if (std::isfinite(value) && value == std::trunc(value) && std::abs(value) < 9.0e15)
    table->insert_or_assign(leaf, static_cast<std::int64_t>(value));
  else
    table->insert_or_assign(leaf, value);
  std::ostringstream os;
  os << doc;
  return os.str();
}

Scenario load_scenario(const std::string& path) { return load_scenario_text(read_scenario_text(path), path); }

namespace {

// The typed model of the draft's kind, with the effects that live outside the clutch applied
// (bearing drag: prescribed slip and rig; stick-time friction: rig and driveline; the torque
// and load cells: prescribed slip, the rig's load cell, the driveline's measured coupling).
rig_models::Model make_model(const Draft& d) {
  switch (d.kind) {
    case ModelKind::kPrescribedSlip: return rig_models::PrescribedSlipModel{d.cycle, d.settings};
    case ModelKind::kRig: {
      rig_models::RigModel m{d.rig, d.cycle, {}};
      m.params.bearing_drag = d.settings.bearing_drag;
      m.params.load_cell = d.settings.load_cell;
      m.settings.duration_s = d.settings.duration_s;
      m.settings.thermal_step_s = d.settings.thermal_step_s;
      m.settings.sample_rate_Hz = d.settings.sample_rate_Hz;
      m.settings.snapshot_times_s = d.settings.snapshot_times_s;
      return m;
    }
    case ModelKind::kDriveline: {
      rig_models::DrivelineModel m{d.driveline, d.manoeuvre, {}, d.settings.torque_cell, d.settings.load_cell};
      m.params.stick_time = d.rig.stick_time;
      m.settings.duration_s = d.settings.duration_s;
      m.settings.slow_step_s = d.settings.thermal_step_s;
      m.settings.sample_rate_Hz = d.settings.sample_rate_Hz;
      return m;
    }
  }
  throw std::logic_error("unknown model kind");
}

}  // namespace

Scenario load_scenario_text(const std::string& text, const std::string& path) {
  Scenario sc;
  Draft s;
  s.path = sc.path = path;
  sc.text = text;
  const toml::table doc = TomlTable::parse_text(text, path);
  TomlTable root(doc, path, "");

  auto head = root.table("scenario");
  sc.name = head.string_or("name", fs::path(path).stem().string());
  s.type = head.choice_or("type", "prescribed_slip", {"prescribed_slip", "rig", "driveline", "network"});
  if (s.type == "network")
    head.fail("type",
              "\"network\" scenarios (docs/formats/network_file.md) work with `shudder run`, `sweep`, `modes`, `plot` "
              "and `diagnose`; "
              "this command needs type = \"prescribed_slip\", \"rig\" or \"driveline\"");
  s.kind = kind_of_type(s.type);
  sc.description = head.string_or("description", "");
  s.settings.duration_s = head.number("duration_s", Range::closed(1e-3, 1e5));
  head.finish();

  read_clutch(root, s);
  if (s.kind == ModelKind::kDriveline) {
    read_driveline(root, s);
    s.settings.sample_rate_Hz = 1000.0;
  } else {
    read_drive(root, s);
  }
  if (s.kind != ModelKind::kDriveline && root.has("driveline"))
    root.fail("driveline", "[driveline] belongs to type = \"driveline\" scenarios");
  if (s.kind != ModelKind::kDriveline && root.has("road"))
    root.fail("road", "[road] belongs to type = \"driveline\" scenarios");
  if (s.kind == ModelKind::kRig) {
    read_rig(root, s);
    s.settings.sample_rate_Hz = 1000.0;  // rig default: the thesis' typical 100 S/s–1 kS/s
  } else {
    root.mark_read("rig");
    if (root.has("rig")) s.warnings.push_back("[rig] is ignored by a " + s.type + " scenario");
  }

  if (auto solver = root.optional_table("solver")) {
    s.clutch.thermal.radial_cells =
        static_cast<int>(solver->integer_or("radial_cells", s.clutch.thermal.radial_cells, 2, 2000));
    s.settings.thermal_step_s =
        solver->number_or("thermal_step_ms", s.settings.thermal_step_s * 1e3, Range::closed(1e-3, 1e4)) * 1e-3;
    const std::string scheme = solver->choice_or("thermal_scheme", "backward_euler", {"backward_euler", "bdf2"});
    if (scheme == "bdf2" && s.kind != ModelKind::kPrescribedSlip)
      solver->fail("thermal_scheme",
                   "\"bdf2\" needs the clutch's heat at each thermal step's end, which only type = \"prescribed_slip\" "
                   "knows; a " +
                       s.type + " scenario steps its thermal field with \"backward_euler\" (remove the key)");
    s.settings.thermal_scheme =
        scheme == "bdf2" ? rig_models::ThermalScheme::kBdf2 : rig_models::ThermalScheme::kBackwardEuler;
    auto& integ = s.kind == ModelKind::kDriveline ? s.driveline.integrator : s.rig.integrator;
    integ.abs_tol = solver->number_or("abs_tol", integ.abs_tol, Range::closed(1e-15, 1e-2));
    integ.rel_tol = solver->number_or("rel_tol", integ.rel_tol, Range::closed(1e-15, 1e-2));
    integ.max_step_s = solver->number_or("max_step_ms", integ.max_step_s * 1e3, Range::closed(1e-6, 1e3)) * 1e-3;
    solver->finish();
  }
  if (auto out = root.optional_table("output")) {
    s.settings.sample_rate_Hz = out->number_or("sample_rate_Hz", s.settings.sample_rate_Hz, Range::closed(1e-3, 1e6));
    if (out->has("snapshot_times_s"))
      s.settings.snapshot_times_s = out->numbers("snapshot_times_s", Range::non_negative(), 0);
    else
      out->mark_read("snapshot_times_s");
    out->finish();
  }
  read_effects(root, s);
  root.finish();

  const auto target = effect_target(s);
  for (const auto& effect : rig_models::effect_registry())
    if (effect.enabled(target)) sc.enabled_effects.push_back(effect.name);

  sc.fluid_path = s.fluid_path;
  sc.fluid_text = s.fluid_text;
  sc.fluid = s.fluid;
  sc.clutch = s.clutch;
  sc.stick_time = s.rig.stick_time;
  sc.warnings = s.warnings;
  sc.model = make_model(s);
  return sc;
}

std::string read_scenario_text(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path, 0, "", "cannot open the file for reading");
  std::ostringstream os;
  os << in.rdbuf();
  return os.str();
}

components::WetPackSpec read_wet_pack(TomlTable& component, const std::string& scenario_path,
                                      std::vector<std::string>& warnings) {
  Draft s;
  s.path = scenario_path;
  s.type = "network";
  s.kind = ModelKind::kRig;  // a wet clutch between two inertias: the rig's effects apply
  read_clutch(component, s);
  read_effects(component, s);
  components::WetPackSpec w;
  w.fluid_path = s.fluid_path;
  w.fluid_text = s.fluid_text;
  w.fluid = s.fluid;
  w.clutch = s.clutch;
  w.bearing_drag = s.settings.bearing_drag;
  w.stick_time = s.rig.stick_time;
  w.oil_volume_given = s.oil_volume_given;
  w.oil_flow_given = s.oil_flow_given;
  const auto target = effect_target(s);
  for (const auto& effect : rig_models::effect_registry())
    if (effect.enabled(target)) w.enabled_effects.push_back(effect.name);
  std::string where = component.full_key("");
  if (!where.empty() && where.back() == '.') where.pop_back();
  for (auto& msg : s.warnings) warnings.push_back(where + ": " + msg);
  return w;
}

clutch::WetClutch Scenario::make_clutch() const {
  try {
    return clutch::WetClutch(clutch, fluid);
  } catch (const std::invalid_argument& e) {
    throw InputError(path, 0, "", e.what());
  }
}

}  // namespace shudder::io
