#include "clutch/wet_clutch.hpp"

#include <algorithm>
#include <cmath>
#include <span>
#include <stdexcept>

#include "clutch/friction_radius.hpp"

namespace shudder::clutch {

namespace {

// The spacing Δr of ring centres r_i = r_0 + i Δr (to round-off: 1e-14 of the largest radius; a
// thermal grid's centres are ~1e-16 off), m; 0 if they are not equally spaced or there is one
// ring. The thermal grid's rings are equal (ThermalModel).
double equal_ring_pitch_m(const Eigen::VectorXd& r) {
  const Eigen::Index n = r.size();
  if (n < 2) return 0.0;
  const double pitch = (r[n - 1] - r[0]) / static_cast<double>(n - 1);
  for (Eigen::Index i = 0; i < n; ++i)
    if (std::abs(r[i] - (r[0] + static_cast<double>(i) * pitch)) > 1e-14 * std::abs(r[n - 1])) return 0.0;
  return pitch > 0.0 ? pitch : 0.0;
}

// Whether r_0 < r_1 < … (and there is a ring).
bool strictly_increasing(const Eigen::VectorXd& r) {
  for (Eigen::Index i = 1; i < r.size(); ++i)
    if (!(r[i] > r[i - 1])) return false;
  return r.size() > 0;
}

// Rates whose tanh is carried along the rings by the recurrence below; tanh of further rates (a
// frozen state whose rings span many rows of a large matrix) is taken ring by ring.
constexpr std::size_t kCarriedRates = 16;
// The recurrence restarts from an exact expm1 every this many rings, so its round-off (a few ε
// per ring carried) stays below ~50 ε of tanh whatever the number of rings.
constexpr Eigen::Index kRingsPerAnchor = 16;
// |2 b v| up to which e = expm1(2 b v) is carried (far from overflow: e^600 ≈ 1e260); tanh is
// ±1 to the last bit from |b v| ≈ 19 on.
constexpr double kMaxCarriedExponent = 600.0;
// Rings evaluated per block: the speed terms of a block live on the stack.
constexpr Eigen::Index kBlockRings = 32;

// The speed-only factors of one block of rings at one slip.
struct SpeedBlock {
  Eigen::Index first = 0, rings = 0;        // rings first .. first + rings - 1
  double speed_mm_s[kBlockRings];           // v_i, clamped to the law's speeds
  double speed_pow[kBlockRings];            // v_i^0.1
  signed char side[kBlockRings];            // -1: v_i clamped up to the lowest speed, 0: inside, +1: above
  double tanh[kCarriedRates][kBlockRings];  // tanh(b_k v_i) of the carried rates
};

// The speed-only factors of a frozen friction's rings at one slip, block after block: v_i^0.1
// and tanh(b_k v_i) for each rate b_k of a list, v_i = r_i |Δω| clamped to the law's speeds. On
// equally spaced rings the unclamped speeds are v_i = v_j + (i − j) Δv, Δv = Δr |Δω|, so with
//   e_i = expm1(2 b v_i):   e_{i+1} = e_i + d + e_i d,   d = expm1(2 b Δv)   ((1 + e) = exp(2 b v))
//   tanh(b v_i) = e_i / (e_i + 2)
// one expm1 per rate and anchor replaces a tanh per rate and ring, the largest cost of a right-hand
// side with wet clutches (docs/performance.md). Both forms are exact; they differ from std::tanh
// by round-off only (tests/clutch/test_wet_clutch.cpp). Which rings are anchors and which rates
// are carried depends on the rate, the slip and the rings alone, so a rate gives the same
// numbers in every list it appears in (ring_torque_pair_Nm equals ring_torque_Nm bit for bit).
class SpeedTermsAlongRings {
 public:
  SpeedTermsAlongRings(const Eigen::VectorXd& r_m, double ring_pitch_m, const FrozenFriction& f,
                       std::span<const double> rates, double abs_slip_rad_s)
      : r_m_(r_m),
        radius_pow_(f.radius_pow),
        rates_(rates),
        abs_slip_(abs_slip_rad_s),
        v_min_(f.min_speed_mm_s),
        v_max_(f.max_speed_mm_s),
        slip_pow_(std::pow(abs_slip_rad_s, 0.1)),
        speed_step_mm_s_(ring_pitch_m * abs_slip_rad_s * 1e3),
        carried_(std::min(rates.size(), kCarriedRates)) {
    for (std::size_t k = 0; k < carried_; ++k) {
      carry_[k] = ring_pitch_m > 0.0 && std::abs(2.0 * rates[k] * v_max_) <= kMaxCarriedExponent;
      since_anchor_[k] = kRingsPerAnchor;  // the first ring inside the speeds is an anchor
    }
  }

  /// Fills `b` for rings first .. first + rings - 1; blocks are filled in increasing order.
  void fill(Eigen::Index first, Eigen::Index rings, SpeedBlock& b) {
    b.first = first;
    b.rings = rings;
    for (Eigen::Index j = 0; j < rings; ++j) {
      const double v_raw = r_m_[first + j] * abs_slip_ * 1e3;
      b.side[j] = v_raw < v_min_ ? -1 : v_raw > v_max_ ? 1 : 0;
      if (b.side[j] == 0) {  // v^0.1 = (r_i in mm)^0.1 · |Δω|^0.1
        b.speed_mm_s[j] = v_raw;
        b.speed_pow[j] = radius_pow_[first + j] * slip_pow_;
      } else {
        const Clamp& c = b.side[j] < 0 ? clamp(below_, v_min_) : clamp(above_, v_max_);
        b.speed_mm_s[j] = c.v;
        b.speed_pow[j] = c.v_pow;
      }
    }
    for (std::size_t k = 0; k < carried_; ++k) fill_tanh(k, b);
  }

 private:
  // A clamped speed's terms, taken once per pass and clamp.
  struct Clamp {
    bool taken = false;
    double v = 0.0, v_pow = 0.0;
    double tanh[kCarriedRates];
  };
  const Clamp& clamp(Clamp& c, double v) {
    if (!c.taken) {
      c.v = v;
      c.v_pow = std::pow(v, 0.1);
      for (std::size_t k = 0; k < carried_; ++k) c.tanh[k] = std::tanh(rates_[k] * v);
      c.taken = true;
    }
    return c;
  }
  void fill_tanh(std::size_t k, SpeedBlock& b) {
    const double rate = rates_[k];
    double* t = b.tanh[k];
    double e = e_[k];
    Eigen::Index since_anchor = since_anchor_[k];
    for (Eigen::Index j = 0; j < b.rings; ++j) {
      if (b.side[j] != 0) {
        t[j] = (b.side[j] < 0 ? below_ : above_).tanh[k];
        since_anchor = kRingsPerAnchor;  // the next ring inside is an anchor
      } else if (!carry_[k]) {
        t[j] = std::tanh(rate * b.speed_mm_s[j]);
      } else {
        if (since_anchor >= kRingsPerAnchor) {
          e = std::expm1(2.0 * rate * b.speed_mm_s[j]);
          since_anchor = 0;
        } else {
          const double d = step(k);
          e += d + e * d;
        }
        ++since_anchor;
        t[j] = e / (e + 2.0);
      }
    }
    e_[k] = e;
    since_anchor_[k] = since_anchor;
  }
  double step(std::size_t k) {
    if (!have_step_[k]) {
      step_[k] = std::expm1(2.0 * rates_[k] * speed_step_mm_s_);
      have_step_[k] = true;
    }
    return step_[k];
  }

  const Eigen::VectorXd& r_m_;
  const Eigen::VectorXd& radius_pow_;
  std::span<const double> rates_;
  double abs_slip_, v_min_, v_max_, slip_pow_, speed_step_mm_s_;
  std::size_t carried_;
  bool carry_[kCarriedRates] = {}, have_step_[kCarriedRates] = {};
  double e_[kCarriedRates] = {}, step_[kCarriedRates] = {};
  Eigen::Index since_anchor_[kCarriedRates];  // rings carried since the last anchor, per rate
  Clamp below_, above_;
};

// Ring torques of one interface for the block's rings of a frozen state:
//   torque_i = r_i A_i p mu_i + viscous_i |Δω|,  mu_i = c_i v_i^0.1 + d_i + Σ_k a_ik tanh(b_k v_i)
// `rate_at[k]` is the index in the block's rate list of the state's rates[k] (nullptr: k).
// One body for ring_torque_Nm and ring_torque_pair_Nm, so both give the same numbers bit for bit.
void block_ring_torques(const FrozenFriction& f, const SpeedBlock& b, const std::size_t* rate_at,
                        const Eigen::VectorXd& radius_area_m3, double pressure_Pa, double abs_slip,
                        Eigen::VectorXd& torque) {
  const Eigen::Index i0 = b.first, m = b.rings;
  double mu[kBlockRings];
  for (Eigen::Index j = 0; j < m; ++j) mu[j] = f.power_weight[i0 + j] * b.speed_pow[j] + f.offset[i0 + j];
  for (std::size_t k = 0; k < f.rates.size(); ++k) {
    const double* w = f.rate_weight.col(static_cast<Eigen::Index>(k)).data() + i0;
    const std::size_t at = rate_at ? rate_at[k] : k;
    if (at < kCarriedRates) {
      const double* t = b.tanh[at];
      for (Eigen::Index j = 0; j < m; ++j) mu[j] += w[j] * t[j];
    } else {  // beyond the carried rates (ring_torque_Nm only)
      for (Eigen::Index j = 0; j < m; ++j) mu[j] += w[j] * std::tanh(f.rates[k] * b.speed_mm_s[j]);
    }
  }
  for (Eigen::Index j = 0; j < m; ++j)
    torque[i0 + j] = radius_area_m3[i0 + j] * pressure_Pa * mu[j] + f.viscous_Nms[i0 + j] * abs_slip;
}

// One frozen state of a pass over the rings: its torques (n_r) and, per rate of the state, the
// index of that rate in the pass's rate list (nullptr: the same index).
struct RingPassState {
  const FrozenFriction* friction;
  const std::size_t* rate_at;
  Eigen::VectorXd* torque;
};

static_assert(kBlockRings % kRingsPerAnchor == 0, "every block starts on an anchor");

// The ring torques of every state in `states` in one pass over the rings, when every ring's
// speed lies inside the law's speeds and every rate of `rates` is carried: a slipping clutch
// above its lowest speed, the case of nearly every right-hand side. Then no ring is clamped and
// the anchors are the rings 0, 16, 32, …, so each block's speed terms are filled by straight
// loops without a test per ring, and block_ring_torques makes the torques from them. The speed
// terms are the same operations in the same order as SpeedTermsAlongRings' on such a slip, so
// the torques are those of the general pass bit for bit. Returns false (nothing written) where
// that case does not hold; the caller then takes the general pass.
bool ring_torques_inside(const Eigen::VectorXd& r_m, bool rings_increasing, double ring_pitch_m,
                         const FrozenFriction& first, std::span<const double> rates, double abs_slip_rad_s,
                         const Eigen::VectorXd& radius_area_m3, double pressure_Pa,
                         std::span<const RingPassState> states) {
  const Eigen::Index n = r_m.size();
  if (n < 1 || !rings_increasing || !(ring_pitch_m > 0.0) || rates.size() > kCarriedRates) return false;
  // Speeds grow with the radius (rounding is monotonic): the end rings bound every ring's speed.
  const double v_min = first.min_speed_mm_s, v_max = first.max_speed_mm_s;
  if (r_m[0] * abs_slip_rad_s * 1e3 < v_min || r_m[n - 1] * abs_slip_rad_s * 1e3 > v_max) return false;
  for (double rate : rates)
    if (!(std::abs(2.0 * rate * v_max) <= kMaxCarriedExponent)) return false;
  const std::size_t n_rates = rates.size();
  const double slip_pow = std::pow(abs_slip_rad_s, 0.1);
  const double speed_step_mm_s = ring_pitch_m * abs_slip_rad_s * 1e3;
  double step[kCarriedRates];  // d_k = expm1(2 b_k Δv), read only between anchors (n > 1)
  if (n > 1)
    for (std::size_t k = 0; k < n_rates; ++k) step[k] = std::expm1(2.0 * rates[k] * speed_step_mm_s);
  for (const RingPassState& s : states) s.torque->resize(n);
  SpeedBlock b;
  for (Eigen::Index i0 = 0; i0 < n; i0 += kBlockRings) {
    const Eigen::Index m = std::min(kBlockRings, n - i0);
    b.first = i0;
    b.rings = m;
    for (Eigen::Index j = 0; j < m; ++j) {
      b.speed_mm_s[j] = r_m[i0 + j] * abs_slip_rad_s * 1e3;
      b.speed_pow[j] = first.radius_pow[i0 + j] * slip_pow;
    }
    // tanh(b_k v_i) = e_i / (e_i + 2): an exact expm1 at each anchor, the recurrence between.
    for (std::size_t k = 0; k < n_rates; ++k) {
      double* t = b.tanh[k];
      for (Eigen::Index a = 0; a < m; a += kRingsPerAnchor) {
        double e = std::expm1(2.0 * rates[k] * b.speed_mm_s[a]);
        t[a] = e / (e + 2.0);
        const Eigen::Index end = std::min(a + kRingsPerAnchor, m);
        for (Eigen::Index j = a + 1; j < end; ++j) {
          const double d = step[k];
          e += d + e * d;
          t[j] = e / (e + 2.0);
        }
      }
    }
    for (const RingPassState& s : states)
      block_ring_torques(*s.friction, b, s.rate_at, radius_area_m3, pressure_Pa, abs_slip_rad_s, *s.torque);
  }
  return true;
}

// Fills the regrouped form of f.curves (FrozenFriction); clears the curves if they do not share
// one speed clamp.
void regroup_by_rate(FrozenFriction& f) {
  const auto n = static_cast<Eigen::Index>(f.curves.size());
  if (n == 0) return;
  f.min_speed_mm_s = f.curves.front().min_speed_mm_s;
  f.max_speed_mm_s = f.curves.front().max_speed_mm_s;
  for (const SpeedCurve& c : f.curves) {
    // One clamp for every ring is what a pass over the rings needs; a law whose curves differ
    // in it (none so far) is evaluated directly.
    if (c.min_speed_mm_s != f.min_speed_mm_s || c.max_speed_mm_s != f.max_speed_mm_s) {
      f.curves.clear();
      return;
    }
    for (double b : c.tanh_rate)
      if (std::find(f.rates.begin(), f.rates.end(), b) == f.rates.end()) f.rates.push_back(b);
  }
  f.rate_weight = Eigen::MatrixXd::Zero(n, static_cast<Eigen::Index>(f.rates.size()));
  f.power_weight.resize(n);
  f.offset.resize(n);
  for (Eigen::Index i = 0; i < n; ++i) {
    const SpeedCurve& c = f.curves[static_cast<std::size_t>(i)];
    f.power_weight[i] = c.power_weight;
    f.offset[i] = c.offset;
    for (std::size_t j = 0; j < c.tanh_rate.size(); ++j) {
      const auto k = std::find(f.rates.begin(), f.rates.end(), c.tanh_rate[j]) - f.rates.begin();
      f.rate_weight(i, k) += c.tanh_weight[j];
    }
  }
}

}  // namespace

WetClutch::WetClutch(WetClutchParams params, Fluid fluid)
    : p_(std::move(params)),
      fluid_(std::move(fluid)),
      thermal_(p_.thermal),
      viscosity_(fluid_.nu40_cSt, fluid_.nu100_cSt) {
  if (!fluid_.friction) throw std::invalid_argument("clutch fluid has no friction law");
  if (p_.sliding_interfaces < 1 || p_.sliding_interfaces > 64)
    throw std::invalid_argument("sliding interfaces must be in [1, 64]");
  if (!(p_.reference_load_N > 0.0)) throw std::invalid_argument("reference load must be > 0");
  if (!(p_.viscous_gap_m > 0.0)) throw std::invalid_argument("viscous gap must be > 0");
  // A law fitted from torque at another friction radius is read at this clutch's
  // (clutch/friction_radius.hpp): the torque it was fitted on is reproduced.
  fluid_ = with_friction_radius(std::move(fluid_), mean_radius_m() * 1e3);
  const auto& r = thermal_.ring_radius_m();
  ring_radius_area_m3_ = r.cwiseProduct(thermal_.ring_area_m2());
  ring_pitch_m_ = equal_ring_pitch_m(r);
  rings_increasing_ = strictly_increasing(r);
}

ThermalState WetClutch::initial_state() const {
  return thermal_.initial_state(p_.start_temp_C, p_.start_temp_C, p_.sump_start_temp_C);
}

double WetClutch::mean_radius_m() const { return model_friction_radius_m(thermal_); }

void WetClutch::ring_mu(double slip_rad_s, double force_N, const Eigen::VectorXd& ring_temp_C, Eigen::VectorXd& mu,
                        RingScratch* scratch) const {
  const auto& r = thermal_.ring_radius_m();
  const double load = friction_load_N(force_N);
  mu.resize(r.size());
  if (!scratch) {  // point by point: allocates nothing (the real-time step relies on that)
    for (Eigen::Index i = 0; i < r.size(); ++i)
      mu[i] = fluid_.friction->mu(r[i] * std::abs(slip_rad_s) * 1e3, friction_temp_C(ring_temp_C[i]), load);
    return;
  }
  RingScratch& w = *scratch;
  const auto n = static_cast<std::size_t>(r.size());
  w.speed_mm_s.resize(n);
  w.temp_C.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    const auto k = static_cast<Eigen::Index>(i);
    w.speed_mm_s[i] = r[k] * std::abs(slip_rad_s) * 1e3;
    w.temp_C[i] = friction_temp_C(ring_temp_C[k]);
  }
  fluid_.friction->mu_at_load(w.speed_mm_s, w.temp_C, load, std::span<double>(mu.data(), n), w.terms);
}

void WetClutch::ring_torque_Nm(double slip_rad_s, double force_N, const Eigen::VectorXd& ring_temp_C,
                               Eigen::VectorXd& torque, RingScratch* scratch) const {
  const auto& r = thermal_.ring_radius_m();
  const auto& a = thermal_.ring_area_m2();
  ring_mu(slip_rad_s, force_N, ring_temp_C, torque, scratch);
  torque = torque.cwiseProduct(r).cwiseProduct(a) * pressure_Pa(force_N);
  if (p_.viscous_shear) {
    const double w = std::abs(slip_rad_s);
    for (Eigen::Index i = 0; i < r.size(); ++i) {
      const double eta_Pa_s = fluid_.density_kg_m3 * viscosity_.kinematic_cSt(ring_temp_C[i]) * 1e-6;
      torque[i] += eta_Pa_s * r[i] * w / p_.viscous_gap_m * r[i] * a[i];
    }
  }
}

double WetClutch::torque_Nm(double slip_rad_s, double force_N, const Eigen::VectorXd& ring_temp_C) const {
  Eigen::VectorXd t;
  ring_torque_Nm(slip_rad_s, force_N, ring_temp_C, t);
  return std::copysign(p_.sliding_interfaces * t.sum(), slip_rad_s);
}

void WetClutch::ring_heat_W(double slip_rad_s, double force_N, const Eigen::VectorXd& ring_temp_C,
                            Eigen::VectorXd& heat, RingScratch* scratch) const {
  ring_torque_Nm(slip_rad_s, force_N, ring_temp_C, heat, scratch);
  heat *= std::abs(slip_rad_s);
}

FrozenFriction WetClutch::freeze(const Eigen::VectorXd& ring_temp_C, double force_N) const {
  const auto& r = thermal_.ring_radius_m();
  const auto& a = thermal_.ring_area_m2();
  FrozenFriction f;
  f.ring_temp_C = ring_temp_C;
  f.load_N = friction_load_N(force_N);
  f.viscous_Nms = Eigen::VectorXd::Zero(r.size());
  f.radius_pow = (r * 1e3).array().pow(0.1);
  f.curves.resize(static_cast<std::size_t>(r.size()));
  for (Eigen::Index i = 0; i < r.size(); ++i) {
    if (!fluid_.friction->speed_curve(friction_temp_C(ring_temp_C[i]), f.load_N,
                                      f.curves[static_cast<std::size_t>(i)])) {
      f.curves.clear();
      break;
    }
  }
  regroup_by_rate(f);
  if (p_.viscous_shear)
    for (Eigen::Index i = 0; i < r.size(); ++i)
      f.viscous_Nms[i] = fluid_.density_kg_m3 * viscosity_.kinematic_cSt(ring_temp_C[i]) * 1e-6 * r[i] * r[i] * a[i] /
                         p_.viscous_gap_m;
  return f;
}

void WetClutch::ring_torque_Nm(const FrozenFriction& f, double abs_slip, double force_N,
                               Eigen::VectorXd& torque) const {
  if (f.curves.empty()) {  // law without a SpeedCurve form: evaluate it directly
    ring_torque_Nm(abs_slip, force_N, f.ring_temp_C, torque);
    return;
  }
  const double p = pressure_Pa(force_N);
  const RingPassState state{&f, nullptr, &torque};
  if (ring_torques_inside(thermal_.ring_radius_m(), rings_increasing_, ring_pitch_m_, f, f.rates, abs_slip,
                          ring_radius_area_m3_, p, std::span<const RingPassState>(&state, 1)))
    return;
  const Eigen::Index n = ring_radius_area_m3_.size();
  torque.resize(n);
  SpeedTermsAlongRings terms(thermal_.ring_radius_m(), ring_pitch_m_, f, f.rates, abs_slip);
  SpeedBlock block;
  for (Eigen::Index i0 = 0; i0 < n; i0 += kBlockRings) {
    terms.fill(i0, std::min(kBlockRings, n - i0), block);
    block_ring_torques(f, block, nullptr, ring_radius_area_m3_, p, abs_slip, torque);
  }
}

void WetClutch::ring_torque_pair_Nm(const FrozenFriction& fa, const FrozenFriction& fb, double abs_slip, double force_N,
                                    Eigen::VectorXd& torque_a, Eigen::VectorXd& torque_b) const {
  // One list of rates for both: a's, then b's that a lacks (none when both ends lie in one
  // bracket of the matrix, the common case).
  std::size_t b_at[kCarriedRates];
  double rates[kCarriedRates];
  std::size_t n_rates = fa.rates.size();
  bool shared = !fa.curves.empty() && !fb.curves.empty() && fa.min_speed_mm_s == fb.min_speed_mm_s &&
                fa.max_speed_mm_s == fb.max_speed_mm_s && n_rates <= kCarriedRates && fb.rates.size() <= kCarriedRates;
  if (shared) {
    std::copy(fa.rates.begin(), fa.rates.end(), rates);
    for (std::size_t j = 0; j < fb.rates.size() && shared; ++j) {
      const auto at = static_cast<std::size_t>(std::find(rates, rates + n_rates, fb.rates[j]) - rates);
      if (at == n_rates) {
        if (n_rates == kCarriedRates)
          shared = false;  // more rates than are carried: two passes
        else
          rates[n_rates++] = fb.rates[j];
      }
      b_at[j] = at;
    }
  }
  if (!shared) {
    ring_torque_Nm(fa, abs_slip, force_N, torque_a);
    ring_torque_Nm(fb, abs_slip, force_N, torque_b);
    return;
  }
  const double p = pressure_Pa(force_N);
  const RingPassState states[2] = {{&fa, nullptr, &torque_a}, {&fb, b_at, &torque_b}};
  if (ring_torques_inside(thermal_.ring_radius_m(), rings_increasing_, ring_pitch_m_, fa,
                          std::span<const double>(rates, n_rates), abs_slip, ring_radius_area_m3_, p, states))
    return;
  const Eigen::Index n = ring_radius_area_m3_.size();
  torque_a.resize(n);
  torque_b.resize(n);
  SpeedTermsAlongRings terms(thermal_.ring_radius_m(), ring_pitch_m_, fa, std::span<const double>(rates, n_rates),
                             abs_slip);
  SpeedBlock block;
  for (Eigen::Index i0 = 0; i0 < n; i0 += kBlockRings) {
    terms.fill(i0, std::min(kBlockRings, n - i0), block);
    block_ring_torques(fa, block, nullptr, ring_radius_area_m3_, p, abs_slip, torque_a);
    block_ring_torques(fb, block, b_at, ring_radius_area_m3_, p, abs_slip, torque_b);
  }
}

}  // namespace shudder::clutch
