// Benchmark of the Haldex driveline (docs/driveline.md): the shipped tight turn
// (scenarios/driveline_tight_turn.toml, 5 s simulated, fluid C, coupling sliding) and the same
// manoeuvre with the stick-slip fluid (the coupling sticks and breaks away ~40 times). Counters:
// integrator steps and stick events; the wall time per 5 s manoeuvre is the figure.
//   ./build/bench/shudder_bench --benchmark_filter=Driveline
#include <benchmark/benchmark.h>

#include <variant>

#include "io/fluid_loader.hpp"
#include "io/scenario.hpp"
#include "rig_models/haldex_driveline.hpp"
#include "rig_models/model.hpp"

using namespace shudder;

namespace {

void run_tight_turn(benchmark::State& state, const char* fluid) {
  auto sc = io::load_scenario(SHUDDER_SOURCE_DIR "/scenarios/driveline_tight_turn.toml");
  if (fluid) sc.fluid = io::load_fluid(std::string(SHUDDER_SOURCE_DIR "/scenarios/fluids/") + fluid);
  const auto clutch = sc.make_clutch();
  dynamics::Recording rec;
  for (auto _ : state) {
    rec = rig_models::simulate(std::get<rig_models::DrivelineModel>(sc.model), clutch);
    benchmark::DoNotOptimize(rec);
  }
  for (const char* name : {"integrator_steps", "stick_events"}) state.counters[name] = rec.find_scalar(name)->value;
}

void BM_Driveline_TightTurn_FluidC(benchmark::State& state) { run_tight_turn(state, nullptr); }
void BM_Driveline_TightTurn_StickSlipFluid(benchmark::State& state) {
  run_tight_turn(state, "schematic_stick_slip.toml");
}

}  // namespace

BENCHMARK(BM_Driveline_TightTurn_FluidC)->Unit(benchmark::kMillisecond)->Iterations(3);
BENCHMARK(BM_Driveline_TightTurn_StickSlipFluid)->Unit(benchmark::kMillisecond)->Iterations(3);
