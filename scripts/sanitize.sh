#!/usr/bin/env bash
# Sanitizer and fuzzing pass (docs/fuzzing.md), called by scripts/test.sh. One clang build
# (build-fuzz, -DSHUDDER_FUZZ=ON) serves both halves: every library is compiled once with
# AddressSanitizer + UndefinedBehaviorSanitizer and libFuzzer's coverage hooks, then
#   1. a fast subset of the unit tests linked against those libraries: every reader of user files
#      (scenario, fluid, measured run CSV/HDF5, measurement CSV, HDF5 run, validation targets,
#      diagnosis JSON), the CLI's bad-input tests (they run the sanitized `shudder`), the clutch and
#      dynamics cores and the rig's motor ripple. The whole suite under ASan takes ~2x the plain
#      run; the slow end-to-end simulations are left to the plain build;
#   2. a bounded libFuzzer run of every harness in fuzz/, seeded from the shipped files
#      (scripts/fuzz_seeds.sh), FUZZ_SECONDS per harness (default 20).
# A second g++ ASan build (SHUDDER_SANITIZE=ON) would cost a full build more for the same checks.
# Any sanitizer report, crash or escaped exception fails the script.
set -euo pipefail
cd "$(dirname "$0")/.."
jobs=${JOBS:-$(nproc)}
fuzz_seconds=${FUZZ_SECONDS:-20}

export ASAN_OPTIONS=${ASAN_OPTIONS:-detect_leaks=1:abort_on_error=1}
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-halt_on_error=1:print_stacktrace=1}

launcher=()
command -v ccache >/dev/null && launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache -DCMAKE_C_COMPILER_LAUNCHER=ccache)
cmake -S . -B build-fuzz -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_C_COMPILER=clang \
  -DCMAKE_CXX_COMPILER=clang++ -DSHUDDER_FUZZ=ON -DBUILD_TESTING=ON "${launcher[@]}" >/dev/null
cmake --build build-fuzz -j"$jobs" --target shudder_tests shudder \
  fuzz_scenario fuzz_fluid fuzz_measured_csv fuzz_measured_hdf5

filter='LoadFluid.*:MeasuredRunTest.*:MeasurementCsv.*:Hdf5Run.*:ScenarioModel.*:ValidationTargets.*'
filter+=':DiagnosisJson.*:CliBadInput.*:ThermalModel.*:WetClutch.*:MakiFrictionMatrix.*'
filter+=':LinearTemperatureFriction.*:DynamicsEnergy.*:DynamicsStickSlip.*:DynamicsNetworkModes.*'
filter+=':MotorRipple.TorqueIs*:MotorRipple.Rejects*:*FuzzRegression.*'
./build-fuzz/tests/shudder_tests --gtest_filter="$filter" --gtest_brief=1

seeds=build-fuzz/seeds
rm -rf "$seeds"
bash scripts/fuzz_seeds.sh build/app/shudder "$seeds"
for h in scenario fluid measured_csv measured_hdf5; do
  corpus=build-fuzz/corpus/$h
  mkdir -p "$corpus" "build-fuzz/artifacts/$h"
  seed_dir=$seeds/${h#measured_}
  echo "sanitize: fuzz_$h for ${fuzz_seconds} s"
  log=build-fuzz/artifacts/$h/last_run.log
  status=0
  # The HDF5 reader's harness runs in fork mode and goes on past findings: Debian's libhdf5
  # (1.10.8) leaks, hangs and reads out of bounds inside the library on some damaged files
  # (docs/fuzzing.md, findings 1-3; not fixable in our reader). They are counted, not failed on.
  extra=(-seed=1)
  [ "$h" = measured_hdf5 ] &&
    extra+=(-fork=1 -ignore_timeouts=1 -ignore_ooms=1 -ignore_crashes=1 -detect_leaks=0)
  ./build-fuzz/fuzz/fuzz_$h "${extra[@]}" -max_total_time="$fuzz_seconds" -timeout=10 -rss_limit_mb=2048 \
    -artifact_prefix="build-fuzz/artifacts/$h/" -print_final_stats=1 "$corpus" "$seed_dir" >"$log" 2>&1 || status=$?
  grep -E '^(stat::number_of_executed_units|stat::average_exec_per_sec|INFO: fuzzed for)' "$log" || true
  if [ "$h" = measured_hdf5 ]; then
    # Fork mode exits with the last finding's status even when told to go on past it.
    echo "sanitize: libhdf5 findings (known, docs/fuzzing.md): $(ls "build-fuzz/artifacts/$h" | grep -c -E '^(crash|timeout|oom|leak)-' || true)"
    status=0
  fi
  if [ "$status" -ne 0 ]; then
    tail -40 "$log"
    echo "sanitize: fuzz_$h found a crash (input in build-fuzz/artifacts/$h)"
    exit 1
  fi
done
echo "sanitize: ASan+UBSan subset and bounded fuzzing passed"
