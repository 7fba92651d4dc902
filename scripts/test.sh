#!/usr/bin/env bash
# Builds shudder from scratch (dependencies via apt-get) and runs every test. SHUDDER_SANITIZE=1
# also runs the sanitizer and bounded fuzzing pass (scripts/sanitize.sh, docs/fuzzing.md; a
# second full build, ~15 min on 2 cores, so not yet part of the default run).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/build.sh
ctest --test-dir build --output-on-failure -j"$(nproc)"
if [ "${SHUDDER_SANITIZE:-0}" = 1 ]; then
  bash scripts/sanitize.sh
fi
