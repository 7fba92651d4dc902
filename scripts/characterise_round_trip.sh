#!/bin/bash
# Round trip of `characterise` through the model (docs/characterisation.md "Round trip through the
# model"): Paper D cycles (1 rpm 5 s, 1 -> 100 rpm in 10 s, hold 2 s, down in 10 s, 1 rpm 3 s) at
# 10, 15, 20 kN from 40, 60, 80 °C with sensor noise, made by
#   own    the project's model (scenarios/paper_g_case2_15kN.toml, `shudder run --measurement --noise`),
#   indep  the independent simulator (tools/independent_sim/indep_sim.py: another thermal model),
# characterised with every friction radius (--radius model | uniform_pressure | uniform_wear) and
# both methods, then replayed through the model the fluid is for (`diagnose --max-effects 0`: the
# baseline replay, JSON channels[].final_rms against .noise), and diagnosed (every candidate, no
# tolerance): the round trip must name nothing.
#
#   scripts/characterise_round_trip.sh [build/app/shudder] [OUT_DIR]
# Prints one line per case: data, radius, method, replayed torque RMS / noise, diagnosis.
# Minutes: each diagnosis replays the nine runs a few hundred times.
set -euo pipefail
SRC=$(cd "$(dirname "$0")/.." && pwd)
SHUDDER=$(realpath "${1:-$SRC/build/app/shudder}")
OUT=${2:-/tmp/characterise_round_trip}
PY=/usr/bin/python3
mkdir -p "$OUT/own" "$OUT/indep"
SCEN="$SRC/scenarios/paper_g_case2_15kN.toml"

seed=1
for f in 10000 15000 20000; do
  for t in 40 60 80; do
    [ -f "$OUT/own/r_${f}_${t}.csv" ] || "$SHUDDER" run "$SCEN" --set drive.normal_force_N=$f --set clutch.start_temp_C=$t \
      -o "$OUT/own/r_${f}_${t}.h5" --measurement "$OUT/own/r_${f}_${t}.csv" --noise --seed $seed > /dev/null
    [ -f "$OUT/indep/r_${f}_${t}.csv" ] || $PY "$SRC/tools/independent_sim/indep_sim.py" run "$OUT/indep/r_${f}_${t}.csv" \
      --fluid "$SRC/scenarios/fluids/lsc_fluid_c.toml" --force-N $f --start-C $t --seed $seed
    seed=$((seed + 1))
  done
done

# The model a fluid is for: the Case 2 scenario with the fitted fluid.
model_with() {  # fluid file -> scenario path
  sed "s|^fluid = .*|fluid = \"$1\"|" "$SCEN" > "${1%.toml}_model.toml"
  echo "${1%.toml}_model.toml"
}

rms() {  # diagnosis JSON -> "torque RMS / noise"
  $PY -c "import json,sys; d=json.load(open(sys.argv[1])); c=[x for x in d['channels'] if x['signal']=='torque_Nm'][0]; \
print('%.3f N m (noise %.3f, %.2fx)' % (c['final_rms'], c['noise'], c['final_rms']/c['noise']))" "$1"
}

named() {
  $PY -c "import json,sys; d=json.load(open(sys.argv[1])); print(d['verdict'], d['missing_effects'], \
[u['effect'] for u in d['not_explained']])" "$1"
}

DIAG=${DIAG:-1}
for data in own indep; do
  runs=$(ls "$OUT/$data"/r_*.csv)
  for radius in model uniform_pressure uniform_wear; do
    for method in sensor inverse; do
      fluid="$OUT/$data/fit_${radius}_${method}.toml"
      base=$(basename "$SCEN")
      "$SHUDDER" characterise $runs -o "$fluid" --nu40-cSt 35 --nu100-cSt 6.7 --radius $radius --method $method \
        --model "$SCEN" > "${fluid%.toml}.txt" 2> "${fluid%.toml}.err" || { echo "$data $radius $method: characterise failed"; continue; }
      model=$(model_with "$fluid")
      "$SHUDDER" diagnose "$model" $runs --max-effects 0 --json "${fluid%.toml}_replay.json" --jobs 2 > /dev/null
      line="$data $radius $method: replayed torque $(rms "${fluid%.toml}_replay.json")"
      if [ "$DIAG" = 1 ]; then
        "$SHUDDER" diagnose "$model" $runs --json "${fluid%.toml}_diag.json" --jobs 2 > /dev/null
        line="$line; diagnosis: $(named "${fluid%.toml}_diag.json")"
      fi
      echo "$line"
    done
  done
done
