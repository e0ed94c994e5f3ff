#!/usr/bin/env bash
# Instruction counts of the grid traversal with the null recorder, a hook-free copy, and the counting
# recorder (callgrind counts instructions, stable on a noisy machine). Usage: scripts/callgrind-recorders.sh [MESH]
set -euo pipefail
cd "$(dirname "$0")/.."
mesh=${1:-../shared/meshes/stanford-bunny.obj}
exe=build/bench/raystep_grid_instructions
[ -x "$exe" ] || { echo "build first: scripts/build.sh"; exit 1; }
tmp=$(mktemp -d)
for v in hookfree null counting; do
  valgrind --tool=callgrind --instr-atstart=no --callgrind-out-file="$tmp/$v.out" "$exe" "$v" "$mesh" >/dev/null 2>"$tmp/$v.err"
  ir=$(grep -E '^totals:' "$tmp/$v.out" | head -1 | awk '{print $2}')
  printf '%-9s %15s instructions\n' "$v" "$ir"
done
rm -rf "$tmp"
