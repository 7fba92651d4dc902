#!/usr/bin/env bash
# Writes the fuzzers' seed corpora (docs/fuzzing.md) from the shipped files, so no binary blob
# is committed: scenarios/*.toml, scenarios/fluids/*.toml, and a measured run as CSV and HDF5
# made by `shudder run --measurement` on a shortened shipped rig scenario.
# Usage: scripts/fuzz_seeds.sh SHUDDER_BINARY OUT_DIR   (makes OUT_DIR/{scenario,fluid,csv,hdf5})
set -euo pipefail
cd "$(dirname "$0")/.."
shudder=$(realpath "$1")
out=$2
mkdir -p "$out"/{scenario,fluid,csv,hdf5}
cp scenarios/*.toml "$out/scenario/"
cp scenarios/fluids/*.toml "$out/fluid/"
# A 0.2 s rig run sampled at 100 Hz: 21 rows, enough for the reader's 10-row minimum and small
# enough that mutations reach every part of the file.
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
sed 's/^duration_s = .*/duration_s = 0.2/' scenarios/rig_case2_15kN_378Hz.toml > "$work/seed.toml"
cp -r scenarios/fluids "$work/"
for ext in csv h5; do
  "$shudder" run "$work/seed.toml" -o "$work/seed_$ext.h5" --measurement "$work/measured.$ext" \
    --sample-rate 100 >/dev/null
done
cp "$work/measured.csv" "$out/csv/"
cp "$work/measured.h5" "$out/hdf5/"
echo "fuzz_seeds: $(ls "$out"/scenario | wc -l) scenarios, $(ls "$out"/fluid | wc -l) fluids, 1 CSV, 1 HDF5 in $out"
