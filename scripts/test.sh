#!/usr/bin/env bash
# The whole test suite: installs and builds what is missing, then runs every test.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/build.sh
ctest --test-dir build --output-on-failure --parallel "$(nproc)"
