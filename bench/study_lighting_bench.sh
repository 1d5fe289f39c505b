#!/usr/bin/env bash
# Wall and CPU time of a fast design study with lighting predictions (docs/studies.md "Lighting predictions"):
# examples/studies/F1-limestone-lighting.json as a Latin hypercube of COUNT candidates (default 1000) x its two
# mixing methods (areal, mastic), each candidate's mixture through the EN 13201 calculation of
# data/examples/lighting/two-lane-road.json, with WORKERS local processes (default 2, the local executor, no Dask),
# from an empty results store. Makes the component fits (examples/fit_components.sh) when data/examples/fits/
# lacks them. Not a test: the figure depends on the machine and its load.
# Usage: bench/study_lighting_bench.sh [BUILD] [COUNT] [WORKERS]
set -euo pipefail
cd "$(dirname "$0")/.."
build="$(cd "${1:-build}" && pwd)"
count="${2:-1000}"
workers="${3:-2}"
if [ ! -f data/examples/fits/soreze-limestone.fit.json ]; then
  echo "making the component fits (examples/fit_components.sh)" >&2
  bash examples/fit_components.sh "$build" data/examples/fits > /dev/null
fi
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
/usr/bin/python3 - "$work" "$count" <<'PY'
import json, os, sys
work, count = sys.argv[1], int(sys.argv[2])
here = os.path.abspath("examples/studies")
s = json.load(open(os.path.join(here, "F1-limestone-lighting.json")))
s["base"] = os.path.join(here, s["base"])
for entry in s["library"].values():
    entry["fit"] = os.path.join(here, entry["fit"])
s["predictions"]["lighting"]["installation"] = os.path.join(here, s["predictions"]["lighting"]["installation"])
s["design"]["count"] = count
json.dump(s, open(os.path.join(work, "study.json"), "w"))
PY
TIMEFORMAT="%R s wall, %U s user + %S s system CPU"
echo "roadbrdf study: $count candidates x 2 methods with lighting predictions, $workers local workers" >&2
time "$build/roadbrdf" study "$work/study.json" -o "$work/out.csv" --store "$work/store.jsonl" --workers "$workers" \
    --quiet
/usr/bin/python3 - "$work/store.jsonl" "$work/out.csv" <<'PY'
import csv, json, statistics, sys
lines = list(open(sys.argv[1]))[1:]
print(f"tasks: {len(lines)}, median CPU per task (2 methods, without start-up): "
      f"{statistics.median(json.loads(l)['cpu_seconds'] for l in lines) * 1000:.1f} ms")
rows = list(csv.DictReader(open(sys.argv[2])))
failed = sum(r["status"] != "ok" for r in rows)
print(f"rows: {len(rows)}, failed: {failed}")
PY
echo "load average: $(cut -d' ' -f1-3 /proc/loadavg)"
