#!/usr/bin/env bash
# Candidates per second of `roadbrdf study` on the fast path (examples/studies/F3-tio2.json: 20 candidates x 2
# mixing methods) and the physical path (examples/studies/F4-coarse-physical.json, first PHYSICAL candidates),
# with 1 and 2 local workers; every run starts from an empty results store. Makes the component fits
# (examples/fit_components.sh) when data/examples/fits/ lacks them.
# Usage: bench/study_bench.sh [BUILD] [PHYSICAL]   (defaults: build, 4)
set -euo pipefail
cd "$(dirname "$0")/.."
build="$(cd "${1:-build}" && pwd)"
physical="${2:-4}"
if [ ! -f data/examples/fits/mastic-soreze-synthetic.fit.json ]; then
  echo "making the component fits (examples/fit_components.sh)" >&2
  bash examples/fit_components.sh "$build" data/examples/fits > /dev/null
fi
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
# The physical study cut to PHYSICAL candidates: its first design point (Gouraudiere 6/10, 15 % mastic) as
# PHYSICAL replicates (other virtual samples, other seeds: distinct tasks of the same cost).
/usr/bin/python3 - "$work" "$physical" <<'PY'
import json, os, sys
work, n = sys.argv[1], int(sys.argv[2])
s = json.load(open("examples/studies/F4-coarse-physical.json"))
here = os.path.abspath("examples/studies")
s["base"] = os.path.join(here, s["base"])
for entry in s["library"].values():
    entry["fit"] = os.path.join(here, entry["fit"])
for v in s["variables"]:
    key = "choices" if "choices" in v else "values"
    v[key] = v[key][:1]
s["replicates"] = n
json.dump(s, open(os.path.join(work, "physical.json"), "w"))
PY
run() {  # STUDY WORKERS LABEL: wall time, and CPU time (user + system of the program and its workers)
  local start end cpu
  TIMEFORMAT="%U %S"
  start=$(date +%s.%N)
  cpu=$( { time "$build/roadbrdf" study "$1" -o "$work/out.csv" --store "$work/store-$3-$2.jsonl" --workers "$2" \
             --quiet 2> "$work/err" ; } 2>&1 )
  end=$(date +%s.%N)
  awk -v n="$(grep -c . "$work/store-$3-$2.jsonl")" -v t0="$start" -v t1="$end" -v w="$2" -v l="$3" -v cpu="$cpu" \
    'BEGIN { c = n - 1; split(cpu, u, " "); printf "%-9s workers %d: %3d candidates in %7.2f s = %7.3f candidates/s (CPU %.2f s per candidate)\n", l, w, c, t1 - t0, c / (t1 - t0), (u[1] + u[2]) / c }'
}
for w in 1 2; do run examples/studies/F3-tio2.json "$w" fast; done
for w in 1 2; do run "$work/physical.json" "$w" physical; done
