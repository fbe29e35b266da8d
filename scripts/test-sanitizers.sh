#!/usr/bin/env bash
# The whole test suite built by clang with AddressSanitizer and
# UndefinedBehaviorSanitizer (and libFuzzer's coverage, so that scripts/fuzz.sh
# reuses this build) in build-sanitize/. Any report fails the run.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
bash scripts/configure-sanitize.sh
cmake --build build-sanitize --parallel "$(nproc)"
export ASAN_OPTIONS=detect_leaks=1:abort_on_error=1
export LSAN_OPTIONS="suppressions=$(pwd)/scripts/lsan.supp"
export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
ctest --test-dir build-sanitize --output-on-failure --parallel "$(nproc)"
