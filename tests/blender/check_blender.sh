#!/usr/bin/env bash
# The glTF exports in Blender (Debian's, headless): every shipped preset's
# default export, the node representation of two, and a 9900-panel array
# (tests/data/grid-10x10.json) are imported and played: every keyframe and every
# whole frame (24 fps) within the file's tolerance of `phedra sample`, the
# scene metadata and the shape keys named by t (tests/blender/check_gltf.py);
# and the modes of `phedra mechanics -o` (tests/blender/check_modes.py).
# The import and frame-change times are printed; bench/blender.sh holds them to
# the targets.
# usage: tests/blender/check_blender.sh PHEDRA_BINARY
set -euo pipefail
phedra="$1"
top="$(cd "$(dirname "$0")/../.." && pwd)"
command -v blender >/dev/null || { echo "blender is not installed (scripts/setup.sh installs it)"; exit 1; }
out="$(mktemp -d)"
trap 'rm -rf "$out"' EXIT
status=0
passed=0
jobs=()  # PRESET FILE pairs, checked in one Blender (each start takes seconds)
for preset in "$top"/presets/*.json; do
  name="$(basename "$preset" .json)"
  [ "$name" = preset.schema ] && continue
  "$phedra" generate "$preset" -o "$out/$name.glb" --quiet >/dev/null 2>&1
  jobs+=("$preset" "$out/$name.glb")
done
for name in default grid-3x3; do
  "$phedra" generate "$top/presets/$name.json" -o "$out/$name-nodes.glb" --nodes --quiet >/dev/null 2>&1
  jobs+=("$top/presets/$name.json" "$out/$name-nodes.glb")
done
"$phedra" generate "$top/tests/data/grid-10x10.json" -o "$out/grid-10x10.glb" --quiet >/dev/null 2>&1
jobs+=("$top/tests/data/grid-10x10.json" "$out/grid-10x10.glb")
blender -b --factory-startup --python "$top/tests/blender/check_gltf.py" -- "$phedra" "${jobs[@]}" >"$out/blender.log" 2>&1 || true
for ((k = 1; k < ${#jobs[@]}; k += 2)); do
  file="${jobs[$k]}"
  line="$(grep -F "phedra-blender: {\"file\": \"$file\"" "$out/blender.log" || true)"
  if [ -z "$line" ]; then
    echo "$file: Blender did not report (the import failed?)"
    status=1
    continue
  fi
  echo "${line#phedra-blender: }"
  if echo "$line" | grep -q '"failures": \[\]'; then passed=$((passed + 1)); else status=1; fi
done
[ "$status" -eq 0 ] || tail -30 "$out/blender.log"
# The stiffness's modes (phedra mechanics -o): shape keys by name, played a field at a time.
"$phedra" mechanics "$top/presets/parallelogram-tube.json" --fraction 0.4 --modes 4 -o "$out/modes.glb" >/dev/null 2>&1
line="$(blender -b --factory-startup --python "$top/tests/blender/check_modes.py" -- "$out/modes.glb" 2>&1 | grep '^phedra-blender-modes: ' || true)"
echo "${line:-modes.glb: Blender did not report}"
if echo "$line" | grep -q '"failures": \[\]'; then passed=$((passed + 1)); else status=1; fi
if [ "$status" -eq 0 ]; then echo "$passed passed, 0 failed"; else echo "Blender checks failed"; fi
exit "$status"
