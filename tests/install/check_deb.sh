#!/usr/bin/env bash
# ctest deb_package: `cpack -G DEB` builds a .deb holding the CLI, the Python module, the
# scenarios and the docs under /usr, depending on the runtime packages of what shudder links.
# Usage: check_deb.sh BUILD_DIR SCRATCH_DIR
set -euo pipefail
build=$1 scratch=$2
rm -rf "$scratch" && mkdir -p "$scratch"
cpack -G DEB --config "$build/CPackConfig.cmake" -B "$scratch" >/dev/null
deb=$(ls "$scratch"/shudder_*_amd64.deb "$scratch"/shudder_*.deb 2>/dev/null | head -1)
[ -n "$deb" ] || { echo "FAIL: no .deb in $scratch"; exit 1; }
contents=$(dpkg-deb -c "$deb")
for f in ./usr/bin/shudder ./usr/share/shudder/scenarios/paper_g_case1_10kN.toml \
         ./usr/share/shudder/scenarios/fluids/lsc_fluid_c.toml ./usr/share/doc/shudder/python.md \
         ./usr/share/doc/shudder/README.md; do
  grep -q " $f\$" <<<"$contents" || { echo "FAIL: $f not in $deb"; exit 1; }
done
grep -qE " ./usr/lib/python3/dist-packages/shudder\..*\.so\$" <<<"$contents" || { echo "FAIL: no Python module in $deb"; exit 1; }
if [ -f "$build/fmu/shudder_clutch.fmu" ]; then
  grep -q " ./usr/share/shudder/fmu/shudder_clutch.fmu\$" <<<"$contents" || { echo "FAIL: no FMU in $deb"; exit 1; }
fi
# Every shared library the CLI and the module need comes from a package the .deb depends on
# (directly, or through hdf5/openmpi, whose packages pull the rest).
depends=$(dpkg-deb -f "$deb" Depends)
for p in libhdf5-103-1 libfftw3-double3 python3-numpy; do
  grep -q "$p" <<<"$depends" || { echo "FAIL: Depends lacks $p: $depends"; exit 1; }
done
echo "ok: $deb ($(wc -l <<<"$contents") entries); Depends: $depends"
