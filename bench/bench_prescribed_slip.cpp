// Benchmark: Paper G Case 1 at 25.3 kN, 10 s simulated, prescribed slip with the thermal model,
// at the default grid (target: <= 50 ms on one core). Also reports the result at the
// default grid and at a grid twice as fine in r, z and t as counters, so the run shows the grid
// is converged (target: within 0.5 %).
//   ./build/bench/shudder_bench --benchmark_counters_tabular=true
#include <benchmark/benchmark.h>

#include <variant>

#include "io/scenario.hpp"
#include "rig_models/model.hpp"
#include "rig_models/prescribed_slip.hpp"

using namespace shudder;

namespace {

io::Scenario case1_25kN(int refine) {
  auto sc = io::load_scenario(SHUDDER_SOURCE_DIR "/scenarios/paper_g_case1_25kN.toml");
  auto& th = sc.clutch.thermal;
  th.radial_cells *= refine;
  th.separator.cells *= refine;
  th.lining.cells *= refine;
  th.core.cells *= refine;
  auto& model = std::get<rig_models::PrescribedSlipModel>(sc.model);
  model.settings.thermal_step_s /= refine;
  return sc;
}

double last(const dynamics::Recording& rec, const char* name) { return rec.find(name)->values.back(); }

void BM_Case1_25kN(benchmark::State& state) {
  const auto sc = case1_25kN(static_cast<int>(state.range(0)));
  const auto clutch = sc.make_clutch();
  const auto& model = std::get<rig_models::PrescribedSlipModel>(sc.model);
  dynamics::Recording rec;
  for (auto _ : state) {
    rec = rig_models::simulate(model, clutch);
    benchmark::DoNotOptimize(rec);
  }
  state.counters["torque_10s_Nm"] = last(rec, "torque_Nm");
  state.counters["thermocouple_10s_C"] = last(rec, "temp_C");
  state.counters["radial_cells"] = sc.clutch.thermal.radial_cells;
  state.counters["thermal_step_ms"] = model.settings.thermal_step_s * 1e3;
}

}  // namespace

BENCHMARK(BM_Case1_25kN)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond);
