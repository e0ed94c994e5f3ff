#!/usr/bin/env bash
# The one test command: install dependencies, build everything (Release), run every test, then build the core
# tests with AddressSanitizer + UndefinedBehaviorSanitizer and run them again, then build the concurrency tests
# with ThreadSanitizer (clang) and run them, then run every fuzz harness for a few seconds on its saved corpus
# (scripts/fuzz.sh --smoke; skipped without clang).
set -euo pipefail
cd "$(dirname "$0")/.."
jobs=$(nproc 2>/dev/null || echo 2)

bash scripts/setup.sh
# ccache, as scripts/build.sh uses it; looked for after the setup, which installs it on a fresh machine (so
# that the first run's sanitizer builds fill the cache for the next run too).
launcher=()
if command -v ccache > /dev/null; then
  launcher=(-DCMAKE_C_COMPILER_LAUNCHER=ccache -DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
  export CCACHE_BASEDIR="$PWD" CCACHE_NOHASHDIR=1  # clones in other folders share the cache
fi
bash scripts/build.sh
(cd build && ctest --output-on-failure -j "$jobs")

echo "== sanitizer pass (ASan + UBSan): core tests =="
# -O1 and line tables (-g1): a third less to compile than -O2 -g, and every report still names file and line;
# the biggest batteries run a quarter of their rays here (tests/core/test_budget.h).
cmake -S . -B build-asan -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DRAYSTEP_SANITIZE=ON "${launcher[@]}" \
  -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g1 -DNDEBUG" -DCMAKE_C_FLAGS_RELWITHDEBINFO="-O1 -g1 -DNDEBUG" \
  -DRAYSTEP_BUILD_BENCH=OFF -DRAYSTEP_BUILD_CLI=OFF -DRAYSTEP_BUILD_GUI=OFF > /dev/null
cmake --build build-asan -j "$jobs" --target raystep_core_tests
(cd build-asan && ASAN_OPTIONS=detect_leaks=1 UBSAN_OPTIONS=print_stacktrace=1 \
  ctest --output-on-failure -j "$jobs" -L core)

echo "== thread sanitizer pass (TSan, clang): the concurrency tests and the planted races =="
cmake -S . -B build-tsan -G Ninja -DCMAKE_BUILD_TYPE=Release -DRAYSTEP_TSAN=ON "${launcher[@]}" \
  -DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++ -DRAYSTEP_BUILD_BENCH=OFF -DRAYSTEP_BUILD_CLI=OFF \
  -DRAYSTEP_BUILD_GUI=OFF -DRAYSTEP_BUILD_VTK_EXPORT=OFF > /dev/null
cmake --build build-tsan -j "$jobs" --target raystep_concurrency_tests raystep_tsan_canary
# clang 14's TSan cannot place its shadow memory on kernels with more than 28 bits of mmap randomisation
# (vm.mmap_rnd_bits); the tests run without address randomisation where the system allows it.
norandom=()
if setarch "$(uname -m)" -R true 2> /dev/null; then norandom=(setarch "$(uname -m)" -R); fi
(cd build-tsan && "${norandom[@]}" ctest --output-on-failure -j "$jobs" -L concurrency)

echo "== fuzz smoke pass (libFuzzer + ASan + UBSan): every reader, 5 s each =="
bash scripts/fuzz.sh --smoke
