#!/usr/bin/env bash
# Configures build-sanitize/: clang, -O1 without debug information (the fastest
# build that still gives useful reports), ASan + UBSan, the fuzz harness; sources
# compiled in batches (unity build: each heavy header once a batch).
set -euo pipefail
cd "$(dirname "$0")/.."
cmake -S . -B build-sanitize -G Ninja -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_BUILD_TYPE=None -DCMAKE_CXX_FLAGS=-O1 \
  -DPHEDRA_FUZZ=ON -DCMAKE_UNITY_BUILD=ON >/dev/null
