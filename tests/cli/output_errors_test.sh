#!/usr/bin/env bash
# Output failures give a clear error, exit 3 and leave no partial file: a full
# disk (simulated with a file-size limit), a directory that cannot be written
# (/proc), a missing directory, and the input named as output.
# usage: tests/cli/output_errors_test.sh PHEDRA_BINARY
set -uo pipefail
phedra="$1"
top="$(cd "$(dirname "$0")/../.." && pwd)"
out="$(mktemp -d)"
trap 'rm -rf "$out"' EXIT
failed=0; passed=0
expect() {  # name, expected exit code, message, command...
  local name="$1" code="$2" message="$3"; shift 3
  local err rc
  err="$("$@" 2>&1 >/dev/null)"; rc=$?
  if [ "$rc" -ne "$code" ] || [[ "$err" != *"$message"* ]]; then
    echo "FAIL $name: exit $rc, message: $err"; failed=$((failed + 1))
  else
    passed=$((passed + 1))
  fi
}
grid="$top/presets/grid-3x3.json"
for ext in json glb fold obj; do
  # A full disk: writes beyond 16 KiB fail (SIGXFSZ ignored, so write() reports EFBIG).
  expect "full disk .$ext" 3 "write failed" bash -c "trap '' XFSZ; ulimit -f 16; exec \"$phedra\" generate \"$grid\" -o \"$out/big.$ext\" --quiet"
done
expect "unwritable directory" 3 "cannot write in /proc" "$phedra" generate "$grid" -o /proc/phedra.glb --quiet
expect "missing directory" 3 "does not exist" "$phedra" generate "$grid" -o "$out/no/such/dir/a.glb" --quiet
mkdir "$out/folder.glb"
expect "output is a directory" 3 "is a directory" "$phedra" generate "$grid" -o "$out/folder.glb" --quiet
rmdir "$out/folder.glb"
cp "$grid" "$out/grid.json"
expect "output is the input" 3 "is the input file" "$phedra" generate "$out/grid.json" -o "$out/grid.json" --quiet
cmp -s "$grid" "$out/grid.json" || { echo "FAIL the input was changed"; failed=$((failed + 1)); }
leftover="$(find "$out" -mindepth 1 ! -name grid.json)"
[ -z "$leftover" ] || { echo "FAIL files left behind: $leftover"; failed=$((failed + 1)); }
echo "$passed passed, $failed failed"
[ "$failed" -eq 0 ]
