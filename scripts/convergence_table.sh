#!/usr/bin/env bash
# Runs `shudder convergence` on every shipped scenario and prints a Markdown table of each
# verdict as written and with every numerical step divided by 4 (docs/convergence_shipped.md
# holds its last output). Usage: bash scripts/convergence_table.sh [path/to/shudder]
set -euo pipefail
cd "$(dirname "$0")/.."
shudder="${1:-./build/app/shudder}"
echo "| scenario | judged | as written | steps / 4 | change (frequency, amplitude) | result |"
echo "|---|---|---|---|---|---|"
for f in scenarios/*.toml scenarios/networks/*.toml; do
  grep -q '^\[scenario\]' "$f" || continue  # data files (validation.toml) are not scenarios
  set +e
  out=$("$shudder" convergence "$f" 2>&1)
  rc=$?
  set -e
  echo "$out" | awk -v file="$f" -v rc="$rc" '
    function flush() {
      if (subject == "") return
      w1 = v1 (f1 != "" ? ", " f1 ", " a1 : ""); w2 = v2 (f2 != "" ? ", " f2 ", " a2 : "")
      printf "| `%s` | %s | %s | %s | %s | %s |\n", file, subject, w1, w2, (df != "" ? df ", " da : "-"),
             (rc == 0 ? "converged" : "NOT converged")
      subject = ""
    }
    /^  thermal step/ { next }
    /^  [^ ]/ { flush(); subject = $1; v1 = v2 = f1 = f2 = a1 = a2 = df = da = ""; next }
    /^    verdict/ { v1 = $2; v2 = $3; if ($2 == "not") { v1 = "not judged"; v2 = "not judged" } }
    /^    frequency/ { f1 = $2 " Hz"; f2 = $4 " Hz"; df = $6 " %" }
    /^    amplitude/ { a1 = $2 " N m"; a2 = $5 " N m"; da = $8 " %" }
    END { flush() }
  '
done
