#!/bin/sh
# Fitting benchmark: roadbrdf against the per-wavelength scipy.optimize.least_squares
# loop a user writes (Debian's python3-scipy; the models reimplemented in NumPy from the papers in
# bench/fit_bench_model.py, independently of the C++ code), on synthetic datasets of 2151 wavelengths
# x 400 geometries (bench/fit_bench_data.py: noise 1 % + 1e-4 sr^-1, 7 significant digits, ~9 MB),
# one thread, for three models:
#   oren-nayar                   free albedo, sigma
#   oren-nayar+torrance-sparrow  free albedo, sigma, ks, roughness; fixed both weights = 1 (not separately
#                                identifiable from albedo / ks) and ior = 1.5
#   hapke                        HG, SHOE; free w, b0, h, xi; data made with B0 0.6, h 0.08, xi -0.25 and
#                                the Hapke (2002) H function; roadbrdf fits with its default exact H,
#                                scipy with the cheaper 2002 approximation; a second roadbrdf run with
#                                --option h_function=hapke2002 fits the same model as scipy for the costs.
# For each model: the WHOLE command `roadbrdf fit DATA.csv --model M --threads 1 -o F.json` with its
# defaults (warm start, amplitude solve, covariance; reading, statistics and writing included), timed
# as process CPU (user + system; the median of 5 runs), against scipy's fit CPU from a fixed start (the model defaults of
# `roadbrdf models`, b0 0.3 for Hapke), and the final costs compared at every wavelength scipy fitted.
# Then the same-start comparison (ON+TS, --no-warm-start --no-amplitude-solve --loss plain)
# and the joint spectral fits (--shared auto: the parameters declared non-spectral are shared).
#
# Usage: bench/fit_bench.sh [BUILD_DIR] [SCIPY_STRIDE]   (defaults: build, 1; STRIDE > 1 fits every
# STRIDE-th wavelength with scipy and extrapolates its time). Timings on a shared machine are noisy.
set -eu
here=$(cd "$(dirname "$0")" && pwd)
build=${1:-$here/../build}
stride=${2:-1}
python=/usr/bin/python3
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cli="$build/roadbrdf"
onts_fix="--fix oren-nayar.weight=1 --fix torrance-sparrow.weight=1 --fix torrance-sparrow.ior=1.5"

# median_cpu RUNS COMMAND...: "CPU WALL" seconds of the median of RUNS runs (bench/cpu_time.py)
median_cpu() { $python "$here/cpu_time.py" "$@"; }
runs=5

for model in oren-nayar oren-nayar+torrance-sparrow hapke; do
  extra=""
  [ "$model" = oren-nayar+torrance-sparrow ] && extra=$onts_fix
  echo "==== $model"
  PYTHONPATH="$here" $python "$here/fit_bench_data.py" "$work/$model.csv" 2151 "$model"
  # shellcheck disable=SC2086
  whole=$(median_cpu $runs "$cli" fit "$work/$model.csv" --model "$model" $extra --threads 1 -o "$work/rb.json" |
    cut -d' ' -f1)
  echo "roadbrdf fit $model --threads 1 (defaults), whole command: $whole s CPU (median of $runs runs)"
  PYTHONPATH="$here" $python "$here/fit_bench_scipy.py" "$work/$model.csv" "$work/sp.json" "$stride" "$model"
  if [ "$model" = hapke ]; then
    whole2=$(median_cpu $runs "$cli" fit "$work/$model.csv" --model hapke --option h_function=hapke2002 --threads 1 \
      -o "$work/rb2.json" | cut -d' ' -f1)
    echo "-- roadbrdf with the exact H (default) against scipy with the 2002 H (times; costs of different models)"
    PYTHONPATH="$here" $python "$here/fit_bench_compare.py" "$work/rb.json" "$work/sp.json" "$whole"
    echo "-- roadbrdf with --option h_function=hapke2002 (the same model as scipy)"
    PYTHONPATH="$here" $python "$here/fit_bench_compare.py" "$work/rb2.json" "$work/sp.json" "$whole2"
  else
    PYTHONPATH="$here" $python "$here/fit_bench_compare.py" "$work/rb.json" "$work/sp.json" "$whole"
  fi
  # shellcheck disable=SC2086
  joint=$(median_cpu 1 "$cli" fit "$work/$model.csv" --model "$model" $extra --shared auto --threads 1 -o "$work/joint.json")
  echo "-- joint fit (--shared auto), whole command: ${joint% *} s CPU, ${joint#* } s wall"
  $python - "$work/joint.json" <<'PY'
import json, sys
f = json.load(open(sys.argv[1]))["fits"][0]
shared = ", ".join("%s %.5f" % (n, f["parameters"][n][0]) for n in f["shared"])
print("   fit %.2f s CPU, %s iterations, %s; shared %s; rmse_total %.3e sr^-1"
      % (f["cpu_seconds"], f["joint_iterations"], f["joint_status"], shared, f["rmse_total"]))
PY
  if [ "$model" = oren-nayar+torrance-sparrow ]; then
    cp "$work/$model.csv" "$work/data.csv"
    cp "$work/sp.json" "$work/sp_same.json"  # scipy's start is the same-start comparison's below
  fi
done

echo "==== oren-nayar+torrance-sparrow, same start at every wavelength"
same="--model oren-nayar+torrance-sparrow $onts_fix --start oren-nayar.albedo=0.5 --start oren-nayar.sigma=0.3 \
  --start torrance-sparrow.ks=0.5 --start torrance-sparrow.roughness=0.3 --loss plain --no-covariance"
# shellcheck disable=SC2086
"$cli" fit "$work/data.csv" $same --threads 1 --no-warm-start --no-amplitude-solve -o "$work/rb.json" > /dev/null
PYTHONPATH="$here" $python "$here/fit_bench_compare.py" "$work/rb.json" "$work/sp_same.json"
