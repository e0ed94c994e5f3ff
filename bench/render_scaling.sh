#!/bin/bash
# Rendering scales with cores (the goal: 2 threads >= 1.8x one thread on a 512x512 render).
# Renders SCENE at 512x512 with 1 and 2 threads, interleaved, REPS times each, and prints the median render
# times (the `time: ... render X ms` line of `raystep render`) and their ratio. Needs a quiet machine: other
# processes on the same cores make the 2-thread time meaningless.
#   bench/render_scaling.sh [RAYSTEP] [SCENE] [REPS] [extra render options, e.g. --aa jitter:2]
set -euo pipefail
here=$(cd "$(dirname "$0")/.." && pwd)
raystep=${1:-$here/build/cli/raystep}
scene=${2:-$here/scenes/cornell.json}
reps=${3:-5}
shift $(( $# < 3 ? $# : 3 ))
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
for ((i = 0; i < reps; ++i)); do
  for t in 1 2; do
    ms=$("$raystep" render "$scene" --threads "$t" --size 512x512 "$@" -o "$out/t$t.png" |
         sed -n 's/.*render \([0-9.]*\) ms.*/\1/p')
    echo "$t $ms"
  done
done | python3 -c '
import statistics, sys
times = {"1": [], "2": []}
for line in sys.stdin:
    threads, ms = line.split()
    times[threads].append(float(ms))
one, two = statistics.median(times["1"]), statistics.median(times["2"])
print("1 thread:  %s ms, median %.1f" % (times["1"], one))
print("2 threads: %s ms, median %.1f" % (times["2"], two))
print("speed-up: %.2fx" % (one / two))'
