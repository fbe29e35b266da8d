#!/usr/bin/env bash
# Installs what phedra needs from Debian packages, only what is missing
# (cairo and the DejaVu fonts draw the PDF and PNG cut sheets of `outlines`;
# chromium runs the viewer's browser test; emscripten and node-acorn build the
# browser core, scripts/build-wasm.sh; Mesa's EGL and llvmpipe are the second
# software WebGL renderer bench/designer.mjs measures; Blender imports and plays
# the glTF exports in tests/blender; its glTF importer needs numpy, which
# Debian's blender package does not depend on; pybind11 builds the Python module,
# pytest runs its tests and matplotlib draws the example's plot; Spectra, CHOLMOD (SuiteSparse) and
# serial OpenBLAS are the mechanics' eigen-solver, factorization and BLAS, LAPACK its dense SVD;
# SciPy (quasi-random sampling), Dask's distributed, Zarr and xarray run and store
# the design-space atlases of python/phedra/atlas; dxflib writes the DXF cut sheets
# (R2000, closed polylines) and ezdxf audits them in the tests; PrusaSlicer slices the
# parts laid flat for printing in tests/prusa), then the npm packages of web/
# and NLopt for the browser core (built once from Debian's source package of it,
# scripts/build-nlopt-wasm.sh).
# Idempotent: a second run installs nothing. Needs root or sudo for apt-get.
set -euo pipefail

packages=(
  g++ cmake ninja-build pkg-config
  zlib1g-dev libeigen3-dev libopenmesh-dev libtinygltf-dev nlohmann-json3-dev libcli11-dev
  catch2 libbenchmark-dev libnlopt-cxx-dev libcairo2-dev fonts-dejavu-core libspectra-dev libsuitesparse-dev liblapack-dev libopenblas0-serial
  emscripten node-acorn
  chromium libegl-mesa0 libgl1-mesa-dri
  blender python3-numpy admesh
  python3-dev python3-pybind11 python3-pytest python3-matplotlib
  python3-scipy python3-distributed python3-zarr python3-xarray
  libdxflib-dev python3-ezdxf
  prusa-slicer
)

missing=()
for package in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$package" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$package")
  fi
done

# Node.js and npm run the client checks of the exports (glTF-Validator, three.js);
# a machine that already has them (any version >= 18) keeps its own.
if ! command -v node >/dev/null || ! command -v npm >/dev/null; then
  missing+=(nodejs npm)
fi

finish() {
  bash "$(dirname "$0")/setup-web.sh"
  bash "$(dirname "$0")/build-nlopt-wasm.sh"
}

if ((${#missing[@]} == 0)); then
  echo "setup: all packages present"
  finish
  exit 0
fi

sudo=""
if [ "$(id -u)" -ne 0 ]; then
  command -v sudo >/dev/null || { echo "setup: need root or sudo to install: ${missing[*]}" >&2; exit 1; }
  sudo="sudo"
fi
echo "setup: installing ${missing[*]}"
$sudo apt-get update -qq
DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
echo "setup: done"
finish
