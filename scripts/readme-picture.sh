#!/usr/bin/env bash
# Makes docs/images/shudder_run.png, the README's picture: the torque plot of the shipped rig
# shudder scenario. Run it after a change that moves that run (tests/docs/test_readme_picture.py
# fails until then). Needs a built `shudder` (scripts/build.sh or run-default.sh) and gnuplot.
set -euo pipefail
cd "$(dirname "$0")/.."
cli=${SHUDDER_CLI:-./build/app/shudder}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
"$cli" run scenarios/rig_shudder_negative_slope.toml -o "$work/shudder.h5" >/dev/null
"$cli" plot "$work/shudder.h5" --what torque -o "$work/shudder_run.png" >/dev/null
mv "$work/shudder_run.png" docs/images/shudder_run.png
echo "readme-picture: wrote docs/images/shudder_run.png"
