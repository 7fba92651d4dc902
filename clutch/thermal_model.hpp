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
// conductances across layer boundaries give flux continuity (eq. 8). Time stepping: backward
// Euler on the whole field (first order, unconditionally stable and non-oscillating for the
// stiff film nodes), solved by a band LU (ring-major numbering: half band width = nodes per
// ring; see banded_lu.hpp), factorised only when dt or the oil flow changes. Sump and rig temperatures lag one step (explicit,
// their time constants are seconds); every flux of the ledger is evaluated with the same
// end-of-step temperatures as the solve, so the discrete energy balance closes to round-off.
//
// Units: SI inside (m, s, W, J, K); temperatures in °C.

#include <Eigen/Dense>
#include <Eigen/SparseCore>
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
  // for sintered-metal facings are ≈ 420 (PHYSICS.md §3), and 500 reproduces the no-oil-flow
  // result (> 160 °C). Density 5000 kg/m³ as printed (porous bronze).
  Layer lining{0.56e-3, 5000.0, 500.0, 15.7, 4};
  Layer core{0.55e-3, 7600.0, 449.0, 46.0, 3};  // half core disc, steel

  // Oil (Paper G Table 1; supply flow Paper D).
  double oil_density_kg_m3 = 868.0;
  double oil_specific_heat_J_per_kgK = 2040.0;
  double film_thickness_m = 10e-6;           // h_mean
  double sump_volume_m3 = 500e-6;            // V_sump
  double supply_flow_m3_s = 200e-6 / 60.0;   // Q_oiltot = 200 ml/min

  // Probes: thermocouple at the back of the separator (Paper G: r = 48 mm, z = 0.5 mm from the
  // separator's back face); IR pyrometer spot (4 mm) on the interface.
  double thermocouple_r_m = 0.048;
  double thermocouple_z_m = 0.5e-3;
  double ir_r_m = 0.048;
  double ir_spot_diameter_m = 4e-3;

  // Effects that live in the thermal field (FORMATS.md names).
  bool interface_oil_cooling = true;
  OilFlowLaw oil_flow;
  bool sump_heating = true;
  bool rig_heat_capacity = false;
  double rig_heat_capacity_J_per_K = 150.0;  // estimate: FORMATS.md example
  double rig_conductance_W_per_K = 10.0;     // estimate: FORMATS.md example
  bool temperature_sensor_lag = false;
  double sensor_time_constant_s = 1.0;       // estimate
  // `thermocouple_offset` (measurement only): the reading is T_probe + dT [K]; estimate — a
  // type K junction's standard tolerance is ±2.2 K, hence the fit's ±10 K bounds.
  bool thermocouple_offset = false;
  double thermocouple_offset_K = 0.0;
};

/// Running energy account of one interface's domain, joules since the start.
struct EnergyLedger {
  double generated_J = 0.0;      // friction (and viscous) heat put into the film
  double to_sump_J = 0.0;        // left the discs through R_in, R_out and the film outlet
  double to_rig_J = 0.0;         // taken by the lumped rig mass
  double initial_stored_J = 0.0; // sum C*T of discs and film at the start (reference 0 °C)
};

struct ThermalState {
  double time_s = 0.0;
  Eigen::VectorXd temp_C;        // (n_nodes) ring-major: node = ring * nodes_per_ring + j
  double inner_temp_C = 0.0;     // Dirichlet value at R_in (held)
  double sump_temp_C = 0.0;      // Dirichlet value at R_out (stirred sump)
  double rig_temp_C = 0.0;       // lumped rig mass
  double sensor_temp_C = 0.0;    // thermocouple reading after its lag (and offset)
  EnergyLedger energy;
};

class ThermalModel;

/// The solver's scratch for one run (not physics state): the system matrix, its band LU and
/// the right-hand side. Owned by whoever steps the model (one per run, or per thread); the LU is
/// re-factorised only when the step size or the oil flow changed since the last step. A step
/// with an unchanged factorisation allocates nothing here.
class ThermalWorkspace {
 public:
  /// Sized and analysed for `model`'s grid; use it only with that model.
  explicit ThermalWorkspace(const ThermalModel& model);

 private:
  friend class ThermalModel;
  Eigen::SparseMatrix<double> system_;  // capacity/dt + conduction + rho*cp*Q * advection
  BandedLu lu_;
  double factored_dt_ = -1.0;
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
  void step(ThermalState& state, ThermalWorkspace& workspace, double dt_s,
            const Eigen::VectorXd& ring_heat_W, double slip_rad_s) const;

  int radial_cells() const { return nr_; }
  int nodes_per_ring() const { return nz_; }
  int film_index() const { return film_j_; }
  const Eigen::VectorXd& ring_radius_m() const { return r_; }  // (n_r) ring centres
  const Eigen::VectorXd& ring_area_m2() const { return area_; } // (n_r) annulus areas
  const Eigen::VectorXd& node_z_m() const { return z_; }        // (nodes_per_ring)
  double contact_area_m2() const { return area_.sum(); }
  const ThermalParams& params() const { return p_; }

  Eigen::VectorXd interface_temps_C(const ThermalState& s) const;  // (n_r) film nodes
  double mean_interface_temp_C(const ThermalState& s) const;       // area-weighted
  double max_temp_C(const ThermalState& s) const;
  double thermocouple_C(const ThermalState& s) const;              // at (r, z), no lag
  double ir_C(const ThermalState& s) const;                        // spot mean on interface
  Eigen::MatrixXd field_C(const ThermalState& s) const;            // (nodes_per_ring x n_r)
  double stored_energy_J(const ThermalState& s) const;             // sum C*T, 0 °C reference
  /// generated - (stored - initial) - to_sump - to_rig, joules.
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

  ThermalParams p_;
  int nr_ = 0, nz_ = 0, film_j_ = 0;
  Eigen::VectorXd r_, area_, z_;          // ring centres, ring areas, node z positions
  Eigen::VectorXd capacity_J_per_K_;      // (n_nodes)
  Eigen::VectorXd g_inner_, g_outer_;     // (n_nodes) conductance to R_in / R_out, W/K
  Eigen::VectorXd g_rig_;                 // (n_r) separator back cell -> rig mass, W/K
  Eigen::VectorXd adv_weight_;            // (n_r) advective conductance per unit rho*cp*Q
  Eigen::SparseMatrix<double> conduction_;  // (n_nodes^2) Laplacian incl. boundary terms
  Eigen::SparseMatrix<double> advection_;   // same pattern, per unit rho*cp*Q
  Eigen::SparseMatrix<double> identity_;    // same pattern, capacity on the diagonal
  ProbeWeights thermocouple_;               // the thermocouple's point
  std::vector<ProbeWeights> ir_points_;     // the IR spot's chord samples
  std::vector<double> ir_chords_;           // their chord-length weights
  friend class ThermalWorkspace;
};

}  // namespace shudder::clutch
