#include "rig_models/effect_registry.hpp"

namespace shudder::rig_models {

namespace {

constexpr double kMaxForce_N = 30000.0;  // rig cylinder maximum (thesis Method), as [drive]

// Bounds and starts: a heat capacity of 30 kJ/K would let a missing oil flow pass for stored
// heat, hence the upper bound of 5 kJ/K: the whole rig side of the clutch, ~10 kg of steel.
std::vector<EffectDefinition> build() {
  using clutch::FilmAdvectionForm;
  using R = ValueRange;
  return {// Acts in clutch::WetClutch: off, every ring uses the clutch start temperature.
          {"temperature_dependent_friction", "friction follows the interface temperature",
           [](auto& t) -> auto& {return t.clutch.temperature_dependent_friction;
}
, {}, {}, {}
}  // namespace
,
    // Acts in clutch::ThermalModel (Paper G eq. 12 through clutch::OilFlowLaw).
    {"interface_oil_cooling", "oil through the interface carries heat away (Paper G eq. 12)",
     [](auto& t) -> auto& {return t.clutch.thermal.interface_oil_cooling;
}  // namespace shudder::rig_models
, {{"a", "-", kSameUnit, R::any(), [](auto& t) -> auto& {return t.clutch.thermal.oil_flow.a;
}
, {}
}
, {"b", "-", kSameUnit, R::closed(-5.0, 5.0), [](auto& t) -> auto& {return t.clutch.thermal.oil_flow.b;
}
, {}
}
, {"c", "K^-d", kSameUnit, R::any(), [](auto& t) -> auto& {return t.clutch.thermal.oil_flow.c;
}
, {}
}
, {"d", "-", kSameUnit, R::closed(-5.0, 5.0), [](auto& t) -> auto& {return t.clutch.thermal.oil_flow.d;
}
, {}
}
, {"e", "-", kSameUnit, R::any(), [](auto& t) -> auto& {return t.clutch.thermal.oil_flow.e;
}
, FitSpec {
  1e-5, 1.0, { 0.016, 0.004, 0.064 }
}
}
,
}
,
    {{"film_advection",
      {"paper_g_literal", "film_energy_balance"},
      [](const ConstEffectTarget& t) { return static_cast<std::size_t>(t.clutch.thermal.oil_flow.form); },
      [](EffectTarget& t, std::size_t option) {
        t.clutch.thermal.oil_flow.form = static_cast<FilmAdvectionForm>(option);
      }}},
{}
}
,
    // Acts in clutch::ThermalModel (Paper G eq. 7): off, the sump holds its start temperature.
    {"sump_heating", "the sump warms with the heat carried out (Paper G eq. 7)",
     [](auto& t) -> auto& {return t.clutch.thermal.sump_heating;
}
, {}, {}, {}
}
,
    // Acts in clutch::ThermalModel: a lumped heat capacity behind the discs.
    {"rig_heat_capacity", "rig parts beyond the discs store heat and give it back",
     [](auto& t) -> auto& {return t.clutch.thermal.rig_heat_capacity;
}
, {{"heat_capacity_J_per_K", "J/K", kSameUnit, R::positive(),
    [](auto& t) -> auto& {return t.clutch.thermal.rig_heat_capacity_J_per_K;
}
, FitSpec {
  1.0, 5000.0, { 150.0, 600.0, 50.0 }
}
}
, {"conductance_W_per_K", "W/K", kSameUnit, R::non_negative(),
   [](auto& t) -> auto& {return t.clutch.thermal.rig_conductance_W_per_K;
}
, FitSpec {
  0.01, 1000.0, { 10.0, 30.0, 3.0 }
}
}
,
}
, {}, {}
}
,
    // Acts in clutch::ThermalModel: a first-order lag of the thermocouple reading.
    {"temperature_sensor_lag", "the temperature sensor lags the disc",
     [](auto& t) -> auto& {return t.clutch.thermal.temperature_sensor_lag;
}
, {{"time_constant_s", "s", kSameUnit, R::positive(),
    [](auto& t) -> auto& {return t.clutch.thermal.sensor_time_constant_s;
}
, FitSpec {
  1e-3, 100.0, { 0.3, 1.0, 3.0 }
}
}
}
, {}, {}
}
,
    // Acts in the torque cell (prescribed slip and components::ClutchContactLaw); heats no disc.
    {"bearing_drag", "the torque cell also carries bearing friction",
     [](auto& t) -> auto& {return t.bearing_drag.enabled;
}
, {{"equivalent_mu", "-", kSameUnit, R::closed(0.0, 0.1), [](auto& t) -> auto& {return t.bearing_drag.equivalent_mu;
}
, FitSpec {
  1e-6, 0.1, { 0.001, 0.005, 0.02 }
}
}
, {"radius_mm", "mm", kMilli, R::positive(), [](auto& t) -> auto& {return t.bearing_drag.radius_m;
}
, {}
}
,
}
, {}, {
  { ModelKind::kDriveline, "it is the rig's torque-cell bearing" }
}
}
,
    // Acts in components::ClutchContactLaw: the static capacity of stick phases.
    {"stick_time_static_friction", "breakaway friction grows with the time stuck",
     [](auto& t) -> auto& {return t.stick_time.enabled;
}
, {{"max_increase", "-", kSameUnit, R::closed(0.0, 5.0), [](auto& t) -> auto& {return t.stick_time.max_increase;
}
, FitSpec {
  1e-3, 5.0, { 0.15, 0.15, 0.4 }
}
}
, {"time_constant_s", "s", kSameUnit, R::positive(), [](auto& t) -> auto& {return t.stick_time.time_constant_s;
}
, FitSpec {
  1e-3, 100.0, { 0.05, 0.5, 0.1 }
}
}
,
}
, {}, {
  { ModelKind::kPrescribedSlip, "the slip is imposed, nothing sticks" }
}
}
,
    // Acts in clutch::WetClutch: the Couette torque of the oil film and its heat.
    {"viscous_shear", "a viscous torque of the oil film, proportional to viscosity and speed",
     [](auto& t) -> auto& {return t.clutch.viscous_shear;
}
,
    // gap in [0.01, 1e4] µm, the fit's own bounds: the Couette torque eta*v/h*A*r grows as
    // 1/h, and below 0.01 µm (a few molecular layers, no continuum film) it exceeds any
    // clutch's capacity (1e-300 µm gives 3.4e298 N m); above 1 cm it is nil.
    {{"gap_um", "µm", kMicro, R::closed(0.01, 1e4), [](auto& t) -> auto& {return t.clutch.viscous_gap_m;
}
, FitSpec {
  0.01, 1e4, { 0.3, 1.0, 3.0 }
}
}
}
, {}, {}
}
,
    // Acts in clutch::WetClutch: off, friction is evaluated at reference_load_N.
    {"load_dependent_friction", "friction depends on the normal force",
     [](auto& t) -> auto& {return t.clutch.load_dependent_friction;
}
, {{"reference_load_N", "N", kSameUnit, R::closed(1.0, kMaxForce_N),
    [](auto& t) -> auto& {return t.clutch.reference_load_N;
}
, {}
}
}
, {}, {}
}
,
    // Measurement faults (docs/formats/diagnosis_json.md names): the physics is unchanged, only the recorded
    // channel. Bounds are estimates: a gain beyond [0.5, 2] or a torque offset beyond ±50 N m
    // is a wrong cell or unit rather than a calibration error (the plausibility checks catch
    // those); ±10 K is over four times a type K junction's standard tolerance (±2.2 K).
    // Acts in the prescribed-slip torque cell (rig_models/prescribed_slip.hpp) and in a
    // driveline's measured coupling torque (rig_models/coupling_measurement.hpp).
    {"torque_sensor_gain", "the torque cell reads a fixed fraction high or low",
     [](auto& t) -> auto& {return t.torque_cell.gain_fault;
}
, {{"gain", "-", kSameUnit, R::positive(), [](auto& t) -> auto& {return t.torque_cell.gain;
}
, FitSpec {
  0.5, 2.0, { 0.97, 1.03, 1.1 }
}
}
}
, {}, {
  { ModelKind::kRig, "the rig's torque cell also drives its speed loop; not modelled there yet" }
}
}
, {"torque_sensor_offset", "the torque cell reads a constant torque too much",
   [](auto& t) -> auto& {return t.torque_cell.offset_fault;
}
, {{"offset_Nm", "N m", kSameUnit, R::closed(-50.0, 50.0), [](auto& t) -> auto& {return t.torque_cell.offset_Nm;
}
, FitSpec { -50.0, 50.0, {1.0, -1.0, 5.0}, true }
}
}
, {}, {
  { ModelKind::kRig, "the rig's torque cell also drives its speed loop; not modelled there yet" }
}
}
,
    // Acts in the recorded normal force (prescribed slip and rig, rig_models/prescribed_slip.hpp;
    // a driveline's measured clamp force, rig_models/coupling_measurement.hpp); a replay drives
    // the model with F_rec / g_F (studies/replay.cpp). Bounds as the torque cell's.
    {"load_sensor_gain", "the load cell reads a fixed fraction high or low",
     [](auto& t) -> auto& {return t.load_cell.gain_fault;
}
, {{"gain", "-", kSameUnit, R::positive(), [](auto& t) -> auto& {return t.load_cell.gain;
}
, FitSpec {
  0.5, 2.0, { 0.97, 1.03, 1.1 }
}
}
}
, {}, {}
}
,
    // Acts in clutch::ThermalModel (the reading of the thermocouple); in a replay the discs
    // then start at the sump's measured temperature (studies/replay.hpp).
    {"thermocouple_offset", "the thermocouple reads a constant temperature too much",
     [](auto& t) -> auto& {return t.clutch.thermal.thermocouple_offset;
}
, {{"offset_K", "K", kSameUnit, R::closed(-10.0, 10.0),
    [](auto& t) -> auto& {return t.clutch.thermal.thermocouple_offset_K;
}
, FitSpec { -10.0, 10.0, {0.5, -0.5, 2.0}, true }
}
}
, {}, {}
}
,
    // Acts in the prescribed-slip runner (rig_models/prescribed_slip.hpp), which accumulates
    // the sliding distance. Bounds: an estimate; a drift beyond ±50 % within a test is a
    // different friction pair, and s0 from 0.1 m (a few revolutions) to 10 km (a life test).
    {"friction_drift", "friction drifts with the sliding distance (running-in, ageing)",
     [](auto& t) -> auto& {return t.friction_drift.enabled;
}
, {{"change", "-", kSameUnit, R::closed(-0.9, 1.0), [](auto& t) -> auto& {return t.friction_drift.change;
}
, FitSpec { -0.5, 0.5, {-0.05, 0.05, -0.15}, true }
}
, {"distance_m", "m", kSameUnit, R::positive(), [](auto& t) -> auto& {return t.friction_drift.distance_m;
}
, FitSpec {
  0.1, 1e4, { 10.0, 3.0, 30.0 }
}
}
,
}
, {}, {
  {ModelKind::kRig, "the rig's contact law does not accumulate the sliding distance yet"}, {
    ModelKind::kDriveline, "the driveline's clutch does not accumulate the sliding distance yet"
  }
}
}
,
}
;
}

}  // namespace

const std::vector<EffectDefinition>& effect_registry() {
  static const std::vector<EffectDefinition> registry = build();
  return registry;
}

const EffectDefinition* find_effect(std::string_view name) {
  for (const auto& e : effect_registry())
    if (e.name == name) return &e;
  return nullptr;
}

std::string effect_names_list() {
  std::string list;
  for (const auto& e : effect_registry()) list += (list.empty() ? "" : ", ") + e.name;
  return list;
}

std::optional<std::string_view> inert_reason(const EffectDefinition& effect, ModelKind kind) {
  for (const auto& i : effect.inert_in)
    if (i.kind == kind) return i.reason;
  return std::nullopt;
}

std::vector<const EffectParameter*> fitted_parameters(const EffectDefinition& effect) {
  std::vector<const EffectParameter*> out;
  for (const auto& p : effect.parameters)
    if (p.fit) out.push_back(&p);
  return out;
}

}  // namespace shudder::rig_models
