#!/bin/sh
# Fitting benchmark (issue 4): the same synthetic dataset (2151 wavelengths x 400 geometries,
# oren-nayar+torrance-sparrow, noise 1 % + 1e-4 sr^-1) fitted per wavelength by plain least squares
# from the same start with roadbrdf (1 thread) and with scipy.optimize.least_squares (Debian's
# python3-scipy, NumPy reimplementation of the same formulas in bench/fit_bench_model.py), then
# the joint spectral fit (shared sigma and roughness).
#
# Free parameters: oren-nayar.albedo, oren-nayar.sigma, torrance-sparrow.ks, torrance-sparrow.roughness;
# fixed: both composite weights = 1 (not separately identifiable from albedo / ks) and ior = 1.5.
# Start: albedo 0.5, sigma 0.3, ks 0.5, roughness 0.3 at every wavelength (roadbrdf: --no-warm-start
# --no-amplitude-solve, so both programs start from exactly the same point; a second roadbrdf run
# shows the defaults, warm start + amplitude solve).
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
common="--model oren-nayar+torrance-sparrow --fix oren-nayar.weight=1 --fix torrance-sparrow.weight=1 \
  --fix torrance-sparrow.ior=1.5 --start oren-nayar.albedo=0.5 --start oren-nayar.sigma=0.3 \
  --start torrance-sparrow.ks=0.5 --start torrance-sparrow.roughness=0.3 --loss plain --no-covariance"

echo "== generating 2151 x 400 synthetic dataset"
PYTHONPATH="$here" $python "$here/fit_bench_data.py" "$work/data.csv"

echo "== roadbrdf, 1 thread, same start at every wavelength"
/usr/bin/time -f "roadbrdf wall %e s (incl. reading the CSV), max RSS %M kB" \
  "$cli" fit "$work/data.csv" $common --threads 1 --no-warm-start --no-amplitude-solve -o "$work/rb.json"

echo "== roadbrdf, 1 thread, defaults (warm start + amplitude solve), with covariance"
/usr/bin/time -f "roadbrdf wall %e s" \
  "$cli" fit "$work/data.csv" $(echo $common | sed 's/--no-covariance//') --threads 1 -o "$work/rb_warm.json"

echo "== scipy.optimize.least_squares (stride $stride)"
PYTHONPATH="$here" $python "$here/fit_bench_scipy.py" "$work/data.csv" "$work/sp.json" "$stride"

echo "== comparison (same start)"
PYTHONPATH="$here" $python "$here/fit_bench_compare.py" "$work/rb.json" "$work/sp.json"
echo "== comparison (roadbrdf defaults)"
PYTHONPATH="$here" $python "$here/fit_bench_compare.py" "$work/rb_warm.json" "$work/sp.json"

echo "== roadbrdf joint spectral fit (shared oren-nayar.sigma, torrance-sparrow.roughness), 1 thread"
/usr/bin/time -f "roadbrdf joint wall %e s (incl. reading the CSV)" \
  "$cli" fit "$work/data.csv" $common --shared oren-nayar.sigma,torrance-sparrow.roughness --threads 1 \
  -o "$work/joint.json"
$python - "$work/joint.json" <<'PY'
import json, sys
f = json.load(open(sys.argv[1]))["fits"][0]
print("joint: fit %.2f s, %s iterations, %s; sigma %.5f rad, roughness %.5f, rmse_total %.3e sr^-1"
      % (f["seconds"], f["joint_iterations"], f["joint_status"], f["parameters"]["oren-nayar.sigma"][0],
         f["parameters"]["torrance-sparrow.roughness"][0], f["rmse_total"]))
PY
