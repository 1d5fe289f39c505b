#!/usr/bin/env bash
# Candidates per second of `roadbrdf study` on the fast path (examples/studies/F1-limestone.json as a Latin
# hypercube of FAST candidates x 2 mixing methods, about 15 ms of CPU each: enough of them that the start-up, 1-4 s,
# does not hide the speed-up of a second worker) and the physical path (examples/studies/F4-coarse-physical.json cut
# to PHYSICAL candidates, about 0.45 s each), with 1 and 2 local workers, and the speed-up of 2 workers next to
# that of a pure CPU loop (what the machine offers two processes at the time); every run starts from an empty
# results store. Makes the component fits (examples/fit_components.sh) when
# data/examples/fits/ lacks them.
# Usage: bench/study_bench.sh [BUILD] [PHYSICAL] [FAST]   (defaults: build, 16, 1000)
set -euo pipefail
cd "$(dirname "$0")/.."
build="$(cd "${1:-build}" && pwd)"
physical="${2:-16}"
fast="${3:-1000}"
if [ ! -f data/examples/fits/mastic-soreze-synthetic.fit.json ]; then
  echo "making the component fits (examples/fit_components.sh)" >&2
  bash examples/fit_components.sh "$build" data/examples/fits > /dev/null
fi
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
# The fast study with FAST candidates; the physical study cut to PHYSICAL candidates: its first design point
# (Gouraudiere 6/10, 15 % mastic) as PHYSICAL replicates (other virtual samples, other seeds: distinct tasks of the
# same cost). Paths made absolute, the copies being in another folder.
/usr/bin/python3 - "$work" "$physical" "$fast" <<'PY'
import json, os, sys
work, n, fast = sys.argv[1], int(sys.argv[2]), int(sys.argv[3])
here = os.path.abspath("examples/studies")


def load(name):
    s = json.load(open(os.path.join(here, name)))
    s["base"] = os.path.join(here, s["base"])
    for entry in s["library"].values():
        entry["fit"] = os.path.join(here, entry["fit"])
    return s


s = load("F1-limestone.json")
s["design"]["count"] = fast
json.dump(s, open(os.path.join(work, "fast.json"), "w"))
s = load("F4-coarse-physical.json")
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
  if ! cpu=$( { time "$build/roadbrdf" study "$1" -o "$work/out.csv" --store "$work/store-$3-$2.jsonl" \
                  --workers "$2" --quiet 2> "$work/err" ; } 2>&1 ); then
    cat "$work/err" >&2
    exit 1
  fi
  end=$(date +%s.%N)
  # The median CPU time of a task (cpu_seconds in the store: the task alone, without the start-up).
  task=$(/usr/bin/python3 -c 'import json, statistics, sys
print(statistics.median(json.loads(l)["cpu_seconds"] for l in list(open(sys.argv[1]))[1:]))' "$work/store-$3-$2.jsonl")
  awk -v n="$(grep -c . "$work/store-$3-$2.jsonl")" -v t0="$start" -v t1="$end" -v w="$2" -v l="$3" -v cpu="$cpu" \
      -v task="$task" \
    'BEGIN { c = n - 1; split(cpu, u, " "); printf "%-9s workers %d: %4d candidates in %7.2f s = %7.3f candidates/s (CPU %.3f s per candidate, task median %.3f s)\n", l, w, c, t1 - t0, c / (t1 - t0), (u[1] + u[2]) / c, task }' \
    | tee -a "$work/lines"
}
speedup() {  # LABEL: candidates/s with 2 workers over 1
  awk -v l="$1" '$1 == l { rate[$3] = $10 } END { printf "%-9s speed-up of 2 workers: %.2f\n", l, rate["2:"] / rate["1:"] }' \
    "$work/lines"
}
# What the machine gives 2 processes now (a shared machine may give less than 2 cores): the same 1-vs-2 ratio for
# a pure CPU loop (4 chunks of about 0.5 s on 1, then 2, processes).
/usr/bin/python3 - <<'PY'
import multiprocessing, time


def spin(n):
    s = 0
    for i in range(n):
        s += i * i
    return s


if __name__ == "__main__":
    wall = {}
    for w in (1, 2):
        with multiprocessing.Pool(w) as pool:
            t = time.perf_counter()
            pool.map(spin, [8_000_000] * 4)
            wall[w] = time.perf_counter() - t
    print(f"baseline  speed-up of 2 processes on a CPU loop: {wall[1] / wall[2]:.2f}")
PY
for w in 1 2; do run "$work/fast.json" "$w" fast; done
speedup fast
for w in 1 2; do run "$work/physical.json" "$w" physical; done
speedup physical
