#!/usr/bin/env bash
# Builds shudder from scratch (dependencies via apt-get) and runs every test, then the sanitizer
# and bounded fuzzing pass (scripts/sanitize.sh; SHUDDER_SKIP_SANITIZE=1 skips it locally).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/build.sh
ctest --test-dir build --output-on-failure -j"$(nproc)"
[ "${SHUDDER_SKIP_SANITIZE:-0}" = 1 ] || bash scripts/sanitize.sh
