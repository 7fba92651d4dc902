#!/usr/bin/env bash
# Builds shudder from scratch (dependencies via apt-get) and runs every test, then the sanitizer
# and bounded fuzzing pass (scripts/sanitize.sh, docs/fuzzing.md: a lean clang ASan+UBSan build,
# a test subset and 10 s per fuzz harness) when it fits CI's 15-minute test budget.
# SHUDDER_SANITIZE=1 always runs the pass, SHUDDER_SANITIZE=0 never does; by default it runs
# unless the plain build and ctest took so long that the pass' expected length would carry the
# whole command past SHUDDER_TEST_BUDGET_S (900 s): a machine that slow skips it and says so.
set -euo pipefail
cd "$(dirname "$0")/.."
start=$SECONDS
bash scripts/build.sh
bash scripts/check-format.sh  # the layout of .clang-format on every tracked C/C++ file
ctest --test-dir build --output-on-failure -j"$(nproc)"
plain=$((SECONDS - start))
echo "test: build and ctest took $plain s"

budget=${SHUDDER_TEST_BUDGET_S:-900}
# The pass' expected wall time: its measured CPU seconds from a cold start without ccache (the
# instrumented build and the test subset: 590 s, docs/fuzzing.md) over the cores, plus ~60 s for
# the seeds and the four bounded fuzz runs.
sanitize_estimate=$(( ${SANITIZE_CPU_S:-590} / $(nproc) + 60 ))
case "${SHUDDER_SANITIZE:-auto}" in
  0) exit 0 ;;
  1) ;;
  *)
    if [ $((plain + sanitize_estimate)) -gt "$budget" ]; then
      echo "test: sanitizer pass skipped: build and ctest took $plain s, the pass needs ~$sanitize_estimate s" \
           "here, over the ${budget} s budget (SHUDDER_SANITIZE=1 runs it anyway)"
      exit 0
    fi ;;
esac
start=$SECONDS
bash scripts/sanitize.sh
echo "test: sanitizer and fuzzing pass took $((SECONDS - start)) s"
