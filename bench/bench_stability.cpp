// Benchmark of the stability map (target <= 1 s on one core): 100 slip speeds
// (20–120 rpm) x 100 interface temperatures (20–120 °C) at 15 kN on the rig with the 378 Hz bar
// and fluid C (scenarios/rig_case1_25kN_378Hz.toml). Counter: map points per second.
#include <benchmark/benchmark.h>

#include <variant>
#include <vector>

#include "io/scenario.hpp"
#include "rig_models/model.hpp"
#include "studies/rig_stability.hpp"

using namespace shudder;

namespace {

std::vector<double> linspace(double a, double b, int n) {
  std::vector<double> v(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) v[static_cast<std::size_t>(i)] = a + (b - a) * i / (n - 1);
  return v;
}

void BM_StabilityMap100x100_FluidC_378Hz(benchmark::State& state) {
  const auto sc = io::load_scenario(SHUDDER_SOURCE_DIR "/scenarios/rig_case1_25kN_378Hz.toml");
  const auto clutch = sc.make_clutch();
  const auto speeds = linspace(20.0, 120.0, 100), temps = linspace(20.0, 120.0, 100);
  for (auto _ : state) {
    auto map = studies::stability_map(std::get<rig_models::RigModel>(sc.model).params, clutch, 15000.0, speeds, temps);
    benchmark::DoNotOptimize(map);
  }
  state.counters["points_per_s"] =
      benchmark::Counter(static_cast<double>(state.iterations()) * 1e4, benchmark::Counter::kIsRate);
}

}  // namespace

BENCHMARK(BM_StabilityMap100x100_FluidC_378Hz)->Unit(benchmark::kMillisecond);
