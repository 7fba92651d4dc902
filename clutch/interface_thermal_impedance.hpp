#pragma once
// Thermal impedance of a friction interface to an oscillating heat flux (1-D, across the discs):
// how far the interface temperature swings for a heat flux δq'' e^{iωt} (W/m²), δT = Z(iω) δq''.
//
// Each side of the interface is a stack of layers ending in an adiabatic plane (the symmetry
// planes of clutch/thermal_model.hpp: the half separator on one side, the lining and the half core
// disc on the other). A layer of thickness L, conductivity k, diffusivity α = k/(ρ c) carries the
// wave γ = √(iω/α) (1/m) with characteristic impedance Z_c = 1/(k γ) (m² K/W); with the impedance
// Z_b of what lies behind it, its face shows (transmission line of the heat equation; Carslaw &
// Jaeger, Conduction of Heat in Solids, 2nd ed. 1959, §2.6 periodic heating)
//     Z = Z_c (Z_b + Z_c tanh γL) / (Z_c + Z_b tanh γL),     Z = Z_c coth γL for an adiabatic back.
// The two sides take the flux in parallel: Z = 1 / (1/Z_sep + 1/Z_lining+core).
// Limits (tests): thick layers (L ≫ √(α/ω)): Z = 1/((e₁ + e₂) √(iω)) with the effusivities
// e = √(k ρ c); slow (L ≪ √(α/ω)): Z = 1/(iω Σ ρ c L), the layers' heat capacity per area.
// Left out: radial conduction and the oil's convection (a few W/K against the discs' conduction
// at these frequencies: docs/physics.md §3), so |Z| is an upper bound on the swing.

#include <complex>

#include "clutch/thermal_model.hpp"

namespace shudder::clutch {

/// Z(iω) (m² K/W) of the interface between `params`' separator and lining (+ core), ω in rad/s
/// (> 0). Throws std::invalid_argument for ω <= 0 or a layer without positive properties.
std::complex<double> interface_thermal_impedance(const ThermalParams& params, double omega_rad_s);

}  // namespace shudder::clutch
