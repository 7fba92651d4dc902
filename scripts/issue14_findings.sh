#!/usr/bin/env bash
# Issue 14's findings re-checked against two builds (docs/issue14_findings.md):
#   bash scripts/issue14_findings.sh OLD_SHUDDER NEW_SHUDDER
# Prints `finding | PASS/FAIL | what was seen` per binary, then old | new; exit 0 only if every
# finding FAILs on OLD and PASSes on NEW. Debian's python3 (h5py, numpy), not a pyenv one.
set -euo pipefail
exec /usr/bin/python3 "$(dirname "$0")/issue14_findings.py" "$@"
