// Benchmark: the fixed-step real-time mode of the prescribed-slip element (docs/realtime.md; target: worst step over
// 10^5 steps of 0.1 ms < 20 µs, thermal update included). Each step is timed on its own with
// steady_clock:
//   *_paced     the steps are released on a 0.1 ms real-time grid (spin-wait), as a
//               hardware-in-the-loop loop runs them; the thermal worker gets the wall time of a
//               slow window to finish. 10^5 steps = 10 s of wall time each.
//   *_unpaced   back to back: the mean is the pure compute cost of a step; the worst step may
//               include waiting for the thermal worker, which had only ~100 fast steps' time.
//   *_sleeping  released on the same grid, but the stepping thread sleeps until each release
//               (clock_nanosleep, absolute time) instead of spinning: how a loop under SCHED_FIFO
//               must wait, since a FIFO thread that spins for 10 s is throttled by the kernel
//               (sched_rt_runtime_us: 5 % of every second goes to other tasks) — a 50 ms gap.
//               For the real-time measurement run it as
//                 sudo chrt -f 80 taskset -c 1 ./build/bench/shudder_bench --benchmark_filter='Realtime.*/paced:2'
// The process' memory is locked (mlockall) while the steps run where the system allows it
// (counter mlocked = 1), so no step waits for a page fault.
// Each step also reports its kind (plain, the thermal handover at a slow window's end, the step
// after it); the counters
// <kind>_n, <kind>_worst_us, <kind>_p9999_us, <kind>_p999_us, <kind>_median_us and
// <kind>_cpu_worst_us show which kind the worst steps are (docs/performance.md).
// Counters: worst_us, mean_us, p999_us / p9999_us (99.9th / 99.99th percentile), over20us (steps above the target),
// all wall time; cpu_worst_us and cpu_mean_us are the stepping thread's CPU time per step
// (CLOCK_THREAD_CPUTIME_ID: excludes preemption by other processes and waiting for the worker,
// so on a shared machine it shows what the step itself costs).
//   ./build/bench/shudder_bench --benchmark_filter=Realtime --benchmark_counters_tabular=true
// BM_FixedStepRig: the rig's whole fixed-step run (the network kinds' mode), CPU per run.
#include <benchmark/benchmark.h>

#include <sys/mman.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <string>
#include <variant>
#include <vector>

#include "io/scenario.hpp"
#include "rig_models/realtime_coupling.hpp"
#include "rig_models/realtime_run.hpp"

using namespace shudder;

namespace {

constexpr long kSteps = 100000;
constexpr double kStep_s = 1e-4;

// How steps are released: back to back, on the 0.1 ms grid by spinning, or on it by sleeping.
enum Pacing : long { kUnpaced = 0, kSpinning = 1, kSleeping = 2 };

// Step kinds (the step function returns one).
enum Kind : int { kPlain = 0, kHandover = 1, kAfterHandover = 2, kKinds = 3 };
constexpr const char* kKindName[kKinds] = {"plain", "handover", "after_handover"};

Kind window_kind(long k, long steps_per_window) {
  if ((k + 1) % steps_per_window == 0) return kHandover;
  if (k % steps_per_window == 0 && k > 0) return kAfterHandover;
  return kPlain;
}

double percentile(const std::vector<double>& sorted, double q) {
  return sorted[std::min(sorted.size() - 1, static_cast<std::size_t>(q * static_cast<double>(sorted.size())))];
}

void kind_counters(benchmark::State& state, const std::vector<double>& us, const std::vector<double>& cpu_us,
                   const std::vector<int>& kind) {
  for (int c = 0; c < kKinds; ++c) {
    std::vector<double> w, cpu;
    for (std::size_t k = 0; k < us.size(); ++k)
      if (kind[k] == c) {
        w.push_back(us[k]);
        cpu.push_back(cpu_us[k]);
      }
    if (w.empty()) continue;
    std::sort(w.begin(), w.end());
    const std::string n = kKindName[c];
    state.counters[n + "_n"] = static_cast<double>(w.size());
    state.counters[n + "_worst_us"] = w.back();
    state.counters[n + "_p9999_us"] = percentile(w, 0.9999);
    state.counters[n + "_p999_us"] = percentile(w, 0.999);
    state.counters[n + "_median_us"] = percentile(w, 0.5);
    state.counters[n + "_cpu_worst_us"] = *std::max_element(cpu.begin(), cpu.end());
  }
}

template <class Step>
void time_steps(benchmark::State& state, long pacing, const rig_models::RealtimeClutch* clutch, Step&& step) {
  using clock = std::chrono::steady_clock;
  std::vector<double> us(kSteps), cpu_us(kSteps);
  std::vector<int> kind(kSteps);
  const auto cpu_now = [] {
    timespec ts{};
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
    return static_cast<double>(ts.tv_sec) * 1e6 + static_cast<double>(ts.tv_nsec) * 1e-3;
  };
  const bool locked = mlockall(MCL_CURRENT | MCL_FUTURE) == 0;
  for (auto _ : state) {
    const auto start = clock::now();
    // The sleeping grid starts at the next whole second plus half a step: the kernel's tick
    // (CONFIG_HZ, aligned to multiples of its period on CLOCK_MONOTONIC) and the thermal
    // worker's polls (multiples of 2.5 ms) then fire half a step after a release, while the
    // stepping thread sleeps, instead of inside a step (docs/realtime.md: measured, a grid that
    // happens to sit just behind the tick puts a 20-40 µs interrupt into every 40th step).
    timespec start_ts{};
    clock_gettime(CLOCK_MONOTONIC, &start_ts);  // steady_clock's clock on Linux
    if (pacing == kSleeping) start_ts = {start_ts.tv_sec + 1, static_cast<long>(kStep_s * 0.5e9)};
    for (long k = 0; k < kSteps; ++k) {
      if (pacing == kSpinning) {
        const auto release =
            start + std::chrono::duration_cast<clock::duration>(std::chrono::duration<double>(k * kStep_s));
        while (clock::now() < release) {
        }
      } else if (pacing == kSleeping) {
        const long ns = start_ts.tv_nsec + k * static_cast<long>(kStep_s * 1e9);
        const timespec release{start_ts.tv_sec + ns / 1000000000L, ns % 1000000000L};
        while (clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &release, nullptr) != 0) {
        }
      }
      const double cpu_a = cpu_now();
      const auto a = clock::now();
      kind[static_cast<std::size_t>(k)] = step(k);
      us[static_cast<std::size_t>(k)] = std::chrono::duration<double, std::micro>(clock::now() - a).count();
      cpu_us[static_cast<std::size_t>(k)] = cpu_now() - cpu_a;
    }
  }
  if (locked) munlockall();
  // SHUDDER_RT_DUMP=FILE: every step's index, kind, wall and thread CPU time (µs), to look at
  // when and how the slowest steps happen.
  if (const char* dump = std::getenv("SHUDDER_RT_DUMP")) {
    if (std::FILE* f = std::fopen(dump, "w")) {
      for (long k = 0; k < kSteps; ++k) {
        const auto i = static_cast<std::size_t>(k);
        std::fprintf(f, "%ld %s %.3f %.3f\n", k, kKindName[kind[i]], us[i], cpu_us[i]);
      }
      std::fclose(f);
    }
  }
  state.counters["mlocked"] = locked ? 1.0 : 0.0;
  std::vector<double> sorted = us;
  std::sort(sorted.begin(), sorted.end());
  double sum = 0.0;
  for (double u : us) sum += u;
  state.counters["worst_us"] = sorted.back();
  state.counters["mean_us"] = sum / kSteps;
  state.counters["p999_us"] = percentile(sorted, 0.999);
  state.counters["p9999_us"] = percentile(sorted, 0.9999);
  double cpu_sum = 0.0;
  for (double u : cpu_us) cpu_sum += u;
  state.counters["cpu_worst_us"] = *std::max_element(cpu_us.begin(), cpu_us.end());
  state.counters["cpu_mean_us"] = cpu_sum / kSteps;
  state.counters["cpu_over20us"] =
      static_cast<double>(std::count_if(cpu_us.begin(), cpu_us.end(), [](double u) { return u > 20.0; }));
  state.counters["over20us"] = static_cast<double>(sorted.end() - std::upper_bound(sorted.begin(), sorted.end(), 20.0));
  state.counters["median_us"] = percentile(sorted, 0.5);
  if (clutch) state.counters["thermal_waits"] = static_cast<double>(clutch->thermal_waits());  // slow-path handovers
  kind_counters(state, us, cpu_us, kind);
}

void BM_RealtimeCoupling(benchmark::State& state) {
  const auto sc = io::load_scenario(SHUDDER_SOURCE_DIR "/scenarios/paper_g_case1_25kN.toml");
  const auto clutch = sc.make_clutch();
  const auto& m = std::get<rig_models::PrescribedSlipModel>(sc.model);
  // The real-time mode's thermal handover every 10 ms (the scenario's own step is for the
  // adaptive run's BDF2, 40 ms): the more frequent handover is the harder case.
  rig_models::RealtimeCoupling c(clutch, m.settings.bearing_drag, {kStep_s, 0.01}, m.cycle.normal_force_N(0.0));
  const long per_window = rig_models::steps_per_thermal_step(c.clutch().settings());
  time_steps(state, state.range(0), &c.clutch(), [&](long k) {
    const double t = static_cast<double>(k) * kStep_s;
    c.step(m.cycle.slip_speed_rpm(t) * 0.10471975511965977, m.cycle.normal_force_N(t));
    return window_kind(k, per_window);
  });
}

// The rig in the fixed-step mode (the adaptive run's network and thermal coupling advanced by
// RK4 at 0.1 ms, dynamics/simulation.hpp), Case 1 for 1 s simulated, thermal updates in line.
void BM_FixedStepRig(benchmark::State& state) {
  const auto sc = io::load_scenario(SHUDDER_SOURCE_DIR "/scenarios/rig_case1_25kN_378Hz.toml");
  const auto clutch = sc.make_clutch();
  auto m = std::get<rig_models::RigModel>(sc.model);
  m.settings.duration_s = 1.0;
  for (auto _ : state) benchmark::DoNotOptimize(rig_models::run_fixed_step(m, clutch, kStep_s));
  state.counters["steps"] = m.settings.duration_s / kStep_s;
}

// The control: the same loop, pacing, timing and locking, with a "step" that is a fixed chain
// of 1,500 dependent multiply-adds (≈ 1.5 µs here, the rig step's median) on registers only —
// no memory traffic, no branch that depends on data, nothing a simulation could make slower. A
// step of it above 20 µs is the machine (interrupts, the hypervisor taking the vCPU), so its
// worst case is the floor under any step code's worst case on that machine (docs/realtime.md).
void BM_RealtimeNullStep(benchmark::State& state) {
  double x = 1.0;
  time_steps(state, state.range(0), nullptr, [&](long k) {
    for (int i = 0; i < 1500; ++i) x = x * 0.9999999 + 1e-7;
    benchmark::DoNotOptimize(x);
    return window_kind(k, 100);
  });
}

// What one slow thermal window costs the worker (rig_models::ThermalTask::run_job's work): the
// backward-Euler step of Case 1's field (20 rings x 12 axial cells) with a fresh factorisation
// and the friction frozen at the new ring temperatures.
// Spread over the 100 fast steps of a window it would add this / 100 to every step.
void BM_RealtimeThermalWindow(benchmark::State& state) {
  const auto sc = io::load_scenario(SHUDDER_SOURCE_DIR "/scenarios/paper_g_case1_25kN.toml");
  const auto clutch = sc.make_clutch();
  const auto& th = clutch.thermal();
  clutch::ThermalState s = clutch.initial_state();
  clutch::ThermalWorkspace ws(th);
  const Eigen::VectorXd heat_W = Eigen::VectorXd::Constant(th.radial_cells(), 50.0);
  double slip = 1.0;
  long k = 0;
  for (auto _ : state) {
    slip += 1e-3;
    // The step length alternates in its last digits so every window re-factorises (the worst
    // case: a flow law that follows the slip does so every window of a ramp).
    th.step(s, ws, (++k % 2 == 0) ? 0.01 : 0.01 * (1.0 + 1e-12), heat_W, slip);
    benchmark::DoNotOptimize(clutch.freeze(th.interface_temps_C(s), 25300.0));
  }
}

}  // namespace

BENCHMARK(BM_RealtimeThermalWindow)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_RealtimeCoupling)
    ->ArgName("paced")
    ->Arg(kUnpaced)
    ->Arg(kSpinning)
    ->Arg(kSleeping)
    ->Iterations(1)
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_FixedStepRig)->Unit(benchmark::kMillisecond)->Iterations(3);
BENCHMARK(BM_RealtimeNullStep)
    ->ArgName("paced")
    ->Arg(kUnpaced)
    ->Arg(kSpinning)
    ->Arg(kSleeping)
    ->Iterations(1)
    ->Unit(benchmark::kMillisecond);
