#!/usr/bin/env bash
# Blender figures of the default glTF export at scale (issue 15): a 9900-panel
# array of 100 parallelogram cells (tests/data/grid-10x10.json) exported with
# the default options, imported by Debian's Blender headless and played.
# Targets: export under 2 s, Blender import under 10 s, a frame change under
# 40 ms, three.js load under 1 s with a draw call per member; every keyframe and
# whole frame within the file's tolerance.
# usage: bench/blender.sh [PHEDRA_BINARY]   (default build/bin/phedra)
set -euo pipefail
top="$(cd "$(dirname "$0")/.." && pwd)"
phedra="${1:-$top/build/bin/phedra}"
out="$(mktemp -d)"
trap 'rm -rf "$out"' EXIT
preset="$top/tests/data/grid-10x10.json"
start=$(date +%s%N)
"$phedra" generate "$preset" -o "$out/grid.glb" --quiet
end=$(date +%s%N)
echo "export (phedra generate, incl. the buildability sweep): $(( (end - start) / 1000000 )) ms; file $(du -h "$out/grid.glb" | cut -f1)"
node "$top/bench/three_load.mjs" "$out/grid.glb"
blender -b --factory-startup --python "$top/tests/blender/check_gltf.py" -- "$phedra" "$preset" "$out/grid.glb" \
  --max-import-seconds 10 --max-frame-seconds 0.04 2>&1 | grep '^phedra-blender: ' | sed 's/^phedra-blender: //'
