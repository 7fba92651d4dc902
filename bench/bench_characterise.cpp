// Benchmark of `characterise` at Paper G's scale (characterise 1,750 synthetic
// ramps; target: <= 30 s wall time on 2 cores). Built from the library as the command uses
// it (analysis::characterise), the data in memory.
//
// Data, generated once: fluid C's matrix (scenarios/fluids/lsc_fluid_c.toml) through the
// prescribed-slip clutch and thermal model, Paper D cycles (10 s ramps, 2 ramps per run) at
// 10, 15, 20 and 25 kN from 12 start temperatures (−20 … 90 °C in 10 °C steps), sampled at
// 100 Hz: 48 simulations, each written as a measured run with sensor noise under ~18 seeds
// (io/measurement_csv) to give 875 runs = 1,750 ramps, 3.4 million samples.
//
//   BM_Characterise_1750Ramps/case  Arg 0: Mäki law, 1: table law, quadratic compensation;
//                                   Arg 2: Mäki law, 3: table law, piecewise compensation.
// Counters: ramps, rows, wall_s.
//   ./build/bench/shudder_bench --benchmark_filter=Characterise
#include <benchmark/benchmark.h>

#include <chrono>

#include "analysis/friction_characterisation.hpp"
#include "io/fluid_loader.hpp"
#include "io/measurement_csv.hpp"
#include "rig_models/prescribed_slip.hpp"

namespace {

using namespace shudder;

const std::vector<analysis::RampRun>& runs_1750() {
  static const std::vector<analysis::RampRun> runs = [] {
    const clutch::Fluid fluid = io::load_fluid(SHUDDER_SOURCE_DIR "/scenarios/fluids/lsc_fluid_c.toml");
    std::vector<analysis::RampRun> out;
    unsigned seed = 1;
    int sim = 0;
    for (double load : {10000.0, 15000.0, 20000.0, 25000.0})
      for (int k = 0; k < 12; ++k, ++sim) {
        clutch::WetClutchParams p;
        p.start_temp_C = p.sump_start_temp_C = -20.0 + 10.0 * k;
        const components::DriveCycle cycle{
            components::PiecewiseLinear({0.0, 5.0, 15.0, 17.0, 27.0, 30.0}, {1.0, 1.0, 100.0, 100.0, 1.0, 1.0}),
            components::PiecewiseLinear({0.0}, {load})};
        rig_models::PrescribedSlipSettings s;
        s.duration_s = 30.0;
        s.sample_rate_Hz = 100.0;
        const auto rec = rig_models::run_prescribed_slip(clutch::WetClutch(p, fluid), cycle, s);
        const int copies = 875 / 48 + (sim < 875 % 48 ? 1 : 0);  // 875 runs in all
        for (int c = 0; c < copies; ++c) {
          io::MeasurementOptions mo;
          mo.noise = true;
          mo.seed = seed++;
          const io::MeasuredRun m = io::make_measurement("run" + std::to_string(seed), rec, mo);
          out.push_back({m.path, m.required("time_s"), m.required("speed_rpm"), m.required("normal_force_N"),
                         m.required("torque_Nm"), m.required("temp_C")});
        }
      }
    return out;
  }();
  return runs;
}

void BM_Characterise_1750Ramps(benchmark::State& state) {
  const auto& runs = runs_1750();
  analysis::CharacterisationSettings s;
  s.law = state.range(0) % 2 == 0 ? analysis::LawKind::kMaki : analysis::LawKind::kTable;
  s.compensation = state.range(0) >= 2 ? analysis::Compensation::kPiecewise : analysis::Compensation::kQuadratic;
  analysis::Characterisation c;
  double wall = 0;
  for (auto _ : state) {
    const auto t0 = std::chrono::steady_clock::now();
    c = analysis::characterise(runs, s);
    wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    benchmark::DoNotOptimize(c.law);
  }
  state.counters["ramps"] = double(c.used.size());
  state.counters["rows"] = double(c.rows.size());
  state.counters["wall_s"] = wall;
}
BENCHMARK(BM_Characterise_1750Ramps)->Arg(0)->Arg(1)->Arg(2)->Arg(3)->Unit(benchmark::kSecond)->Iterations(1);

}  // namespace
