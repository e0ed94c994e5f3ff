#!/usr/bin/env bash
# Configure and build raystep (Release) in build/. Usage: scripts/build.sh [extra cmake args]
set -euo pipefail
cd "$(dirname "$0")/.."
jobs=$(nproc 2>/dev/null || echo 2)
# ccache (scripts/setup.sh installs it) keeps compiled objects outside the clone: a fresh clone on a machine
# that built raystep before compiles only what changed.
launcher=()
if command -v ccache > /dev/null; then
  launcher=(-DCMAKE_C_COMPILER_LAUNCHER=ccache -DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
  # Paths below the clone hashed relative to it, so that clones in other folders share the cache.
  export CCACHE_BASEDIR="$PWD" CCACHE_NOHASHDIR=1
fi
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release "${launcher[@]}" "$@" > build.cmake.log 2>&1 ||
  { cat build.cmake.log; exit 1; }
rm -f build.cmake.log
cmake --build build -j "$jobs"
