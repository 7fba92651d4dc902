#pragma once
// Time signals that drive a network: a clutch's normalised normal force, a source's torque or
// speed, an engine's throttle. The building blocks engineers use for engagement and shift
// schedules (as Modelica.Blocks.Sources or Simscape's signal sources):
//
//   constant   y = value
//   table      y from (time_s[i], value[i]): "linear" interpolates, "step" holds value[i] until
//              time_s[i+1]; before the first point and after the last the end values hold
//   step       y = before for t < time_s, after from time_s on
//   sine       y = offset + amplitude sin(2π f (t − start_s) + φ) from start_s, offset before it
//   pulse      y = high for (t − start_s) mod period_s < width_s (t >= start_s), else low
//   ramp       y = from_value until start_s, linear to to_value at start_s + duration_s, then held
//   product    y = y_1(t) · y_2(t)
//   held       y = a value set from outside while the network runs (an FMU's input, fmu/network_fmu.cpp):
//              no knots, slope 0; its range over a run (max_over, min_over) is the scenario signal's
//              it stands in for, so the builder's checks judge the scenario as written
//
// Units: t in s, y in the unit of the key the signal drives (documented with each component).
// derivative(t) is dy/dt where defined (0 at and across jumps: a speed source fed a step jumps
// its node's speed, which the integrator meets as an event at the knot, docs/formats/network_file.md).

#include <memory>
#include <string>
#include <vector>

namespace shudder::components {

class Signal {
 public:
  enum class Kind { kConstant, kTable, kStep, kSine, kPulse, kRamp, kProduct, kHeld };

  static Signal constant(double value);
  /// times strictly increasing, one value per time (std::invalid_argument otherwise).
  static Signal table(std::vector<double> times_s, std::vector<double> values, bool linear);
  static Signal step(double time_s, double before, double after);
  static Signal sine(double offset, double amplitude, double frequency_Hz, double phase_rad, double start_s);
  /// 0 < width_s <= period_s.
  static Signal pulse(double low, double high, double period_s, double width_s, double start_s);
  /// duration_s >= 0 (0: a step at start_s).
  static Signal ramp(double from_value, double to_value, double start_s, double duration_s);
  static Signal product(Signal a, Signal b);
  /// The value `*value` (which the caller changes between integration steps) in place of
  /// `stands_for`, whose range max_over/min_over report.
  static Signal held(std::shared_ptr<const double> value, Signal stands_for);

  double operator()(double t_s) const;
  double derivative(double t_s) const;
  /// Largest and smallest value over [t0, t1] (exact for every kind but a product, which is
  /// sampled at the knots of its factors and 1000 points between).
  double max_over(double t0_s, double t1_s) const;
  double min_over(double t0_s, double t1_s) const;
  /// Times in (t0, t1) where the signal or its slope jumps (table knots, steps, pulse edges,
  /// ramp ends), ascending: a stepper that must not step across them ends its steps there.
  std::vector<double> knots(double t0_s, double t1_s) const;
  Kind kind() const { return kind_; }

 private:
  Kind kind_ = Kind::kConstant;
  std::vector<double> times_, values_;  // table
  bool linear_ = true;
  double a_ = 0, b_ = 0, c_ = 0, d_ = 0, e_ = 0;  // per kind, see the factories
  std::shared_ptr<const Signal> f1_, f2_;         // product; held: f1_ is the signal it stands for
  std::shared_ptr<const double> held_;            // held
};

}  // namespace shudder::components
