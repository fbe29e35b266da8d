#!/usr/bin/env bash
# Builds the phedra core for the browser with Debian's emscripten (issue 8; repair, issue 14):
# web/wasm/phedra.mjs + phedra.wasm (an ES module whose default export is the factory `createPhedra`, see
# wasm/bindings.cpp). Only Eigen, nlohmann-json, tinygltf's header, Spectra's headers and NLopt
# (compiled from Debian's source package by scripts/build-nlopt-wasm.sh) are
# needed besides the project's own sources. Incremental: an object is rebuilt when its source or a
# header changed (em++ -MMD dependency files in build-wasm/).
set -euo pipefail
cd "$(dirname "$0")/.."
export NODE_PATH="${NODE_PATH:-/usr/share/nodejs}"  # emscripten's optimizer needs Debian's node-acorn
command -v em++ >/dev/null || { echo "build-wasm: em++ not found (bash scripts/setup.sh installs emscripten)" >&2; exit 1; }
out=build-wasm
mkdir -p "$out/include" "$out/obj" web/wasm
# Only the headers phedra needs, not all of /usr/include (host headers would shadow emscripten's libc).
ln -sfn /usr/include/eigen3/Eigen "$out/include/Eigen"
ln -sfn /usr/include/nlohmann "$out/include/nlohmann"
ln -sfn /usr/include/tiny_gltf.h "$out/include/tiny_gltf.h"
ln -sfn /usr/include/Spectra "$out/include/Spectra"
bash scripts/build-nlopt-wasm.sh  # NLopt for repair, from Debian's source package (once)
# -O2: from scratch 83 s here against 101 s at -O3 (2 cores, 2026-12-06), the designer's drag steps
# (bench/designer.mjs) the same within their run-to-run noise.
flags=(-std=c++20 -O2 -fwasm-exceptions -DNDEBUG -Igenerator/include -Itubes/include -Icouplings/include
       -Iio/include -Ianalysis/include -Imechanics/include -Iexporters/include -Irepair/include -I"$out/include"
       -I"$out/nlopt/include")
# One translation unit a module (its sources #included in order, as CMake's unity
# build does): the heavy headers are compiled once a module, not once a file.
modules=(generator tubes couplings io analysis repair)
exporter_sources=(exporters/src/fold_export.cpp exporters/src/gltf_*.cpp exporters/src/keyframes.cpp
                  exporters/src/time_map.cpp exporters/src/panel_tree.cpp)
mkdir -p "$out/unity"
unity() {  # unity NAME FILE...: $out/unity/NAME.cpp, rewritten only when its list changes
  local name="$1" text=""
  shift
  for f in "$@"; do text+="#include \"$PWD/$f\""$'\n'; done
  if [[ ! -f "$out/unity/$name.cpp" || "$(cat "$out/unity/$name.cpp")"$'\n' != "$text" ]]; then
    printf '%s' "$text" > "$out/unity/$name.cpp"
  fi
}
sources=()
for m in "${modules[@]}"; do
  files=()
  for f in "$m"/src/*.cpp; do
    case "$f" in *atlas*) ;; *) files+=("$f") ;; esac  # atlases are read by the command (zlib), not the pages
  done
  unity "$m" "${files[@]}"
  sources+=("$out/unity/$m.cpp")
done
unity exporters "${exporter_sources[@]}"
# Mechanics without its plots (cairo), its AVX2 atan2, CHOLMOD (Eigen's own Cholesky) and
# the mobility (LAPACK) of the command's report: the energy landscape and the figures.
mechanics_sources=()
for f in mechanics/src/*.cpp; do
  case "$f" in *chart*|*_avx2*|*_avx512*|*mobility*|*dense_svd*|*mechanics_report*|*supernodal_solve*) ;; *) mechanics_sources+=("$f") ;; esac
done
unity mechanics "${mechanics_sources[@]}"
sources+=("$out/unity/mechanics.cpp" "$out/unity/exporters.cpp" wasm/tinygltf_implementation.cpp wasm/bindings.cpp)
objects=()
pids=()
jobs="$(nproc)"
for src in "${sources[@]}"; do
  obj="$out/obj/$(echo "$src" | tr '/' '_').o"
  objects+=("$obj")
  dep="${obj%.o}.d"
  stale=0
  if [[ ! -f "$obj" || "$src" -nt "$obj" ]]; then
    stale=1
  elif [[ -f "$dep" ]]; then
    for h in $(sed -e 's/\\$//' -e 's/^[^:]*://' "$dep"); do
      [[ -f "$h" && "$h" -nt "$obj" ]] && { stale=1; break; }
    done
  fi
  if (( stale )); then
    em++ "${flags[@]}" -MMD -MF "$dep" -c "$src" -o "$obj" &
    pids+=($!)
    if (( ${#pids[@]} >= jobs )); then wait "${pids[0]}"; pids=("${pids[@]:1}"); fi
  fi
done
for pid in "${pids[@]}"; do wait "$pid"; done
em++ "${objects[@]}" "$out/nlopt/lib/libnlopt.a" -O2 -fwasm-exceptions --bind -sMODULARIZE=1 -sEXPORT_NAME=createPhedra -sALLOW_MEMORY_GROWTH=1 \
  -sENVIRONMENT=web,node -sEXPORT_ES6=1 -o web/wasm/phedra.mjs
echo "build-wasm: web/wasm/phedra.mjs, web/wasm/phedra.wasm ($(stat -c %s web/wasm/phedra.wasm) bytes)"
