// Benchmarks of the test rig: Paper G Case 2 (30 s simulated) on the rig with the
// 378 Hz bar and the thermal model, with fluid C (no shudder; target <= 0.5 s on one core) and
// with the schematic negative-slope fluid (shudders; target <= 3 s). Counters report integrator
// steps, right-hand-side evaluations and stick/slip events.
#include <benchmark/benchmark.h>

#include <variant>

#include "io/fluid_loader.hpp"
#include "io/scenario.hpp"
#include "rig_models/lsctr_rig.hpp"
#include "rig_models/model.hpp"

using namespace shudder;

namespace {

void run_case2(benchmark::State& state, const char* fluid) {
  auto sc = io::load_scenario(SHUDDER_SOURCE_DIR "/scenarios/rig_case2_15kN_378Hz.toml");
  if (fluid) sc.fluid = io::load_fluid(std::string(SHUDDER_SOURCE_DIR "/scenarios/fluids/") + fluid);
  const auto clutch = sc.make_clutch();
  dynamics::Recording rec;
  for (auto _ : state) {
    rec = rig_models::simulate(std::get<rig_models::RigModel>(sc.model), clutch);
    benchmark::DoNotOptimize(rec);
  }
  for (const char* name : {"integrator_steps", "rhs_evaluations", "stick_events", "breakaway_events"})
    state.counters[name] = rec.find_scalar(name)->value;
}

void BM_RigCase2_378Hz_FluidC(benchmark::State& state) { run_case2(state, nullptr); }
void BM_RigCase2_378Hz_NegativeSlope(benchmark::State& state) { run_case2(state, "schematic_negative_slope.toml"); }

}  // namespace

BENCHMARK(BM_RigCase2_378Hz_FluidC)->Unit(benchmark::kMillisecond)->Iterations(3);
BENCHMARK(BM_RigCase2_378Hz_NegativeSlope)->Unit(benchmark::kMillisecond)->Iterations(2);
BENCHMARK_MAIN();
