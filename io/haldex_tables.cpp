#include "io/haldex_tables.hpp"

namespace shudder::io {

void read_haldex_hydraulics(TomlTable& h, components::HaldexHydraulicsParams& hp) {
  // A first-generation coupling; the lumped keys of a generation-mixing model are refused with
  // what replaces them.
  if (h.has("torque_per_bar_Nm"))
    h.fail("torque_per_bar_Nm",
           "was a later generation's figure; the Gen I coupling's torque per bar follows "
           "from piston_area_cm2 and the pack (the clutch's interfaces and radii)");
  if (h.has("leak_time_constant_s"))
    h.fail("leak_time_constant_s",
           "is replaced by the throttle valve (valve_area_mm2, the controller's opening) "
           "and the leakage leak_cm3_s_per_bar over the compliance");
  const auto positive = [&](const char* key, double& v) { v = h.number_or(key, v, Range::positive()); };
  hp.relief_pressure_bar = h.number_or("relief_pressure_bar", hp.relief_pressure_bar, Range::closed(1.0, 200.0));
  positive("piston_area_cm2", hp.piston_area_cm2);
  positive("pump_displacement_cm3_per_rev", hp.pump_displacement_cm3_per_rev);
  positive("chamber_volume_cm3", hp.chamber_volume_cm3);
  positive("bulk_modulus_bar", hp.bulk_modulus_bar);
  positive("pack_stiffness_N_per_mm", hp.pack_stiffness_N_per_mm);
  hp.valve_area_mm2 = h.number_or("valve_area_mm2", hp.valve_area_mm2, Range::non_negative());
  hp.discharge_coefficient =
      h.number_or("discharge_coefficient", hp.discharge_coefficient, Range{0.0, 1.0, true, false});
  hp.leak_cm3_s_per_bar = h.number_or("leak_cm3_s_per_bar", hp.leak_cm3_s_per_bar, Range::non_negative());
  positive("oil_density_kg_m3", hp.oil_density_kg_m3);
  hp.preload_torque_Nm = h.number_or("preload_torque_Nm", hp.preload_torque_Nm, Range::non_negative());
  hp.valve_time_constant_ms =
      h.number_or("valve_time_constant_ms", hp.valve_time_constant_ms, Range{0.0, 1e4, true, false});
  h.finish();
}

void read_haldex_controller(TomlTable& c, components::HaldexControllerParams& cp) {
  // Speeds in km/h, slip in axle rpm.
  cp.lock_slip_rpm = c.number_or("lock_slip_rpm", cp.lock_slip_rpm, Range::positive());
  cp.pedal_gain = c.number_or("pedal_gain", cp.pedal_gain, Range::closed(0.0, 1.0));
  cp.parking_speed_km_h = c.number_or("parking_speed_km_h", cp.parking_speed_km_h, Range::closed(0.0, 300.0));
  cp.parking_turn_ratio = c.number_or("parking_turn_ratio", cp.parking_turn_ratio, Range::positive());
  cp.fast_speed_km_h = c.number_or("fast_speed_km_h", cp.fast_speed_km_h, Range::closed(0.0, 400.0));
  cp.top_speed_km_h = c.number_or("top_speed_km_h", cp.top_speed_km_h, Range{cp.fast_speed_km_h, 500.0, true, false});
  cp.fast_demand = c.number_or("fast_demand", cp.fast_demand, Range::closed(0.0, 1.0));
  cp.control_period_ms = c.number_or("control_period_ms", cp.control_period_ms, Range{0.0, 1e3, true, false});
  cp.speed_filter_time_constant_ms =
      c.number_or("speed_filter_time_constant_ms", cp.speed_filter_time_constant_ms, Range::closed(0.0, 1e4));
  c.finish();
}

}  // namespace shudder::io
