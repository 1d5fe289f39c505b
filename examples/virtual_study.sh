#!/usr/bin/env bash
# The virtual-sample ground truth for the mixing methods (docs/virtual-study.md).
# Usage: examples/virtual_study.sh BUILD_DIR OUT_DIR
#   BUILD_DIR: a build with the `roadbrdf` program and the Python module (BUILD_DIR/python).
# Writes fits/, formulations/, surfaces/, data/, vfits/, vformulations/, mix/ and report.md in OUT_DIR.
# Cost: about 40 s CPU on one core (renders on one thread, fits on one thread); see docs/virtual-study.md.
set -euo pipefail
if [ $# -ne 2 ]; then echo "usage: $0 BUILD_DIR OUT_DIR" >&2; exit 2; fi
root="$(cd "$(dirname "$0")/.." && pwd)"
build="$(cd "$1" && pwd)"
mkdir -p "$2"
out="$(cd "$2" && pwd)"
rb="$build/roadbrdf"
py=/usr/bin/python3
helper="$root/examples/virtual_study.py"
export PYTHONPATH="$build/python${PYTHONPATH:+:$PYTHONPATH}"
grid="$root/data/examples/grid/cerema-like-grid.csv"
bands=450:850:100          # nm
samples=4096               # paths per geometry
size=30mm; cell=0.2; seed=1  # the virtual sample of demo section 7
mkdir -p "$out"/{fits,formulations,surfaces,data,vfits,vformulations,mix}
render() { "$rb" render "$1" --grid "$grid" --wavelengths "$bands" --samples "$samples" --threads 1 -o "$2" >/dev/null; }
fit() {  # the models of demo section 3
  "$rb" fit "$1" --model oren-nayar --model oren-nayar+torrance-sparrow --model hapke \
      --fix oren-nayar.weight=1 --fix torrance-sparrow.weight=1 --multistart 8 --wavelengths "$bands" \
      -o "$2" >/dev/null 2>&1
}
section() { printf '\n==== %s\n' "$*" >&2; }
SECONDS=0

section "1. Fits of the (synthetic) measured single materials and mastics, bands $bands nm"
for f in "$root"/data/examples/single/*.csv "$root"/data/examples/mastics/*.csv; do
  fit "$f" "$out/fits/$(basename "$f" .csv).fit.json"
done
cp "$root"/data/examples/formulations/F*.json "$out/formulations/"

section "2. Virtual F1-F4 (same generator settings as demo section 7), their one-material twins, fits, mixing"
declare -A rock_of=([1]="garonne" [2]="lazard" [3]="lazard" [4]="garonne gouraudiere")
virtual_case() {  # TAG K SIZE SEED [SURFACE OPTIONS]: virtual Fk, its virtual components (same macro-texture),
                  # their fits, mix
  local tag="$1" k="$2" sz="$3" sd="$4" materials j m r
  shift 4
  "$rb" surface "$out/formulations/F$k.json" --size "$sz" --cell "$cell" --seed "$sd" "$@" \
      -o "$out/surfaces/$tag.surface.json" > "$out/surfaces/$tag.txt" 2>&1
  render "$out/surfaces/$tag.surface.json" "$out/data/$tag.csv"
  # Component j = the j-th distinct fit of the surface's materials: 0 = the mastic, then the rocks of the
  # coarse classes in formulation order (classes of one rock share its fit). Every cell gets that material.
  materials=$("$py" -c 'import json,sys; f=[m["fit"] for m in json.load(open(sys.argv[1]))["materials"]]; print(" ".join(dict.fromkeys(f)))' \
      "$out/surfaces/$tag.surface.json")
  j=0
  for m in $materials; do
    "$py" "$helper" relabel "$out/surfaces/$tag.surface.json" "$out/surfaces/$tag-comp$j.surface.json" \
        "$out/surfaces/$m"
    render "$out/surfaces/$tag-comp$j.surface.json" "$out/data/$tag-comp$j.csv"
    j=$((j + 1))
  done
  fit "$out/data/$tag-comp0.csv" "$out/vfits/$tag-mastic.fit.json"
  local rocks=()
  j=1
  for r in ${rock_of[$k]}; do
    fit "$out/data/$tag-comp$j.csv" "$out/vfits/$tag-$r.fit.json"
    rocks+=(--rock "$r=$out/vfits/$tag-$r.fit.json")
    j=$((j + 1))
  done
  "$py" "$helper" formulation "$out/formulations/F$k.json" "$out/vformulations/$tag.json" \
      --mastic "$out/vfits/$tag-mastic.fit.json" "${rocks[@]}"
  "$rb" mix "$out/vformulations/$tag.json" --data "$out/data/$tag.csv" --method all --folds 5 \
      -o "$out/mix/$tag.mix.json" > "$out/mix/$tag.txt" 2>&1
}
for k in 1 2 3 4; do virtual_case "F$k" "$k" "$size" "$seed"; done
virtual_case F1-60mm-seed2 1 60mm 2   # another, larger realisation of F1
# The same four textures with the mastic raised until it covers 25 % of the plan (a realistic exposed mastic
# fraction, as measured by image analysis of a photo of a real surface; the default level 0.7 T leaves 5-7 %).
for k in 1 2 3 4; do virtual_case "F$k-m25" "$k" "$size" "$seed" --mastic-fraction 0.25; done
# Where the mastic is seen on F1-m25: single scattering of a white Lambertian sample, and of the same with black
# grains (see section 3).
"$py" "$helper" relabel "$out/surfaces/F1-m25.surface.json" "$out/surfaces/F1-m25-share-all.surface.json" lambert:1
"$py" "$helper" relabel "$out/surfaces/F1-m25.surface.json" "$out/surfaces/F1-m25-share-mastic.surface.json" \
    lambert:1 lambert:0 lambert:0
for v in all mastic; do
  "$rb" render "$out/surfaces/F1-m25-share-$v.surface.json" --grid "$grid" --wavelengths 550:650:100 \
      --samples "$samples" --threads 1 --max-bounces 1 -o "$out/data/F1-m25-share-$v.csv" >/dev/null
done

section "3. Diagnosis experiments on the virtual F1"
"$rb" surface "$out/fits/mastic-garonne-bitumen.fit.json" --flat -o "$out/surfaces/flat-mastic.surface.json" >/dev/null
# Ideal detector (no cone): the render of a flat sample must equal the fit exactly.
"$rb" render "$out/surfaces/flat-mastic.surface.json" --grid "$grid" --wavelengths "$bands" --samples 64 \
    --acceptance 0 --threads 1 -o "$out/data/flat-mastic.csv" >/dev/null
cp "$out/data/F1-comp0.csv" "$out/data/F1-all-mastic.csv"
cp "$out/data/F1-comp1.csv" "$out/data/F1-all-garonne.csv"
"$py" "$helper" relabel "$out/surfaces/F1.surface.json" "$out/surfaces/F1-all-lambert.surface.json" lambert:0.5
render "$out/surfaces/F1-all-lambert.surface.json" "$out/data/F1-all-lambert.csv"
# Single scattering (--max-bounces 1) of a white Lambertian sample, and of the same with black grains:
# the ratio is the mastic's share of the lit-and-seen (cosine-weighted) area at each geometry.
"$py" "$helper" relabel "$out/surfaces/F1.surface.json" "$out/surfaces/F1-share-all.surface.json" lambert:1
"$py" "$helper" relabel "$out/surfaces/F1.surface.json" "$out/surfaces/F1-share-mastic.surface.json" \
    lambert:1 lambert:0 lambert:0
for v in all mastic; do
  "$rb" render "$out/surfaces/F1-share-$v.surface.json" --grid "$grid" --wavelengths 550:650:100 --samples "$samples" \
      --threads 1 --max-bounces 1 -o "$out/data/F1-share-$v.csv" >/dev/null
done
# The demo's comparison: the measured-sample fits as end-members, judged against the virtual F1.
"$rb" mix "$out/formulations/F1.json" --data "$out/data/F1.csv" --method all --folds 5 \
    -o "$out/mix/F1-real-fits.mix.json" > "$out/mix/F1-real-fits.txt" 2>&1

section "4. Laboratory-like components: rock trays (the mixture's grains, floor at 0.3 T, all rock) and the flat mastic"
for k in 1 2 3 4; do
  "$rb" surface "$out/formulations/F$k.json" --size "$size" --cell "$cell" --seed "$seed" --matrix-level 0.3 \
      -o "$out/surfaces/F$k-tray.surface.json" > "$out/surfaces/F$k-tray.txt" 2>&1
  rocks=()
  for r in ${rock_of[$k]}; do
    "$py" "$helper" relabel "$out/surfaces/F$k-tray.surface.json" "$out/surfaces/F$k-tray-$r.surface.json" \
        "$out/fits/$r.fit.json"
    render "$out/surfaces/F$k-tray-$r.surface.json" "$out/data/F$k-tray-$r.csv"
    fit "$out/data/F$k-tray-$r.csv" "$out/vfits/F$k-tray-$r.fit.json"
    rocks+=(--rock "$r=$out/vfits/F$k-tray-$r.fit.json")
  done
  mastic=$("$py" -c 'import json,sys; print(json.load(open(sys.argv[1]))["mastic"]["fit"].split("/")[-1])' \
      "$out/formulations/F$k.json")
  "$py" "$helper" formulation "$out/formulations/F$k.json" "$out/vformulations/F$k-lab.json" \
      --mastic "$out/fits/$mastic" "${rocks[@]}"
  "$rb" mix "$out/vformulations/F$k-lab.json" --data "$out/data/F$k.csv" --method all --folds 5 \
      -o "$out/mix/F$k-lab.mix.json" > "$out/mix/F$k-lab.txt" 2>&1
done

section "5. Report"
"$py" "$helper" report "$out" > "$out/report.md"
echo "virtual study done in ${SECONDS} s wall; tables in $out/report.md" >&2
