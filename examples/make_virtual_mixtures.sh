#!/usr/bin/env bash
# Regenerates the SYNTHETIC "measured" mixtures data/examples/mixed/F1-F4.csv from virtual samples
# rendered by the path tracer, so that no mixing method's formula made them (data/examples/README.md).
# Usage: examples/make_virtual_mixtures.sh [BUILD_DIR] [WORK_DIR] [OUT_DIR]
#   defaults: build, build/virtual-mixtures, data/examples/mixed. Not run by the tests.
# Steps:
#   1. fit the bundled component datasets (data/examples/single, data/examples/mastics) as the demo does
#      (examples/fit_components.sh: all 108 wavelengths) into WORK_DIR/fits;
#   2. copy data/examples/formulations/F*.json to WORK_DIR/formulations (their "../fits/" paths then point at
#      those fits) and build each virtual sample with `roadbrdf surface` (fixed seed, settings below);
#   3. render it on the bundled instrument grid at 350:2490:20 nm (the render's Monte Carlo standard errors
#      become the sigma_ columns), round like the other example files (BRDF 5, sigma 2 significant digits),
#      write the header and validate with `roadbrdf convert`.
# Cost: see data/examples/README.md ("Mixed samples F1-F4") for the measured CPU time.
# The previous, circular F1-F4 (nonlinear geometric mixing formula) are still made by
# examples/make_example_data.sh, outside the source tree (build/mixed-geometric/; see data/examples/README.md).
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
cd "$root"
build="${1:-build}"
work="${2:-$build/virtual-mixtures}"
out="${3:-data/examples/mixed}"
rb="$build/roadbrdf"
grid=data/examples/grid/cerema-like-grid.csv
wavelengths=350:2490:20   # nm, the example wavelengths (108)
samples=4096              # paths per geometry (one geometric path serves every wavelength)
size=30mm; cell=0.2; seed=1; mastic_fraction=0.25
mkdir -p "$work/fits" "$work/formulations" "$work/surfaces" "$work/renders" "$out"
SECONDS=0

echo "== 1. component fits (as demo section 3)" >&2
bash examples/fit_components.sh "$build" "$work/fits" >/dev/null
cp data/examples/formulations/F*.json "$work/formulations/"

declare -A label=(
  [1]="F1 (synthetic, virtual sample): bitumen + Garonne 0/2, 2/6, 6/10"
  [2]="F2 (synthetic, virtual sample): bitumen + Soreze limestone 0/2 + Lazard 2/6, 6/10"
  [3]="F3 (synthetic, virtual sample): TiO2 synthetic binder + Soreze limestone 0/2 + Lazard 2/6, 6/10"
  [4]="F4 (synthetic, virtual sample): bitumen + Garonne 0/2, 2/6 + Gouraudiere 6/10")
for k in 1 2 3 4; do
  echo "== 2-3. virtual F$k" >&2
  "$rb" surface "$work/formulations/F$k.json" --size "$size" --cell "$cell" --seed "$seed" \
      --mastic-fraction "$mastic_fraction" -o "$work/surfaces/F$k.surface.json" > "$work/surfaces/F$k.txt" 2>&1
  "$rb" render "$work/surfaces/F$k.surface.json" --grid "$grid" --wavelengths "$wavelengths" --samples "$samples" \
      --seed 1 --threads 1 -o "$work/renders/F$k.csv" > "$work/renders/F$k.txt"
  # texture statistics printed by `surface`: MPD line, mastic level, projected area fraction of every material
  stats=$(awk '/^MPD/ { mpd = $0 }
      /mastic level [0-9.]+ mm/ { match($0, /mastic level [0-9.]+ mm/); level = substr($0, RSTART, RLENGTH) }
      /^material/ { t = 1; next } t && /^wrote/ { t = 0 }
      t { n = split($0, w, /  +/); areas = areas (areas ? "; " : "") w[1] " " w[2] }
      END { print mpd "; " level "; projected area fractions: " areas }' "$work/surfaces/F$k.txt")
  awk -F, -v label="${label[$k]}" -v k="$k" -v size="$size" -v cell="$cell" -v seed="$seed" \
      -v mf="$mastic_fraction" -v samples="$samples" -v stats="$stats" '
    /^# (roadbrdf spectral|sample:|units:)/ { next }
    /^#/ { meta = meta $0 "\n"; next }   # metadata written by render (instrument, cone, paths, seed, ...)
    /^gamma/ {
      print "# roadbrdf spectral BRDF dataset (wide CSV); angles in degrees, wavelengths in nm, BRDF and sigma in sr^-1"
      printf "%s", meta
      print "# sample: " label
      print "# synthetic: yes: path-traced virtual sample (roadbrdf render) of roadbrdf surface F" k ".json, materials = fits of the synthetic component datasets; not a measurement (see data/examples/README.md)"
      print "# made by: examples/make_virtual_mixtures.sh: surface --size " size " --cell " cell " --seed " seed " --mastic-fraction " mf "; render --samples " samples " --seed 1; values rounded to 5 significant digits (sigma to 2)"
      print "# surface: " stats
      print "# units: sr^-1"
      print; m = (NF - 4) / 2; next
    }
    {
      line = $1 "," $2 "," $3 "," $4
      for (j = 5; j <= 4 + m; j++) line = line "," sprintf("%.5g", $j)
      for (j = 5 + m; j <= 4 + 2 * m; j++) {
        if ($j + 0 <= 0) { print "zero or negative sigma in row " NR > "/dev/stderr"; exit 1 }
        line = line "," sprintf("%.2g", $j)
      }
      print line
    }' "$work/renders/F$k.csv" > "$work/renders/F$k-rounded.csv"
  "$rb" convert "$work/renders/F$k-rounded.csv" -o "$out/F$k.csv"   # validates, normalises the header
done
echo "virtual mixtures done in ${SECONDS} s wall; files in $out" >&2
