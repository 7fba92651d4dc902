#!/usr/bin/env bash
# Installs every Debian dependency (if missing) and builds everything in ./build (Release): the
# `shudder` executable, tests, benchmarks, the Python module, `shudder-mpi` and the FMU.
# Warnings are errors only where SHUDDER_WERROR=ON is set (CI's .ci/run does): a user's newer
# compiler may warn where ours does not, and that must not stop their build.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
# Every part switched on by name: a build/ configured by scripts/run-default.sh (which switches
# them off) would otherwise keep them off from its cache.
# Ninja where build/ is new (it compiles the libraries side by side); an existing build/ keeps
# the generator it was made with, which CMake cannot change in place.
generator=()
[ -f build/CMakeCache.txt ] || generator=(-G Ninja)
cmake -S . -B build "${generator[@]}" -DCMAKE_BUILD_TYPE=Release -DSHUDDER_QUICK_BUILD=OFF -DBUILD_TESTING=ON \
      -DSHUDDER_PYTHON=ON -DSHUDDER_MPI=ON -DSHUDDER_FMU=ON -DSHUDDER_BENCH=ON -DSHUDDER_PCH=ON \
      -DSHUDDER_UNITY_BUILD=ON -DSHUDDER_UNITY_BATCH_SIZE=8 -DSHUDDER_WERROR="${SHUDDER_WERROR:-OFF}" >/dev/null
cmake --build build -j"$(nproc)"
