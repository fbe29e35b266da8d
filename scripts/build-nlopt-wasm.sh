#!/usr/bin/env bash
# NLopt for the browser (issue 14: the designer's Repair runs the same core):
# Debian's source package of the NLopt the native build uses (libnlopt-dev),
# compiled with Debian's emscripten into build-wasm/nlopt/ (static libnlopt.a and
# the generated nlopt.hpp). The source comes through apt from the machine's own
# Debian archive (deb-src entries made from its deb entries, in a private list
# directory: the system's apt configuration is not touched). Idempotent: does
# nothing once built.
set -euo pipefail
cd "$(dirname "$0")/.."
prefix="$PWD/build-wasm/nlopt"
[[ -f "$prefix/lib/libnlopt.a" && -f "$prefix/include/nlopt.hpp" ]] && exit 0
command -v emcmake >/dev/null || { echo "build-nlopt-wasm: emcmake not found (bash scripts/setup.sh installs emscripten)" >&2; exit 1; }
work="$PWD/build-wasm/nlopt-src"
rm -rf "$work"
mkdir -p "$work/lists/partial" "$work/parts" "$work/cache/archives/partial"
# deb-src twins of the Debian archive entries (one-line and deb822 formats).
touch "$work/sources.list"
for f in /etc/apt/sources.list /etc/apt/sources.list.d/*.list; do
  [[ -f "$f" ]] && grep -h '^deb .*debian' "$f" | sed 's/^deb /deb-src /' >> "$work/sources.list" || true
done
for f in /etc/apt/sources.list.d/*.sources; do
  [[ -f "$f" ]] && grep -q 'debian' "$f" && sed 's/^Types:.*/Types: deb-src/' "$f" > "$work/parts/$(basename "$f")"
done
apt_options=(-o "Dir::Etc::SourceList=$work/sources.list" -o "Dir::Etc::SourceParts=$work/parts"
             -o "Dir::State::Lists=$work/lists" -o "Dir::Cache=$work/cache" -o "APT::Sandbox::User=root")
version="$(dpkg-query -W -f='${Version}' libnlopt-dev 2>/dev/null || true)"
package="nlopt${version:+=$version}"
echo "build-nlopt-wasm: fetching the source of $package from the Debian archive"
apt-get "${apt_options[@]}" -qq update
(cd "$work" && apt-get "${apt_options[@]}" -qq source --download-only "$package")
tar -xzf "$work"/nlopt_*.orig.tar.gz -C "$work"
source_dir="$(find "$work" -mindepth 1 -maxdepth 1 -type d -name 'nlopt-*' | head -1)"
export NODE_PATH="${NODE_PATH:-/usr/share/nodejs}"
emcmake cmake -S "$source_dir" -B "$work/build" -DCMAKE_BUILD_TYPE=Release -DCMAKE_INSTALL_PREFIX="$prefix" \
  -DBUILD_SHARED_LIBS=OFF -DNLOPT_CXX=OFF -DNLOPT_PYTHON=OFF -DNLOPT_OCTAVE=OFF -DNLOPT_MATLAB=OFF \
  -DNLOPT_GUILE=OFF -DNLOPT_SWIG=OFF -DNLOPT_FORTRAN=OFF -DNLOPT_TESTS=OFF -DWITH_THREADLOCAL=OFF >/dev/null
cmake --build "$work/build" --parallel "$(nproc)" >/dev/null
cmake --install "$work/build" >/dev/null
rm -rf "$work"
echo "build-nlopt-wasm: $prefix/lib/libnlopt.a"
