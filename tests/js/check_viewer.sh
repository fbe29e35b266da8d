#!/usr/bin/env bash
# The viewer page in headless Chromium on an exported array.
# usage: tests/js/check_viewer.sh PHEDRA_BINARY
set -euo pipefail
phedra="$1"
top="$(cd "$(dirname "$0")/../.." && pwd)"
out="$(mktemp -d)"
trap 'rm -rf "$out"' EXIT
"$phedra" generate "$top/presets/grid-3x3.json" -o "$out/grid.glb" --quiet >/dev/null
node "$top/tests/js/viewer_test.mjs" "$phedra" "$out/grid.glb" "$out/viewer.png"
