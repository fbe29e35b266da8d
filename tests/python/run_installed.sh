#!/usr/bin/env bash
# The Python package as a researcher installs it (docs/python.md): a fresh venv of
# Debian's python3 that sees its system packages (numpy, pytest), `pip install .`
# from this clone (its compiled core from the CMake build in BUILD_DIR, reused),
# then the Python tests against the installed package, run from outside the
# sources (so that nothing but the installed package can be imported).
# usage: tests/python/run_installed.sh BUILD_DIR PHEDRA_BINARY
set -euo pipefail
build="$(cd "$1" && pwd)"
export PHEDRA="$2"
top="$(cd "$(dirname "$0")/../.." && pwd)"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
/usr/bin/python3 -m venv --system-site-packages "$work/venv"  # Debian's: it has numpy, pytest, setuptools
PHEDRA_BUILD_DIR="$build" "$work/venv/bin/pip" install --no-input --quiet --disable-pip-version-check "$top"
cd "$work"
unset PYTHONPATH
"$work/venv/bin/python" - "$work/venv" <<'PY'
import sys
import phedra
assert phedra.__file__.startswith(sys.argv[1]), f"phedra imported from {phedra.__file__}, not the venv"
print(f"phedra {phedra.__version__} installed in {sys.argv[1]}")
PY
exec "$work/venv/bin/python" -m pytest -q -p no:cacheprovider "$top/tests/python"
