#!/usr/bin/env bash
# The robustness audit's findings re-checked against two builds (docs/audit_findings.md):
#   bash scripts/audit_findings.sh OLD_SHUDDER NEW_SHUDDER
# Prints `finding | PASS/FAIL | what was seen` per binary, then old | new; exit 0 only if every
# finding FAILs on OLD and PASSes on NEW. Debian's python3 (h5py, numpy), not a pyenv one.
set -euo pipefail
exec /usr/bin/python3 "$(dirname "$0")/audit_findings.py" "$@"
