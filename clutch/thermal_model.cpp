#include "clutch/thermal_model.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>
#include <tuple>

#include "core/units.hpp"

namespace shudder::clutch {

namespace {

// Storage steps this close (relative) share one factorisation (factorise_if_changed).
constexpr double kSameStepRelative = 1e-12;

void require_positive(double x, const std::string& what) {
  if (!std::isfinite(x) || !(x > 0.0)) throw std::invalid_argument(what + " must be a positive finite number");
}

void require_layer(const Layer& l, const std::string& name) {
  require_positive(l.thickness_m, name + " thickness");
  require_positive(l.density_kg_m3, name + " density");
  require_positive(l.specific_heat_J_per_kgK, name + " specific heat");
  require_positive(l.conductivity_W_per_mK, name + " conductivity");
  if (l.cells < 1 || l.cells > 200) throw std::invalid_argument(name + " cells must be in [1, 200]");
}

// Linear interpolation weight of x in a sorted vector of positions, clamped at both ends.
std::pair<int, double> locate(const Eigen::VectorXd& pos, double x) {
  const int n = static_cast<int>(pos.size());
  if (n == 1 || x <= pos[0]) return {0, 0.0};
  if (x >= pos[n - 1]) return {n - 2, 1.0};
  int i = 0;
  while (pos[i + 1] < x) ++i;
  return {i, (x - pos[i]) / (pos[i + 1] - pos[i])};
}

}  // namespace

ThermalWorkspace::ThermalWorkspace(const ThermalModel& model)
    : system_(model.conduction_), lu_(model.nr_ * model.nz_, model.nz_) {
  rhs_.resize(model.nr_ * model.nz_);
}

ThermalModel::ThermalModel(ThermalParams params) : p_(std::move(params)) {
  require_positive(p_.inner_radius_m, "inner radius");
  require_positive(p_.outer_radius_m, "outer radius");
  if (!(p_.outer_radius_m > p_.inner_radius_m)) throw std::invalid_argument("outer radius must exceed inner radius");
  if (p_.radial_cells < 2 || p_.radial_cells > 2000) throw std::invalid_argument("radial cells must be in [2, 2000]");
  require_layer(p_.separator, "separator");
  require_layer(p_.lining, "lining");
  require_layer(p_.core, "core");
  require_positive(p_.oil_density_kg_m3, "oil density");
  require_positive(p_.oil_specific_heat_J_per_kgK, "oil specific heat");
  require_positive(p_.film_thickness_m, "oil film thickness");
  require_positive(p_.sump_volume_m3, "sump volume");
  if (!(p_.supply_flow_m3_s >= 0.0)) throw std::invalid_argument("oil supply flow must be >= 0");
  require_positive(p_.rig_heat_capacity_J_per_K, "rig heat capacity");
  if (!(p_.rig_conductance_W_per_K >= 0.0)) throw std::invalid_argument("rig conductance must be >= 0");
  require_positive(p_.sensor_time_constant_s, "sensor time constant");
  require_positive(p_.ir_spot_diameter_m, "IR spot diameter");
  build_grid();
}

void ThermalModel::build_grid() {
  nr_ = p_.radial_cells;
  film_j_ = p_.separator.cells;
  nz_ = p_.separator.cells + 1 + p_.lining.cells + p_.core.cells;
  const int n = nr_ * nz_;
  const double dr = (p_.outer_radius_m - p_.inner_radius_m) / nr_;

  // Radial rings.
  r_.resize(nr_);
  area_.resize(nr_);
  for (int i = 0; i < nr_; ++i) {
    const double lo = p_.inner_radius_m + i * dr;
    r_[i] = lo + 0.5 * dr;
    area_[i] = std::numbers::pi * ((lo + dr) * (lo + dr) - lo * lo);
  }

  // Axial nodes: per node its thickness, conductivity and rho*cp (film: zero thickness).
  std::vector<double> dz(nz_, 0.0), k(nz_, 0.0), rhoc(nz_, 0.0);
  z_.resize(nz_);
  int j = 0;
  double z0 = 0.0;
  for (const Layer* l : {&p_.separator, &p_.lining, &p_.core}) {
    const double h = l->thickness_m / l->cells;
    for (int c = 0; c < l->cells; ++c, ++j) {
      dz[j] = h;
      k[j] = l->conductivity_W_per_mK;
      rhoc[j] = l->density_kg_m3 * l->specific_heat_J_per_kgK;
      z_[j] = z0 + (c + 0.5) * h;
    }
    z0 += l->thickness_m;
    if (l == &p_.separator) {
      z_[j] = z0;  // film node at the separator | lining interface
      ++j;
    }
  }
  const auto is_film = [this](int jj) { return jj == film_j_; };

  capacity_J_per_K_.resize(n);
  g_inner_ = Eigen::VectorXd::Zero(n);
  g_outer_ = Eigen::VectorXd::Zero(n);
  g_rig_ = Eigen::VectorXd::Zero(nr_);
  adv_weight_.resize(nr_);

  std::vector<Eigen::Triplet<double>> cond, adv, cap, pattern;
  const auto couple = [&](int a, int b, double g) {
    cond.emplace_back(a, a, g);
    cond.emplace_back(b, b, g);
    cond.emplace_back(a, b, -g);
    cond.emplace_back(b, a, -g);
  };
  const double film_rhoc = p_.oil_density_kg_m3 * p_.oil_specific_heat_J_per_kgK;

  for (int i = 0; i < nr_; ++i) {
    const double lo = p_.inner_radius_m + i * dr;
    for (int jj = 0; jj < nz_; ++jj) {
      const int a = node(i, jj);
      // Storage.
      capacity_J_per_K_[a] = is_film(jj) ? film_rhoc * p_.film_thickness_m * area_[i] : rhoc[jj] * dz[jj] * area_[i];
      cap.emplace_back(a, a, capacity_J_per_K_[a]);
      // Axial conduction to the next node up (series half-cell resistances; the film node
      // has no thickness of its own).
      if (jj + 1 < nz_) {
        const auto half = [&](int q) { return is_film(q) ? 0.0 : 0.5 * dz[q] / k[q]; };
        const double resist = half(jj) + half(jj + 1);
        couple(a, node(i, jj + 1), area_[i] / resist);
      }
      if (is_film(jj)) continue;  // radial conduction in the oil film is neglected (Paper G)
      // Radial conduction to the next ring, and Dirichlet faces at R_in / R_out.
      if (i + 1 < nr_) couple(a, node(i + 1, jj), units::kTwoPi * (lo + dr) * dz[jj] * k[jj] / dr);
      if (i == 0) g_inner_[a] = units::kTwoPi * p_.inner_radius_m * dz[jj] * k[jj] / (0.5 * dr);
      if (i == nr_ - 1) g_outer_[a] = units::kTwoPi * p_.outer_radius_m * dz[jj] * k[jj] / (0.5 * dr);
      cond.emplace_back(a, a, g_inner_[a] + g_outer_[a]);
    }
    // Rig heat path from the separator's back face (z = 0), shared in proportion to area.
    if (p_.rig_heat_capacity && p_.rig_conductance_W_per_K > 0.0) {
      const double g_face =
          p_.rig_conductance_W_per_K * area_[i] /
          (std::numbers::pi * (p_.outer_radius_m * p_.outer_radius_m - p_.inner_radius_m * p_.inner_radius_m));
      const double g_half = area_[i] * p_.separator.conductivity_W_per_mK / (0.5 * dz[0]);
      g_rig_[i] = 1.0 / (1.0 / g_face + 1.0 / g_half);
      cond.emplace_back(node(i, 0), node(i, 0), g_rig_[i]);
    }
    // Upwind film advection, per unit rho*cp*Q (see oil_flow.hpp for the two forms).
    adv_weight_[i] = p_.oil_flow.form == FilmAdvectionForm::kPaperGLiteral ? r_[i] * r_[i] / p_.film_thickness_m : 1.0;
    const int f = node(i, film_j_);
    adv.emplace_back(f, f, adv_weight_[i]);
    if (i > 0) adv.emplace_back(f, node(i - 1, film_j_), -adv_weight_[i]);
  }

  // Give all three matrices the same sparsity pattern so their value arrays can be combined
  // entry by entry without re-assembly.
  for (const auto* list : {&cond, &adv, &cap})
    for (const auto& t : *list) pattern.emplace_back(t.row(), t.col(), 0.0);
  const auto assemble = [&](std::vector<Eigen::Triplet<double>> entries) {
    entries.insert(entries.end(), pattern.begin(), pattern.end());
    Eigen::SparseMatrix<double> m(n, n);
    m.setFromTriplets(entries.begin(), entries.end());
    m.makeCompressed();
    return m;
  };
  conduction_ = assemble(cond);
  advection_ = assemble(adv);
  identity_ = assemble(cap);

  // Probe points. The IR spot: kSamples chords across a circle of the spot's diameter.
  thermocouple_ = probe_weights(p_.thermocouple_r_m, p_.thermocouple_z_m);
  constexpr int kSamples = 41;
  const double radius = 0.5 * p_.ir_spot_diameter_m;
  ir_points_.clear();
  ir_chords_.clear();
  for (int k = 0; k < kSamples; ++k) {
    const double x = radius * (2.0 * (k + 0.5) / kSamples - 1.0);
    ir_chords_.push_back(std::sqrt(radius * radius - x * x));
    ir_points_.push_back(probe_weights(p_.ir_r_m + x, z_[film_j_]));
  }
}

ThermalState ThermalModel::initial_state(double start_temp_C, double inner_temp_C, double sump_temp_C) const {
  ThermalState s;
  s.temp_C = Eigen::VectorXd::Constant(nr_ * nz_, start_temp_C);
  s.inner_temp_C = inner_temp_C;
  s.sump_temp_C = sump_temp_C;
  s.rig_temp_C = start_temp_C;
  s.sensor_temp_C = thermocouple_C(s) + (p_.thermocouple_offset ? p_.thermocouple_offset_K : 0.0);
  s.energy.initial_stored_J = stored_energy_J(s);
  return s;
}

double ThermalModel::interface_flow_m3_s(double slip_rad_s, double mean_temp_C) const {
  if (!p_.interface_oil_cooling) return 0.0;
  return p_.supply_flow_m3_s * p_.oil_flow.fraction(slip_rad_s, mean_temp_C);
}

double ThermalModel::sump_heat_capacity_J_per_K() const {
  return p_.oil_density_kg_m3 * p_.oil_specific_heat_J_per_kgK * p_.sump_volume_m3;
}

void ThermalModel::factorise_if_changed(ThermalWorkspace& w, double storage_step_s, double flow_W_per_K,
                                        double time_s) const {
  // A multi-rate run's steps are differences of products t0 + k·step and differ from each other
  // by a few ulp: such a step reuses the factorisation (its storage term is then off by
  // < 1e-12 relative, far below the scheme's own error), where a bitwise test would refactorise
  // on every step. The flow term is compared exactly: it moves with the physics.
  const bool same_step = std::abs(storage_step_s - w.factored_storage_step_s_) <= kSameStepRelative * storage_step_s;
  if (same_step && flow_W_per_K == w.factored_flow_W_per_K_) return;
  double* m = w.system_.valuePtr();
  const double* c = conduction_.valuePtr();
  const double* a = advection_.valuePtr();
  const double* cap = identity_.valuePtr();
  for (Eigen::Index e = 0; e < w.system_.nonZeros(); ++e) m[e] = cap[e] / storage_step_s + c[e] + flow_W_per_K * a[e];
  if (!w.lu_.factorize(w.system_))
    throw std::runtime_error("thermal solve: factorisation failed at t = " + std::to_string(time_s) + " s");
  w.factored_storage_step_s_ = storage_step_s;
  w.factored_flow_W_per_K_ = flow_W_per_K;
}

void ThermalModel::add_sources(const ThermalState& s, ThermalWorkspace& w, const Eigen::VectorXd& ring_heat_W,
                               double flow_W_per_K) const {
  for (int i = 0; i < nr_; ++i) {
    w.rhs_[node(i, film_j_)] += ring_heat_W[i];
    w.rhs_[node(i, 0)] += g_rig_[i] * s.rig_temp_C;
  }
  w.rhs_[node(0, film_j_)] += flow_W_per_K * adv_weight_[0] * s.inner_temp_C;
}

void ThermalModel::check_finite(const Eigen::VectorXd& next, double time_s) const {
  for (Eigen::Index a = 0; a < next.size(); ++a)
    if (!std::isfinite(next[a]))
      throw std::runtime_error("thermal solve produced a non-finite temperature at t = " + std::to_string(time_s) +
                               " s, ring " + std::to_string(a / nz_) + ", axial node " + std::to_string(a % nz_));
}

std::pair<double, double> ThermalModel::outflows(const ThermalState& s, const Eigen::VectorXd& next,
                                                 double flow_W_per_K, double dt) const {
  const Eigen::Index n = next.size();
  const double out_inner = g_inner_.dot(next - Eigen::VectorXd::Constant(n, s.inner_temp_C)) * dt;
  const double out_outer = g_outer_.dot(next - Eigen::VectorXd::Constant(n, s.sump_temp_C)) * dt;
  double out_oil = 0.0, to_rig = 0.0;
  for (int i = 0; i < nr_; ++i) {
    const double upstream = i == 0 ? s.inner_temp_C : next[node(i - 1, film_j_)];
    out_oil += flow_W_per_K * adv_weight_[i] * (next[node(i, film_j_)] - upstream) * dt;
    to_rig += g_rig_[i] * (next[node(i, 0)] - s.rig_temp_C) * dt;
  }
  return {out_inner + out_outer + out_oil, to_rig};
}

void ThermalModel::finish_step(ThermalState& s, double dt, double to_sump_J, double to_rig_J) const {
  s.time_s += dt;
  if (p_.sump_heating) s.sump_temp_C += to_sump_J / sump_heat_capacity_J_per_K();
  if (p_.rig_heat_capacity) s.rig_temp_C += to_rig_J / p_.rig_heat_capacity_J_per_K;
  const double probe_now = thermocouple_C(s) + (p_.thermocouple_offset ? p_.thermocouple_offset_K : 0.0);
  s.sensor_temp_C = p_.temperature_sensor_lag
                        ? probe_now + (s.sensor_temp_C - probe_now) * std::exp(-dt / p_.sensor_time_constant_s)
                        : probe_now;
}

void ThermalModel::step(ThermalState& s, ThermalWorkspace& w, double dt, const Eigen::VectorXd& ring_heat_W,
                        double slip_rad_s) const {
  if (!(dt > 0.0)) throw std::invalid_argument("thermal step must be > 0");
  const double flow_W_per_K =
      p_.oil_density_kg_m3 * p_.oil_specific_heat_J_per_kgK * interface_flow_m3_s(slip_rad_s, mean_interface_temp_C(s));
  factorise_if_changed(w, dt, flow_W_per_K, s.time_s);

  // Right-hand side: storage, boundary temperatures, heat input, oil inlet, rig mass.
  w.rhs_ = capacity_J_per_K_.cwiseProduct(s.temp_C) / dt + g_inner_ * s.inner_temp_C + g_outer_ * s.sump_temp_C;
  add_sources(s, w, ring_heat_W, flow_W_per_K);
  w.lu_.solve_in_place(w.rhs_);
  check_finite(w.rhs_, s.time_s);
  // Energy ledger with the same end-of-step temperatures the solve used.
  const auto [to_sump, to_rig] = outflows(s, w.rhs_, flow_W_per_K, dt);
  s.energy.generated_J += ring_heat_W.sum() * dt;
  s.energy.to_sump_J += to_sump;
  s.energy.to_rig_J += to_rig;

  s.temp_C.swap(w.rhs_);   // the new field; the old one's storage is the next right-hand side
  s.history.step_s = 0.0;  // a BDF2 step after this one has no valid history
  finish_step(s, dt, to_sump, to_rig);
}

void ThermalModel::step_bdf2(ThermalState& s, ThermalWorkspace& w, double dt, const Eigen::VectorXd& ring_heat_end_W,
                             double slip_end_rad_s) const {
  if (!(dt > 0.0)) throw std::invalid_argument("thermal step must be > 0");
  auto& h = s.history;
  const Eigen::Index n = s.temp_C.size();
  if (!(h.step_s > 0.0) || h.temp_C.size() != n) {
    // Start (or restart) with one backward Euler step: one first-order step's error is
    // O(dt²), which keeps the run second order.
    h.temp_C = s.temp_C;
    const EnergyLedger before = s.energy;
    step(s, w, dt, ring_heat_end_W, slip_end_rad_s);
    h.step_s = dt;
    h.heat_W = ring_heat_end_W.sum();
    h.to_sump_W = (s.energy.to_sump_J - before.to_sump_J) / dt;
    h.to_rig_W = (s.energy.to_rig_J - before.to_rig_J) / dt;
    return;
  }
  const double ratio = dt / h.step_s;  // w of the header
  const double a = (1.0 + 2.0 * ratio) / (1.0 + ratio), b = 1.0 + ratio, c = ratio * ratio / (1.0 + ratio);
  const double mean_now_C = film_mean_C(s.temp_C);
  const double mean_end_C = mean_now_C + ratio * (mean_now_C - film_mean_C(h.temp_C));
  const double flow_W_per_K =
      p_.oil_density_kg_m3 * p_.oil_specific_heat_J_per_kgK * interface_flow_m3_s(slip_end_rad_s, mean_end_C);
  factorise_if_changed(w, dt / a, flow_W_per_K, s.time_s);

  w.rhs_ = capacity_J_per_K_.cwiseProduct(b * s.temp_C - c * h.temp_C) / dt + g_inner_ * s.inner_temp_C +
           g_outer_ * s.sump_temp_C;
  add_sources(s, w, ring_heat_end_W, flow_W_per_K);
  w.lu_.solve_in_place(w.rhs_);
  check_finite(w.rhs_, s.time_s);

  // Ledger: trapezoidal sums of the rates at the step's two ends, and the scheme's own term
  // (header) from the fields and rates alone, so that its closure checks the solve.
  const auto [to_sump_W, to_rig_W] = outflows(s, w.rhs_, flow_W_per_K, 1.0);
  const double heat_W = ring_heat_end_W.sum();
  const double to_sump = 0.5 * dt * (h.to_sump_W + to_sump_W), to_rig = 0.5 * dt * (h.to_rig_W + to_rig_W);
  s.energy.generated_J += 0.5 * dt * (h.heat_W + heat_W);
  s.energy.to_sump_J += to_sump;
  s.energy.to_rig_J += to_rig;
  s.energy.scheme_storage_J +=
      ratio / (1.0 + ratio) * capacity_J_per_K_.dot((w.rhs_ - s.temp_C) - ratio * (s.temp_C - h.temp_C)) -
      0.5 * dt * ((heat_W - h.heat_W) - (to_sump_W + to_rig_W - h.to_sump_W - h.to_rig_W));

  h.temp_C.swap(s.temp_C);  // history: the field at t
  s.temp_C.swap(w.rhs_);    // the new field; the oldest one's storage is the next right-hand side
  h.step_s = dt;
  h.heat_W = heat_W;
  h.to_sump_W = to_sump_W;
  h.to_rig_W = to_rig_W;
  finish_step(s, dt, to_sump, to_rig);
}

void ThermalModel::predicted_interface_temps_C(const ThermalState& s, double dt, Eigen::VectorXd& out) const {
  out.resize(nr_);
  const auto& h = s.history;
  const bool known = h.step_s > 0.0 && h.temp_C.size() == s.temp_C.size();
  const double ratio = known ? dt / h.step_s : 0.0;
  for (int i = 0; i < nr_; ++i) {
    const double now = s.temp_C[node(i, film_j_)];
    out[i] = known ? now + ratio * (now - h.temp_C[node(i, film_j_)]) : now;
  }
}

double ThermalModel::film_mean_C(const Eigen::VectorXd& field) const {
  Eigen::VectorXd t(nr_);
  for (int i = 0; i < nr_; ++i) t[i] = field[node(i, film_j_)];
  return t.dot(area_) / area_.sum();
}

Eigen::VectorXd ThermalModel::interface_temps_C(const ThermalState& s) const {
  Eigen::VectorXd t(nr_);
  for (int i = 0; i < nr_; ++i) t[i] = s.temp_C[node(i, film_j_)];
  return t;
}

double ThermalModel::mean_interface_temp_C(const ThermalState& s) const { return film_mean_C(s.temp_C); }

double ThermalModel::max_temp_C(const ThermalState& s) const { return s.temp_C.maxCoeff(); }

ThermalModel::ProbeWeights ThermalModel::probe_weights(double r_m, double z_m) const {
  ProbeWeights w;
  std::tie(w.i, w.wr) = locate(r_, r_m);
  std::tie(w.j, w.wz) = locate(z_, z_m);
  w.i1 = std::min(w.i + 1, nr_ - 1);
  w.j1 = std::min(w.j + 1, nz_ - 1);
  return w;
}

double ThermalModel::probe(const ThermalState& s, const ProbeWeights& w) const {
  const double lo = (1 - w.wz) * s.temp_C[node(w.i, w.j)] + w.wz * s.temp_C[node(w.i, w.j1)];
  const double hi = (1 - w.wz) * s.temp_C[node(w.i1, w.j)] + w.wz * s.temp_C[node(w.i1, w.j1)];
  return (1 - w.wr) * lo + w.wr * hi;
}

double ThermalModel::thermocouple_C(const ThermalState& s) const { return probe(s, thermocouple_); }

double ThermalModel::ir_C(const ThermalState& s) const {
  // Mean over a circular spot of the interface: each radius weighted by its chord length
  // (points and weights fixed in build_grid).
  double sum = 0.0, weight = 0.0;
  for (std::size_t k = 0; k < ir_points_.size(); ++k) {
    sum += ir_chords_[k] * probe(s, ir_points_[k]);
    weight += ir_chords_[k];
  }
  return sum / weight;
}

Eigen::MatrixXd ThermalModel::field_C(const ThermalState& s) const {
  Eigen::MatrixXd f(nz_, nr_);
  for (int i = 0; i < nr_; ++i)
    for (int j = 0; j < nz_; ++j) f(j, i) = s.temp_C[node(i, j)];
  return f;
}

double ThermalModel::stored_energy_J(const ThermalState& s) const { return capacity_J_per_K_.dot(s.temp_C); }

double ThermalModel::energy_imbalance_J(const ThermalState& s) const {
  const auto& e = s.energy;
  return e.generated_J - (stored_energy_J(s) - e.initial_stored_J) - e.scheme_storage_J - e.to_sump_J - e.to_rig_J;
}

}  // namespace shudder::clutch
