#!/usr/bin/env bash
# Thick plates (generate --thickness) as binary STL in Blender (Debian's,
# headless): every shipped preset that can be built (not the anti-parallelogram
# ones), plates 1 % of its size thick (--thickness-mm 1 --model-size 100),
# imported by every STL importer Blender has; one closed, consistently wound,
# outward solid a plate, as many as phedra wrote, and the volume phedra printed
# (tests/blender/stl_in_blender.py).
# usage: tests/blender/check_stl.sh PHEDRA_BINARY
set -euo pipefail
phedra="$1"
top="$(cd "$(dirname "$0")/../.." && pwd)"
command -v blender >/dev/null || { echo "blender is not installed (scripts/setup.sh installs it)"; exit 1; }
out="$(mktemp -d)"
trap 'rm -rf "$out"' EXIT
args=()
for preset in "$top"/presets/*.json; do
  name="$(basename "$preset" .json)"
  [[ "$name" == preset.schema || "$name" == anti-parallelogram* ]] && continue
  said="$("$phedra" generate "$preset" --thickness-mm 1 --model-size 100 -o "$out/$name.stl" 2>/dev/null)"
  plates="$(sed -n 's/^wrote [^:]*: \([0-9]*\) plates .*/\1/p' <<<"$said")"
  volume="$(sed -n 's/.*, volume \([^ ]*\) .*/\1/p' <<<"$said")"
  [[ -n "$plates" && -n "$volume" ]] || { echo "phedra generate $name --thickness-mm 1 said: $said"; exit 1; }
  args+=("$out/$name.stl" "$plates" "$volume")
done
blender -b --factory-startup --python-exit-code 1 -P "$top/tests/blender/stl_in_blender.py" -- "${args[@]}"
