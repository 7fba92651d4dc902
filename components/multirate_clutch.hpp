#pragma once
// The multi-rate coupling of docs/architecture.md for a torsional network with any number of
// wet-clutch contacts (every network that has one: the rig, the Haldex car, a user's drivetrain,
// all run by components/network_stepper.hpp): the torsional states are integrated adaptively to
// the end of each slow step, sampled on the way; then each clutch's thermal model is advanced over
// the step with the exact friction energy per ring its contact accumulated, and the mean slip
// (relative rotation / step) for the oil flow; each clutch context (the held inputs the contact
// law reads) gets the ring temperatures for the next step, the caller may update other held
// inputs (a control unit's command), and the stepper restarts. The thermal solvers' workspaces
// live here, one per clutch and run.
//
// Ring temperatures across a slow step: a continuous first-order hold. Holding each
// ring's thermal-update value over the step (a zero-order hold) would make the friction torque
// a staircase with a step at every update: a numerical forcing at 1/Δt_th and its harmonics (the
// 10 ms step's third harmonic, 300 Hz, sits on the 300 Hz bar mode and would set the onset of
// shudder). With T_k the interface temperatures of the update at t_k, the friction over
// [t_k, t_k+1] sees each ring move linearly (ClutchContext::set_ring_temperature_ramp) from
//   S_k = E_k (where the previous step's ramp ended: no jump at t_k)   to
//   E_k+1 = T_k + (T_k − T_k−1) Δt_k+1 / Δt_k   (linear extrapolation of the last two updates).
// Exact for a linear warming; otherwise E_k+1 − T(t_k+1) = O(Δt² T''), and the next ramp is
// re-anchored on the new update, so the error does not accumulate. The first step holds the
// start temperatures (no history). The remaining forcing is a slope change per step, ~Δt T''
// instead of a step ~T' (its harmonics fall as 1/n², not 1/n).
// Energy: unchanged bookkeeping. The heat handed to the thermal step is the ring heat the
// integrator accumulated, the integral of the same M_i |Δω| the motion felt, whatever
// temperature the friction read; so the mechanical account (source work = Δkinetic + Δelastic +
// friction heat + losses) and the thermal one (heat in = stored + to sump + to rig) close as
// before (components/energy_guard.hpp bounds 1e-3 and 1e-6).
// A thermal update that leaves ±1e4 °C (or is not finite) throws std::runtime_error, a numerical
// failure like a non-finite mechanical state: the hold would otherwise hand the integrator
// friction at such temperatures and it would creep on with ever smaller steps.
// Slow steps end exactly on the duration and on the sample times they meet: summed steps drift
// by round-off (1000 × 10 ms gives 9.99999999999983 s, which would lose the last sample; from
// ~2 s a step would end just before the sample meant to close it, so that sample would come
// after the step's update while earlier ones come before it). Step k
// ends at t0 + k·step, moved onto the duration or the sample k'/rate when within 1e-9 of a step;
// a sample at a step's end is always delivered before that step's update.

#include <functional>
#include <vector>

#include "clutch/friction_data_range.hpp"
#include "clutch/wet_clutch.hpp"
#include "dynamics/simulation.hpp"
#include "components/clutch_contact.hpp"

namespace shudder::components {

struct SlowStep {
  double ta_s, tb_s;
  const dynamics::Sample& before;  // at ta_s
  const dynamics::Sample& after;   // at tb_s, before the restart
};

/// One wet-clutch contact of the network in the multi-rate coupling: the context its law is bound
/// to, the clutch, its thermal state (advanced in place) and, optionally, its friction data tally.
struct MultirateClutch {
  ClutchContext* context = nullptr;
  const clutch::WetClutch* clutch = nullptr;
  clutch::ThermalState* state = nullptr;
  int contact = -1;
  clutch::FrictionDataRange* data_range = nullptr;
  /// The clamp force at a sample, for the data tally, when it is a state of the run (an
  /// actuator's pressure) rather than the context's held force; the step's mean of its ends.
  std::function<double(const dynamics::Sample&)> clamp_force_N = nullptr;
};

/// The coupling above for any number of wet clutches (none: the network alone, stepped and
/// restarted at each slow step): each clutch's thermal model advanced over every slow step with
/// the heat its own contact accumulated, and its own first-order hold. `breaks_s` are times where
/// an input jumps (a step in a source or a force): the stepper stops and restarts there, so no
/// step straddles the jump (dopri5's error control would otherwise meet it as a kink).
/// `at_break` (if given) is called at each break, the simulation there, before the restart: a
/// sampled controller sets its held output for the next period (breaks within round-off of a
/// slow step's end are taken at that end, after its thermal update and before `after_step`).
void run_multirate(dynamics::Simulation& sim, const std::vector<MultirateClutch>& clutches, double duration_s,
                   double slow_step_s, double sample_rate_Hz,
                   const std::function<void(const dynamics::Sample&)>& on_sample,
                   const std::function<void(const SlowStep&)>& after_step, const std::vector<double>& breaks_s = {},
                   const std::function<void(double t_s)>& at_break = nullptr);

/// The coupling of run_multirate (above) taken in pieces: advance_to(t) completes every slow
/// step that ends by t and integrates the torsional states on into the step under way, whose
/// thermal update waits until a later call reaches its end. run_multirate is one call to the
/// duration; an FMU calls it once per communication step. Slow steps, breaks and samples fall
/// at the same times whatever the pieces (the ends of the pieces are not restarts), so a run in
/// pieces follows the run in one call (the fixed-step stepper: to round-off, its steps cut at
/// the pieces' ends). `end_s` may be infinite (no duration: slow steps unbounded, no samples
/// delivered, but slow-step ends still snapped onto the sample times k / sample_rate_Hz as a
/// run's are, so they fall at the same instants).
class MultirateCoupling {
 public:
  MultirateCoupling(dynamics::Simulation& sim, const std::vector<MultirateClutch>& clutches, double end_s,
                    double slow_step_s, double sample_rate_Hz, std::vector<double> breaks_s = {},
                    std::function<void(double t_s)> at_break = nullptr);
  ~MultirateCoupling();
  MultirateCoupling(const MultirateCoupling&) = delete;
  MultirateCoupling& operator=(const MultirateCoupling&) = delete;
  /// Advances the simulation to min(t_s, end_s).
  void advance_to(double t_s, const std::function<void(const dynamics::Sample&)>& on_sample,
                  const std::function<void(const SlowStep&)>& after_step);
  /// More breaks, sorted and after every break given so far: a coupling without an end learns
  /// a periodic controller's instants piece by piece. Breaks already passed are dropped.
  void add_breaks(const std::vector<double>& later_s);

 private:
  struct Slot;
  double step_end(long k) const;
  void finish_slow_step(double ta, double tb, const dynamics::Sample& sb);

  dynamics::Simulation& sim_;
  double end_s_, slow_step_s_, sample_rate_Hz_, t0_s_, snap_s_;
  long n_samples_ = 0;
  std::vector<double> sample_times_, breaks_s_;
  std::function<void(double)> at_break_;
  std::vector<Slot> slots_;
  long k_ = 1;           // the slow step under way
  double ta_s_ = 0.0;    // its start
  dynamics::Sample sa_;  // the simulation there
};

}  // namespace shudder::components
