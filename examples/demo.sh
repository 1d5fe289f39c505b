#!/usr/bin/env bash
# roadbrdf demo: the main job on the bundled example data. Run by `make demo`.
# Usage: bash examples/demo.sh [BUILD]
set -euo pipefail
cd "$(dirname "$0")/.."
build="${1:-build}"
rb="$build/roadbrdf"
out="$build/demo"
mkdir -p "$out"

section() { printf '\n==== %s\n' "$*"; }

section "1. The model library: BRDF [sr^-1] of every model at the report's parameter sets"
geometries=examples/demo-geometries.csv
labels=$(grep -v '^#' "$geometries" | tail -n +2 | cut -d, -f5 | paste -sd' ')
printf '%-34s' "parameter set"; for l in $labels; do printf '%11s' "$l"; done; echo
evaluate_row() {  # label model args...
  local label="$1" model="$2"; shift 2
  printf '%-34s' "$label"
  "$rb" eval "$model" "$@" --geometry "$geometries" | grep -v '^#' | tail -n +2 | awk -F, '{printf "%11.4g", $NF}'
  echo
}
while IFS='|' read -r label model args; do
  case "$label" in \#*|'') continue ;; esac
  label="$(echo "$label" | sed 's/ *$//')"; model="$(echo "$model" | tr -d ' ')"
  # shellcheck disable=SC2086
  evaluate_row "$label" "$model" $args
done < examples/report-parameter-sets.txt
for model in $("$rb" models --json | /usr/bin/python3 -c 'import json,sys; print(" ".join(m["name"] for m in json.load(sys.stdin)))'); do
  evaluate_row "$model (defaults)" "$model"
done

section "2. Measurements: quality check of a measured sample and calibration with a real Spectralon panel"
"$rb" check data/examples/mixed/F1.csv | head -n 25
"$rb" calibrate data/examples/calibration/sample-radiance.csv \
    --reference data/examples/calibration/reference-radiance.csv --dark data/examples/calibration/dark.csv \
    --panel-reflectance data/third-party/spectralon/Spectralon_Num4.txt -o "$out/soreze-calibrated.csv"
echo "calibrated BRDF written to $out/soreze-calibrated.csv"

section "3. Fitting every single-material sample and mastic (models ranked by BIC)"
mkdir -p "$out/fits" "$out/formulations"
fit_sample() {  # name file
  local name="$1" file="$2"
  echo "-- $name"
  "$rb" fit "$file" --model oren-nayar --model oren-nayar+torrance-sparrow --model hapke \
      --fix oren-nayar.weight=1 --fix torrance-sparrow.weight=1 --multistart 8 -o "$out/fits/$name.fit.json" 2>/dev/null \
      | sed -n '2,99p'
}
for f in data/examples/single/*.csv data/examples/mastics/*.csv; do
  fit_sample "$(basename "$f" .csv)" "$f"
done
for k in 1 2 3 4; do
  "$rb" fit "data/examples/mixed/F$k.csv" --model oren-nayar+torrance-sparrow \
      --fix oren-nayar.weight=1 --fix torrance-sparrow.weight=1 --multistart 8 -o "$out/fits/F$k-measured.fit.json" >/dev/null 2>&1
done

section "4. Mixing: predicting F1-F4 from their components, compared with the measured mixtures"
cp data/examples/formulations/F*.json "$out/formulations/"
for k in 1 2 3 4; do
  echo "-- F$k"
  "$rb" mix "$out/formulations/F$k.json" --data "data/examples/mixed/F$k.csv" --method all \
      --reference "$out/fits/F$k-measured.fit.json" -o "$out/F$k.mix.json" 2>/dev/null
done
