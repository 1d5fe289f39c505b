#!/usr/bin/env bash
# Wall time and peak memory of `roadbrdf report` and of each `roadbrdf plot` kind on a 2151-band sample
# (goal: the report with five models under 8 s, each figure under 1.5 s and 150 MB).
#
# The sample: a sand-like Hapke BRDF (w rising from 0.25 at 350 nm to 0.65 at 2500 nm, B0 0.4, h 0.08,
# xi -0.25) simulated with 2 % + 5e-4 sr^-1 noise on 30 geometries of the bundled instrument grid (every
# third line) at 350:2500:1 nm, as bench/albedo_uncertainty_bench.sh makes it. The report fits five models
# (lambert, oren-nayar, hapke, ross-li, lambert+torrance-sparrow); the figures read a fit file of those
# models and its albedo / r-table JSON, made once and not timed.
# Each command is timed by /usr/bin/time -v: wall ("Elapsed") and the peak resident set ("Maximum resident
# set size") of the process tree's largest process (roadbrdf runs python3, which does the work).
#
# Usage: bench/report_bench.sh [BUILD] [REPEATS]   (default build, 1; with REPEATS > 1 the median wall
# and the largest RSS of the repeats are printed). Data kept in ${REPORT_BENCH_DIR:-/tmp/report-speed}.
# The machine is shared: wall times depend on the load (printed with the results).
set -euo pipefail
cd "$(dirname "$0")/.."
build="$(cd "${1:-build}" && pwd)"
repeats="${2:-1}"
work="${REPORT_BENCH_DIR:-/tmp/report-speed}"
rb="$build/roadbrdf"
[ -x "$rb" ] || { echo "no $rb: build it first (cmake --build $build --target roadbrdf _roadbrdf)" >&2; exit 1; }
mkdir -p "$work"
models=(lambert oren-nayar hapke ross-li lambert+torrance-sparrow)
margs=()
for m in "${models[@]}"; do margs+=(--model "$m"); done

if [ ! -s "$work/sand.fit.json" ]; then
  echo "making the 2151-band data, fits, albedo and r-table in $work (once, not timed)" >&2
  awk -F, 'NR <= 2 || (NR - 3) % 3 == 0' data/examples/grid/cerema-like-grid.csv > "$work/grid30.csv"
  printf 'wavelength_nm,w\n350,0.25\n2500,0.65\n' > "$work/w.csv"
  "$rb" simulate hapke -p b0=0.4 -p h=0.08 -p xi=-0.25 --spectral "w=$work/w.csv" \
    --grid "$work/grid30.csv" --wavelengths 350:2500:1 --noise relative=0.02,absolute=0.0005 --seed 7 \
    -o "$work/sand.csv"
  "$rb" fit "$work/sand.csv" "${margs[@]}" --fix lambert.weight=1 --fix torrance-sparrow.weight=1 \
    --threads 2 --quiet -o "$work/sand.fit.json" > /dev/null
  "$rb" albedo "$work/sand.fit.json" --fit hapke --sun-zenith 0:60:30 --no-uncertainty --json \
    -o "$work/sand.albedo.json" > /dev/null
  "$rb" rtable "$work/sand.fit.json" --fit hapke -o "$work/sand.rtable.csv" 2> /dev/null
fi

# name|command (run by bash; $rb and $work expanded here)
cases=(
  "report|$rb report $work/sand.csv ${margs[*]} --quiet -o $work/sand-report.html"
  "plot spectral|$rb plot spectral $work/sand.csv $work/sand.fit.json --geometry 40,0,40,180 -o $work/spectral.png"
  "plot hemisphere|$rb plot hemisphere $work/sand.fit.json --data $work/sand.csv --theta-i 40 --wavelength 600 -o $work/hemisphere.png"
  "plot plane|$rb plot plane --model $work/sand.fit.json --data $work/sand.csv --theta-i 40 --wavelength 600 -o $work/plane.png"
  "plot fit|$rb plot fit $work/sand.csv $work/sand.fit.json --wavelength 600 -o $work/fit.png"
  "plot albedo|$rb plot albedo $work/sand.albedo.json -o $work/albedo.png"
  "plot albedo fit|$rb plot albedo $work/sand.fit.json --fit hapke -o $work/albedo-fit.png"
  "plot rtable|$rb plot rtable $work/sand.rtable.csv -o $work/rtable.png"
  "plot rtable fit|$rb plot rtable $work/sand.fit.json --fit hapke -o $work/rtable-fit.png"
  "plot params|$rb plot params $work/sand.fit.json -o $work/params.png"
)

printf 'load before: %s\n' "$(cut -d' ' -f1-3 /proc/loadavg)"
printf '%-16s %10s %10s %12s\n' command "wall [s]" "CPU [s]" "peak RSS [MB]"
for c in "${cases[@]}"; do
  name="${c%%|*}"
  cmd="${c#*|}"
  walls=() cpus=() rss=0
  for ((k = 0; k < repeats; k++)); do
    if ! /usr/bin/time -v -o "$work/time.txt" bash -c "$cmd" > "$work/out.txt" 2>&1; then
      echo "$name failed:" >&2
      cat "$work/out.txt" >&2
      exit 1
    fi
    walls+=("$(awk -F': ' '/Elapsed/ {n = split($2, t, ":"); s = 0; for (i = 1; i <= n; i++) s = s * 60 + t[i]; print s}' "$work/time.txt")")
    cpus+=("$(awk -F': ' '/User time/ {u = $2} /System time/ {s = $2} END {print u + s}' "$work/time.txt")")
    r=$(awk -F': ' '/Maximum resident/ {print $2}' "$work/time.txt")
    ((r > rss)) && rss=$r
  done
  wall=$(printf '%s\n' "${walls[@]}" | sort -g | awk '{a[NR] = $1} END {print a[int((NR + 1) / 2)]}')
  cpu=$(printf '%s\n' "${cpus[@]}" | sort -g | awk '{a[NR] = $1} END {print a[int((NR + 1) / 2)]}')
  printf '%-16s %10.2f %10.2f %12.0f\n' "$name" "$wall" "$cpu" "$((rss / 1024))"
done
printf 'load after: %s\n' "$(cut -d' ' -f1-3 /proc/loadavg)"
