#!/usr/bin/env bash
# Sanitizer and fuzzing pass (docs/fuzzing.md), run by scripts/test.sh (CI) after the plain build
# and ctest. One clang build (build-sanitize, -DSHUDDER_FUZZ=ON) serves both halves: the libraries
# are compiled once with AddressSanitizer + UndefinedBehaviorSanitizer and libFuzzer's coverage
# hooks, at -O1 without debug info (the pass must fit CI's 15-minute budget beside the plain build;
# reproduce a finding in the campaign build of docs/fuzzing.md for file:line stacks), then
#   1. a subset of the unit tests, the only test files this build compiles (tests/CMakeLists.txt):
#      every reader of user files (scenario, fluid, measured run CSV/HDF5, measurement CSV, HDF5
#      run, validation targets, diagnosis JSON), the CLI's bad-input tests (they run the sanitized
#      `shudder`), the clutch and dynamics cores and the rig's motor ripple. The slow end-to-end
#      simulations are left to the plain build;
#   2. a bounded libFuzzer run of every harness in fuzz/, seeded from the shipped files
#      (scripts/fuzz_seeds.sh, which needs the plain build's build/app/shudder), FUZZ_SECONDS per
#      harness (default 10).
# A second g++ ASan build (SHUDDER_SANITIZE=ON) would cost a full build more for the same checks.
# Any sanitizer report, crash or escaped exception fails the script.
set -euo pipefail
cd "$(dirname "$0")/.."
jobs=${JOBS:-$(nproc)}
fuzz_seconds=${FUZZ_SECONDS:-10}
build=build-sanitize

export ASAN_OPTIONS=${ASAN_OPTIONS:-detect_leaks=1:abort_on_error=1}
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-halt_on_error=1:print_stacktrace=1}

launcher=()
command -v ccache >/dev/null && launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache -DCMAKE_C_COMPILER_LAUNCHER=ccache)
cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g0 -DNDEBUG" \
  -DCMAKE_C_FLAGS_RELWITHDEBINFO="-O1 -g0 -DNDEBUG" -DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++ \
  -DSHUDDER_FUZZ=ON -DBUILD_TESTING=ON -DSHUDDER_PYTHON=OFF "${launcher[@]}" >/dev/null
cmake --build "$build" -j"$jobs" --target shudder_tests shudder \
  fuzz_scenario fuzz_fluid fuzz_measured_csv fuzz_measured_hdf5

filter='LoadFluid.*:MeasuredRunTest.*:MeasurementCsv.*:Hdf5Run.*:ScenarioModel.*:ValidationTargets.*'
filter+=':DiagnosisJson.*:CliBadInput.*:ThermalModel.*:WetClutch.*:MakiFrictionMatrix.*'
filter+=':LinearTemperatureFriction.*:DynamicsEnergy.*:DynamicsStickSlip.*:DynamicsNetworkModes.*'
filter+=':MotorRipple.TorqueIs*:MotorRipple.Rejects*:*FuzzRegression.*:IsolatedRead.*'
./$build/tests/shudder_tests --gtest_filter="$filter" --gtest_brief=1

seeds=$build/seeds
rm -rf "$seeds"
bash scripts/fuzz_seeds.sh build/app/shudder "$seeds"
for h in scenario fluid measured_csv measured_hdf5; do
  corpus=$build/corpus/$h
  mkdir -p "$corpus" "$build/artifacts/$h"
  seed_dir=$seeds/${h#measured_}
  echo "sanitize: fuzz_$h for ${fuzz_seconds} s"
  log=$build/artifacts/$h/last_run.log
  status=0
  # The HDF5 reader's harness runs in fork mode and goes on past findings: Debian's libhdf5
  # (1.10.8) leaks, hangs and reads out of bounds inside the library on some damaged files
  # (docs/fuzzing.md, "Limits"; not fixable in our reader). They are counted, not failed on.
  extra=(-seed=1 -timeout=10)
  [ "$h" = measured_hdf5 ] &&
    extra+=(-fork=1 -ignore_timeouts=1 -ignore_ooms=1 -ignore_crashes=1 -detect_leaks=0 -timeout=3)  # a hang costs 3 s, not 10
  ./$build/fuzz/fuzz_$h "${extra[@]}" -max_total_time="$fuzz_seconds" -rss_limit_mb=2048 \
    -artifact_prefix="$build/artifacts/$h/" -print_final_stats=1 "$corpus" "$seed_dir" >"$log" 2>&1 || status=$?
  grep -E '^(stat::number_of_executed_units|stat::average_exec_per_sec|INFO: fuzzed for)' "$log" || true
  if [ "$h" = measured_hdf5 ]; then
    # Fork mode exits with the last finding's status even when told to go on past it.
    echo "sanitize: libhdf5 findings (known, docs/fuzzing.md): $(ls "$build/artifacts/$h" | grep -c -E '^(crash|timeout|oom|leak)-' || true)"
    status=0
  fi
  if [ "$status" -ne 0 ]; then
    tail -40 "$log"
    echo "sanitize: fuzz_$h found a crash (input in $build/artifacts/$h)"
    exit 1
  fi
done
echo "sanitize: ASan+UBSan subset and bounded fuzzing passed"
