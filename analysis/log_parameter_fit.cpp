#include "analysis/log_parameter_fit.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <unsupported/Eigen/LevenbergMarquardt>

namespace shudder::analysis {

namespace {

// Cost assigned to an infeasible point: the solver sees a wall, never a NaN.
constexpr double kInfeasibleResidual = 1e6;

bool is_linear(const LogParameterProblem& p, std::size_t j) { return !p.linear.empty() && p.linear[j]; }

struct Tracker {
  const LogParameterProblem& problem;
  int evaluations = 0;
  LogParameterFit best;

  std::vector<double> clamp(std::vector<double> v) const {
    for (std::size_t j = 0; j < v.size(); ++j) v[j] = std::clamp(v[j], problem.lower[j], problem.upper[j]);
    return v;
  }
  // The best start's residual: the LM run's first call asks for it again.
  std::vector<double> origin;
  Eigen::VectorXd origin_residual;

  // Returns false when the budget is spent (the LM run then stops).
  bool evaluate(const std::vector<double>& raw, Eigen::VectorXd& r) {
    if (evaluations >= problem.max_evaluations) return false;
    ++evaluations;
    const auto values = clamp(raw);
    // The same point again (the LM run's start): the stored residual, no second simulation.
    // Still counted against the budget, so a fit takes the same steps as when it was simulated.
    if (!origin.empty() && values == origin) {
      r = origin_residual;
      return true;
    }
    r.resize(problem.residuals);
    bool ok = false;
    try {
      ok = problem.evaluate(values, r);
    } catch (const std::exception&) {
      ok = false;
    }
    if (ok && !r.allFinite()) ok = false;
    if (!ok) {
      r.setConstant(kInfeasibleResidual);
      return true;
    }
    const double cost = r.squaredNorm();
    if (!best.feasible || cost < best.cost) {
      best.values = values;
      best.cost = cost;
      best.feasible = true;
    }
    return true;
  }
};

struct Functor : Eigen::DenseFunctor<double> {
  Functor(Tracker& t, std::vector<double> origin, int n, int m)
      : Eigen::DenseFunctor<double>(n, m), tracker(t), origin(std::move(origin)) {}
  Tracker& tracker;
  std::vector<double> origin;  // p_start: theta = log(p / p_start), or (p - p_start) / span

  std::vector<double> parameters(const InputType& theta) const {
    const auto& p = tracker.problem;
    std::vector<double> v(origin.size());
    for (std::size_t j = 0; j < v.size(); ++j) {
      const double th = theta[static_cast<Eigen::Index>(j)];
      v[j] = is_linear(p, j) ? origin[j] + th * (p.upper[j] - p.lower[j]) : origin[j] * std::exp(th);
    }
    return v;
  }
  int operator()(const InputType& theta, ValueType& f) {
    // Cache: lmder asks for f(x) and then J(x) at the same x; the Jacobian reuses f.
    if (!tracker.evaluate(parameters(theta), f)) return -1;
    last_theta = theta;
    last_f = f;
    return 0;
  }
  int df(const InputType& theta, JacobianType& jac) {
    ValueType f0;
    if (last_theta.size() == theta.size() && last_theta == theta) {
      f0 = last_f;
    } else if (!tracker.evaluate(parameters(theta), f0)) {
      return -1;
    }
    jac.resize(values(), inputs());
    const double h = tracker.problem.step;
    for (Eigen::Index j = 0; j < inputs(); ++j) {
      InputType t = theta;
      t[j] += h;
      ValueType f1;
      if (!tracker.evaluate(parameters(t), f1)) return -1;
      jac.col(j) = (f1 - f0) / h;
    }
    return 0;
  }
  InputType last_theta;
  ValueType last_f;
};

}  // namespace

LogParameterFit fit_log_parameters(const LogParameterProblem& p) {
  const std::size_t n = p.lower.size();
  if (n == 0 || p.upper.size() != n || p.starts.empty() || p.residuals < static_cast<int>(n) ||
      !(p.linear.empty() || p.linear.size() == n))
    throw std::invalid_argument("fit_log_parameters: inconsistent problem sizes");
  for (std::size_t j = 0; j < n; ++j)
    if (!((is_linear(p, j) || p.lower[j] > 0) && p.upper[j] > p.lower[j]))
      throw std::invalid_argument("fit_log_parameters: bounds must satisfy 0 < lower < upper");

  Tracker tracker{p, 0, {}, {}, {}};
  // Pick the best start by one evaluation each.
  std::vector<double> origin;
  double origin_cost = std::numeric_limits<double>::infinity();
  for (const auto& s : p.starts) {
    if (s.size() != n) throw std::invalid_argument("fit_log_parameters: a start has the wrong size");
    Eigen::VectorXd r;
    const auto v = tracker.clamp(s);
    if (!tracker.evaluate(v, r)) break;
    const double c = r.squaredNorm();
    if (c < origin_cost) {
      origin_cost = c;
      origin = v;
      tracker.origin_residual = r;
    }
  }
  tracker.origin = origin;
  if (!origin.empty() && tracker.evaluations < p.max_evaluations) {
    Functor f(tracker, origin, static_cast<int>(n), p.residuals);
    Eigen::LevenbergMarquardt<Functor> lm(f);
    lm.setFactor(1.0);  // first step at most a factor e in each parameter
    // Stop at 0.1 % parameter change or 0.01 % misfit change: the misfit is in noise units, so
    // a relative 1e-4 of J ≈ 1–100 is far below what the selection can tell apart (0.05), and
    // 0.1 % is far inside the 20 % an identifiable parameter must meet. Tighter tolerances
    // cost a fifth more simulations (each one a full replay) for no visible change.
    lm.setXtol(1e-3);
    lm.setFtol(1e-4);
    lm.setGtol(0.0);
    lm.setMaxfev(p.max_evaluations);
    Eigen::VectorXd theta = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(n));
    lm.minimize(theta);
  }
  LogParameterFit out = tracker.best;
  out.evaluations = tracker.evaluations;
  return out;
}

}  // namespace shudder::analysis
