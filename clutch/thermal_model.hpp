#pragma once
// Axisymmetric r–z temperature field of one sliding interface (Paper G eqs. 2–12, Table 1).
//
// Domain: half separator (z = 0 .. Z_sd) | interface oil film (z = Z_sd) | friction lining |
// half core disc, between R_in and R_out. In every layer
//
//     rho*cp*dT/dt = k * ( (1/r) d/dr (r dT/dr) + d²T/dz² )                    (Paper G eq. 3)
//
// Boundaries: z faces adiabatic (eq. 2) unless `rig_heat_capacity` links the separator's back
// face to a lumped rig mass; T(R_in) held at its start value; T(R_out) = sump temperature.
// The film node of each radial ring (capacity rho_oil*cp_oil*h_mean per area) balances
//
//     generation q_i  -  conduction into separator and lining  -  oil advection  = film storage
//
// (Paper G eq. 9), the advection being the eq. 12 flow through the contact (see oil_flow.hpp)
// with the oil entering at R_in at the inner boundary temperature. The sump (eq. 7) is a stirred
// volume that receives every joule leaving the discs through R_in, R_out and the film outlet.
//
// Discretisation: finite volumes, cell-centred, uniform within a layer; harmonic (series)
// conductances across layer boundaries give flux continuity (eq. 8). Time stepping, two schemes
// on the whole field, both implicit, unconditionally stable and damping the stiff film nodes
// (time constant ≈ 25 µs against steps of milliseconds) instead of ringing on them:
//   step()      backward Euler, first order:  C (T1 - T0) / dt = -K T1 + q
//   step_bdf2() BDF2 with variable steps, second order (docs/thermal_model.md, "Time scheme"):
//               C (a T1 - b T0 + c T-1) / dt = -K T1 + q(t1),  w = dt / dt_prev,
//               a = (1 + 2w) / (1 + w),  b = 1 + w,  c = w² / (1 + w)
//               (w = 1: 3/2, 2, 1/2). Its first step, and any after a step(), is backward Euler.
// Either is solved by a band LU (ring-major numbering: half band width = nodes per ring; see
// banded_lu.hpp), factorised only when the step's storage term or the oil flow changes. Sump and
// rig temperatures lag one step (explicit, their time constants are seconds); every flux of the
// ledger is evaluated with the same end-of-step temperatures as the solve, so the discrete energy
// balance closes to round-off. Backward Euler books each step's heat and outflows as their
// end-of-step rates times dt (Simpson's mean heat, for the prescribed-slip runner), exactly
// what its solve balances. BDF2 books them by the trapezoidal rule over the step's two ends
// (second order, like the scheme: the heat generated is then not biased by dt/2 of its rise),
// whereas its solve balances
//     C (T1 - T0) + C w / (1 + w) [ (T1 - T0) - w (T0 - T-1) ] = dt (q1 - out1);
// the difference, C w/(1+w) [...] - dt/2 [ (q1 - q0) - (out1 - out0) ], telescopes over a run to
// terms of the first and last steps only (bounded, O(dt), no drift) and is kept as the ledger's
// `scheme_storage_J`, so that the balance still closes to round-off.
//
// Units: SI inside (m, s, W, J, K); temperatures in °C.

#include <Eigen/Dense>
#include <Eigen/SparseCore>
#include <utility>
#include <vector>

#include "clutch/banded_lu.hpp"
#include "clutch/oil_flow.hpp"

namespace shudder::clutch {

struct Layer {
  double thickness_m = 0.0;
  double density_kg_m3 = 0.0;
  double specific_heat_J_per_kgK = 0.0;
  double conductivity_W_per_mK = 0.0;
  int cells = 1;  // axial cells in this layer
};

struct ThermalParams {
  // Geometry (Paper G Table 1).
  double inner_radius_m = 0.0381;
  double outer_radius_m = 0.0564;
  int radial_cells = 20;
  Layer separator{0.75e-3, 7600.0, 449.0, 46.0, 4};  // half separator disc, steel
  // Lining: Paper G prints cp = 5000 J/kgK; read as 500 (one zero too many): handbook values
  // for sintered-metal facings are ≈ 420 (docs/physics.md §3), and 500 reproduces the no-oil-flow
  // result (> 160 °C). Density 5000 kg/m³ as printed (porous bronze).
  Layer lining{0.56e-3, 5000.0, 500.0, 15.7, 4};
  Layer core{0.55e-3, 7600.0, 449.0, 46.0, 3};  // half core disc, steel

  // Oil (Paper G Table 1; supply flow Paper D).
  double oil_density_kg_m3 = 868.0;
  double oil_specific_heat_J_per_kgK = 2040.0;
  double film_thickness_m = 10e-6;          // h_mean
  double sump_volume_m3 = 500e-6;           // V_sump
  double supply_flow_m3_s = 200e-6 / 60.0;  // Q_oiltot = 200 ml/min

  // Probes: thermocouple at the back of the separator (Paper G: r = 48 mm, z = 0.5 mm from the
  // separator's back face); IR pyrometer spot (4 mm) on the interface.
  double thermocouple_r_m = 0.048;
  double thermocouple_z_m = 0.5e-3;
  double ir_r_m = 0.048;
  double ir_spot_diameter_m = 4e-3;

  // Effects that live in the thermal field (docs/formats/diagnosis_json.md names).
  bool interface_oil_cooling = true;
  OilFlowLaw oil_flow;
  bool sump_heating = true;
  bool rig_heat_capacity = false;
  double rig_heat_capacity_J_per_K = 150.0;  // estimate (docs/effects.md)
  double rig_conductance_W_per_K = 10.0;     // estimate (docs/effects.md)
  bool temperature_sensor_lag = false;
  double sensor_time_constant_s = 1.0;  // estimate
  // `thermocouple_offset` (measurement only): the reading is T_probe + dT [K]; estimate — a
  // type K junction's standard tolerance is ±2.2 K, hence the fit's ±10 K bounds.
  bool thermocouple_offset = false;
  double thermocouple_offset_K = 0.0;
};

/// Running energy account of one interface's domain, joules since the start.
struct EnergyLedger {
  double generated_J = 0.0;       // friction (and viscous) heat put into the film
  double to_sump_J = 0.0;         // left the discs through R_in, R_out and the film outlet
  double to_rig_J = 0.0;          // taken by the lumped rig mass
  double initial_stored_J = 0.0;  // sum C*T of discs and film at the start (reference 0 °C)
  double scheme_storage_J = 0.0;  // BDF2 only: its storage term beyond the change of sum C*T
};

struct ThermalState {
  double time_s = 0.0;
  Eigen::VectorXd temp_C;      // (n_nodes) ring-major: node = ring * nodes_per_ring + j
  double inner_temp_C = 0.0;   // Dirichlet value at R_in (held)
  double sump_temp_C = 0.0;    // Dirichlet value at R_out (stirred sump)
  double rig_temp_C = 0.0;     // lumped rig mass
  double sensor_temp_C = 0.0;  // thermocouple reading after its lag (and offset)
  EnergyLedger energy;
  // BDF2's history: the field one step back, that step's length, and the heat and outflow
  // rates at its end (for the ledger's trapezoidal sums). step_s = 0 means none (before the
  // first step, or after a backward Euler step).
  struct History {
    Eigen::VectorXd temp_C;
    double step_s = 0.0;
    double heat_W = 0.0, to_sump_W = 0.0, to_rig_W = 0.0;
  } history;
};

class ThermalModel;

/// The solver's scratch for one run (not physics state): the system matrix, its band LU and
/// the right-hand side. Owned by whoever steps the model (one per run, or per thread); the LU is
/// re-factorised only when the step size (by more than 1e-12 relative) or the oil flow changed
/// since the last step. A step with an unchanged factorisation allocates nothing here.
class ThermalWorkspace {
 public:
  /// Sized and analysed for `model`'s grid; use it only with that model.
  explicit ThermalWorkspace(const ThermalModel& model);

 private:
  friend class ThermalModel;
  Eigen::SparseMatrix<double> system_;  // capacity/dt + conduction + rho*cp*Q * advection
  BandedLu lu_;
  double factored_storage_step_s_ = -1.0;  // the matrix' capacity term is C / this (dt / a)
  double factored_flow_W_per_K_ = -1.0;
  Eigen::VectorXd rhs_;  // right-hand side, solved in place into the new temperatures
};

class ThermalModel {
 public:
  /// Validates and builds the grid; throws std::invalid_argument naming the bad parameter.
  explicit ThermalModel(ThermalParams params);

  ThermalState initial_state(double start_temp_C, double inner_temp_C, double sump_temp_C) const;

  /// Advances by dt. ring_heat_W (n_r): mean heat power delivered to each ring's film over the
  /// step (energy = ring_heat_W * dt exactly); slip_rad_s sets the interface oil flow.
  /// `workspace` (made for this model) carries the factorisation from step to step.
  void step(ThermalState& state, ThermalWorkspace& workspace, double dt_s, const Eigen::VectorXd& ring_heat_W,
            double slip_rad_s) const;

  /// Advances by dt with BDF2 (second order; see the header). ring_heat_end_W (n_r): the heat
  /// power into each ring's film at the step's end, t + dt (energy booked = ring_heat_end_W * dt);
  /// slip_end_rad_s: the slip there. The oil flow's temperature is the film mean extrapolated to
  /// t + dt. Keeps the history in `state`; its first step is backward Euler.
  void step_bdf2(ThermalState& state, ThermalWorkspace& workspace, double dt_s, const Eigen::VectorXd& ring_heat_end_W,
                 double slip_end_rad_s) const;

  /// The film (interface) temperatures extrapolated linearly from the last two fields to
  /// t + dt_s, T0 + w (T0 - T-1) with w = dt_s / previous_step_s: what a friction law needs at
  /// the end of a BDF2 step without an iteration (its error, O(dt²), keeps BDF2 second order).
  /// Without history, the current film temperatures. `out` is resized to n_r.
  void predicted_interface_temps_C(const ThermalState& s, double dt_s, Eigen::VectorXd& out) const;

  int radial_cells() const { return nr_; }
  int nodes_per_ring() const { return nz_; }
  int film_index() const { return film_j_; }
  const Eigen::VectorXd& ring_radius_m() const { return r_; }    // (n_r) ring centres
  const Eigen::VectorXd& ring_area_m2() const { return area_; }  // (n_r) annulus areas
  const Eigen::VectorXd& node_z_m() const { return z_; }         // (nodes_per_ring)
  double contact_area_m2() const { return area_.sum(); }
  const ThermalParams& params() const { return p_; }

  Eigen::VectorXd interface_temps_C(const ThermalState& s) const;  // (n_r) film nodes
  double mean_interface_temp_C(const ThermalState& s) const;       // area-weighted
  double max_temp_C(const ThermalState& s) const;
  double thermocouple_C(const ThermalState& s) const;    // at (r, z), no lag
  double ir_C(const ThermalState& s) const;              // spot mean on interface
  Eigen::MatrixXd field_C(const ThermalState& s) const;  // (nodes_per_ring x n_r)
  double stored_energy_J(const ThermalState& s) const;   // sum C*T, 0 °C reference
  /// generated - (stored - initial) - scheme_storage - to_sump - to_rig, joules (round-off).
  double energy_imbalance_J(const ThermalState& s) const;
  double sump_heat_capacity_J_per_K() const;
  double interface_flow_m3_s(double slip_rad_s, double mean_temp_C) const;

 private:
  int node(int ring, int j) const { return ring * nz_ + j; }
  void build_grid();
  // A probe point's bilinear weights: ring i (and i + 1) with weight wr, node j (and j + 1)
  // with weight wz; fixed by the grid, so found once.
  struct ProbeWeights {
    int i = 0, i1 = 0, j = 0, j1 = 0;
    double wr = 0.0, wz = 0.0;
  };
  ProbeWeights probe_weights(double r_m, double z_m) const;
  double probe(const ThermalState& s, const ProbeWeights& w) const;
  double film_mean_C(const Eigen::VectorXd& field) const;  // area-weighted film temperature
  void factorise_if_changed(ThermalWorkspace& w, double storage_step_s, double flow_W_per_K, double time_s) const;
  // Adds the boundary, heat, oil-inlet and rig terms to w.rhs_ (storage term already there).
  void add_sources(const ThermalState& s, ThermalWorkspace& w, const Eigen::VectorXd& ring_heat_W,
                   double flow_W_per_K) const;
  void check_finite(const Eigen::VectorXd& next, double time_s) const;
  // The outflows {to sump, to rig} with the end-of-step field `next`, times dt (J; W for dt = 1).
  std::pair<double, double> outflows(const ThermalState& s, const Eigen::VectorXd& next, double flow_W_per_K,
                                     double dt) const;
  // Time, sump, rig mass and sensor after the field has been replaced.
  void finish_step(ThermalState& s, double dt, double to_sump_J, double to_rig_J) const;

  ThermalParams p_;
  int nr_ = 0, nz_ = 0, film_j_ = 0;
  Eigen::VectorXd r_, area_, z_;            // ring centres, ring areas, node z positions
  Eigen::VectorXd capacity_J_per_K_;        // (n_nodes)
  Eigen::VectorXd g_inner_, g_outer_;       // (n_nodes) conductance to R_in / R_out, W/K
  Eigen::VectorXd g_rig_;                   // (n_r) separator back cell -> rig mass, W/K
  Eigen::VectorXd adv_weight_;              // (n_r) advective conductance per unit rho*cp*Q
  Eigen::SparseMatrix<double> conduction_;  // (n_nodes^2) Laplacian incl. boundary terms
  Eigen::SparseMatrix<double> advection_;   // same pattern, per unit rho*cp*Q
  Eigen::SparseMatrix<double> identity_;    // same pattern, capacity on the diagonal
  ProbeWeights thermocouple_;               // the thermocouple's point
  std::vector<ProbeWeights> ir_points_;     // the IR spot's chord samples
  std::vector<double> ir_chords_;           // their chord-length weights
  friend class ThermalWorkspace;
};

}  // namespace shudder::clutch
