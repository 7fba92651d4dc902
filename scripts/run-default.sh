#!/usr/bin/env bash
# The first result: installs only what the `shudder` executable needs, builds only it, and runs
# the default scenario (Paper G Case 1 at 25.3 kN): prints a summary and writes
# out/paper_g_case1_25kN.h5. scripts/test.sh builds and installs the rest.
# Built for build time: Ninja compiles every library at once, each library as one batch, at -O1
# (SHUDDER_QUICK_BUILD; runs take about 1.5 times as long as fully optimised). scripts/build.sh,
# run by the test command, rebuilds build/ fully optimised.
set -euo pipefail
cd "$(dirname "$0")/.."
start=$SECONDS
bash scripts/install-deps.sh cli
generator=()
[ -f build/CMakeCache.txt ] || generator=(-G Ninja)  # an existing build/ keeps its generator
cmake -S . -B build "${generator[@]}" -DCMAKE_BUILD_TYPE=Release -DSHUDDER_QUICK_BUILD=ON -DBUILD_TESTING=OFF \
      -DSHUDDER_PYTHON=OFF -DSHUDDER_MPI=OFF -DSHUDDER_FMU=OFF -DSHUDDER_BENCH=OFF -DSHUDDER_PCH=ON \
      -DSHUDDER_UNITY_BUILD=ON -DSHUDDER_UNITY_BATCH_SIZE=0 >/dev/null
cmake --build build -j"$(nproc)" --target shudder
mkdir -p out
./build/app/shudder run scenarios/paper_g_case1_25kN.toml -o out/paper_g_case1_25kN.h5
echo "run-default: first result in $((SECONDS - start)) s"
