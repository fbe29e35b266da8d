#!/usr/bin/env bash
# The viewer page in headless Chromium on an exported array (every panel
# buildable), a node-per-panel export and a tube with bow-tie panels (drawn red).
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
# The node-per-panel layout: the same folds, hinge plot and exports.
"$phedra" generate "$top/presets/default.json" -o "$out/nodes.glb" --nodes --quiet >/dev/null
node "$top/tests/js/viewer_test.mjs" "$phedra" "$out/nodes.glb" "$shots/viewer-nodes.png" 56 0 nodes
"$phedra" generate "$top/tests/data/repairable-tube.json" -o "$out/tube.glb" --quiet >/dev/null 2>&1
node "$top/tests/js/viewer_test.mjs" "$phedra" "$out/tube.glb" "$shots/viewer-invalid.png" 20 4
