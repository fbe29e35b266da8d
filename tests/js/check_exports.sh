#!/usr/bin/env bash
# Exports every shipped preset to glTF and checks it in real clients: the
# Khronos glTF-Validator (0 errors, 0 warnings) and three.js (GLTFLoader +
# AnimationMixer at every keyframe against `phedra sample`).
# usage: tests/js/check_exports.sh PHEDRA_BINARY
set -euo pipefail
phedra="$1"
top="$(cd "$(dirname "$0")/../.." && pwd)"
out="$(mktemp -d)"
trap 'rm -rf "$out"' EXIT
status=0
files=()
for preset in "$top"/presets/*.json; do
  name="$(basename "$preset" .json)"
  [ "$name" = preset.schema ] && continue
  "$phedra" generate "$preset" -o "$out/$name.glb" --quiet >/dev/null
  files+=("$out/$name.glb")
  node "$top/tests/js/compare_three.mjs" "$phedra" "$preset" "$out/$name.glb" || status=1
done
"$phedra" generate "$top/presets/grid-3x3.json" -o "$out/grid-3x3.gltf" --ping-pong --quiet >/dev/null
"$phedra" generate "$top/presets/default.json" -o "$out/static.glb" --at 1.0 --quiet >/dev/null
files+=("$out/grid-3x3.gltf" "$out/static.glb")
node "$top/tests/js/validate_gltf.mjs" "${files[@]}" || status=1
if [ "$status" -eq 0 ]; then echo "${#files[@]} passed, 0 failed"; else echo "glTF client checks failed"; fi
exit "$status"
