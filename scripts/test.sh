#!/usr/bin/env bash
# Builds shudder from scratch (dependencies via apt-get) and runs every test. SHUDDER_SANITIZE=1
# then runs the sanitizer and bounded fuzzing pass (scripts/sanitize.sh, docs/fuzzing.md: one
# clang ASan+UBSan build, a test subset and 20 s per fuzz harness). It is not in the default run:
# the plain build and ctest already take ~7 min of CI's 15-minute test budget on 2 cores, and the
# instrumented build is a second full build of about the same length.
set -euo pipefail
cd "$(dirname "$0")/.."
start=$SECONDS
bash scripts/build.sh
ctest --test-dir build --output-on-failure -j"$(nproc)"
echo "test: build and ctest took $((SECONDS - start)) s"
if [ "${SHUDDER_SANITIZE:-0}" = 1 ]; then
  start=$SECONDS
  bash scripts/sanitize.sh
  echo "test: sanitizer and fuzzing pass took $((SECONDS - start)) s"
fi
