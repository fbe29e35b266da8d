#!/usr/bin/env bash
# Installs missing dependencies, configures and builds phedra (Release) in build/.
# Sources are compiled in batches (CMake's unity build: each heavy header, CLI11,
# Catch, nlohmann-json, Eigen, once a batch; half the build time). Extra
# arguments go to the CMake configure step (-DCMAKE_UNITY_BUILD=OFF for a
# build that recompiles single files).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release -DCMAKE_UNITY_BUILD=ON "$@" >/dev/null
cmake --build build --parallel "$(nproc)"
