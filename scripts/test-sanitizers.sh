#!/usr/bin/env bash
# The test suite built by clang with AddressSanitizer and
# UndefinedBehaviorSanitizer (and libFuzzer's coverage on the libraries the fuzz
# harness runs, so that scripts/fuzz.sh reuses this build) in build-sanitize/. Any report fails the run.
# Every C++ test runs (every module's), with smaller batches of the slow
# property tests (PHEDRA_SANITIZE_BUILD); not run here: the clients of the
# exports (three.js, the glTF validator, Blender, ezdxf, PrusaSlicer, the pages in Chromium, the
# WebAssembly core, the Python module: not built here), which test files and
# pages the Release run already checks, the terminal's progress bar, the BLAS kernels'
# choice and the shell test of failed outputs (the command's behaviour: the Release
# run checks them), the optimization of the mechanics' gap (a minute-long search; the mechanics'
# figures and the optimizer run under the sanitizers in their own tests), the optimizer's JSON key
# order and the repair's --objective fields (the command's words and a choice of objective: their
# searches run under the sanitizers in the other optimize and repair tests), logic tests that
# repeat searches the sanitizers see elsewhere (a repair that reaches part of the interval, 20 s
# here against 1.4 s; the thickest plates at two thicknesses, 21 s against 4 s; the thickness
# suggested for plates that hardly fold; the pin hinges' clearance over the thick interval of three
# presets, whose layout search the pin hinge test runs here, and the printer's refusals and
# generate --print-in-place's, the command's words: the bodies printed in place are tested here), the Google Benchmark binary (not built here), and `bench --quick` (timings; the bench cases and the cache reading
# are tested apart, and the Release run runs it).
# usage: bash scripts/test-sanitizers.sh [FUZZ_SECONDS]: with a number, scripts/fuzz.sh runs that
# long beside the suite once the build is done (CI: the suite's tests leave a core idle
# part of the time; fuzzing after the suite cost its whole time on the clock).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
bash scripts/configure-sanitize.sh
cmake --build build-sanitize --parallel "$(nproc)"
export ASAN_OPTIONS=detect_leaks=1:abort_on_error=1
export LSAN_OPTIONS="suppressions=$(pwd)/scripts/lsan.supp"
export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
clients='^(optimize targets the mechanics: the gap reached, checked by phedra mechanics on the written file|repair --objective fields: fewer fields changed than the nearest design, verified|optimize --json, key order and --vary|pin hinges: no part cuts into another at t\* nor anywhere in the thick interval|pin hinges for a printer: plates too thin for its parts refused with the thickness and scale that work|generate --print-in-place: the bodies in one object, and every refusal|repair: a design buildable over part of the interval is never a result, and the closest says how much|thick plates: the thickest that fit, the same whatever thickness check ran at, with every hinge mode and unit|thick plates on cut sheets that hardly fold: said in words on the first page and by the command, with a thickness that folds|gltf_in_real_clients|gltf_in_blender|stl_in_blender|dxf_in_ezdxf|print_beds_in_prusaslicer|viewer_in_headless_chromium|build_wasm|wasm_core_in_node|designer_.*|progress_bar_only_on_a_terminal|blas_kernels_for_the_processor|output_failures_leave_no_partial_file)$'
fuzz_pid=""
if [[ -n "${1:-}" ]]; then
  bash scripts/fuzz.sh "$1" > build-sanitize/fuzz.log 2>&1 &
  fuzz_pid=$!
fi
status=0
ctest --test-dir build-sanitize --output-on-failure --parallel "$(nproc)" -E "$clients|bench --quick" || status=$?
if [[ -n "$fuzz_pid" ]]; then
  fuzz_status=0
  wait "$fuzz_pid" || fuzz_status=$?
  tail -n 25 build-sanitize/fuzz.log
  if (( fuzz_status != 0 )); then
    echo "test-sanitizers: the fuzzing run failed (exit $fuzz_status): build-sanitize/fuzz.log" >&2
    status=1
  fi
fi
exit "$status"
