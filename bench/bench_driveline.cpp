// Benchmark of the Haldex driveline (docs/driveline.md, docs/performance.md): the shipped tight
// turn (scenarios/driveline_tight_turn.toml, 5 s simulated, fluid C, coupling sliding), the same
// manoeuvre with the stick-slip fluid, and the 10 s manoeuvres of the ≥ 100× real-time target (on one
// core): the tight turn and the full-lock parking turn
// (scenarios/driveline_parking_turn.toml, controller deciding) run for 10 s, and the parking turn
// as shipped (5 s; target ≤ 50 ms). The simulation only
// (rig_models::simulate); the run's stability maps and prediction are `Driveline_RunAnalysis`.
// Counters: integrator steps, stick events, and the factor over real time (simulated s / CPU s).
//   ./build/bench/shudder_bench --benchmark_filter=Driveline
#include <benchmark/benchmark.h>

#include <ctime>
#include <variant>

#include "io/fluid_loader.hpp"
#include "io/scenario.hpp"
#include "rig_models/haldex_driveline.hpp"
#include "rig_models/model.hpp"
#include "studies/model_studies.hpp"

using namespace shudder;

namespace {

double process_cpu_s() { return static_cast<double>(std::clock()) / CLOCKS_PER_SEC; }

void run_driveline(benchmark::State& state, const char* scenario, const char* fluid, double duration_s) {
  auto sc = io::load_scenario(std::string(SHUDDER_SOURCE_DIR "/scenarios/") + scenario);
  if (fluid) sc.fluid = io::load_fluid(std::string(SHUDDER_SOURCE_DIR "/scenarios/fluids/") + fluid);
  auto& model = std::get<rig_models::DrivelineModel>(sc.model);
  if (duration_s > 0) model.settings.duration_s = duration_s;
  const auto clutch = sc.make_clutch();
  dynamics::Recording rec;
  const double cpu0 = process_cpu_s();
  for (auto _ : state) {
    rec = rig_models::simulate(model, clutch);
    benchmark::DoNotOptimize(rec);
  }
  const double cpu_per_run_s = (process_cpu_s() - cpu0) / static_cast<double>(state.iterations());
  for (const char* name : {"integrator_steps", "stick_events"}) state.counters[name] = rec.find_scalar(name)->value;
  state.counters["x_real_time"] = model.settings.duration_s / cpu_per_run_s;
}

void BM_Driveline_TightTurn_FluidC(benchmark::State& state) {
  run_driveline(state, "driveline_tight_turn.toml", nullptr, 0.0);
}
void BM_Driveline_TightTurn_StickSlipFluid(benchmark::State& state) {
  run_driveline(state, "driveline_tight_turn.toml", "schematic_stick_slip.toml", 0.0);
}
void BM_Driveline_TightTurn_10s(benchmark::State& state) {
  run_driveline(state, "driveline_tight_turn.toml", nullptr, 10.0);
}
// The shipped parking turn as it is (5 s): the target "5 s parking turn <= 50 ms".
void BM_Driveline_ParkingTurn(benchmark::State& state) {
  run_driveline(state, "driveline_parking_turn.toml", nullptr, 0.0);
}
void BM_Driveline_ParkingTurn_10s(benchmark::State& state) {
  run_driveline(state, "driveline_parking_turn.toml", nullptr, 10.0);
}

// What `shudder run` adds after the simulation: the verdict's prediction and the three coupling
// stability maps (12 × 9 cells each) of studies::add_run_analysis.
void BM_Driveline_RunAnalysis(benchmark::State& state) {
  const auto sc = io::load_scenario(SHUDDER_SOURCE_DIR "/scenarios/driveline_tight_turn.toml");
  const auto& model = std::get<rig_models::DrivelineModel>(sc.model);
  const auto clutch = sc.make_clutch();
  const dynamics::Recording simulated = rig_models::simulate(model, clutch);
  for (auto _ : state) {
    dynamics::Recording rec = simulated;
    benchmark::DoNotOptimize(studies::add_run_analysis(model, clutch, sc.clutch.start_temp_C, rec));
  }
}

}  // namespace

BENCHMARK(BM_Driveline_TightTurn_FluidC)->Unit(benchmark::kMillisecond)->Iterations(3);
BENCHMARK(BM_Driveline_TightTurn_StickSlipFluid)->Unit(benchmark::kMillisecond)->Iterations(3);
BENCHMARK(BM_Driveline_TightTurn_10s)->Unit(benchmark::kMillisecond)->Iterations(3);
BENCHMARK(BM_Driveline_ParkingTurn)->Unit(benchmark::kMillisecond)->Iterations(3);
BENCHMARK(BM_Driveline_ParkingTurn_10s)->Unit(benchmark::kMillisecond)->Iterations(3);
BENCHMARK(BM_Driveline_RunAnalysis)->Unit(benchmark::kMillisecond)->Iterations(3);
