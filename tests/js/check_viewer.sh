#!/usr/bin/env bash
# The viewer page in headless Chromium on an exported array (every panel
# buildable) and on a tube with bow-tie panels (drawn red).
# usage: tests/js/check_viewer.sh PHEDRA_BINARY
set -euo pipefail
phedra="$1"
top="$(cd "$(dirname "$0")/../.." && pwd)"
out="$(mktemp -d)"
trap 'rm -rf "$out"' EXIT
shots="$(dirname "$phedra")/../tests"
mkdir -p "$shots"
"$phedra" generate "$top/presets/grid-3x3.json" -o "$out/grid.glb" --quiet >/dev/null
node "$top/tests/js/viewer_test.mjs" "$phedra" "$out/grid.glb" "$shots/viewer.png" 216 0
"$phedra" generate "$top/tests/data/repairable-tube.json" -o "$out/tube.glb" --quiet >/dev/null 2>&1
node "$top/tests/js/viewer_test.mjs" "$phedra" "$out/tube.glb" "$shots/viewer-invalid.png" 20 4
