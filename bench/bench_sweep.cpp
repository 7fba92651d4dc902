// Benchmark of `shudder sweep` in parallel: scenarios/sweep_torsion_bar.toml
// (20 s simulated per case) over 41 bar frequencies, 100:500:10 Hz, run through the built CLI
// exactly as a user would:
//   shudder sweep scenarios/sweep_torsion_bar.toml
//       --set rig.torsion_bar.natural_frequency_Hz=100:500:10 --jobs N --quiet -o OUT.h5
// Each iteration runs the whole sweep with --jobs 1 and then with --jobs 2, from scratch (the
// output and its resume parts are removed first, so no case is reused). The counters are the two
// wall times, the speed-up wall(1)/wall(2) (target >= 1.8 on 2 cores) and the 1-minute load
// average before the run: other work on the machine takes cores from --jobs 2, so read the
// speed-up together with it.
//   ./build/bench/shudder_bench --benchmark_filter=Sweep --benchmark_counters_tabular=true
#include <benchmark/benchmark.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <stdexcept>
#include <string>

namespace {

namespace fs = std::filesystem;

double run_sweep_s(const fs::path& dir, int jobs) {
  const fs::path out = dir / ("sweep_jobs" + std::to_string(jobs) + ".h5");
  fs::remove(out);
  fs::remove_all(out.string() + ".parts");
  const std::string cmd = std::string("'") + SHUDDER_CLI +
                          "' sweep '" SHUDDER_SOURCE_DIR
                          "/scenarios/sweep_torsion_bar.toml' --set rig.torsion_bar.natural_frequency_Hz=100:500:10"
                          " --jobs " +
                          std::to_string(jobs) + " --quiet -o '" + out.string() + "'";
  const auto t0 = std::chrono::steady_clock::now();
  if (std::system(cmd.c_str()) != 0) throw std::runtime_error("sweep failed: " + cmd);
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

void BM_SweepTorsionBar41x20s_Jobs1VsJobs2(benchmark::State& state) {
  const fs::path dir = fs::temp_directory_path() / "shudder_bench_sweep";
  fs::create_directories(dir);
  double wall1 = 0.0, wall2 = 0.0, load = 0.0;
  for (auto _ : state) {
    double avg[1] = {0.0};
    if (getloadavg(avg, 1) == 1) load = avg[0];
    wall1 = run_sweep_s(dir, 1);
    wall2 = run_sweep_s(dir, 2);
    state.SetIterationTime(wall1 + wall2);
  }
  state.counters["wall_jobs1_s"] = wall1;
  state.counters["wall_jobs2_s"] = wall2;
  state.counters["speedup"] = wall1 / wall2;
  state.counters["loadavg_1min"] = load;
  fs::remove_all(dir);
}

}  // namespace

BENCHMARK(BM_SweepTorsionBar41x20s_Jobs1VsJobs2)->UseManualTime()->Unit(benchmark::kSecond)->Iterations(1);
