#!/usr/bin/env bash
# The main job on a preset (default: presets/default.json): installs and builds
# what is missing, then shows the P-hedron, exports its folding motion over the
# whole flexion interval as animated glTF and as the motion JSON, and checks it.
# Outputs go to out/.
set -euo pipefail
cd "$(dirname "$0")/.."
preset="${1:-presets/default.json}"
bash scripts/build.sh
mkdir -p out
name="$(basename "$preset" .json)"
echo
./build/bin/phedra info "$preset"
echo
./build/bin/phedra generate "$preset" -o "out/$name.glb"
./build/bin/phedra generate "$preset" -o "out/$name-samples.json" --count 41
echo
./build/bin/phedra check "$preset"
echo
echo "Watch it fold: ./build/bin/phedra view out/$name.glb  (then open the printed address)"
echo "Design it in the browser: bash scripts/build-wasm.sh && ./build/bin/phedra view $preset"
