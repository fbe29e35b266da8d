#!/usr/bin/env bash
# Exports every shipped preset and checks the files in real clients: the
# Khronos glTF-Validator (0 errors, 0 warnings), three.js (GLTFLoader +
# AnimationMixer at every keyframe and halfway between keyframes against
# `phedra sample`), in both representations (morph targets, the default, and
# --nodes), the npm `fold` package (FOLD frames), and the modes of `phedra
# mechanics -o` (check_modes_three.mjs).
# usage: tests/js/check_exports.sh PHEDRA_BINARY
set -euo pipefail
phedra="$1"
top="$(cd "$(dirname "$0")/../.." && pwd)"
out="$(mktemp -d)"
trap 'rm -rf "$out"' EXIT
status=0
files=()
folds=()
for preset in "$top"/presets/*.json; do
  name="$(basename "$preset" .json)"
  [ "$name" = preset.schema ] && continue
  "$phedra" generate "$preset" -o "$out/$name.glb" --quiet >/dev/null
  files+=("$out/$name.glb")
  node "$top/tests/js/compare_three.mjs" "$phedra" "$preset" "$out/$name.glb" || status=1
  "$phedra" generate "$preset" -o "$out/$name.fold" --count 11 --quiet >/dev/null
  folds+=("$out/$name.fold")
done
node "$top/tests/js/check_fold.mjs" "${folds[@]}" || status=1
"$phedra" generate "$top/presets/grid-3x3.json" -o "$out/grid-3x3.gltf" --ping-pong --quiet >/dev/null
"$phedra" generate "$top/presets/default.json" -o "$out/static.glb" --at 1.0 --quiet >/dev/null
for name in default grid-3x3 merged-tube helix-tube; do
  "$phedra" generate "$top/presets/$name.json" -o "$out/$name-nodes.glb" --nodes --quiet >/dev/null
  node "$top/tests/js/compare_three.mjs" "$phedra" "$top/presets/$name.json" "$out/$name-nodes.glb" || status=1
  files+=("$out/$name-nodes.glb")
done
"$phedra" generate "$top/presets/grid-3x3.json" -o "$out/grid-3x3-nodes-ping.gltf" --nodes --ping-pong --quiet >/dev/null
"$phedra" generate "$top/presets/default.json" -o "$out/static-nodes.glb" --nodes --at 1.0 --quiet >/dev/null
files+=("$out/grid-3x3-nodes-ping.gltf" "$out/static-nodes.glb")
# The configuration curve through the flexion limits, both representations.
"$phedra" generate "$top/presets/default.json" -o "$out/cycle.glb" --cycle --nodes --quiet >/dev/null
"$phedra" generate "$top/presets/anti-parallelogram-tube.json" -o "$out/cycle-morph.gltf" --cycle --quiet >/dev/null
files+=("$out/grid-3x3.gltf" "$out/static.glb" "$out/cycle.glb" "$out/cycle-morph.gltf")
# The stiffness's modes (phedra mechanics -o): played in three.js, validated below.
"$phedra" mechanics "$top/presets/parallelogram-tube.json" --fraction 0.4 --modes 4 -o "$out/modes.glb" >/dev/null
"$phedra" mechanics "$top/presets/grid-3x3.json" --panels n4b5 --modes 3 -o "$out/grid-modes.glb" -o "$out/grid-modes.gltf" >/dev/null
node "$top/tests/js/check_modes_three.mjs" "$phedra" "$top/presets/parallelogram-tube.json" "$out/modes.glb" || status=1
node "$top/tests/js/check_modes_three.mjs" "$phedra" "$top/presets/grid-3x3.json" "$out/grid-modes.glb" || status=1
files+=("$out/modes.glb" "$out/grid-modes.glb" "$out/grid-modes.gltf")
node "$top/tests/js/validate_gltf.mjs" "${files[@]}" || status=1
if [ "$status" -eq 0 ]; then echo "$(( ${#files[@]} + ${#folds[@]} )) passed, 0 failed"; else echo "export client checks failed"; fi
exit "$status"
