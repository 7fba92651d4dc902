// No heap allocation inside a real-time step (docs/realtime.md). This binary interposes
// malloc/calloc/realloc/free (glibc lets an executable replace them; the originals stay
// reachable as __libc_*), so every allocation is counted: operator new (libstdc++ calls malloc)
// and Eigen's dynamic storage (std::malloc) alike. The count is per thread: the thermal task's
// worker thread may allocate, the stepping thread must not. The prescribed-slip element is stepped
// 10^4 times, i.e. across 100 thermal handovers. The rig's network in the fixed-step mode
// (dynamics/simulation.hpp) is advanced over 10^4 steps between samples and mode changes.
#include <gtest/gtest.h>

#include <cstddef>
#include <string>

#include "io/scenario.hpp"
#include "rig_models/realtime_coupling.hpp"
#include "dynamics/simulation.hpp"
#include "rig_models/lsctr_rig.hpp"

namespace {
thread_local long g_allocations = 0;  // trivial type: static TLS, no allocation on first use
}  // namespace

extern "C" {
void* __libc_malloc(std::size_t);
void* __libc_calloc(std::size_t, std::size_t);
void* __libc_realloc(void*, std::size_t);
void __libc_free(void*);
void* malloc(std::size_t n) {
  ++g_allocations;
  return __libc_malloc(n);
}
void* calloc(std::size_t n, std::size_t size) {
  ++g_allocations;
  return __libc_calloc(n, size);
}
void* realloc(void* p, std::size_t n) {
  ++g_allocations;
  return __libc_realloc(p, n);
}
void free(void* p) { __libc_free(p); }
}

namespace shudder {
namespace {

const std::string kScenarios = std::string(SHUDDER_SOURCE_DIR) + "/scenarios/";

TEST(RealtimeAlloc, CountingHookSeesAllocations) {
  const long before = g_allocations;
  auto* v = new std::string(100, 'x');  // longer than the small-string buffer
  delete v;
  EXPECT_GE(g_allocations - before, 2);
  const long eigen_before = g_allocations;
  Eigen::VectorXd x = Eigen::VectorXd::Zero(50);  // Eigen's storage: std::malloc
  EXPECT_EQ(g_allocations - eigen_before, 1);
  EXPECT_EQ(x.size(), 50);
}

TEST(RealtimeAlloc, PrescribedSlipStepAllocatesNothing) {
  const io::Scenario sc = io::load_scenario(kScenarios + "paper_g_case1_25kN.toml");
  const clutch::WetClutch clutch = sc.make_clutch();
  rig_models::RealtimeCoupling c(clutch, {}, {1e-4, 0.01}, 25300.0);
  for (int k = 0; k < 200; ++k) c.step(1.0 + 1e-3 * k, 25300.0);  // past the first handovers
  const long before = g_allocations;
  for (int k = 0; k < 10000; ++k) c.step(1.2 + 1e-3 * k, 25300.0 - 0.1 * k);
  EXPECT_EQ(g_allocations - before, 0);
  EXPECT_GT(c.thermal().interface_max_C, 20.5);  // the thermal updates did happen
}

TEST(RealtimeAlloc, RigNetworkFixedStepAllocatesNothingWhileSlipping) {
  // The rig's own network and clutch law, slipping at the cycle's speed (Case 1: no stick), the
  // ring temperatures held: the right-hand side and RK4 of every step, without samples.
  const io::Scenario sc = io::load_scenario(kScenarios + "rig_case1_25kN_378Hz.toml");
  const clutch::WetClutch clutch = sc.make_clutch();
  const auto& m = std::get<rig_models::RigModel>(sc.model);
  const rig_models::LsctrRig rig(m.params, clutch, m.cycle);
  const components::OwnedNetwork built = rig.build();
  components::ClutchContext* context = &built.clutch_context();
  const dynamics::TorsionalNetwork& net = built.network();
  dynamics::IntegratorSettings settings;
  settings.fixed_step_s = 1e-4;
  dynamics::Simulation sim(net, settings);
  // In steady sliding, as the rig's run starts: the bar and the speed loop's integral carry the
  // friction torque (a start from an untwisted bar would swing the housing into a stick).
  const double w0 = 2 * 3.141592653589793 * m.cycle.slip_speed_rpm(0.0) / 60.0;
  const double torque_Nm = rig.clutch_contact().kinetic_torque_Nm(*context, w0, 0.0);
  sim.initialize(0.0, Eigen::Vector2d(0.0, torque_Nm / rig.bar_stiffness_Nm_per_rad()), Eigen::Vector2d(w0, 0.0),
                 Eigen::VectorXd::Constant(1, torque_Nm / rig.motor_ki()));
  sim.advance(0.02);  // the stepper's and the right-hand side's buffers sized
  const long before = g_allocations;
  sim.advance(1.02);
  EXPECT_EQ(g_allocations - before, 0);
  EXPECT_EQ(sim.counters().steps, 10200);
  EXPECT_EQ(sim.counters().stick_events + sim.counters().breakaway_events + sim.counters().reversal_events, 0);
}

}  // namespace
}  // namespace shudder
