#!/usr/bin/env bash
# The one test command: install dependencies, build everything (Release), run every test, then build the core
# tests with AddressSanitizer + UndefinedBehaviorSanitizer and run them again, then run every fuzz harness for a
# few seconds on its saved corpus (scripts/fuzz.sh --smoke; skipped without clang).
set -euo pipefail
cd "$(dirname "$0")/.."
jobs=$(nproc 2>/dev/null || echo 2)

bash scripts/setup.sh
bash scripts/build.sh
(cd build && ctest --output-on-failure -j "$jobs")

echo "== sanitizer pass (ASan + UBSan): core tests =="
cmake -S . -B build-asan -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DRAYSTEP_SANITIZE=ON \
  -DRAYSTEP_BUILD_BENCH=OFF -DRAYSTEP_BUILD_CLI=OFF -DRAYSTEP_BUILD_GUI=OFF > /dev/null
cmake --build build-asan -j "$jobs" --target raystep_core_tests
(cd build-asan && ASAN_OPTIONS=detect_leaks=1 UBSAN_OPTIONS=print_stacktrace=1 \
  ctest --output-on-failure -j "$jobs" -L core)

echo "== fuzz smoke pass (libFuzzer + ASan + UBSan): every reader, 5 s each =="
bash scripts/fuzz.sh --smoke
