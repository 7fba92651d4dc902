#include "components/signal.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

namespace shudder::components {

Signal Signal::constant(double value) {
  Signal s;
  s.kind_ = Kind::kConstant;
  s.a_ = value;
  return s;
}

Signal Signal::table(std::vector<double> times_s, std::vector<double> values, bool linear) {
  if (times_s.empty() || times_s.size() != values.size())
    throw std::invalid_argument("a table signal needs one value per time and at least one point");
  for (std::size_t i = 1; i < times_s.size(); ++i)
    if (!(times_s[i] > times_s[i - 1])) throw std::invalid_argument("a table signal's times must strictly increase");
  Signal s;
  s.kind_ = Kind::kTable;
  s.times_ = std::move(times_s);
  s.values_ = std::move(values);
  s.linear_ = linear;
  return s;
}

Signal Signal::step(double time_s, double before, double after) {
  Signal s;
  s.kind_ = Kind::kStep;
  s.a_ = time_s;
  s.b_ = before;
  s.c_ = after;
  return s;
}

Signal Signal::sine(double offset, double amplitude, double frequency_Hz, double phase_rad, double start_s) {
  Signal s;
  s.kind_ = Kind::kSine;
  s.a_ = offset;
  s.b_ = amplitude;
  s.c_ = frequency_Hz;
  s.d_ = phase_rad;
  s.e_ = start_s;
  return s;
}

Signal Signal::pulse(double low, double high, double period_s, double width_s, double start_s) {
  if (!(period_s > 0) || !(width_s > 0) || width_s > period_s)
    throw std::invalid_argument("a pulse needs 0 < width_s <= period_s");
  Signal s;
  s.kind_ = Kind::kPulse;
  s.a_ = low;
  s.b_ = high;
  s.c_ = period_s;
  s.d_ = width_s;
  s.e_ = start_s;
  return s;
}

Signal Signal::ramp(double from_value, double to_value, double start_s, double duration_s) {
  if (!(duration_s >= 0)) throw std::invalid_argument("a ramp's duration_s must be >= 0");
  Signal s;
  s.kind_ = Kind::kRamp;
  s.a_ = from_value;
  s.b_ = to_value;
  s.c_ = start_s;
  s.d_ = duration_s;
  return s;
}

Signal Signal::product(Signal a, Signal b) {
  Signal s;
  s.kind_ = Kind::kProduct;
  s.f1_ = std::make_shared<const Signal>(std::move(a));
  s.f2_ = std::make_shared<const Signal>(std::move(b));
  return s;
}

Signal Signal::held(std::shared_ptr<const double> value, Signal stands_for) {
  Signal s;
  s.kind_ = Kind::kHeld;
  s.held_ = std::move(value);
  s.f1_ = std::make_shared<const Signal>(std::move(stands_for));
  return s;
}

double Signal::operator()(double t) const {
  switch (kind_) {
    case Kind::kConstant: return a_;
    case Kind::kTable: {
      if (t <= times_.front()) return values_.front();
      if (t >= times_.back()) return values_.back();
      const auto hi = static_cast<std::size_t>(std::upper_bound(times_.begin(), times_.end(), t) - times_.begin());
      const std::size_t lo = hi - 1;
      if (!linear_) return values_[lo];
      const double w = (t - times_[lo]) / (times_[hi] - times_[lo]);
      return values_[lo] + w * (values_[hi] - values_[lo]);
    }
    case Kind::kStep: return t < a_ ? b_ : c_;
    case Kind::kSine: return t < e_ ? a_ : a_ + b_ * std::sin(2.0 * std::numbers::pi * c_ * (t - e_) + d_);
    case Kind::kPulse: {
      if (t < e_) return a_;
      const double phase = std::fmod(t - e_, c_);
      return phase < d_ ? b_ : a_;
    }
    case Kind::kRamp:
      if (t <= c_) return d_ > 0 || t < c_ ? a_ : b_;
      if (t >= c_ + d_) return b_;
      return a_ + (b_ - a_) * (t - c_) / d_;
    case Kind::kProduct: return (*f1_)(t) * (*f2_)(t);
    case Kind::kHeld: return *held_;
  }
  return 0.0;
}

double Signal::derivative(double t) const {
  switch (kind_) {
    case Kind::kConstant:
    case Kind::kStep:
    case Kind::kPulse:
    case Kind::kHeld: return 0.0;
    case Kind::kTable: {
      if (!linear_ || t < times_.front() || t >= times_.back()) return 0.0;
      const auto hi = static_cast<std::size_t>(std::upper_bound(times_.begin(), times_.end(), t) - times_.begin());
      const std::size_t lo = hi - 1;
      return (values_[hi] - values_[lo]) / (times_[hi] - times_[lo]);
    }
    case Kind::kSine:
      return t < e_ ? 0.0 : b_ * 2.0 * std::numbers::pi * c_ * std::cos(2.0 * std::numbers::pi * c_ * (t - e_) + d_);
    case Kind::kRamp: return (d_ > 0 && t >= c_ && t < c_ + d_) ? (b_ - a_) / d_ : 0.0;
    case Kind::kProduct: return f1_->derivative(t) * (*f2_)(t) + (*f1_)(t)*f2_->derivative(t);
  }
  return 0.0;
}

std::vector<double> Signal::knots(double t0, double t1) const {
  std::vector<double> k;
  const auto add = [&](double t) {
    if (t > t0 && t < t1) k.push_back(t);
  };
  switch (kind_) {
    case Kind::kConstant:
    case Kind::kHeld: break;
    case Kind::kSine: add(e_); break;
    case Kind::kTable:
      for (double t : times_) add(t);
      break;
    case Kind::kStep: add(a_); break;
    case Kind::kRamp:
      add(c_);
      add(c_ + d_);
      break;
    case Kind::kPulse: {
      // At most 1e6 edges (a pulse train faster than that is not a schedule).
      const double first = std::max(0.0, std::floor((t0 - e_) / c_));
      for (double n = first; n < first + 5e5; ++n) {
        const double rise = e_ + n * c_;
        if (rise >= t1) break;
        add(rise);
        add(rise + d_);
      }
      break;
    }
    case Kind::kProduct: {
      k = f1_->knots(t0, t1);
      const auto k2 = f2_->knots(t0, t1);
      k.insert(k.end(), k2.begin(), k2.end());
      break;
    }
  }
  std::sort(k.begin(), k.end());
  k.erase(std::unique(k.begin(), k.end()), k.end());
  return k;
}

namespace {
// Values at the ends, the knots (both sides) and, for the smooth kinds, enough points between.
std::vector<double> probe_values(const Signal& s, double t0, double t1) {
  std::vector<double> v{s(t0), s(t1)};
  for (double t : s.knots(t0, t1)) {
    v.push_back(s(t));
    v.push_back(s(std::nextafter(t, t0)));
  }
  if (s.kind() == Signal::Kind::kSine || s.kind() == Signal::Kind::kProduct)
    for (int i = 1; i < 1000; ++i) v.push_back(s(t0 + (t1 - t0) * i / 1000.0));
  return v;
}
}  // namespace

double Signal::max_over(double t0, double t1) const {
  if (kind_ == Kind::kHeld) return f1_->max_over(t0, t1);
  if (kind_ == Kind::kSine && t1 >= e_) return std::max(a_, a_ + std::abs(b_));
  const auto v = probe_values(*this, t0, t1);
  return *std::max_element(v.begin(), v.end());
}

double Signal::min_over(double t0, double t1) const {
  if (kind_ == Kind::kHeld) return f1_->min_over(t0, t1);
  if (kind_ == Kind::kSine && t1 >= e_) return std::min(a_, a_ - std::abs(b_));
  const auto v = probe_values(*this, t0, t1);
  return *std::min_element(v.begin(), v.end());
}

}  // namespace shudder::components
