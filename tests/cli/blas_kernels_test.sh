#!/usr/bin/env bash
# The command runs OpenBLAS's kernels for the processor: where Debian's OpenBLAS
# does not know it and falls back to Prescott's (SSE3) although it has AVX2 and
# FMA, phedra starts itself again with newer ones; a choice of the user's
# (OPENBLAS_CORETYPE) is kept. OPENBLAS_VERBOSE=2 makes OpenBLAS print its choice.
# usage: tests/cli/blas_kernels_test.sh PHEDRA_BINARY
set -euo pipefail
phedra="$1"
top="$(cd "$(dirname "$0")/../.." && pwd)"
out="$(mktemp -d)"
trap 'rm -rf "$out"' EXIT
failed=0
passed=0
core() { grep -o 'Core: [A-Za-z0-9]*' "$1" | tail -n 1 | cut -d' ' -f2; }
if ! ldd "$phedra" | grep -q libopenblas; then
  echo "the BLAS is not OpenBLAS: nothing to choose"; echo "0 passed, 0 failed"; exit 0
fi
OPENBLAS_VERBOSE=2 "$phedra" info "$top/presets/default.json" > "$out/info.txt" 2>&1 || { echo "phedra info failed"; failed=1; }
grep -q '^t\*:' "$out/info.txt" && passed=$((passed + 1)) || { echo "phedra info printed no t* (after a restart?)"; failed=1; }
chosen=$(core "$out/info.txt")
if grep -qw avx2 /proc/cpuinfo && grep -qw fma /proc/cpuinfo; then
  if [ "$chosen" = Prescott ]; then echo "Prescott's kernels on a processor with AVX2 and FMA"; failed=1; else passed=$((passed + 1)); fi
fi
OPENBLAS_CORETYPE=Prescott OPENBLAS_VERBOSE=2 "$phedra" info "$top/presets/default.json" > "$out/own.txt" 2>&1
if [ "$(core "$out/own.txt")" = Prescott ]; then passed=$((passed + 1)); else echo "the user's OPENBLAS_CORETYPE was not kept"; failed=1; fi
echo "chosen kernels: $chosen"
echo "$passed passed, $failed failed"
exit "$failed"
