#!/usr/bin/env bash
# Coverage-guided fuzzing of every reader of outside input (fuzz/): builds the libFuzzer harnesses with clang
# in build-fuzz (the core library and the harnesses only), runs each in turn, one at a time, and prints per
# harness the executions, the coverage (libFuzzer's final cov: edges and ft: features) and the findings.
#   scripts/fuzz.sh [SECONDS]     each harness SECONDS (default 60) on its saved corpus plus the inputs that
#                                 earlier runs found (build-fuzz/corpus/NAME, kept between runs)
#   scripts/fuzz.sh --smoke       each harness 5 s on the saved corpus only (the test command runs this)
#   FUZZERS="obj scene" scripts/fuzz.sh 300    only these harnesses
# Memory is bounded by the input cap: inputs of at most 64 KiB (-max_len), no single allocation above
# 64 MiB (-malloc_limit_mb, 1024 x the cap: a reader that sizes a vector from a count in the file trips it)
# and at most 1 GiB resident (-rss_limit_mb, of which ASan's shadow and quarantine take a few hundred MiB).
# An input that takes more than 5 s is a finding too (-timeout: quadratic work on long lines, deep nesting).
# A finding (crash, leak, wrong exception, refusal without the file name, memory or time limit) is saved as
# build-fuzz/findings/NAME-*; the script exits 1 if there is one. Make each a regression test in tests/.
set -euo pipefail
cd "$(dirname "$0")/.."

seconds=60
smoke=0
if [[ "${1:-}" == "--smoke" ]]; then
  smoke=1
  seconds=5
elif [[ -n "${1:-}" ]]; then
  seconds=$1
fi
fuzzers=${FUZZERS:-"obj scene trace lesson ray_files cli_values"}
max_len=65536
limits=(-max_len=$max_len -malloc_limit_mb=64 -rss_limit_mb=1024 -timeout=5)

if ! command -v clang++ > /dev/null; then
  echo "fuzz: clang++ not found: the libFuzzer harnesses are skipped (apt-get install clang)"
  exit 0
fi

# Paths below the clone hashed relative to it, as scripts/build.sh: clones in other folders share the cache.
export CCACHE_BASEDIR=${CCACHE_BASEDIR:-$PWD} CCACHE_NOHASHDIR=1
launcher=()
if command -v ccache > /dev/null; then
  launcher=(-DCMAKE_C_COMPILER_LAUNCHER=ccache -DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
fi
# -O1 (libFuzzer's usual level, with -g from the fuzz option): a cold build of the instrumented core is the
# smoke pass's main cost on a fresh machine.
CC=clang CXX=clang++ cmake -S . -B build-fuzz -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -DNDEBUG" -DCMAKE_C_FLAGS_RELWITHDEBINFO="-O1 -DNDEBUG" -DRAYSTEP_BUILD_FUZZERS=ON \
  -DRAYSTEP_BUILD_TESTS=OFF -DRAYSTEP_BUILD_BENCH=OFF -DRAYSTEP_BUILD_CLI=OFF -DRAYSTEP_BUILD_GUI=OFF \
  -DRAYSTEP_BUILD_VTK_EXPORT=OFF "${launcher[@]}" > /dev/null
targets=()
for f in $fuzzers; do targets+=("${f}_fuzz"); done
cmake --build build-fuzz -j 2 --target "${targets[@]}"

mkdir -p build-fuzz/findings build-fuzz/logs
export ASAN_OPTIONS=detect_leaks=1:quarantine_size_mb=64
export UBSAN_OPTIONS=print_stacktrace=1
status=0
printf '%-11s %8s %12s %7s %7s  %s\n' harness seconds executions cov ft findings
for f in $fuzzers; do
  dict=()
  case $f in
    scene | trace) dict=(-dict=fuzz/dict/json.dict) ;;
    *) [[ -f fuzz/dict/$f.dict ]] && dict=(-dict=fuzz/dict/$f.dict) ;;
  esac
  # libFuzzer adds what it finds to the first folder: a scratch one, so that fuzz/corpus stays as committed.
  if ((smoke)); then
    work=$(mktemp -d)
  else
    work=build-fuzz/corpus/$f
    mkdir -p "$work"
  fi
  log=build-fuzz/logs/$f.log
  before=$(ls build-fuzz/findings | grep -c "^$f-" || true)
  rc=0
  "build-fuzz/fuzz/${f}_fuzz" "${limits[@]}" "${dict[@]}" -max_total_time="$seconds" -print_final_stats=1 \
    -artifact_prefix="build-fuzz/findings/$f-" "$work" "fuzz/corpus/$f" > "$log" 2>&1 || rc=$?
  ((smoke)) && rm -rf "$work"
  after=$(ls build-fuzz/findings | grep -c "^$f-" || true)
  execs=$(grep -o 'stat::number_of_executed_units: *[0-9]*' "$log" | grep -o '[0-9]*$' || echo "?")
  cov=$(grep -o 'cov: [0-9]*' "$log" | tail -1 | grep -o '[0-9]*' || echo "?")
  ft=$(grep -o 'ft: [0-9]*' "$log" | tail -1 | grep -o '[0-9]*' || echo "?")
  found=$((after - before))
  note=$found
  if ((rc != 0 || found > 0)); then
    status=1
    note="$found (exit $rc; see $log and build-fuzz/findings/$f-*)"
  fi
  printf '%-11s %8s %12s %7s %7s  %s\n' "$f" "$seconds" "$execs" "$cov" "$ft" "$note"
done
exit $status
