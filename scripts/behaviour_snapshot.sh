#!/usr/bin/env bash
# Records what `shudder` produces for every shipped scenario, so a refactoring can be checked
# against an earlier commit: run outputs (HDF5) and summaries, modes, screening JSON, a sweep's
# /cases, and the diagnosis JSON of docs/diagnosis.md's worked examples.
#
#   bash scripts/behaviour_snapshot.sh BUILD_DIR OUT_DIR [--slow]
#   bash scripts/compare_snapshot.sh OLD_DIR NEW_DIR
#
# --slow also records the 30 s LSCTR diagnosis example (~1 min on 2 cores).
set -euo pipefail
cd "$(dirname "$0")/.."
build=$(realpath "$1")
out=$(mkdir -p "$2" && realpath "$2")
slow=${3:-}
shudder="$build/app/shudder"
root=$PWD

# Every shipped scenario: HDF5 run + summary (the Output/Profile lines name paths or times).
for s in scenarios/*.toml; do
  name=$(basename "$s" .toml)
  "$shudder" run "$s" -o "$out/run_$name.h5" > "$out/run_$name.txt" 2>&1 || echo "exit $?" >> "$out/run_$name.txt"
  sed -i -e '/^Output: /d' -e '/^Profile: /d' "$out/run_$name.txt"
done
for s in scenarios/rig_*.toml; do
  "$shudder" modes "$s" > "$out/modes_$(basename "$s" .toml).txt" 2>&1 || true
done
for f in scenarios/fluids/*.toml; do
  "$shudder" screen "$f" --json "$out/screen_$(basename "$f" .toml).json" > "$out/screen_$(basename "$f" .toml).txt" 2>&1 || true
done
"$shudder" sweep scenarios/sweep_torsion_bar.toml --set rig.torsion_bar.natural_frequency_Hz=100:500:100 \
  --jobs 2 --quiet -o "$out/sweep.h5" > /dev/null

# Validation document (no plots: gnuplot output is not what is compared).
mkdir -p "$out/validate"
"$shudder" validate --scenarios scenarios --docs "$out/validate" --no-plots > "$out/validate.txt" 2>&1 || true
sed -i '/; wrote /d' "$out/validate.txt"
mv "$out/validate/validation.md" "$out/validation.md" && rmdir "$out/validate"

# Diagnosis worked examples (docs/diagnosis.md sections 1 and 3).
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
"$shudder" run scenarios/paper_g_case2_15kN_rig_heat.toml -o "$work/c2.h5" \
  --measurement "$work/c2_14.8kN.csv" --sample-rate 100 --noise --seed 3 > /dev/null
"$shudder" diagnose scenarios/paper_g_case2_15kN.toml "$work/c2_14.8kN.csv" --json "$out/diag_case2.json" --jobs 2 \
  | grep -v '^Time: \|^JSON: ' > "$out/diag_case2.txt"
for L in 10.4 25.3; do
  sed -e "s/normal_force_N = 14800.0/normal_force_N = ${L/./}00.0/" -e "s|\"fluids/|\"$root/scenarios/fluids/|" \
    scenarios/paper_g_case2_15kN_rig_heat.toml > "$work/rig_heat_$L.toml"
done
"$shudder" run "$work/rig_heat_10.4.toml" -o "$work/a.h5" --measurement "$work/c2_10.4kN.csv" --sample-rate 100 --noise --seed 1 > /dev/null
"$shudder" run "$work/rig_heat_25.3.toml" -o "$work/b.h5" --measurement "$work/c2_25.3kN.csv" --sample-rate 100 --noise --seed 2 > /dev/null
"$shudder" diagnose scenarios/paper_g_case2_15kN.toml "$work/c2_10.4kN.csv" "$work/c2_25.3kN.csv" \
  "$work/c2_14.8kN.csv" --json "$out/diag_three_loads.json" --jobs 2 > /dev/null
for V in 0.5 1.5; do
  sed -e "s|\"fluids/|\"$root/scenarios/fluids/|" -e "s/speed_rpm = \[0.5, 0.5\]/speed_rpm = [$V, $V]/" \
    scenarios/rig_stick_time_probe.toml > "$work/stick_$V.toml"
  printf '\n[effects.stick_time_static_friction]\nenabled = true\nmax_increase = 0.15\ntime_constant_s = 0.05\n' >> "$work/stick_$V.toml"
done
"$shudder" run "$work/stick_0.5.toml" -o "$work/s1.h5" --measurement "$work/stick_0.5rpm.csv" --noise --seed 21 > /dev/null
"$shudder" run "$work/stick_1.5.toml" -o "$work/s2.h5" --measurement "$work/stick_1.5rpm.csv" --noise --seed 22 > /dev/null
"$shudder" diagnose scenarios/rig_stick_time_probe.toml "$work/stick_0.5rpm.csv" "$work/stick_1.5rpm.csv" \
  --json "$out/diag_stick_time.json" --jobs 2 > /dev/null
cp "$work/c2_14.8kN.csv" "$out/measured_case2.csv"
if [ "$slow" = "--slow" ]; then
  sed -e "s|\"fluids/|\"$root/scenarios/fluids/|" scenarios/rig_case2_15kN_378Hz.toml > "$work/lsctr.toml"
  printf '\n[effects.rig_heat_capacity]\nenabled = true\nheat_capacity_J_per_K = 300.0\nconductance_W_per_K = 20.0\n' >> "$work/lsctr.toml"
  "$shudder" run "$work/lsctr.toml" -o "$work/l.h5" --measurement "$work/lsctr.csv" --sample-rate 1000 --noise --seed 3 > /dev/null
  "$shudder" diagnose scenarios/rig_case2_15kN_378Hz.toml "$work/lsctr.csv" --json "$out/diag_lsctr.json" --jobs 2 > /dev/null
fi
echo "snapshot written to $out"
