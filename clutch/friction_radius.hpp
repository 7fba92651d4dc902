#pragma once
// The friction radius: the one definition of every conversion between a clutch's torque and its
// friction coefficient, used by the clutch model, `characterise`, `screen` and the replay.
//
//   M = mu · F · r_eff · n          torque of n sliding interfaces at a uniform mu (N m, N, m)
//   v = omega · r_eff               sliding speed at which that mu is read
//                                   (core/units.hpp mm_s_per_rpm: 1 rpm = 4.82 mm/s at 46 mm)
//
// r_eff depends on how the pressure is spread over the annulus ri..ro (docs/physics.md §9):
//   uniform pressure   r_eff = 2/3 (ro³ − ri³)/(ro² − ri²)    (47.84 mm for 38.1–56.4 mm)
//   uniform wear       r_eff = the stated mean radius         (the thesis: 46 mm)
//   model              r_eff = Σ r_i A_i / Σ A_i over the clutch model's rings: the model puts a
//                      uniform pressure on rings (clutch/wet_clutch.hpp), so for a uniform mu its
//                      torque is exactly mu F r_eff n at this radius (the uniform-pressure value
//                      to within the rings' discretisation: 47.839 mm for Paper G's annulus).
//
// A friction law fitted from torque at one radius r_law and used by a model whose radius is
// r_model reproduces the torque it was fitted on when it is read as
//   mu_model(v) = k · mu_law(k · v),  k = r_law / r_model
// (at every slip omega: the model's mean ring slides at omega r_model, the law's data at
// omega r_law, and mu_model F r_model n = mu_law F r_law n). clutch::Fluid records r_law
// (fluid files: [friction_radius], docs/fluid_format.md); the clutch model applies the
// conversion when it is built (with_friction_radius).

#include <memory>
#include <string>
#include <string_view>

#include "clutch/fluid.hpp"
#include "clutch/friction_law.hpp"
#include "clutch/thermal_model.hpp"

namespace shudder::clutch {

enum class RadiusConvention { kUniformPressure, kUniformWear };

/// "uniform_pressure" or "uniform_wear".
const char* radius_convention_name(RadiusConvention c);
/// The convention named `name`; false if it is neither name.
bool parse_radius_convention(std::string_view name, RadiusConvention& out);

/// 2/3 (ro³ − ri³)/(ro² − ri²), in the unit of the radii. Requires ro > ri >= 0.
double uniform_pressure_radius(double inner, double outer);

/// The clutch model's friction radius: sum r_i A_i / sum A_i over the thermal model's rings, m.
double model_friction_radius_m(const ThermalModel& thermal);
/// The same for a clutch with these thermal parameters (builds its ThermalModel).
double model_friction_radius_m(const ThermalParams& thermal);

/// mu = M / (F r_eff n); 0 when F r_eff n is not positive.
double mu_from_torque(double torque_Nm, double force_N, double radius_m, int interfaces);
/// M = mu F r_eff n.
double torque_from_mu(double mu, double force_N, double radius_m, int interfaces);

/// `law` read at another radius: mu(v) = k · law(k v), k = law_radius / model_radius. Speed
/// ranges are divided by k; a SpeedCurve form is kept (its rates and weights scaled).
std::shared_ptr<const FrictionLaw> friction_at_radius(std::shared_ptr<const FrictionLaw> law, double law_radius_mm,
                                                      double model_radius_mm);

/// The fluid as a model of radius `model_radius_mm` must read it: unchanged when the fluid
/// records no radius (its mu is a local coefficient, e.g. Paper G's matrix) or the same one
/// (within 1e-9 relative); else its law converted (friction_at_radius) and its recorded
/// radius set to the model's.
Fluid with_friction_radius(Fluid fluid, double model_radius_mm);

}  // namespace shudder::clutch
