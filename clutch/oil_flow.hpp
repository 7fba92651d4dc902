#pragma once
// Interface oil flow, Paper G eq. 12 (empirical; constants a–e unpublished, calibrated here):
//
//     Q_oil = Q_oiltot * ( a * (Δω + 1)^b + c * T_mean^d + e )
//
// Units (Paper G states none; our choice): Δω = |slip speed| in rad/s, T_mean = area-mean
// interface temperature in KELVIN (so the power is defined for sub-zero starts), Q in m³/s.
// The bracket is the fraction of the supplied flow that passes through the contact; it is
// clamped at zero (a flow cannot reverse).
//
// How the flow cools the interface film (per radial ring i, upwind in r, outward flow):
//   film_energy_balance  heat removed = rho*cp*Q * (T_i - T_{i-1})                [W]
//                        — the film's own energy balance, dimensionally consistent.
//   paper_g_literal      heat removed = rho*cp*Q/(2*pi*h_mean) * r_i * dT/dr * A_i
//                        = rho*cp*Q * r_i²/h_mean * (T_i - T_{i-1})                [W·m]
//                        — Paper G eqs. 9–11 as printed. The term is not dimensionally
//                        consistent (a stray length, r²/h ≈ 150–320), yet Paper G calibrated
//                        a–e with it, so a "small fraction" of Q_tot reproduces its results.
//                        It stands for all the cooling the model lacks (groove convection,
//                        conduction into the rig). See docs/thermal_model.md.

namespace shudder::clutch {

enum class FilmAdvectionForm { kPaperGLiteral, kFilmEnergyBalance };

// Defaults: calibrated against Paper G Case 1 (10.4 and 25.3 kN, with and without oil flow and
// temperature-dependent friction) and Paper B's ramp; docs/thermal_model.md shows the scan.
// The targets are met best by a constant 1.6 % of Q_tot: a speed term (a, b) cools the end of
// the ramp more and shrinks the constant-temperature torque gap below Paper G's "quite large";
// a positive temperature term (flow ~ 1/viscosity) starves Paper B's 60 °C start of cooling.
struct OilFlowLaw {
  double a = 0.0;    // weight of the slip-speed term (dimensionless); calibrated
  double b = 1.0;    // exponent of (Δω + 1), Δω in rad/s
  double c = 0.0;    // weight of the temperature term, per K^d; calibrated
  double d = 1.0;    // exponent of T_mean in K
  double e = 0.016;  // fraction flowing at zero slip and zero temperature term; calibrated
  FilmAdvectionForm form = FilmAdvectionForm::kPaperGLiteral;

  /// Fraction of the supplied flow through the interface (>= 0).
  double fraction(double slip_rad_s, double mean_temp_C) const;
};

}  // namespace shudder::clutch
