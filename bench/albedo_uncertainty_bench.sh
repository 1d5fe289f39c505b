#!/usr/bin/env bash
# CPU time of `roadbrdf albedo` with and without the standard uncertainties, for 2151-band fits of
# Hapke, Ross-Li and Oren-Nayar: a sand-like Hapke BRDF (w rising from 0.25 at 350 nm to 0.65 at
# 2500 nm, B0 0.4, h 0.08, xi -0.25) simulated with 2 % + 5e-4 sr^-1 noise on 30 geometries of the
# bundled instrument grid (every third line) at 350:2500:1 nm, fitted by each model, then
# `albedo FIT --fit M --sun-zenith 0:60:30 --diffuse-fraction 0.2 --json` (black-sky at 3 zeniths,
# white-sky, blue-sky and broadband, with their uncertainties) timed by /usr/bin/time (user + system
# CPU seconds: the machine is shared, so CPU rather than wall time), on one thread (`--threads 1`,
# where the build has the option: the goal is stated for one core, and TBB's idle workers would add
# their spinning to the CPU time).
#
# Usage: bench/albedo_uncertainty_bench.sh [BUILD] [BEFORE_BUILD]
#   BUILD: the build to measure (default build); BEFORE_BUILD: another build (e.g. of the previous
#   commit) whose times are printed beside, with the largest difference of their uncertainties.
# The data and fits are kept in ${ALBEDO_BENCH_DIR:-/tmp/albedo-speed} and made once.
set -euo pipefail
cd "$(dirname "$0")/.."
build="$(cd "${1:-build}" && pwd)"
before="${2:-}"
[ -n "$before" ] && before="$(cd "$before" && pwd)"
work="${ALBEDO_BENCH_DIR:-/tmp/albedo-speed}"
mkdir -p "$work"
models=(hapke ross-li oren-nayar)

if [ ! -f "$work/sand.fit.json" ]; then
  echo "making the 2151-band data and fits in $work (once)" >&2
  awk -F, 'NR <= 2 || (NR - 3) % 3 == 0' data/examples/grid/cerema-like-grid.csv > "$work/grid30.csv"
  printf 'wavelength_nm,w\n350,0.25\n2500,0.65\n' > "$work/w.csv"
  "$build/roadbrdf" simulate hapke -p b0=0.4 -p h=0.08 -p xi=-0.25 --spectral "w=$work/w.csv" \
    --grid "$work/grid30.csv" --wavelengths 350:2500:1 --noise relative=0.02,absolute=0.0005 --seed 7 \
    -o "$work/sand.csv"
  args=()
  for m in "${models[@]}"; do args+=(--model "$m"); done
  "$build/roadbrdf" fit "$work/sand.csv" "${args[@]}" --threads 2 --quiet -o "$work/sand.fit.json" > /dev/null
fi

cpu() {  # BUILD OUT ARGS...: user + system seconds of one albedo run
  local b="$1" out="$2"
  shift 2
  local one=()
  if "$b/roadbrdf" albedo --help | grep -q -- --threads; then one=(--threads 1); fi
  /usr/bin/time -f "%U %S" -o "$work/time" "$b/roadbrdf" albedo "$work/sand.fit.json" --sun-zenith 0:60:30 \
    --diffuse-fraction 0.2 --json --quiet -o "$out" "${one[@]}" "$@" 2> "$work/stderr"
  awk '{printf "%.2f", $1 + $2}' "$work/time"
}

printf '%-11s %12s %12s' model "values [s]" "with u [s]"
[ -n "$before" ] && printf ' %18s %18s %12s' "before values [s]" "before with u [s]" "max |du|/u"
printf '\n'
for m in "${models[@]}"; do
  values=$(cpu "$build" "$work/$m-values.json" --fit "$m" --no-uncertainty)
  with=$(cpu "$build" "$work/$m.json" --fit "$m")
  printf '%-11s %12s %12s' "$m" "$values" "$with"
  if [ -n "$before" ]; then
    # The build before may lack --no-uncertainty: its values-only time is then that of --wavelengths
    # (uncertainties are given at the fit's own wavelengths only).
    if "$before/roadbrdf" albedo --help | grep -q -- --no-uncertainty; then
      b_values=$(cpu "$before" "$work/$m-before-values.json" --fit "$m" --no-uncertainty)
    else
      b_values=$(cpu "$before" "$work/$m-before-values.json" --fit "$m" --wavelengths 350:2500:1)
    fi
    b_with=$(cpu "$before" "$work/$m-before.json" --fit "$m")
    diff=$(/usr/bin/python3 - "$work/$m.json" "$work/$m-before.json" <<'PY'
import json, math, sys
a, b = (json.load(open(p))["uncertainty"] for p in sys.argv[1:3])
worst = 0.0
def walk(x, y):
    global worst
    if isinstance(x, list):
        for p, q in zip(x, y):
            walk(p, q)
    elif isinstance(x, (int, float)) and isinstance(y, (int, float)) and y > 0:
        worst = max(worst, abs(x - y) / y)
for key in ("black_sky", "white_sky", "blue_sky"):
    if a and b and a.get(key) is not None:
        walk(a[key], b[key])
print("%.2e" % worst)
PY
)
    printf ' %18s %18s %12s' "$b_values" "$b_with" "$diff"
  fi
  printf '\n'
done
