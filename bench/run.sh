#!/usr/bin/env bash
# Run every benchmark program in BUILD/bench (default build/) on one core, then the comparison and
# end-to-end scripts (bench/fit_bench.sh, bench/render_speed.sh), and print the figures.
# Usage: bash bench/run.sh [BUILD]
set -euo pipefail
build="${1:-build}"
for b in "$build"/bench/*_bench; do
  [ -x "$b" ] || continue
  echo "== $(basename "$b")"
  taskset -c 0 "$b" --benchmark_min_time=0.2 || "$b" --benchmark_min_time=0.2
done
for s in bench/*_bench.sh; do
  [ -f "$s" ] || continue
  echo "== $(basename "$s")"
  bash "$s" "$build"
done
echo "== render_speed.sh (virtual gonioreflectometer, 432 geometries x 20 bands at 1 %)"
bash bench/render_speed.sh "$build"
