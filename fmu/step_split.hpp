#pragma once
// How the FMU takes a communication step of length H with its internal fixed step h
// (docs/fmu.md "Step sizes"): whole internal steps, then, when H is not a whole multiple of h,
// one shorter step for the rest, so the step ends exactly at the master's tCurrent + H.
//
// Masters compute step sizes from their own clock (differences of absolute times, or t += h
// with the last step trimmed to the stop time), so a step meant as n·h arrives off by
// round-off. A rest within the tolerance below is that round-off, not a step: it is dropped
// and the step is n whole internal steps, which keeps the run on the internal grid (and equal
// to `shudder run --fixed-step`).
#include <algorithm>
#include <cmath>
#include <limits>

namespace shudder::fmu {

/// The largest rest (s) treated as round-off rather than a step, for a step from tc of length H:
///   max(1e-6 · h, 64 ulp(max(|tc|, |tc + H|)))
/// 1e-6 · h (1e-10 s at h = 0.1 ms) covers a summing master's clock near the start (t += 1e-4
/// is 1.5e-13 s off after 1.5 s and 2.5e-10 s after 1 s from 1800 s is beyond it and is then
/// honoured as a shorter step); dropping it changes a step's heat by at most 1e-6 relative.
/// The time term grows with |t|: the master cannot place times finer than an ulp of its clock,
/// and a difference of two absolute times is off by up to one ulp of each (2.3e-13 s at
/// 1800 s; it takes over from 1e-6 · h beyond |t| ≈ 7000 s at 0.1 ms).
inline double step_tolerance_s(double h, double tc, double H) {
  const double t = std::max(std::abs(tc), std::abs(tc + H));
  const double ulp = std::nextafter(t, std::numeric_limits<double>::infinity()) - t;
  return std::max(1e-6 * h, 64.0 * ulp);
}

struct StepSplit {
  double whole_steps = 0.0;    // internal steps of length h
  double last_fraction = 0.0;  // then one step of last_fraction · h (0: none), 0 < fraction < 1 + tol/h
};

/// Splits H (> 0) into whole internal steps of h and the rest beyond `tol` (step_tolerance_s).
/// A step shorter than `tol` is all round-off: no internal step (the master's time still
/// advances).
inline StepSplit split_step(double H, double h, double tol) {
  const double whole = std::floor((H + tol) / h);
  const double rest = H - whole * h;
  if (rest <= tol) return {whole, 0.0};
  return {whole, rest / h};
}

}  // namespace shudder::fmu
