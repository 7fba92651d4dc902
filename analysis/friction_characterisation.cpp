#include "analysis/friction_characterisation.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <limits>
#include <numeric>

#include "clutch/friction_radius.hpp"
#include "clutch/linear_friction.hpp"
#include "core/units.hpp"
#include "clutch/maki_friction.hpp"
#include "clutch/table_friction.hpp"
#include "analysis/temperature_surface.hpp"
#include "core/nan.hpp"

namespace shudder::analysis {

const char* compensation_name(Compensation c) {
  switch (c) {
    case Compensation::kNone: return "none";
    case Compensation::kLinear: return "linear";
    case Compensation::kQuadratic: return "quadratic";
    case Compensation::kPiecewise: return "piecewise";
  }
  return "?";
}

const char* law_name(LawKind k) {
  switch (k) {
    case LawKind::kMaki: return "maki";
    case LawKind::kLinear: return "linear";
    case LawKind::kTable: return "table";
  }
  return "?";
}

double FrictionConversion::effective_radius_mm() const {
  switch (rule) {
    case RadiusRule::kUniformWear: return mean_radius_mm;
    case RadiusRule::kModel: return model_radius_mm;
    case RadiusRule::kUniformPressure: break;
  }
  return clutch::uniform_pressure_radius(inner_radius_mm, outer_radius_mm);
}

clutch::RadiusConvention FrictionConversion::convention() const {
  return rule == RadiusRule::kUniformWear ? clutch::RadiusConvention::kUniformWear
                                          : clutch::RadiusConvention::kUniformPressure;
}

namespace {

std::string g(double x, int digits = 4) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*g", digits, x);
  return buf;
}

std::string row_name(double load_N, double temp_C) {
  return "row " + g(load_N / 1000.0) + " kN, " + g(temp_C, 3) + " °C";
}

// Groups sorted values: a new group starts where the gap to the previous value exceeds
// tol(previous). Returns each value's group and the groups' means.
std::pair<std::vector<int>, std::vector<double>> cluster(const std::vector<double>& x, const auto& tol) {
  std::vector<std::size_t> order(x.size());
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](auto a, auto b) { return x[a] < x[b]; });
  std::vector<int> group(x.size(), 0);
  std::vector<double> sum, mean;
  std::vector<int> count;
  for (std::size_t k = 0; k < order.size(); ++k) {
    const double v = x[order[k]];
    if (k == 0 || v - x[order[k - 1]] > tol(x[order[k - 1]])) {
      sum.push_back(0.0);
      count.push_back(0);
    }
    sum.back() += v;
    ++count.back();
    group[order[k]] = int(sum.size()) - 1;
  }
  for (std::size_t i = 0; i < sum.size(); ++i) mean.push_back(sum[i] / count[i]);
  return {group, mean};
}

// Linear interpolation in ln v of y over increasing xs, held beyond the ends; NaN-free input.
double interp_log(const std::vector<double>& xs, const std::vector<double>& ys, double x) {
  if (xs.size() == 1 || x <= xs.front()) return ys.front();
  if (x >= xs.back()) return ys.back();
  const std::size_t k = std::size_t(std::upper_bound(xs.begin(), xs.end(), x) - xs.begin()) - 1;
  const double w = std::log(x / xs[k]) / std::log(xs[k + 1] / xs[k]);
  return (1.0 - w) * ys[k] + w * ys[k + 1];
}

struct Sample {
  double v_mm_s, mu, temp_C;
};

// A row's compensated mu at a node: a quadratic in ln v fitted (weights = sample counts) to the
// bin means within ±30 % in speed of the node, read at the node. A bin at 5 rpm holds ~3
// samples of a 10 s ramp (the torque cell's noise: 1.3 % of mu per sample at 10 kN); the
// window pools ~5 bins, and a quadratic leaves only the curve's third-order change over it.
// Fewer than 3 bins in the window: linear interpolation between the bins around the node.
double node_value(const std::vector<double>& v, const std::vector<double>& mu, const std::vector<double>& count,
                  double node) {
  constexpr double kHalfWidth = 0.3;  // in ln v: ±30 % (estimate: the nodes are 5 rpm apart at 20 rpm, ±25 %)
  std::vector<double> x, y, w;
  for (std::size_t b = 0; b < v.size(); ++b)
    if (std::abs(std::log(v[b] / node)) <= kHalfWidth) {
      x.push_back(std::log(v[b] / node));
      y.push_back(mu[b]);
      w.push_back(count[b]);
    }
  if (x.size() < 3) return interp_log(v, mu, node);
  Eigen::MatrixXd a(long(x.size()), 3);
  Eigen::VectorXd yy(long(x.size())), ww(long(x.size()));
  for (std::size_t i = 0; i < x.size(); ++i) {
    a(long(i), 0) = 1.0;
    a(long(i), 1) = x[i];
    a(long(i), 2) = x[i] * x[i];
    yy(long(i)) = y[i];
    ww(long(i)) = w[i];
  }
  const Eigen::VectorXd sw = ww.array().sqrt();
  const Eigen::VectorXd q = (sw.asDiagonal() * a).colPivHouseholderQr().solve(sw.cwiseProduct(yy));
  return std::isfinite(q(0)) ? q(0) : interp_log(v, mu, node);
}

// A ramp's (mu, T) at a node speed: the means over its samples within ±5 % of the node speed
// (a single sample would carry the torque cell's full noise, ~1e-3 in mu at 15 kN; a 10 s
// ramp at 50 S/s puts ~5 samples in the window at 50 rpm, ~50 at 100 rpm of a 1–20 s ramp).
// nullopt if the ramp does not reach the node.
std::optional<std::pair<double, double>> at_node(const std::vector<Sample>& s, double speed_mm_s) {
  double sm = 0.0, st = 0.0;
  int n = 0;
  for (const Sample& p : s)
    if (std::abs(p.v_mm_s - speed_mm_s) <= 0.05 * speed_mm_s) {
      sm += p.mu;
      st += p.temp_C;
      ++n;
    }
  if (n == 0) return std::nullopt;
  return std::pair{sm / n, st / n};
}

// Weighted linear least squares; returns coefficients and (if cov) the unscaled covariance
// (X^T W X)^-1 (NaN where singular).
Eigen::VectorXd wls(const Eigen::MatrixXd& x, const Eigen::VectorXd& y, const Eigen::VectorXd& w,
                    Eigen::MatrixXd* cov = nullptr) {
  const Eigen::VectorXd sw = w.array().sqrt();
  const Eigen::MatrixXd xs = sw.asDiagonal() * x;
  const Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(xs);
  const Eigen::VectorXd beta = qr.solve(sw.cwiseProduct(y));
  if (cov) {
    const Eigen::MatrixXd n = xs.transpose() * xs;
    Eigen::FullPivLU<Eigen::MatrixXd> lu(n);
    *cov = lu.isInvertible() ? Eigen::MatrixXd(lu.inverse()) : Eigen::MatrixXd::Constant(n.rows(), n.cols(), kNaN);
  }
  return beta;
}

}  // namespace

std::array<double, 4> fit_maki_curve(const std::vector<double>& v, const std::vector<double>& mu,
                                     const std::vector<double>& weight, double sigma2, std::array<double, 4>* se) {
  const long n = long(v.size());
  if (n < 5) throw std::runtime_error("a Mäki fit needs at least 5 speeds; got " + std::to_string(n));
  Eigen::VectorXd y(n), w(n);
  for (long i = 0; i < n; ++i) {
    y(i) = mu[std::size_t(i)];
    w(i) = weight[std::size_t(i)];
  }
  // For a given C2 the model is linear in (C1, C3, C4): solve it and return the weighted SSR.
  const auto solve = [&](double c2, Eigen::Vector3d& coef) {
    Eigen::MatrixXd x(n, 3);
    for (long i = 0; i < n; ++i) {
      const double vi = v[std::size_t(i)];
      x(i, 0) = std::tanh(c2 * vi);
      x(i, 1) = std::pow(vi, 0.1);
      x(i, 2) = 1.0;
    }
    coef = wls(x, y, w);
    const Eigen::VectorXd r = x * coef - y;
    return (w.array() * r.array().square()).sum();
  };
  // C2 from 1e-5 to 1 per mm/s (kMakiC2Min/Max): Paper G's sets use 1e-4 … 1.3e-2; below 1e-5
  // tanh is linear over any measured range (C1·C2 then acts as one slope), above 1 it is a step
  // below 1 mm/s.
  constexpr int kGrid = 61;
  const double lo = std::log(kMakiC2Min), hi = std::log(kMakiC2Max);
  std::vector<double> cost(kGrid);
  Eigen::Vector3d coef;
  int best = 0;
  for (int k = 0; k < kGrid; ++k) {
    cost[std::size_t(k)] = solve(std::exp(lo + (hi - lo) * k / (kGrid - 1)), coef);
    if (!(cost[std::size_t(k)] >= cost[std::size_t(best)])) best = k;
  }
  // Golden section on ln C2 between the best point's neighbours.
  double a = lo + (hi - lo) * std::max(best - 1, 0) / (kGrid - 1);
  double b = lo + (hi - lo) * std::min(best + 1, kGrid - 1) / (kGrid - 1);
  const double phi = (std::sqrt(5.0) - 1.0) / 2.0;
  double c = b - phi * (b - a), d = a + phi * (b - a);
  double fc = solve(std::exp(c), coef), fd = solve(std::exp(d), coef);
  for (int it = 0; it < 60; ++it) {
    if (fc < fd) {
      b = d;
      d = c;
      fd = fc;
      c = b - phi * (b - a);
      fc = solve(std::exp(c), coef);
    } else {
      a = c;
      c = d;
      fc = fd;
      d = a + phi * (b - a);
      fd = solve(std::exp(d), coef);
    }
  }
  const double c2 = std::exp(0.5 * (a + b));
  const double ssr = solve(c2, coef);
  if (!std::isfinite(ssr) || !coef.allFinite())
    throw std::runtime_error("the Mäki least-squares fit gave no finite parameters");
  const std::array<double, 4> p{coef(0), c2, coef(1), coef(2)};
  if (se) {
    Eigen::MatrixXd j(n, 4);
    for (long i = 0; i < n; ++i) {
      const double vi = v[std::size_t(i)], th = std::tanh(c2 * vi);
      j(i, 0) = th;
      j(i, 1) = p[0] * vi * (1.0 - th * th);
      j(i, 2) = std::pow(vi, 0.1);
      j(i, 3) = 1.0;
    }
    Eigen::MatrixXd cov;
    wls(j, y, w, &cov);
    for (int k = 0; k < 4; ++k) (*se)[std::size_t(k)] = std::sqrt(std::max(sigma2 * cov(k, k), 0.0));
  }
  return p;
}

Characterisation characterise(const std::vector<RampRun>& runs, const CharacterisationSettings& s) {
  Characterisation out;
  const double r_mm = s.conversion.effective_radius_mm();
  out.effective_radius_mm = r_mm;
  if (!(r_mm > 0) || s.conversion.interfaces < 1)
    throw std::invalid_argument("the friction radius and the number of interfaces must be positive");
  const double mm_s_per_rpm = units::mm_s_per_rpm(r_mm);

  // 1. Ramps, and each ramp's reference temperature.
  for (std::size_t r = 0; r < runs.size(); ++r) {
    const RampSearch found = find_ramps(runs[r], r, s.ramps);
    out.rejected.insert(out.rejected.end(), found.rejected.begin(), found.rejected.end());
    if (found.ramps.empty())
      throw CharacterisationInputError(
          runs[r].name, found.rejected.empty()
                            ? "no speed ramp found (the speed never changes faster than " + g(s.ramps.min_rate_rpm_s) +
                                  " rpm/s over " + g(s.ramps.min_span_rpm) +
                                  " rpm); characterise needs up- or down-ramps (Paper D/E cycles)"
                            : "no usable speed ramp: " + std::to_string(found.rejected.size()) +
                                  " candidate(s) rejected, the first because it " + found.rejected.front().reason);
    double last_up = kNaN;
    for (const Ramp& ramp : found.ramps) {
      double ref = ramp.start_temp_C;
      if (ramp.direction == RampDirection::kUp)
        last_up = ref;
      else if (std::isfinite(last_up))
        ref = last_up;
      out.used.push_back(ramp);
      out.used_ref_temp_C.push_back(ref);
    }
  }

  // 2. Rows: load clusters x temperature clusters (or the requested temperatures).
  std::vector<double> loads;
  for (const Ramp& r : out.used) loads.push_back(r.load_N);
  auto [load_group, load_axis] = cluster(loads, [&](double x) { return s.load_tolerance * x; });
  out.loads_N = load_axis;
  std::vector<int> temp_group;
  if (s.row_temps_C.empty()) {
    auto [tg, ta] = cluster(out.used_ref_temp_C, [&](double) { return s.temp_tolerance_C; });
    temp_group = tg;
    out.temps_C = ta;
  } else {
    out.temps_C = s.row_temps_C;
    std::sort(out.temps_C.begin(), out.temps_C.end());
    std::vector<Ramp> kept;
    std::vector<double> kept_ref;
    std::vector<int> kept_load;
    for (std::size_t i = 0; i < out.used.size(); ++i) {
      int best = -1;
      for (std::size_t k = 0; k < out.temps_C.size(); ++k)
        if (std::abs(out.used_ref_temp_C[i] - out.temps_C[k]) <= s.temp_tolerance_C &&
            (best < 0 || std::abs(out.used_ref_temp_C[i] - out.temps_C[k]) <
                             std::abs(out.used_ref_temp_C[i] - out.temps_C[std::size_t(best)])))
          best = int(k);
      if (best < 0) {
        out.rejected.push_back({out.used[i].run, out.used[i].t_start_s, out.used[i].t_end_s,
                                "starts at " + g(out.used_ref_temp_C[i], 3) + " °C, outside ±" + g(s.temp_tolerance_C) +
                                    " °C of every requested row temperature"});
        continue;
      }
      kept.push_back(out.used[i]);
      kept_ref.push_back(out.used_ref_temp_C[i]);
      kept_load.push_back(load_group[i]);
      temp_group.push_back(best);
    }
    out.used = kept;
    out.used_ref_temp_C = kept_ref;
    load_group = kept_load;
    double lo = std::numeric_limits<double>::infinity(), hi = -lo;
    for (const Ramp& r : out.used) {
      lo = std::min(lo, r.start_temp_C);
      hi = std::max(hi, r.start_temp_C);
    }
    for (std::size_t k = 0; k < out.temps_C.size(); ++k)
      if (std::find(temp_group.begin(), temp_group.end(), int(k)) == temp_group.end())
        throw CharacterisationInputError(
            runs.front().name + (runs.size() > 1 ? " (and the other runs)" : ""),
            "requested row temperature " + g(out.temps_C[k], 3) + " °C: no ramp starts within ±" +
                g(s.temp_tolerance_C) + " °C" +
                (out.used.empty() ? std::string() : " (ramps start at " + g(lo, 3) + "–" + g(hi, 3) + " °C)") +
                "; request temperatures the runs reach or widen --temp-tolerance");
  }
  const std::size_t nl = out.loads_N.size(), nt = out.temps_C.size();

  // 3. Samples: mu from torque, speed at the effective radius.
  const double r_m = r_mm / 1000.0;
  std::vector<std::vector<Sample>> samples(out.used.size());
  out.min_temp_C = std::numeric_limits<double>::infinity();
  out.max_temp_C = -out.min_temp_C;
  for (std::size_t i = 0; i < out.used.size(); ++i) {
    const Ramp& ramp = out.used[i];
    const RampRun& run = runs[ramp.run];
    // The hold at the ramp's low end (Paper D's N0 before an up-ramp, the hold after a
    // down-ramp) joins it for up to 1 s: at 1 rpm a 10 s ramp leaves one or two samples within
    // ±5 % of the node (the torque cell's noise: 1 % in mu each at 10 kN), the hold ~50 at the
    // same temperature.
    std::size_t first = ramp.first, last = ramp.last;
    const auto at_low_end = [&](std::size_t k) {
      return std::abs(std::abs(run.speed_rpm[k]) - ramp.min_rpm) <= 0.02 * ramp.min_rpm;
    };
    if (ramp.direction == RampDirection::kUp)
      while (first > 0 && at_low_end(first - 1) && run.time_s[ramp.first] - run.time_s[first - 1] <= 1.0) --first;
    else
      while (last + 1 < run.time_s.size() && at_low_end(last + 1) &&
             run.time_s[last + 1] - run.time_s[ramp.last] <= 1.0)
        ++last;
    for (std::size_t k = first; k <= last; ++k) {
      const double rpm = run.speed_rpm[k];
      if (std::abs(rpm) < 0.5) continue;  // below half an rpm the sign of slip is uncertain
      const double f = run.normal_force_N[k];
      if (!(f > 0)) continue;
      const double mu =
          clutch::mu_from_torque(std::copysign(1.0, rpm) * run.torque_Nm[k], f, r_m, s.conversion.interfaces) -
          s.conversion.bearing_drag_mu;
      samples[i].push_back({std::abs(rpm) * mm_s_per_rpm, mu, run.temp_C[k]});
      out.min_temp_C = std::min(out.min_temp_C, run.temp_C[k]);
      out.max_temp_C = std::max(out.max_temp_C, run.temp_C[k]);
    }
  }

  // Node speeds (Paper D: 1, 5, 10, …, 100 rpm) inside the ramps' common speed range.
  double vmin = 0.0, vmax = std::numeric_limits<double>::infinity();
  for (const auto& smp : samples) {
    if (smp.empty()) continue;
    const auto [mn, mx] =
        std::minmax_element(smp.begin(), smp.end(), [](auto& a, auto& b) { return a.v_mm_s < b.v_mm_s; });
    vmin = std::max(vmin, mn->v_mm_s);
    vmax = std::min(vmax, mx->v_mm_s);
  }
  std::vector<double> nodes = s.node_rpm;
  if (nodes.empty()) {
    nodes.push_back(1.0);
    for (double rpm = 5.0; rpm <= 100.0 + 1e-9; rpm += 5.0) nodes.push_back(rpm);
  }
  // A node within 2 % of the common range's ends is kept at the end (1 rpm ramps start there).
  for (double rpm : nodes) {
    const double v = std::clamp(rpm * mm_s_per_rpm, vmin, vmax);
    if (std::abs(v - rpm * mm_s_per_rpm) <= 0.02 * rpm * mm_s_per_rpm &&
        (out.node_speeds_mm_s.empty() || v > out.node_speeds_mm_s.back())) {
      out.node_rpm.push_back(rpm);
      out.node_speeds_mm_s.push_back(v);
    }
  }
  if (out.node_rpm.size() < 2)
    throw CharacterisationInputError(runs.front().name, "the ramps share a speed range of only " +
                                                            g(vmin / mm_s_per_rpm) + "–" + g(vmax / mm_s_per_rpm) +
                                                            " rpm; at least two node speeds are needed");
  out.min_speed_mm_s = out.node_speeds_mm_s.front();
  out.max_speed_mm_s = out.node_speeds_mm_s.back();
  const std::size_t nn = out.node_rpm.size();

  // 4. Temperature compensation: correction(load group, v, T_from -> T_to).
  std::function<double(int, double, double, double)> correct = [](int, double, double, double) { return 0.0; };
  std::vector<std::shared_ptr<const TemperatureSurface>> surfaces;  // piecewise: one per load
  if (s.compensation == Compensation::kLinear) {
    out.alpha_fitted = !s.alpha_per_C;
    if (s.alpha_per_C) {
      out.alpha_per_C = *s.alpha_per_C;
    } else {
      // Within-group slope of mu on T; groups = load x 64 log speed bins (fixed effects).
      constexpr int kBins = 64;
      const double l0 = std::log(vmin), l1 = std::log(vmax);
      std::vector<double> n(nl * kBins, 0), st(nl * kBins, 0), sm(nl * kBins, 0), stt(nl * kBins, 0),
          stm(nl * kBins, 0);
      for (std::size_t i = 0; i < out.used.size(); ++i)
        for (const Sample& p : samples[i]) {
          const int b = std::clamp(int((std::log(p.v_mm_s) - l0) / (l1 - l0) * kBins), 0, kBins - 1);
          const std::size_t k = std::size_t(load_group[i]) * kBins + std::size_t(b);
          n[k] += 1;
          st[k] += p.temp_C;
          sm[k] += p.mu;
          stt[k] += p.temp_C * p.temp_C;
          stm[k] += p.temp_C * p.mu;
        }
      double sxx = 0, sxy = 0;
      for (std::size_t k = 0; k < n.size(); ++k)
        if (n[k] > 1) {
          sxx += stt[k] - st[k] * st[k] / n[k];
          sxy += stm[k] - st[k] * sm[k] / n[k];
        }
      if (!(sxx > 0))
        throw CharacterisationInputError(runs.front().name,
                                         "linear compensation cannot fit alpha: the temperature "
                                         "does not vary at any speed; give --alpha");
      out.alpha_per_C = sxy / sxx;
    }
    const double alpha = out.alpha_per_C;
    correct = [alpha](int, double, double from, double to) { return alpha * (to - from); };
  } else if (s.compensation == Compensation::kQuadratic) {
    // Per load and node: mu = a + bT + cT² over every ramp crossing the node.
    std::vector<std::vector<QuadraticNode>> per_load(nl);
    for (std::size_t l = 0; l < nl; ++l) {
      for (std::size_t k = 0; k < nn; ++k) {
        std::vector<double> ts, ms;
        for (std::size_t i = 0; i < out.used.size(); ++i) {
          if (std::size_t(load_group[i]) != l) continue;
          if (auto p = at_node(samples[i], out.node_speeds_mm_s[k])) {
            ms.push_back(p->first);
            ts.push_back(p->second);
          }
        }
        const auto [tmin, tmax] = std::minmax_element(ts.begin(), ts.end());
        if (ts.size() < 3 || *tmax - *tmin < 2.0 * s.temp_tolerance_C)
          throw CharacterisationInputError(
              runs.front().name,
              "quadratic compensation at " + g(out.loads_N[l] / 1000.0) + " kN, " + g(out.node_rpm[k]) + " rpm: " +
                  std::to_string(ts.size()) + " ramp(s) over " + (ts.empty() ? std::string("0") : g(*tmax - *tmin, 3)) +
                  " °C; Paper D's quadratic needs ramps at 3 or more temperatures spanning more than " +
                  g(2.0 * s.temp_tolerance_C) + " °C per load (use --compensation linear or none)");
        Eigen::MatrixXd x(long(ts.size()), 3);
        Eigen::VectorXd y(long(ts.size()));
        for (std::size_t i = 0; i < ts.size(); ++i) {
          x(long(i), 0) = 1.0;
          x(long(i), 1) = ts[i];
          x(long(i), 2) = ts[i] * ts[i];
          y(long(i)) = ms[i];
        }
        const Eigen::VectorXd q = wls(x, y, Eigen::VectorXd::Ones(long(ts.size())));
        const double rms = std::sqrt((x * q - y).squaredNorm() / double(ts.size()));
        per_load[l].push_back({out.loads_N[l], out.node_rpm[k], q(0), q(1), q(2), int(ts.size()), rms});
        out.quadratic.push_back(per_load[l].back());
      }
    }
    const std::vector<double> node_v = out.node_speeds_mm_s;
    correct = [per_load, node_v](int l, double v, double from, double to) {
      std::vector<double> d(node_v.size());
      for (std::size_t k = 0; k < node_v.size(); ++k) {
        const QuadraticNode& q = per_load[std::size_t(l)][k];
        d[k] = q.b * (to - from) + q.c * (to * to - from * from);
      }
      return interp_log(node_v, d, v);
    };
  } else if (s.compensation == Compensation::kPiecewise) {
    // Per load: one surface mu(v, T), piecewise linear in T between knots at the rows, fitted to
    // every sample of the load's ramps at once (analysis/temperature_surface.hpp).
    surfaces.resize(nl);
    for (std::size_t l = 0; l < nl; ++l) {
      std::vector<SurfaceSample> pts;
      double lo = std::numeric_limits<double>::infinity(), hi = -lo;
      for (std::size_t i = 0; i < out.used.size(); ++i) {
        if (std::size_t(load_group[i]) != l) continue;
        for (const Sample& p : samples[i]) {
          if (p.v_mm_s < vmin * 0.999 || p.v_mm_s > vmax * 1.001) continue;
          pts.push_back({p.v_mm_s, p.temp_C, p.mu});
          lo = std::min(lo, p.temp_C);
          hi = std::max(hi, p.temp_C);
        }
      }
      std::vector<double> rows_at_load;
      for (std::size_t i = 0; i < out.used.size(); ++i)
        if (std::size_t(load_group[i]) == l) rows_at_load.push_back(out.temps_C[std::size_t(temp_group[i])]);
      std::sort(rows_at_load.begin(), rows_at_load.end());
      rows_at_load.erase(std::unique(rows_at_load.begin(), rows_at_load.end()), rows_at_load.end());
      // One start temperature: along a ramp speed and temperature rise together, so the
      // surface could not tell them apart (only the smoothing would decide).
      if (rows_at_load.size() < 2)
        throw CharacterisationInputError(runs.front().name,
                                         "piecewise compensation at " + g(out.loads_N[l] / 1000.0) +
                                             " kN: ramps start at 1 row temperature; it needs ramps from 2 or more "
                                             "row temperatures per load to separate speed from temperature (use "
                                             "--compensation linear or none)");
      auto knots = temperature_knots(rows_at_load, lo, hi);
      try {
        surfaces[l] = std::make_shared<TemperatureSurface>(out.node_speeds_mm_s, std::move(knots), pts);
      } catch (const std::invalid_argument& e) {
        throw CharacterisationInputError(
            runs.front().name, "piecewise compensation at " + g(out.loads_N[l] / 1000.0) + " kN: " + e.what());
      }
      out.piecewise.push_back({out.loads_N[l], surfaces[l]->temp_knots_C(), surfaces[l]->rms_residual()});
    }
    correct = [surfaces](int l, double v, double from, double to) {
      const TemperatureSurface& f = *surfaces[std::size_t(l)];
      return f(v, to) - f(v, from);
    };
  }

  // 5. Rows: binned means of compensated samples, up/down at the nodes.
  // hot_row: one more row at the hottest temperature the ramps reach, made of the top row's
  // ramps compensated up to it (the compensation's own mu(T)); without it the law holds the top
  // row's mu above that row, where the hottest runs heat the clutch.
  const bool hot = s.hot_row && s.compensation != Compensation::kNone && s.law != LawKind::kLinear &&
                   out.max_temp_C > out.temps_C.back() + s.temp_tolerance_C;
  if (hot) {
    out.temps_C.push_back(out.max_temp_C);
    out.hot_row_temp_C = out.max_temp_C;
  }
  const std::size_t nt_all = out.temps_C.size();
  std::vector<std::vector<std::size_t>> members(nt_all * nl);
  for (std::size_t i = 0; i < out.used.size(); ++i) {
    members[std::size_t(temp_group[i]) * nl + std::size_t(load_group[i])].push_back(i);
    if (hot && std::size_t(temp_group[i]) == nt - 1) members[nt * nl + std::size_t(load_group[i])].push_back(i);
  }
  const int kBins = std::max(s.speed_bins, 5);
  const double l0 = std::log(vmin), l1 = std::log(vmax);
  std::vector<double> within_ss(nt_all * nl, 0.0), n_samples(nt_all * nl, 0.0);
  for (std::size_t it = 0; it < nt_all; ++it)
    for (std::size_t il = 0; il < nl; ++il) {
      const auto& m = members[it * nl + il];
      RowFit row;
      row.i_temp = it;
      row.i_load = il;
      row.load_N = out.loads_N[il];
      row.temp_C = out.temps_C[it];
      if (m.empty()) {
        if (s.law != LawKind::kLinear)
          throw CharacterisationInputError(runs.front().name, row_name(row.load_N, row.temp_C) + " has no ramp; a " +
                                                                  law_name(s.law) + " law needs ramps at every load (" +
                                                                  std::to_string(nl) + ") at every temperature (" +
                                                                  std::to_string(nt_all) +
                                                                  "); add runs, pass --row-temps, or use --law linear");
        continue;
      }
      if (int(m.size()) < s.min_ramps_per_row)
        throw CharacterisationInputError(runs[out.used[m.front()].run].name,
                                         row_name(row.load_N, row.temp_C) + " has " + std::to_string(m.size()) +
                                             " ramp(s); at least " + std::to_string(s.min_ramps_per_row) +
                                             " are needed (--min-ramps)");
      std::vector<double> n(std::size_t(kBins), 0), sv(n), sm(n), smm(n), sr(n);
      std::vector<double> up_r(nn, 0), up_c(nn, 0), dn_r(nn, 0), dn_c(nn, 0), up_n(nn, 0), dn_n(nn, 0);
      row.min_speed_mm_s = std::numeric_limits<double>::infinity();
      row.max_speed_mm_s = 0.0;
      row.min_temp_C = std::numeric_limits<double>::infinity();
      row.max_temp_C = -row.min_temp_C;
      for (std::size_t i : m) {
        const bool up = out.used[i].direction == RampDirection::kUp;
        (up ? row.ramps_up : row.ramps_down)++;
        for (const Sample& p : samples[i]) {
          const double mc = p.mu + correct(load_group[i], p.v_mm_s, p.temp_C, row.temp_C);
          const int b = std::clamp(int((std::log(p.v_mm_s) - l0) / (l1 - l0) * kBins), 0, kBins - 1);
          if (p.v_mm_s < vmin * 0.999 || p.v_mm_s > vmax * 1.001) continue;
          const auto bb = std::size_t(b);
          n[bb] += 1;
          sv[bb] += p.v_mm_s;
          sm[bb] += mc;
          smm[bb] += mc * mc;
          sr[bb] += p.mu;
          row.min_speed_mm_s = std::min(row.min_speed_mm_s, p.v_mm_s);
          row.max_speed_mm_s = std::max(row.max_speed_mm_s, p.v_mm_s);
          row.min_temp_C = std::min(row.min_temp_C, p.temp_C);
          row.max_temp_C = std::max(row.max_temp_C, p.temp_C);
        }
        for (std::size_t k = 0; k < nn; ++k)
          if (auto p = at_node(samples[i], out.node_speeds_mm_s[k])) {
            const double mc = p->first + correct(load_group[i], out.node_speeds_mm_s[k], p->second, row.temp_C);
            (up ? up_r : dn_r)[k] += p->first;
            (up ? up_c : dn_c)[k] += mc;
            (up ? up_n : dn_n)[k] += 1;
          }
      }
      for (int b = 0; b < kBins; ++b) {
        const auto bb = std::size_t(b);
        if (n[bb] < 1) continue;
        row.bin_speed_mm_s.push_back(sv[bb] / n[bb]);
        row.bin_mu.push_back(sm[bb] / n[bb]);
        row.bin_mu_raw.push_back(sr[bb] / n[bb]);
        row.bin_count.push_back(n[bb]);
        within_ss[it * nl + il] += smm[bb] - sm[bb] * sm[bb] / n[bb];
        n_samples[it * nl + il] += n[bb];
      }
      int gaps = 0;
      for (std::size_t k = 0; k < nn; ++k) {
        row.up_raw.push_back(up_n[k] > 0 ? up_r[k] / up_n[k] : kNaN);
        row.up_comp.push_back(up_n[k] > 0 ? up_c[k] / up_n[k] : kNaN);
        row.down_raw.push_back(dn_n[k] > 0 ? dn_r[k] / dn_n[k] : kNaN);
        row.down_comp.push_back(dn_n[k] > 0 ? dn_c[k] / dn_n[k] : kNaN);
        if (up_n[k] > 0 && dn_n[k] > 0) {
          row.up_down_gap_raw += std::abs(row.up_raw[k] - row.down_raw[k]);
          row.up_down_gap_comp += std::abs(row.up_comp[k] - row.down_comp[k]);
          ++gaps;
        }
        row.node_mu.push_back(node_value(row.bin_speed_mm_s, row.bin_mu, row.bin_count, out.node_speeds_mm_s[k]));
      }
      if (gaps > 0) {
        row.up_down_gap_raw /= gaps;
        row.up_down_gap_comp /= gaps;
      }
      if (row.bin_speed_mm_s.size() < 5)
        throw CharacterisationInputError(runs[out.used[m.front()].run].name,
                                         row_name(row.load_N, row.temp_C) + " covers only " +
                                             std::to_string(row.bin_speed_mm_s.size()) +
                                             " speed bins; a fit needs at least 5 (longer or slower ramps)");
      out.rows.push_back(std::move(row));
    }

  // The law's rows stop at the highest reference temperature; above it the law holds that row.
  if (out.max_temp_C > out.temps_C.back() + s.temp_tolerance_C)
    out.warnings.push_back("the ramps heat the temperature channel to " + g(out.max_temp_C, 3) + " °C, " +
                           g(out.max_temp_C - out.temps_C.back(), 2) + " K above the top row (" +
                           g(out.temps_C.back(), 3) +
                           " °C): above it the law holds that row's mu, so a model "
                           "replaying the hottest runs reads it outside its data there (add ramps that start near " +
                           g(out.max_temp_C, 3) + " °C" +
                           (s.compensation == Compensation::kNone ? ", or a compensation and --hot-row" : "") + ")");

  // 6. The law.
  if (s.law == LawKind::kMaki) {
    std::vector<clutch::MakiSet> sets(nt_all * nl);
    std::vector<std::string> c2_low_rows, c2_high_rows;  // rows whose C2 sits on a search bound
    for (RowFit& row : out.rows) {
      const std::size_t cell = row.i_temp * nl + row.i_load;
      std::array<double, 4> p;
      try {
        p = fit_maki_curve(row.bin_speed_mm_s, row.bin_mu, row.bin_count);
        // Residual variance per sample: within-bin scatter plus the fit's misfit of the means.
        double ss = within_ss[cell];
        const clutch::MakiSet set{p[0], p[1], p[2], p[3]};
        for (std::size_t b = 0; b < row.bin_mu.size(); ++b)
          ss += row.bin_count[b] * std::pow(set.mu(row.bin_speed_mm_s[b]) - row.bin_mu[b], 2);
        p = fit_maki_curve(row.bin_speed_mm_s, row.bin_mu, row.bin_count, ss / std::max(n_samples[cell] - 4.0, 1.0),
                           &row.maki_se);
      } catch (const std::runtime_error& e) {
        throw std::runtime_error(row_name(row.load_N, row.temp_C) + ": " + e.what());
      }
      row.maki = p;
      sets[cell] = {p[0], p[1], p[2], p[3]};
      // C2 on (within kMakiBoundMargin of) its search range's end: the data do not determine it.
      const double c2_margin = kMakiBoundMargin * std::log(kMakiC2Max / kMakiC2Min);
      if (std::log(p[1] / kMakiC2Min) < c2_margin)
        c2_low_rows.push_back(g(row.load_N / 1000.0) + " kN at " + g(row.temp_C, 3) + " °C");
      else if (std::log(kMakiC2Max / p[1]) < c2_margin)
        c2_high_rows.push_back(g(row.load_N / 1000.0) + " kN at " + g(row.temp_C, 3) + " °C");
      for (int k = 0; k <= 64; ++k) {
        const double v = out.min_speed_mm_s * std::pow(out.max_speed_mm_s / out.min_speed_mm_s, k / 64.0);
        const double mu = sets[cell].mu(v);
        if (!(mu > 0.0 && mu <= 1.0))
          throw std::runtime_error(row_name(row.load_N, row.temp_C) + ": the fitted Mäki set gives mu = " + g(mu) +
                                   " at " + g(v) +
                                   " mm/s, outside (0, 1]; the fit did not converge to a plausible law "
                                   "(try --law table)");
      }
    }
    // One warning per bound, naming its rows: the same cause on many rows reads once.
    const auto bound_warning = [&](const std::vector<std::string>& rows, const std::string& meaning) {
      if (rows.empty()) return;
      std::string list;
      for (const auto& r : rows) list += (list.empty() ? "" : ", ") + r;
      out.warnings.push_back("the Mäki rate C2 sits on its search bound [" + g(kMakiC2Min) + ", " + g(kMakiC2Max) +
                             "] per mm/s in " + std::to_string(rows.size()) + " of " + std::to_string(out.rows.size()) +
                             " rows (" + list + "): " + meaning +
                             "; the law holds inside its data, its coefficients are not the fluid's (try --law table)");
    };
    bound_warning(c2_low_rows, "tanh(C2 v) is linear over the data, so only C1·C2 is determined, not C1 and C2");
    bound_warning(c2_high_rows, "tanh(C2 v) is a step below the data's speeds, so C1 acts as a constant");
    out.law = std::make_shared<clutch::MakiFrictionMatrix>(out.loads_N, out.temps_C, sets, out.min_speed_mm_s,
                                                           out.max_speed_mm_s);
  } else if (s.law == LawKind::kTable) {
    std::vector<double> mu(nt_all * nl * nn);
    for (const RowFit& row : out.rows)
      for (std::size_t k = 0; k < nn; ++k) mu[(row.i_temp * nl + row.i_load) * nn + k] = row.node_mu[k];
    out.law = std::make_shared<clutch::TableFriction>(out.node_speeds_mm_s, out.temps_C, out.loads_N, mu);
  } else {
    std::size_t il = 0;
    for (std::size_t l = 1; l < nl; ++l)
      if (std::abs(out.loads_N[l] - s.linear_load_N) < std::abs(out.loads_N[il] - s.linear_load_N)) il = l;
    out.linear_load_N = out.loads_N[il];
    std::vector<const RowFit*> at_load;
    for (const RowFit& row : out.rows)
      if (row.i_load == il) at_load.push_back(&row);
    if (at_load.size() < 2)
      throw CharacterisationInputError(runs.front().name, "a linear law needs rows at 2 or more temperatures at " +
                                                              g(out.linear_load_N / 1000.0) + " kN; found " +
                                                              std::to_string(at_load.size()));
    std::vector<clutch::LinearTemperaturePoint> points;
    for (std::size_t k = 0; k < nn; ++k) {
      Eigen::MatrixXd x(long(at_load.size()), 2);
      Eigen::VectorXd y(long(at_load.size()));
      for (std::size_t i = 0; i < at_load.size(); ++i) {
        x(long(i), 0) = at_load[i]->temp_C;
        x(long(i), 1) = 1.0;
        y(long(i)) = at_load[i]->node_mu[k];
      }
      Eigen::MatrixXd cov;
      const Eigen::VectorXd q = wls(x, y, Eigen::VectorXd::Ones(x.rows()), &cov);
      const double dof = double(x.rows()) - 2.0;
      const double s2 = dof > 0 ? (x * q - y).squaredNorm() / dof : kNaN;
      out.lines.push_back({out.node_rpm[k], q(0), q(1), std::sqrt(s2 * cov(0, 0)), std::sqrt(s2 * cov(1, 1))});
      points.push_back({out.node_speeds_mm_s[k], q(0), q(1)});
    }
    out.law = std::make_shared<clutch::LinearTemperatureFriction>(points);
  }

  // 7. Residuals of the law against every row's binned means.
  for (RowFit& row : out.rows) {
    double ss = 0, w = 0;
    row.max_residual = 0;
    for (std::size_t b = 0; b < row.bin_mu.size(); ++b) {
      const double r = out.law->mu(row.bin_speed_mm_s[b], row.temp_C, row.load_N) - row.bin_mu[b];
      ss += row.bin_count[b] * r * r;
      w += row.bin_count[b];
      row.max_residual = std::max(row.max_residual, std::abs(r));
    }
    row.rms_residual = std::sqrt(ss / w);
    if (!std::isfinite(row.rms_residual))
      throw std::runtime_error(row_name(row.load_N, row.temp_C) + ": the fitted law gives a non-finite residual");
  }
  return out;
}

}  // namespace shudder::analysis
