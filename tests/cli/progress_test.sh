#!/usr/bin/env bash
# Long exports show a progress bar on a terminal, none when standard error is not
# a terminal or with --quiet. `script` gives the command a pseudo-terminal.
# usage: tests/cli/progress_test.sh PHEDRA_BINARY
set -euo pipefail
phedra="$1"
top="$(cd "$(dirname "$0")/../.." && pwd)"
out="$(mktemp -d)"
trap 'rm -rf "$out"' EXIT
run="$phedra generate $top/presets/grid-3x3.json -o $out/a.glb --hinge-tolerance 1e-4"
failed=0
script -qec "$run" /dev/null > "$out/tty.txt"
grep -q 'keyframes \[#*-*\] [0-9]*%' "$out/tty.txt" || { echo "no progress bar on a terminal"; failed=1; }
script -qec "$run --quiet" /dev/null > "$out/quiet.txt"
if grep -q 'keyframes \[' "$out/quiet.txt"; then echo "a progress bar despite --quiet"; failed=1; fi
$run > "$out/pipe.txt" 2>&1
if grep -q 'keyframes \[' "$out/pipe.txt"; then echo "a progress bar without a terminal"; failed=1; fi
if [ "$failed" -eq 0 ]; then echo "3 passed, 0 failed"; fi
exit "$failed"
