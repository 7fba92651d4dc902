#pragma once
// Nonlinear least squares over positive (and signed, see `linear`) parameters with Eigen's Levenberg–Marquardt
// (unsupported/Eigen/LevenbergMarquardt, the MINPACK lmder algorithm).
//
// The solver works on theta_j = log(p_j / p_start_j): positivity is built in, steps are
// relative (a heat capacity in J/K and a friction coefficient of 0.005 are equally easy), and
// the start is theta = 0. A parameter marked `linear` (a signed one: a sensor offset) is
// theta_j = (p_j - p_start_j) / (upper_j - lower_j) instead. Values are clamped to [lower, upper] before every
// evaluation. The Jacobian is a forward difference with step h in theta (relative step h in p), because the residuals
// come from simulations; h = 2e-3 keeps the truncation error (~h) and the simulation's own noise (~1e-6 relative for an
// adaptive integrator, ÷h) both near 1e-3. Every evaluation counts against max_evaluations; the best point ever
// evaluated is returned, so an exhausted budget still gives the best fit found.

#include <Eigen/Dense>
#include <functional>
#include <vector>

namespace shudder::analysis {

struct LogParameterProblem {
  int residuals = 0;  // length of the residual vector (>= number of parameters)
  /// Residuals at physical parameter values; false = the model cannot be evaluated there.
  std::function<bool(const std::vector<double>& values, Eigen::VectorXd& residual)> evaluate;
  std::vector<double> lower, upper;         // bounds, 0 < lower < upper (linear: lower < upper)
  std::vector<bool> linear;                 // empty, or per parameter: fitted linearly
  std::vector<std::vector<double>> starts;  // tried in order; LM starts from the best one
  int max_evaluations = 60;
  double step = 2e-3;  // finite-difference step in log space
};

struct LogParameterFit {
  std::vector<double> values;  // best parameters (physical units)
  double cost = 0.0;           // sum of squared residuals there
  int evaluations = 0;
  bool feasible = false;  // false if no evaluation succeeded
};

LogParameterFit fit_log_parameters(const LogParameterProblem& problem);

}  // namespace shudder::analysis
