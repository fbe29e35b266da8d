#!/usr/bin/env bash
# Parts laid flat for printing (generate --layout print) in PrusaSlicer
# (Debian's prusa-slicer, its command line): the plates of parallelogram-tube
# and grid-3x3, 3 mm and 1 mm thick, as 3MF on 200 x 200 mm beds. For every bed
# file: `--info` says manifold for as many objects as phedra put on that bed;
# it slices without supports at the places phedra gave (--dont-arrange; exit 0,
# G-code written); every extrusion of the G-code lies on the bed (no skirt: it
# runs 6 mm around the parts, and the parts keep 5 mm from the edges); and the
# slicer's objects stand on the bed (min_z = 0). The tube with pin hinges: its
# knuckles and pins on their ends, manifold and on the bed (not sliced here: its
# 318 small tall parts take PrusaSlicer a minute a bed; it slices them, exit 0).
# And the tube printed in place (below).
# usage: tests/prusa/check_print_beds.sh PHEDRA_BINARY
set -euo pipefail
phedra="$1"
top="$(cd "$(dirname "$0")/../.." && pwd)"
command -v prusa-slicer >/dev/null || { echo "prusa-slicer is not installed (scripts/setup.sh installs it)"; exit 1; }
out="$(mktemp -d)"
trap 'rm -rf "$out"' EXIT
check() {  # check slice|info NAME PRESET THICKNESS_MM [OPTIONS...]
  local slice="$1" name="$2" preset="$3" thickness="$4"
  shift 4
  local said
  said="$("$phedra" generate "$top/presets/$preset" --thickness-mm "$thickness" --layout print --bed 200x200 "$@" \
          -o "$out/$name.3mf" 2>/dev/null)"
  local files=("$out/$name".3mf)
  [[ -f "${files[0]}" ]] || files=("$out/$name"-*.3mf)
  [[ -f "${files[0]}" ]] || { echo "$name: phedra wrote no file: $said"; exit 1; }
  local total=0
  for f in "${files[@]}"; do
    # Objects on this bed: PrusaSlicer's --info prints a block per object.
    local info objects manifold
    info="$(prusa-slicer --info "$f" 2>/dev/null)"
    objects="$(grep -c '^manifold = ' <<<"$info")"
    manifold="$(grep -c '^manifold = yes' <<<"$info")"
    [[ "$objects" -gt 0 && "$objects" == "$manifold" ]] || { echo "$f: $manifold of $objects objects manifold"; exit 1; }
    if grep '^min_z = ' <<<"$info" | grep -vq '^min_z = 0.000000$'; then
      echo "$f: an object does not stand on the bed:"; grep '^min_z' <<<"$info" | sort | uniq -c; exit 1
    fi
    total=$((total + objects))
    [[ "$slice" == slice ]] || continue
    prusa-slicer --export-gcode --dont-arrange --bed-shape 0x0,200x0,200x200,0x200 --support-material=0 --skirts 0 \
      --layer-height 0.2 --first-layer-height 0.2 -o "${f%.3mf}.gcode" "$f" >"$out/slice.log" 2>&1 \
      || { echo "$f: PrusaSlicer did not slice it without supports:"; tail -5 "$out/slice.log"; exit 1; }
    # Every extruding move on the bed: X and Y within [0, 200] mm.
    awk -v file="$f" '
      /^G1 / { x = ""; y = ""; e = 0
               for (i = 2; i <= NF; ++i) { c = substr($i, 1, 1); v = substr($i, 2) + 0
                 if (c == "X") x = v; else if (c == "Y") y = v; else if (c == "E" && v > 0) e = 1; else if (c == ";") break }
               if (e && x != "" && (x < 0 || x > 200)) { print file ": extrusion at X " x; bad = 1 }
               if (e && y != "" && (y < 0 || y > 200)) { print file ": extrusion at Y " y; bad = 1 }
               if (e) ++moves }
      END { if (moves < 100) { print file ": only " moves " extrusions"; bad = 1 }; exit bad }' "${f%.3mf}.gcode"
  done
  local parts
  parts="$(sed -n 's/^wrote [^:]*: \([0-9]*\) plates.*/\1/p' <<<"$said")"
  local hinge_parts
  hinge_parts="$(sed -n 's/^wrote [^:]*: [0-9]* plates and \([0-9]*\) hinge parts.*/\1/p' <<<"$said")"
  [[ "$total" == "$((parts + ${hinge_parts:-0}))" ]] || { echo "$name: $total objects in PrusaSlicer, phedra said: $said"; exit 1; }
  echo "$name: ${#files[@]} bed(s), $total objects, manifold, on the bed$([[ "$slice" == slice ]] && echo ", sliced without supports")"
}
check slice tube parallelogram-tube.json 3
check slice grid grid-3x3.json 1
check info tube-pins parallelogram-tube.json 2 --hinge pin
# Printed in place (generate --print-in-place): one object of every body's
# closed shells, placed whole; PrusaSlicer reads one object, manifold, with as
# many parts (its connected shells) as phedra wrote. (It slices with supports,
# exit 0, in 14 s here: not run in CI.)
said="$("$phedra" generate "$top/presets/parallelogram-tube.json" --thickness-mm 1.5 --model-size 150 --hinge pin \
        --print-in-place -o "$out/in-place.3mf" 2>/dev/null)"
shells="$(sed -n 's/^printed in place: [0-9]* bodies (.*; \([0-9]*\) closed shells.*/\1/p' <<<"$said")"
info="$(prusa-slicer --info "$out/in-place.3mf" 2>/dev/null)"
[[ "$(grep -c '^manifold = yes' <<<"$info")" == 1 && "$(grep -c '^manifold = ' <<<"$info")" == 1 ]] \
  || { echo "in-place: not one manifold object:"; grep '^manifold' <<<"$info"; exit 1; }
parts="$(sed -n 's/^number_of_parts = *\([0-9]*\)/\1/p' <<<"$info")"
[[ -n "$shells" && "$parts" == "$shells" ]] || { echo "in-place: PrusaSlicer reads $parts parts, phedra said: $said"; exit 1; }
echo "in-place: one object, manifold, $parts shells"
