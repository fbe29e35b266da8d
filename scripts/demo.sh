#!/usr/bin/env bash
# The main job on a preset (default: presets/default.json): installs and builds
# what is missing, then shows the P-hedron, samples its motion over the whole
# flexion interval and checks it. Outputs go to out/.
set -euo pipefail
cd "$(dirname "$0")/.."
preset="${1:-presets/default.json}"
bash scripts/build.sh
mkdir -p out
name="$(basename "$preset" .json)"
echo
./build/bin/phedra info "$preset"
echo
./build/bin/phedra sample "$preset" --count 41 -o "out/$name-samples.json"
echo "wrote out/$name-samples.json: 41 configurations from t_lambda to t_mu (labels, faces, vertices)"
echo
./build/bin/phedra check "$preset"
