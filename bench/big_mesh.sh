#!/bin/bash
# A mesh of about 2 million triangles (issue 15's pathological input): MESH subdivided LEVELS times (each
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

python3 - "$mesh" "$levels" "$copies" "$big" <<'EOF'
import sys
src, levels, copies, dst = sys.argv[1], int(sys.argv[2]), int(sys.argv[3]), sys.argv[4]
v, f = [], []
for line in open(src):
    p = line.split()
    if not p: continue
    if p[0] == 'v': v.append(tuple(float(x) for x in p[1:4]))
    elif p[0] == 'f':
        idx = [int(x.split('/')[0]) for x in p[1:]]
        idx = [i - 1 if i > 0 else len(v) + i for i in idx]
        for k in range(1, len(idx) - 1): f.append((idx[0], idx[k], idx[k + 1]))
for _ in range(levels):
    mid, nf = {}, []
    def m(a, b):
        key = (a, b) if a < b else (b, a)
        if key not in mid:
            mid[key] = len(v)
            v.append(tuple((x + y) / 2 for x, y in zip(v[a], v[b])))
        return mid[key]
    for a, b, c in f:
        ab, bc, ca = m(a, b), m(b, c), m(c, a)
        nf += [(a, ab, ca), (ab, b, bc), (ca, bc, c), (ab, bc, ca)]
    f = nf
lo = [min(p[i] for p in v) for i in range(3)]
hi = [max(p[i] for p in v) for i in range(3)]
step = (hi[0] - lo[0]) * 1.1
with open(dst, 'w') as o:
    for c in range(copies):
        o.writelines('v %.9g %.9g %.9g\n' % (x + c * step, y, z) for x, y, z in v)
    for c in range(copies):
        base = c * len(v) + 1
        o.writelines('f %d %d %d\n' % (a + base, b + base, cc + base) for a, b, cc in f)
print('mesh: %s subdivided %d times, %d copies: %d triangles, %d vertices' %
      (src, levels, copies, len(f) * copies, len(v) * copies))
EOF

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
