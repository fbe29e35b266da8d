#!/usr/bin/env bash
# Fuzzes the whole pipeline (parse, build, evaluate, check, export to memory)
# with libFuzzer under AddressSanitizer and UndefinedBehaviorSanitizer.
# usage: bash scripts/fuzz.sh [SECONDS=600]
# Builds in build-sanitize/ (shared with scripts/test-sanitizers.sh). The corpus
# grows in build-sanitize/corpus (seeded from the presets, the bad presets and
# the reference cases); a finding is written as build-sanitize/crash-* and the
# script exits non-zero.
set -euo pipefail
cd "$(dirname "$0")/.."
seconds="${1:-600}"
bash scripts/setup.sh >/dev/null
bash scripts/configure-sanitize.sh
cmake --build build-sanitize --target phedra_fuzz_design --parallel "$(nproc)"
mkdir -p build-sanitize/corpus
cp -n presets/*.json presets/developed/*.json tests/data/developed-no-flex.json tests/data/zero-volume-at-t-star.json tests/data/bad/*.json tests/data/cases/*.json build-sanitize/corpus/ 2>/dev/null || true
export ASAN_OPTIONS=detect_leaks=1:abort_on_error=1
export LSAN_OPTIONS="suppressions=$(pwd)/scripts/lsan.supp"
export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
cd build-sanitize
./fuzz/phedra_fuzz_design corpus -max_total_time="$seconds" -timeout=20 -rss_limit_mb=4096 -max_len=8192 \
  -print_final_stats=1 -artifact_prefix=./
