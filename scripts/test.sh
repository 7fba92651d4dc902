#!/usr/bin/env bash
# Builds shudder from scratch (dependencies via apt-get), runs every test, then the sanitizer and
# bounded fuzzing pass (scripts/sanitize.sh, docs/fuzzing.md: one clang ASan+UBSan build, a test
# subset and 20 s per fuzz harness). SHUDDER_SANITIZE=0 skips that pass (a second build).
set -euo pipefail
cd "$(dirname "$0")/.."
start=$SECONDS
bash scripts/build.sh
ctest --test-dir build --output-on-failure -j"$(nproc)"
echo "test: build and ctest took $((SECONDS - start)) s"
if [ "${SHUDDER_SANITIZE:-1}" = 1 ]; then
  start=$SECONDS
  bash scripts/sanitize.sh
  echo "test: sanitizer and fuzzing pass took $((SECONDS - start)) s"
fi
