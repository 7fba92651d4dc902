// Benchmarks of network scenarios (docs/formats/network_file.md; figures in docs/performance.md):
//   Network20Bodies4WetClutches  20 bodies and 4 wet clutches, 2 s simulated (target: >= 100x
//                                real time in-process): a motor turns a chain of 16 inertias on
//                                shafts at 60 rpm; four wet clutches (fluid C, 10 kN) join chain
//                                nodes 4, 8, 12, 16 to four housings on torsion bars to ground,
//                                each slipping all the run with its own thermal model.
//   Network20Bodies4WetClutches10Rings  the same with [solver] radial_cells = 10 (half the
//                                rings of each clutch's thermal grid): what a coarser grid buys.
//   NetworkScaling/B/C           the same build with B chain bodies and C clutches (C housings),
//                                for how cost grows with bodies and with clutches.
// Counter real_time_factor = simulated seconds per wall second.
#include <benchmark/benchmark.h>

#include <chrono>
#include <sstream>
#include <string>

#include "studies/network_run.hpp"
#include "io/network_scenario.hpp"

using namespace shudder;

namespace {

constexpr double kDuration_s = 2.0;

// The network's scenario text: `chain` inertias, `clutches` wet clutches spread along the chain.
std::string network_text(int chain, int clutches, int radial_cells = 20) {
  std::ostringstream os;
  os << "[scenario]\ntype = \"network\"\nduration_s = " << kDuration_s << "\n[output]\nsample_rate_Hz = 1000\n";
  os << "[solver]\nradial_cells = " << radial_cells << "\n";
  os << "[network.motor]\ntype = \"motor\"\nnode = \"body_0\"\nspeed_rpm = 60\nkp_Nms_per_rad = 10\n"
        "ki_Nm_per_rad = 300\ntorque_limit_Nm = 2000\n";
  for (int i = 0; i < chain; ++i) {
    os << "[network.body_" << i << "]\ntype = \"inertia\"\ninertia_kg_m2 = 0.05\nspeed_rpm = 60\n";
    if (i > 0)
      os << "[network.shaft_" << i << "]\ntype = \"shaft\"\nfrom = \"body_" << i - 1 << "\"\nto = \"body_" << i
         << "\"\nstiffness_Nm_per_rad = 2e4\ndamping_Nms_per_rad = 2\n";
  }
  for (int c = 0; c < clutches; ++c) {
    const int at = (c + 1) * chain / clutches - 1;
    os << "[network.housing_" << c << "]\ntype = \"inertia\"\ninertia_kg_m2 = 0.02\n";
    os << "[network.bar_" << c << "]\ntype = \"shaft\"\nfrom = \"housing_" << c
       << "\"\nto = \"ground\"\nstiffness_Nm_per_rad = 1e5\ndamping_Nms_per_rad = 1\n";
    os << "[network.clutch_" << c << "]\ntype = \"clutch\"\nlaw = \"wet\"\nfrom = \"body_" << at
       << "\"\nto = \"housing_" << c << "\"\nmax_force_N = 10000\n[network.clutch_" << c
       << ".clutch]\nfluid = \"" SHUDDER_SOURCE_DIR << "/scenarios/fluids/lsc_fluid_c.toml\"\nstart_temp_C = 40\n";
  }
  return os.str();
}

void run(benchmark::State& state, int chain, int clutches, int radial_cells = 20) {
  const auto sc = io::load_network_scenario_text(network_text(chain, clutches, radial_cells), "bench_network.toml");
  double wall_s = 0.0;
  studies::NetworkRun result;
  for (auto _ : state) {
    const auto t0 = std::chrono::steady_clock::now();
    result = studies::run_network(sc.spec);
    wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    benchmark::DoNotOptimize(result);
  }
  state.counters["real_time_factor"] = kDuration_s / wall_s;
  state.counters["bodies"] = chain + clutches;
  state.counters["clutches"] = clutches;
  state.counters["integrator_steps"] = result.recording.find_scalar("integrator_steps")->value;
}

void BM_Network20Bodies4WetClutches(benchmark::State& state) { run(state, 16, 4); }
void BM_Network20Bodies4WetClutches10Rings(benchmark::State& state) { run(state, 16, 4, 10); }
void BM_NetworkScaling(benchmark::State& state) {
  run(state, static_cast<int>(state.range(0)), static_cast<int>(state.range(1)));
}

}  // namespace

BENCHMARK(BM_Network20Bodies4WetClutches)->Unit(benchmark::kMillisecond)->Iterations(3);
BENCHMARK(BM_Network20Bodies4WetClutches10Rings)->Unit(benchmark::kMillisecond)->Iterations(3);
BENCHMARK(BM_NetworkScaling)
    ->Args({8, 0})
    ->Args({16, 0})
    ->Args({32, 0})
    ->Args({64, 0})
    ->Args({16, 1})
    ->Args({16, 2})
    ->Args({16, 4})
    ->Args({16, 8})
    ->Unit(benchmark::kMillisecond)
    ->Iterations(2);
