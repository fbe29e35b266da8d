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
# NLopt's configure checks, answered as Debian's emscripten answers them (its musl libc;
# measured with a full configure, 2026-12-06): each check is a compile and link by
# emcc, about a second each, 33 s in all against 1 s with the answers given. The
# generated nlopt_config.h is the same either way.
cat > "$work/checks.cmake" <<'CHECKS'
foreach(yes HAS_FPIC HAVE_COPYSIGN HAVE_GETOPT HAVE_GETOPT_H HAVE_GETPID HAVE_GETTIMEOFDAY HAVE_LIBM HAVE_STDDEF_H
            HAVE_STDINT_H HAVE_SYS_TIME_H HAVE_SYS_TYPES_H HAVE_TIME HAVE_TIME_H HAVE_UNISTD_H)
  set(${yes} 1 CACHE INTERNAL "")
endforeach()
foreach(no HAVE_GETTID_SYSCALL HAVE_ISINF HAVE_ISNAN HAVE_QSORT_R)
  set(${no} "" CACHE INTERNAL "")
endforeach()
set(HAVE_FPCLASSIFY TRUE CACHE INTERNAL "")
foreach(type UINT32_T UNSIGNED_INT UNSIGNED_LONG)
  set(HAVE_SIZEOF_${type} TRUE CACHE INTERNAL "")
  set(SIZEOF_${type} 9 CACHE INTERNAL "")  # what check_type_size reports under emscripten
  set(SIZEOF_${type}_run_result 9 CACHE INTERNAL "")
endforeach()
CHECKS
emcmake cmake -C "$work/checks.cmake" -S "$source_dir" -B "$work/build" -DCMAKE_BUILD_TYPE=Release -DCMAKE_INSTALL_PREFIX="$prefix" \
  -DBUILD_SHARED_LIBS=OFF -DNLOPT_CXX=OFF -DNLOPT_PYTHON=OFF -DNLOPT_OCTAVE=OFF -DNLOPT_MATLAB=OFF \
  -DNLOPT_GUILE=OFF -DNLOPT_SWIG=OFF -DNLOPT_FORTRAN=OFF -DNLOPT_TESTS=OFF -DWITH_THREADLOCAL=OFF >/dev/null
cmake --build "$work/build" --parallel "$(nproc)" >/dev/null
cmake --install "$work/build" >/dev/null
rm -rf "$work"
echo "build-nlopt-wasm: $prefix/lib/libnlopt.a"
