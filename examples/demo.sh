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
