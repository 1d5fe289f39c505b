#!/bin/sh
# The fit speed goal as a user measures it: the WHOLE command `roadbrdf fit DATA.csv --model M --threads 1
# -o F.json` (process CPU, user + system, median of 5 runs by bench/cpu_time.py) against the plain
# per-wavelength scipy loop (bench/fit_bench_plain.py: least_squares, method 'trf', 2-point Jacobian, the
# same plain start at every wavelength; Debian's python3-scipy), the same model on both sides, on the
# synthetic 2151-wavelength x 400-geometry datasets of bench/fit_bench_data.py:
#   hapke         HG, SHOE, 2002 H (roadbrdf: --option h_function=hapke2002); data B0 0.6 (interior optimum)
#   hapke-bound   the same model; data B0 1, the upper bound of its range: half the wavelengths' optima
#                 lie on the bound, as in fits of real sands
#   oren-nayar    albedo, sigma
# and the final costs compared at every wavelength scipy fitted (bench/fit_bench_compare.py: the ratio of
# the scipy loop's CPU to the whole roadbrdf command's).
#
# Usage: bench/fit_bench_plain.sh [BUILD_DIR] [SCIPY_STRIDE]   (defaults: build, 1; STRIDE > 1 fits every
# STRIDE-th wavelength with scipy and extrapolates its time). Timings on a shared machine are noisy.
set -eu
here=$(cd "$(dirname "$0")" && pwd)
build=${1:-$here/../build}
stride=${2:-1}
python=/usr/bin/python3
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cli="$build/roadbrdf"
runs=5

for data in hapke hapke-bound oren-nayar; do
  echo "==== $data"
  model=${data%-bound}
  option=""
  [ "$model" = hapke ] && option="--option h_function=hapke2002"
  PYTHONPATH="$here" $python "$here/fit_bench_data.py" "$work/$data.csv" 2151 "$data"
  # shellcheck disable=SC2086
  whole=$($python "$here/cpu_time.py" $runs "$cli" fit "$work/$data.csv" --model "$model" $option --threads 1 \
    -o "$work/rb.json" | cut -d' ' -f1)
  echo "roadbrdf fit $model $option --threads 1, whole command: $whole s CPU (median of $runs runs)"
  PYTHONPATH="$here" $python "$here/fit_bench_plain.py" "$work/$data.csv" "$work/sp.json" "$data" "$stride"
  PYTHONPATH="$here" $python "$here/fit_bench_compare.py" "$work/rb.json" "$work/sp.json" "$whole"
done
