#!/usr/bin/env bash
# Builds shudder and runs the default scenario (Paper G Case 1 at 25.3 kN): prints a summary
# and writes out/paper_g_case1_25kN.h5.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/build.sh
mkdir -p out
./build/app/shudder run scenarios/paper_g_case1_25kN.toml -o out/paper_g_case1_25kN.h5
