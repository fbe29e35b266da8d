#!/usr/bin/env bash
# Thick plates (generate --thickness) as binary STL in Blender (Debian's,
# headless): every shipped preset that can be built (not the anti-parallelogram
# ones), plates 1 % of its size thick (--thickness-mm 1 --model-size 100),
# imported by every STL importer Blender has; one closed, consistently wound,
# outward solid a plate, as many as phedra wrote, and the volume phedra printed
# (tests/blender/stl_in_blender.py); and the tube with pin hinges (its knuckles
# and pins too).
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
# Pin hinges (--hinge pin): the plates, then every knuckle and pin, each its own closed solid.
said="$("$phedra" generate "$top/presets/parallelogram-tube.json" --thickness-mm 1.5 --model-size 100 --hinge pin -o "$out/pins.stl" 2>/dev/null)"
plates="$(sed -n 's/^wrote [^:]*: \([0-9]*\) plates .*/\1/p' <<<"$said")"
volume="$(sed -n 's/^wrote .*, volume \([^ ]*\) .*/\1/p' <<<"$said")"
knuckles="$(sed -n 's/^pin hinges: [0-9]* hinges, \([0-9]*\) knuckles.*/\1/p' <<<"$said")"
pins="$(sed -n 's/.* \([0-9]*\) pins (radius.*/\1/p' <<<"$said")"
parts="$(sed -n 's/.*), volume \([^ ;]*\)[^;]*; plates cut back.*/\1/p' <<<"$said")"
[[ -n "$plates" && -n "$volume" && -n "$knuckles" && -n "$pins" && -n "$parts" ]] || { echo "phedra generate --hinge pin said: $said"; exit 1; }
args+=("$out/pins.stl" "$((plates + knuckles + pins))" "$(python3 -c "print($volume + $parts)")")
blender -b --factory-startup --python-exit-code 1 -P "$top/tests/blender/stl_in_blender.py" -- "${args[@]}"
