#!/bin/bash
# Round trip of `characterise` through the model (docs/characterisation.md "Round trip through the
# model"): Paper D cycles (1 rpm 5 s, 1 -> 100 rpm in 10 s, hold 2 s, down in 10 s, 1 rpm 3 s) at
# 10, 15, 20 kN from 40, 60, 80 °C with sensor noise, made by
#   own    the project's model (scenarios/paper_g_case2_15kN.toml, `shudder run --measurement --noise`),
#   indep  the independent simulator (tools/independent_sim/indep_sim.py: another thermal model),
# characterised with every friction radius (--radius model | uniform_pressure | uniform_wear) and
# both methods, then replayed through the model the fluid is for (`diagnose --max-effects 0`: the
# baseline replay, JSON channels[].final_rms against .noise), and diagnosed (every candidate, no
# tolerance; DIAG below): the round trip must name nothing.
#
#   [DIAG=each|all|0] [DATA="own indep"] [RADII=...] [METHODS=...] \
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

# DIAG=all: diagnose the nine runs together; DIAG=each: each run alone, made again with a fresh
# noise seed (100 + its index), against the fluid characterised from the nine; DIAG=0: replay only.
DIAG=${DIAG:-each}
RADII=${RADII:-model uniform_pressure uniform_wear}
METHODS=${METHODS:-sensor inverse}
DATA=${DATA:-own indep}
fresh() {  # data, force, temp, seed -> a fresh run's CSV
  local out="$OUT/$1/fresh_${2}_${3}.csv"
  if [ ! -f "$out" ]; then
    if [ "$1" = own ]; then
      "$SHUDDER" run "$SCEN" --set drive.normal_force_N=$2 --set clutch.start_temp_C=$3 -o "${out%.csv}.h5" \
        --measurement "$out" --noise --seed $4 > /dev/null
    else
      $PY "$SRC/tools/independent_sim/indep_sim.py" run "$out" --fluid "$SRC/scenarios/fluids/lsc_fluid_c.toml" \
        --force-N $2 --start-C $3 --seed $4
    fi
  fi
  echo "$out"
}
for data in $DATA; do
  runs=$(ls "$OUT/$data"/r_*.csv)
  for radius in $RADII; do
    for method in $METHODS; do
      fluid="$OUT/$data/fit_${radius}_${method}.toml"
      base=$(basename "$SCEN")
      "$SHUDDER" characterise $runs -o "$fluid" --nu40-cSt 35 --nu100-cSt 6.7 --radius $radius --method $method \
        --model "$SCEN" > "${fluid%.toml}.txt" 2> "${fluid%.toml}.err" || { echo "$data $radius $method: characterise failed"; continue; }
      model=$(model_with "$fluid")
      "$SHUDDER" diagnose "$model" $runs --max-effects 0 --json "${fluid%.toml}_replay.json" --jobs 2 > /dev/null
      line="$data $radius $method: replayed torque $(rms "${fluid%.toml}_replay.json")"
      if [ "$DIAG" = all ]; then
        "$SHUDDER" diagnose "$model" $runs --json "${fluid%.toml}_diag.json" --jobs 2 > /dev/null
        line="$line; diagnosis: $(named "${fluid%.toml}_diag.json")"
      fi
      echo "$line"
      if [ "$DIAG" = each ]; then
        k=100
        for f in 10000 15000 20000; do
          for t in 40 60 80; do
            k=$((k + 1))
            run=$(fresh $data $f $t $k)
            "$SHUDDER" diagnose "$model" "$run" --json "${fluid%.toml}_diag_${f}_${t}.json" --jobs 2 > /dev/null
            echo "  $data $radius $method, $((f / 1000)) kN from $t C, seed $k: $(named "${fluid%.toml}_diag_${f}_${t}.json")"
          done
        done
      fi
    done
  done
done
