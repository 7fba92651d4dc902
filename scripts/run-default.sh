#!/usr/bin/env bash
# The first result: installs only what the `shudder` executable needs, builds only it, and runs
# the default scenario (Paper G Case 1 at 25.3 kN): prints a summary and writes
# out/paper_g_case1_25kN.h5. scripts/test.sh builds and installs the rest.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh cli
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DBUILD_TESTING=OFF -DSHUDDER_PYTHON=OFF -DSHUDDER_MPI=OFF \
      -DSHUDDER_FMU=OFF -DSHUDDER_BENCH=OFF -DSHUDDER_PCH=ON -DSHUDDER_UNITY_BUILD=ON >/dev/null
cmake --build build -j"$(nproc)" --target shudder
mkdir -p out
./build/app/shudder run scenarios/paper_g_case1_25kN.toml -o out/paper_g_case1_25kN.h5
