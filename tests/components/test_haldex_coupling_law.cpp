// The Haldex coupling's contact law (components/haldex_coupling_law) integrated by the network's
// simulation, its pressure and valve being states of the law, against closed forms:
//   * at a clamp force F its torque, capacity and ring heats are the wet pack's at F (bit for bit);
//   * slipping at a constant Δω with the valve shut and no leakage, the pump fills the
//     compliance: p(t) = D |Δω| t / C, the torque following it;
//   * the valve follows a command with its lag: u(t) = u_cmd + (u0 − u_cmd) e^(−t/τ_v);
//   * LOCKED under a constant torque T0 with the valve shut, the pump is still (Δω = 0) and the
//     leakage drains the pressure, p(t) = p0 e^(−t G/C); the coupling breaks away when its
//     capacity falls to T0, at t* = (C/G) ln(p0 / p*), p* the pressure whose capacity is T0.
//     The event is located on the same dense output as a held force's (1e-10 s); the expected
//     time is good to the integrator's relative tolerance on p (1e-8 here), so 1e-6 s.
// C, D, G are computed here from the parameters, not read from the class.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <numbers>
#include <vector>

#include "clutch/linear_friction.hpp"
#include "clutch/wet_clutch.hpp"
#include "dynamics/network.hpp"
#include "dynamics/simulation.hpp"
#include "components/haldex_coupling_law.hpp"

namespace shudder::components {
namespace {

using dynamics::kGround;

clutch::WetClutch pack() {
  clutch::Fluid fluid;
  fluid.name = "constant";
  // μ_k = 0.11 at every speed and temperature; μ_s = 1.2 μ_k.
  fluid.friction = std::make_shared<clutch::LinearTemperatureFriction>(
      std::vector<clutch::LinearTemperaturePoint>{{1.0, 0.0, 0.11}, {1000.0, 0.0, 0.11}});
  fluid.breakaway_ratio = 1.2;
  clutch::WetClutchParams p;
  p.sliding_interfaces = 16;
  p.start_temp_C = 40.0;
  return clutch::WetClutch(p, fluid);
}

double compliance_m3_per_Pa(const HaldexHydraulicsParams& p) {
  const double area = p.piston_area_cm2 * 1e-4;
  return p.chamber_volume_cm3 * 1e-6 / (p.bulk_modulus_bar * 1e5) + area * area / (p.pack_stiffness_N_per_mm * 1e3);
}

struct Rig {
  clutch::WetClutch clutch = pack();
  std::shared_ptr<ClutchContext> context;
  std::shared_ptr<HaldexCommand> command = std::make_shared<HaldexCommand>();
  std::shared_ptr<HaldexCouplingLaw> law;
  Rig(const HaldexHydraulicsParams& h, double start_bar) {
    const ClutchContact contact(clutch, BearingDrag{}, StickTimeFriction{});
    context = std::make_shared<ClutchContext>(contact.start_inputs(PiecewiseLinear({0.0}, {0.0})));
    law = std::make_shared<HaldexCouplingLaw>(contact, context, HaldexHydraulics(h, 1.0), command, start_bar);
  }
};

TEST(HaldexCouplingLaw, IsTheWetPackAtTheClampForceOfItsPressure) {
  Rig r(HaldexHydraulicsParams{}, 0.0);
  const ClutchContact contact(r.clutch, BearingDrag{}, StickTimeFriction{});
  const double z[2] = {7.0, 0.3};
  const double force = 7.0 * 1e5 * HaldexHydraulicsParams{}.piston_area_cm2 * 1e-4;
  ClutchContext held(contact.start_inputs(PiecewiseLinear({0.0}, {force})));
  EXPECT_DOUBLE_EQ(r.law->clamp_force_N(z), force);
  EXPECT_DOUBLE_EQ(r.law->kinetic_torque_Nm(2.0, 0.1, z), contact.kinetic_torque_Nm(held, 2.0, 0.1));
  EXPECT_DOUBLE_EQ(r.law->static_capacity_Nm(0.1, 0.0, z), contact.static_capacity_Nm(held, 0.1, 0.0));
  std::vector<double> q(static_cast<std::size_t>(r.law->heat_channels())), q_held(q.size());
  r.law->channel_heat_W(2.0, 0.1, z, q.data());
  contact.channel_heat_W(held, 2.0, 0.1, q_held.data());
  EXPECT_EQ(q, q_held);
  // No pressure, no force, no torque (Gen I: no preload).
  const double empty[2] = {0.0, 1.0};
  EXPECT_DOUBLE_EQ(r.law->kinetic_torque_Nm(2.0, 0.1, empty), 0.0);
}

TEST(HaldexCouplingLaw, SlippingWithTheValveShutThePumpFillsTheComplianceAndTheValveLagsItsCommand) {
  HaldexHydraulicsParams h;
  h.leak_cm3_s_per_bar = 0.0;
  Rig r(h, 0.0);
  r.command->opening = 0.0;  // shut
  dynamics::TorsionalNetwork net;
  net.add_inertia({"input", 0.1});
  const double slip = 2.0;  // rad/s, held by a speed source against the grounded output
  net.add_speed_source({"drive", 0, [slip](double) { return slip; }, [](double) { return 0.0; }});
  net.add_contact({"coupling", 0, kGround, r.law});
  dynamics::Simulation sim(net, {1e-10, 1e-10, 1e-3, 1e-6, 1e-10});
  Eigen::VectorXd w(1);
  w << slip;
  sim.initialize(0.0, Eigen::VectorXd::Zero(1), w);
  // Before the start the valve was open; the shut command takes τ_v to act.
  r.command->opening = 0.0;
  const double t = 0.05;
  sim.advance(t);
  const auto s = sim.sample();
  const double pump_m3_per_rad = h.pump_displacement_cm3_per_rev * 1e-6 / (2 * std::numbers::pi);
  const double expected_bar = pump_m3_per_rad * slip * t / compliance_m3_per_Pa(h) / 1e5;
  EXPECT_NEAR(s.contact_states[HaldexCouplingLaw::kPressure], expected_bar, 1e-8 * expected_bar);
  EXPECT_NEAR(s.contact_torque_Nm[0], r.law->kinetic_torque_Nm(slip, t, s.contact_states.data()), 1e-9);
  EXPECT_GT(s.contact_torque_Nm[0], 0.0);
  // The valve (started at the command, 0) now follows a new command 0.8 with its lag.
  r.command->opening = 0.8;
  sim.restart();
  sim.advance(t + 0.03);
  const double tau = 1e-3 * h.valve_time_constant_ms;
  EXPECT_NEAR(sim.sample().contact_states[HaldexCouplingLaw::kOpening], 0.8 * (1 - std::exp(-0.03 / tau)), 1e-8);
}

TEST(HaldexCouplingLaw, ALockedCouplingBreaksAwayWhenItsPressureHasLeakedToWhatTheHeldTorqueNeeds) {
  HaldexHydraulicsParams h;
  h.leak_cm3_s_per_bar = 0.05;
  const double p0 = 5.0;
  Rig r(h, p0);
  r.command->opening = 0.0;
  const double held_Nm = 150.0;
  dynamics::TorsionalNetwork net;
  net.add_inertia({"input", 0.1});
  net.add_torque_source({"load", 0, [held_Nm](double) { return held_Nm; }});
  net.add_contact({"coupling", 0, kGround, r.law});
  dynamics::Simulation sim(net, {1e-10, 1e-8, 1e-3, 1e-6, 1e-10});
  sim.initialize(0.0, Eigen::VectorXd::Zero(1), Eigen::VectorXd::Zero(1));
  ASSERT_EQ(sim.mode(0), dynamics::ContactMode::kStuck);
  // p*: the capacity is proportional to the force (μ_s does not depend on load here).
  const double z0[2] = {1.0, 0.0};
  const double capacity_per_bar = r.law->static_capacity_Nm(0.0, 0.0, z0);
  const double p_star = held_Nm / capacity_per_bar;
  ASSERT_LT(p_star, p0);
  const double tau_s = compliance_m3_per_Pa(h) / (h.leak_cm3_s_per_bar * 1e-6 / 1e5);
  const double t_star = tau_s * std::log(p0 / p_star);
  sim.advance(t_star - 1e-6);
  EXPECT_EQ(sim.mode(0), dynamics::ContactMode::kStuck);
  EXPECT_NEAR(sim.sample().contact_states[HaldexCouplingLaw::kPressure], p0 * std::exp(-(t_star - 1e-6) / tau_s),
              1e-8 * p0);
  sim.advance(t_star + 1e-6);
  EXPECT_NE(sim.mode(0), dynamics::ContactMode::kStuck);
  EXPECT_EQ(sim.counters().breakaway_events, 1);
}

}  // namespace
}  // namespace shudder::components
