#!/bin/sh
# Fitting benchmark of every registered model (target: no model below 10x): roadbrdf against the
# per-wavelength scipy.optimize.least_squares loop a user writes, as bench/fit_bench.sh does for oren-nayar,
# oren-nayar+torrance-sparrow and hapke, for the other models too. The NumPy models are written from the
# papers (bench/fit_bench_model.py, bench/fit_bench_model_more.py), independently of the C++ code; the data
# (bench/fit_bench_data.py: 2151 wavelengths x 400 geometries, noise 1 % + 1e-4 sr^-1, 7 significant digits),
# the free parameters, the fixed ones and scipy's start (the model defaults) per model are in
# bench/fit_bench_cases.py. For each model: the WHOLE command `roadbrdf fit DATA.csv --model M [--fix ...]
# --threads 1 -o F.json` with its defaults, process CPU, median of 5 runs (bench/cpu_time.py), against
# scipy's fit CPU (every STRIDE-th wavelength, extrapolated), and the final costs compared at every
# wavelength scipy fitted (bench/fit_bench_compare.py). A summary line per model at the end. The NumPy models
# are checked against `roadbrdf eval` first (bench/fit_bench_check_models.py).
#
# Usage: bench/fit_bench_all.sh [BUILD_DIR] [SCIPY_STRIDE] [MODEL...]   (defaults: build, 1, every model;
# the stride can be given per model as MODEL:STRIDE, e.g. kelemen-szirmay-kalos:50: its scipy loop takes
# ~20 min CPU at stride 1, the others 2-15 s)
set -eu
here=$(cd "$(dirname "$0")" && pwd)
build=${1:-$here/../build}
stride=${2:-1}
if [ $# -ge 2 ]; then shift 2; else shift $#; fi
models=${*:-"lambert oren-nayar ashikhmin-shirley simonot lafortune torrance-sparrow kelemen-szirmay-kalos burley \
retro-phong ross-li hapke oren-nayar+torrance-sparrow"}
python=/usr/bin/python3
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cli="$build/roadbrdf"
runs=5
: > "$work/summary"
# The NumPy models against `roadbrdf eval` first (bench/fit_bench_check_models.py): a convention mismatch stops here.
PYTHONPATH="$here" $python "$here/fit_bench_check_models.py" "$cli"

for spec in $models; do
  model=${spec%%:*}
  s=$stride
  [ "$spec" != "$model" ] && s=${spec#*:}
  case $model in
    oren-nayar+torrance-sparrow)
      fix="--fix oren-nayar.weight=1 --fix torrance-sparrow.weight=1 --fix torrance-sparrow.ior=1.5" ;;
    oren-nayar | hapke) fix="" ;;
    *) fix=$(PYTHONPATH="$here" $python "$here/fit_bench_cases.py" fix "$model") ;;
  esac
  echo "==== $model $fix"
  PYTHONPATH="$here" $python "$here/fit_bench_data.py" "$work/data.csv" 2151 "$model"
  head -1 "$work/data.csv"
  # shellcheck disable=SC2086
  whole=$($python "$here/cpu_time.py" $runs "$cli" fit "$work/data.csv" --model "$model" $fix --threads 1 \
    -o "$work/rb.json" | cut -d' ' -f1)
  echo "roadbrdf fit $model --threads 1 (defaults), whole command: $whole s CPU (median of $runs runs)"
  PYTHONPATH="$here" $python "$here/fit_bench_scipy.py" "$work/data.csv" "$work/sp.json" "$s" "$model"
  PYTHONPATH="$here" $python "$here/fit_bench_compare.py" "$work/rb.json" "$work/sp.json" "$whole"
  $python - "$work/rb.json" "$work/sp.json" "$whole" "$model" >> "$work/summary" <<'PY'
import json, sys
rb = json.load(open(sys.argv[1]))["fits"][0]
sp = json.load(open(sys.argv[2]))
whole = float(sys.argv[3])
index = {round(w, 6): i for i, w in enumerate(rb["wavelengths"])}
rel = [(rb["cost"][index[round(w, 6)]] - c) / c for w, c in zip(sp["wavelengths"], sp["cost"])]
worse = sum(r > 1e-6 for r in rel)
c_sp = sp["cpu_seconds"] * sp.get("stride", 1)
print("%-28s scipy %8.2f s (stride %d)  roadbrdf %.3f s  ratio %6.1fx  worse %d of %d, max excess %.1e, "
      "total cost rb/sp - 1 = %.1e"
      % (sys.argv[4], c_sp, sp.get("stride", 1), whole, c_sp / whole, worse, len(rel), max(rel),
         sum(rb["cost"][index[round(w, 6)]] for w in sp["wavelengths"]) / sum(sp["cost"]) - 1.0))
PY
done
echo "==== summary (scipy fit CPU, extrapolated; roadbrdf whole command CPU, median of $runs)"
cat "$work/summary"
