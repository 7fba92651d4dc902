#pragma once
// Whether an engagement's record holds a real oscillation or one transient. The shudder detector
// (analysis/shudder_detection.hpp) was made for steady sliding; over a clutch's engagement the
// torque follows the force ramp, and a ramp's corner leaves one bump in the detrended torque
// that the detector measures like an oscillation's half peak-to-peak. An oscillation repeats:
//
//   swings     r = T − M_P[T] (M_P the centred moving mean over one period P = 1/f), counted
//              as alternating excursions beyond ±level: each time r passes +level after last
//              passing −level (or the reverse) is one swing; a sustained oscillation of amplitude
//              A > level gives two swings per period, one corner gives at most one.
//   stick onsets  samples where the contact becomes stuck after slipping.
//   period amplitudes  half peak-to-peak of r over each whole period P from the record's end
//              backwards (the last entry first): how the oscillation's size ends up.
//
// Units: t in s, T in N m, f in Hz, level in N m.

#include <cstddef>
#include <span>
#include <vector>

namespace shudder::studies {

int oscillation_swings(std::span<const double> time_s, std::span<const double> torque_Nm, double frequency_Hz,
                       double level_Nm);
int stick_onsets(std::span<const double> stuck);
std::vector<double> period_amplitudes_from_end(std::span<const double> time_s, std::span<const double> torque_Nm,
                                               double frequency_Hz);

}  // namespace shudder::studies
