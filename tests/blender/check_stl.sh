#!/usr/bin/env bash
# Thick plates (generate --thickness) as binary STL in Blender (Debian's,
# headless): three presets' plates imported by every STL importer Blender has;
# one closed, consistently wound, outward solid a plate, as many as phedra wrote,
# and the volume phedra printed (tests/blender/stl_in_blender.py).
# usage: tests/blender/check_stl.sh PHEDRA_BINARY
set -euo pipefail
phedra="$1"
top="$(cd "$(dirname "$0")/../.." && pwd)"
command -v blender >/dev/null || { echo "blender is not installed (scripts/setup.sh installs it)"; exit 1; }
out="$(mktemp -d)"
trap 'rm -rf "$out"' EXIT
args=()
for c in "parallelogram-tube 0.08 40" "grid-3x3 0.0707 216" "default 0.08 56"; do
  read -r name thickness plates <<<"$c"
  said="$("$phedra" generate "$top/presets/$name.json" --thickness "$thickness" -o "$out/$name.stl")"
  args+=("$out/$name.stl" "$plates" "$(sed -n 's/.*, volume \([^ ]*\) .*/\1/p' <<<"$said")")
done
blender -b --factory-startup --python-exit-code 1 -P "$top/tests/blender/stl_in_blender.py" -- "${args[@]}"
