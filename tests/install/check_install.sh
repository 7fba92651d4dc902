#!/usr/bin/env bash
# ctest install_prefix: `cmake --install` into a scratch prefix, then the installed CLI and
# Python module run from there (not from the build tree): --version names the project version,
# `import shudder` finds the module via PYTHONPATH and runs an installed scenario.
# Usage: check_install.sh BUILD_DIR PREFIX PYTHONDIR(relative to PREFIX)
set -euo pipefail
build=$1 prefix=$2 pydir=$3
rm -rf "$prefix"
cmake --install "$build" --prefix "$prefix" >/dev/null
version=$(grep -m1 -oE 'project\(shudder VERSION [0-9.]+' "$(dirname "$0")/../../CMakeLists.txt" | awk '{print $3}')
out=$(cd / && "$prefix/bin/shudder" --version)
echo "installed: $out"
case "$out" in "shudder $version"*) ;; *) echo "FAIL: --version printed '$out', expected 'shudder $version...'"; exit 1;; esac
if [ -x "$build/app/shudder-mpi" ]; then  # `sweep --mpi` looks for it beside shudder (app/mpi_sweep.hpp)
  test -x "$prefix/bin/shudder-mpi" || { echo "FAIL: shudder-mpi not installed beside shudder"; exit 1; }
fi
test -f "$prefix/share/shudder/scenarios/paper_g_case1_10kN.toml" || { echo "FAIL: scenarios not installed"; exit 1; }
test -f "$prefix/share/doc/shudder/python.md" || { echo "FAIL: docs not installed"; exit 1; }
test -f "$prefix/share/doc/shudder/README.md" || { echo "FAIL: README not installed"; exit 1; }
if [ -f "$build/fmu/shudder_clutch.fmu" ]; then  # the FMU, where this build makes one
  cmp -s "$build/fmu/shudder_clutch.fmu" "$prefix/share/shudder/fmu/shudder_clutch.fmu" || { echo "FAIL: FMU not installed"; exit 1; }
fi
cd / && PYTHONPATH="$prefix/$pydir" /usr/bin/python3 -c '
import sys, shudder
assert shudder.__file__.startswith(sys.argv[1]), shudder.__file__
r = shudder.run(sys.argv[2])
assert r.signals["time_s"].size > 0
print("python:", shudder.__version__, shudder.__file__)
' "$prefix" "$prefix/share/shudder/scenarios/paper_g_case1_10kN.toml"
