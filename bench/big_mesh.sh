#!/bin/bash
# A mesh of about 2 million triangles (the pathological input of bench/README.md, "Memory and big inputs"): MESH subdivided LEVELS times (each
# triangle into 4 at its edges' midpoints, shared between neighbours so the surface stays watertight), then
# COPIES copies side by side, written to /tmp (never committed). Then, one thread: builds and casts 65,536
# camera and 65,536 random rays with each structure in STRUCTS (`raystep cast`: build and trace times, max RSS
# from /usr/bin/time -v), checks that every structure gives the same hits as the first one, and that the first
# agrees with brute force on the first BRUTE rays of each set.
#   bench/big_mesh.sh [RAYSTEP] [MESH] [LEVELS] [COPIES] [STRUCTS] [BRUTE]
#   defaults: build/cli/raystep, the bunny (69,451 triangles), 2 levels, 2 copies (2,222,432), "kd bvh", 256
set -euo pipefail
here=$(cd "$(dirname "$0")/.." && pwd)
raystep=${1:-$here/build/cli/raystep}
mesh=${2:-/work/shared/meshes/stanford-bunny.obj}
levels=${3:-2}
copies=${4:-2}
structs=${5:-kd bvh}
brute=${6:-256}
out=$(mktemp -d /tmp/big_mesh.XXXXXX)
trap 'rm -rf "$out"' EXIT
big=$out/big.obj

python3 "$here/scripts/make_big_mesh.py" --levels "$levels" --copies "$copies" --out "$big" "$mesh"

for kind in camera random; do
  if [ $kind = camera ]; then size=(--size 256x256); else size=(--count 65536 --seed 3); fi
  "$raystep" rays "$big" --kind $kind "${size[@]}" -o "$out/$kind.rays" > /dev/null
  first=""
  for s in $structs; do
    /usr/bin/time -v "$raystep" cast "$big" --accel "$s" --threads 1 --reps 1 --rays "$out/$kind.rays" \
      --hits "$out/$kind.$s.hits" > "$out/log" 2> "$out/time"
    rss=$(sed -n 's/.*Maximum resident set size (kbytes): //p' "$out/time")
    echo "$kind $s: $(grep -o 'hits: [0-9]* of [0-9]* rays' "$out/log"), $(grep -o 'build_ms=.*' "$out/log"),\
 max RSS $((rss / 1024)) MB"
    if [ -z "$first" ]; then
      first=$s
    elif cmp -s "$out/$kind.$first.hits" "$out/$kind.$s.hits"; then
      echo "  $s: the same hits as $first, all 65,536 rays"
    else
      echo "  $s: DIFFERENT hits from $first"
    fi
  done
  # brute force on a prefix of the rays (32 bytes per ray, 8 bytes per hit)
  head -c $((brute * 32)) "$out/$kind.rays" > "$out/sub.rays"
  "$raystep" cast "$big" --accel brute --threads 1 --reps 1 --rays "$out/sub.rays" --hits "$out/sub.hits" \
    > /dev/null
  if cmp -s "$out/sub.hits" <(head -c $((brute * 8)) "$out/$kind.$first.hits"); then
    echo "  brute force: the same hits as $first on the first $brute rays"
  else
    echo "  brute force: DIFFERENT hits from $first on the first $brute rays"
  fi
done
