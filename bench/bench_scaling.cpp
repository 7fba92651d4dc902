// How cost grows (docs/performance.md): Paper G Case 1 (prescribed slip + thermal model) against
// the thermal grid and the simulated time; the whole `shudder run` process against the 6 ms
// target; a sweep's peak memory against its case count. Each benchmark states the figure it
// re-measures; the exponents in docs/performance.md are log-log slopes between these rows.
//   ./build/bench/shudder_bench --benchmark_filter=Scaling --benchmark_format=json
#include <benchmark/benchmark.h>

#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>
#include <variant>
#include <vector>

#include "clutch/banded_lu.hpp"
#include "io/scenario.hpp"
#include "rig_models/model.hpp"
#include "rig_models/prescribed_slip.hpp"

using namespace shudder;

namespace {

namespace fs = std::filesystem;

// Case 1 as the scaling figures of docs/performance.md were measured: backward Euler at 10 ms
// (the shipped scenario's BDF2 at 40 ms has 4x fewer steps; the exponents are the same).
io::Scenario case1() {
  io::Scenario sc = io::load_scenario(SHUDDER_SOURCE_DIR "/scenarios/paper_g_case1_25kN.toml");
  auto& settings = std::get<rig_models::PrescribedSlipModel>(sc.model).settings;
  settings.thermal_scheme = rig_models::ThermalScheme::kBackwardEuler;
  settings.thermal_step_s = 0.01;
  return sc;
}

// Cost vs rings x axial cells: radial cells = range(0); every layer's axial cells x range(1)
// (default grid: 20 rings x 12 axial nodes). Time step and simulated time fixed (10 ms, 10 s).
void BM_Scaling_Case1Grid(benchmark::State& state) {
  auto sc = case1();
  auto& th = sc.clutch.thermal;
  th.radial_cells = static_cast<int>(state.range(0));
  th.separator.cells *= static_cast<int>(state.range(1));
  th.lining.cells *= static_cast<int>(state.range(1));
  th.core.cells *= static_cast<int>(state.range(1));
  const auto clutch = sc.make_clutch();
  const auto& model = std::get<rig_models::PrescribedSlipModel>(sc.model);
  for (auto _ : state) {
    auto rec = rig_models::simulate(model, clutch);
    benchmark::DoNotOptimize(rec);
  }
  state.counters["nodes"] = clutch.thermal().radial_cells() * clutch.thermal().nodes_per_ring();
}

// Cost vs simulated time: Case 1 run for range(0) seconds (the ramp ends at 10 s and holds).
void BM_Scaling_Case1Duration(benchmark::State& state) {
  auto sc = case1();
  auto& model = std::get<rig_models::PrescribedSlipModel>(sc.model);
  model.settings.duration_s = static_cast<double>(state.range(0));
  model.settings.snapshot_times_s.clear();
  const auto clutch = sc.make_clutch();
  for (auto _ : state) {
    auto rec = rig_models::simulate(model, clutch);
    benchmark::DoNotOptimize(rec);
  }
  state.counters["simulated_s"] = model.settings.duration_s;
}

// User + system CPU of all waited-for children so far, seconds.
double children_cpu_s() {
  rusage ru{};
  getrusage(RUSAGE_CHILDREN, &ru);
  return static_cast<double>(ru.ru_utime.tv_sec + ru.ru_stime.tv_sec) +
         1e-6 * static_cast<double>(ru.ru_utime.tv_usec + ru.ru_stime.tv_usec);
}

// Runs `cmd` in a shell; returns the wall time, adds the child's peak RSS (kB) to `peak_kB`.
double run_timed(const std::string& cmd, long& peak_kB) {
  const auto t0 = std::chrono::steady_clock::now();
  if (std::system(cmd.c_str()) != 0) throw std::runtime_error("failed: " + cmd);
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  rusage ru{};
  getrusage(RUSAGE_CHILDREN, &ru);
  peak_kB = std::max(peak_kB, ru.ru_maxrss);
  return wall;
}

// The target: Paper G Case 1, the whole process (start-up, TOML, simulation, HDF5 write,
// summary) <= 6 ms. Manual time = the wall time of `shudder run` (plus the shell's fork/exec,
// ~1 ms: compare with Scaling_CliHelp, the start-up alone). peak_RSS_kB: target <= 20 MB.
// range(0) other files share the output's directory: the writer scans that directory for stale
// temporaries of the output (io/atomic_file.hpp), so a crowded directory (a shared /tmp: 5,000
// entries) costs that scan, ~0.2 µs of kernel time per entry even with the plain readdir.
// child_CPU_ms: user + system CPU of the child processes per run (the shell's fork/exec
// included), the comparable figure on a shared machine.
void BM_Scaling_Case1WholeProcess(benchmark::State& state) {
  const fs::path dir = fs::temp_directory_path() / ("shudder_bench_case1_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  for (long k = 0; k < state.range(0); ++k) std::ofstream(dir / ("other_" + std::to_string(k) + ".txt"));
  const fs::path out = dir / "case1.h5";
  const std::string cmd = std::string("'") + SHUDDER_CLI +
                          "' run '" SHUDDER_SOURCE_DIR "/scenarios/paper_g_case1_25kN.toml' -o '" + out.string() +
                          "' >/dev/null";
  long peak_kB = 0;
  const double cpu0 = children_cpu_s();
  for (auto _ : state) state.SetIterationTime(run_timed(cmd, peak_kB));
  state.counters["peak_RSS_kB"] = static_cast<double>(peak_kB);
  state.counters["child_CPU_ms"] = 1e3 * (children_cpu_s() - cpu0) / static_cast<double>(state.iterations());
  fs::remove_all(dir);
}

// Start-up alone: `shudder --help` (dynamic loading, static initialisation, CLI11).
void BM_Scaling_CliHelp(benchmark::State& state) {
  const std::string cmd = std::string("'") + SHUDDER_CLI + "' --help >/dev/null";
  long peak_kB = 0;
  for (auto _ : state) state.SetIterationTime(run_timed(cmd, peak_kB));
  state.counters["peak_RSS_kB"] = static_cast<double>(peak_kB);
}

// The thermal step's band solve at Case 1's grid (20 rings x 12 nodes: 240 unknowns, half band
// 12), once per 10 ms step, 1000 per run (docs/performance.md: 3.5 -> 2.0 µs when the sweeps
// went row by row). A diagonally dominant band matrix like the thermal system's.
void BM_Scaling_ThermalBandSolve(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0)), b = static_cast<int>(state.range(1));
  std::vector<Eigen::Triplet<double>> t;
  for (int i = 0; i < n; ++i) {
    for (int j = std::max(0, i - b); j <= std::min(n - 1, i + b); ++j)
      if (j != i) t.emplace_back(i, j, -1.0 / (1.0 + std::abs(i - j)));
    t.emplace_back(i, i, 2.0 * b + 1.0);
  }
  Eigen::SparseMatrix<double> a(n, n);
  a.setFromTriplets(t.begin(), t.end());
  clutch::BandedLu lu(n, b);
  if (!lu.factorize(a)) throw std::runtime_error("band benchmark: factorisation failed");
  const Eigen::VectorXd rhs = Eigen::VectorXd::LinSpaced(n, 1.0, 2.0);
  Eigen::VectorXd x(n);
  for (auto _ : state) {
    x = rhs;
    lu.solve_in_place(x);
    benchmark::DoNotOptimize(x.data());
  }
}

// A sweep's memory against its case count: Case 1 over range(0) normal forces, --jobs 2.
// peak_RSS_kB should not grow with the count (the cases are written to part files as they
// finish and merged one at a time). Wall time per case: the sweep's overhead per case.
void BM_Scaling_SweepCases(benchmark::State& state) {
  const long cases = state.range(0);
  const fs::path out = fs::temp_directory_path() / ("shudder_bench_sweep_" + std::to_string(cases) + ".h5");
  const std::string cmd = std::string("'") + SHUDDER_CLI +
                          "' sweep '" SHUDDER_SOURCE_DIR
                          "/scenarios/paper_g_case1_25kN.toml' --set drive.normal_force_N=10000:" +
                          std::to_string(10000 + 100 * (cases - 1)) + ":100 --jobs 2 --quiet -o '" + out.string() + "'";
  long peak_kB = 0;
  double wall = 0.0;
  for (auto _ : state) {
    fs::remove(out);
    fs::remove_all(out.string() + ".parts");
    wall = run_timed(cmd, peak_kB);
    state.SetIterationTime(wall);
  }
  state.counters["cases"] = static_cast<double>(cases);
  state.counters["wall_per_case_ms"] = wall / static_cast<double>(cases) * 1e3;
  state.counters["peak_RSS_kB"] = static_cast<double>(peak_kB);
  fs::remove(out);
}

}  // namespace

BENCHMARK(BM_Scaling_Case1Grid)->ArgsProduct({{10, 20, 40, 80}, {1, 2, 4}})->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Scaling_Case1Duration)->Arg(5)->Arg(10)->Arg(20)->Arg(40)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Scaling_Case1WholeProcess)
    ->Arg(0)
    ->Arg(5000)
    ->UseManualTime()
    ->Unit(benchmark::kMillisecond)
    ->Iterations(20);
BENCHMARK(BM_Scaling_CliHelp)->UseManualTime()->Unit(benchmark::kMillisecond)->Iterations(20);
BENCHMARK(BM_Scaling_ThermalBandSolve)
    ->Args({240, 12})
    ->Args({480, 12})
    ->Args({240, 24})
    ->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_Scaling_SweepCases)->Arg(10)->Arg(40)->UseManualTime()->Unit(benchmark::kSecond)->Iterations(1);
