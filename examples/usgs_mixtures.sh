#!/usr/bin/env bash
# Real intimate mixtures of the USGS Spectral Library v7 (splib07a; Kokaly et al. 2017,
# doi:10.5066/F7RR1WDJ) through the roadbrdf chain (docs/mixing.md, "Real intimate mixtures"):
#   end-member spectrum -> dataset (convert --from usgs, BRDF = R/pi at an assumed geometry)
#   -> Hapke fit (single-scattering albedo per wavelength) -> one formulation per mixture (wt %)
#   -> mix --method hapke and --method areal -> RMS reflectance error against the measured mixture;
#   -> calibrated hapke: mix-calibrate on the other mixtures (leave-one-out) -> mix --cross-sections.
#
# Usage: bash examples/usgs_mixtures.sh BUILD OUT [SET ...] [--check-ratio K]
#   BUILD  build folder (with roadbrdf and python/) or the roadbrdf program in it
#   OUT    output folder; per set: OUT/SET/{data,fits,formulations,mix}/, OUT/SET/rms.csv, OUT/SET/spectra.png
#   SET    dalton (default: Dalton et al. 2002 calcite-epidote-chlorite, 10 mixtures), calcite-clay,
#          ironoxide-quartz, or all
#   --check-ratio K   exit 1 unless hapke is >= K times better than areal on more than half of each set's mixtures
#   --check-loo-mean X  exit 1 unless the leave-one-out calibrated hapke RMS, averaged over the mixtures, is <= X
#   --check-calibration-improves  exit 1 unless that mean is below the uncalibrated hapke mean
# Data: ../shared/real-data/usgs-splib07a-mixtures next to the repository (never copied into it), or
# $ROADBRDF_USGS_DATA. Exit status 77 (skipped) when it is absent.
#
# Assumptions (stated again in every formulation file):
# - Geometry: the splib07a files do not record the lab geometry (PROVENANCE.md); 30 deg incidence, nadir
#   view is assumed ($ROADBRDF_USGS_GEOMETRY overrides it, theta_i=..,phi_i=..,theta_r=..,phi_r=..).
# - End-member fit: Hapke with the Hapke (1981) H-function, no opposition effect (b0=0), isotropic
#   single-particle phase function (xi=0) and h=0.05 fixed: one reflectance per wavelength determines one
#   unknown, the single-scattering albedo w.
# - Densities [g/cm3] (Anthony et al., Handbook of Mineralogy, Mineralogical Society of America): calcite 2.71,
#   epidote 3.45 (3.38-3.49), Fe-clinochlore 3.0 (2.60-3.02, rising with Fe), montmorillonite 2.35 (2-3),
#   kaolinite 2.63 (2.61-2.68), hematite 5.26, goethite 4.27 (3.3-4.3), quartz 2.65.
# - Grain size: every component of a mixture gets the same size class, so that the cross-section weights
#   M/(rho D) of both methods are the volume fractions. True for Dalton's 75-150 um series; not known for the
#   clays and oxides (PROVENANCE.md), whose real grains are far finer (which hapke would weight far more).
set -euo pipefail
repo="$(cd "$(dirname "$0")/.." && pwd)"

usage() {
  echo "usage: $0 BUILD OUT [dalton|calcite-clay|ironoxide-quartz|all ...] [--check-ratio K] [--check-loo-mean X]" \
       "[--check-calibration-improves]" >&2
  exit 2
}
[ $# -ge 2 ] || usage
build="$1"
out="$2"
shift 2
check=()
sets=()
while [ $# -gt 0 ]; do
  case "$1" in
    --check-ratio) [ $# -ge 2 ] || usage; check+=(--check-ratio "$2"); shift 2 ;;
    --check-loo-mean) [ $# -ge 2 ] || usage; check+=(--check-loo-mean "$2"); shift 2 ;;
    --check-calibration-improves) check+=(--check-calibration-improves); shift ;;
    all) sets+=(dalton calcite-clay ironoxide-quartz); shift ;;
    dalton|calcite-clay|ironoxide-quartz) sets+=("$1"); shift ;;
    *) usage ;;
  esac
done
[ ${#sets[@]} -gt 0 ] || sets=(dalton)

if [ -f "$build" ] && [ -x "$build" ]; then
  roadbrdf="$(cd "$(dirname "$build")" && pwd)/$(basename "$build")"
  build="$(dirname "$roadbrdf")"
else
  build="$(cd "$build" && pwd)"
  roadbrdf="$build/roadbrdf"
fi
[ -x "$roadbrdf" ] || { echo "$0: no roadbrdf program in $build" >&2; exit 2; }
python="${PYTHON:-/usr/bin/python3}"
export PYTHONPATH="$build/python${PYTHONPATH:+:$PYTHONPATH}"
export MPLBACKEND=Agg

data="${ROADBRDF_USGS_DATA:-$repo/../shared/real-data/usgs-splib07a-mixtures}"
if [ ! -d "$data/spectra" ]; then
  echo "$0: SKIPPED: USGS splib07a mixtures not available ($data is absent; see docs/mixing.md)" >&2
  exit 77
fi
geometry="${ROADBRDF_USGS_GEOMETRY:-theta_i=30,phi_i=0,theta_r=0,phi_r=0}"
angles="$(echo "$geometry" | sed -E 's/(theta_i|phi_i|theta_r|phi_r)=//g')"
hapke_fit=(-m hapke --option h_function=hapke1981 --fix b0=0 --fix xi=0 --fix h=0.05 --wavelengths 400:2400:10)

# One set: wavelength file, end-members "name|file|density", mixtures "name|file|name=wt,name=wt",
# size class d_min, d_max [mm].
define_set() {
  case "$1" in
    dalton)
      title="Dalton et al. (2002) calcite-epidote-chlorite, 75-150 um, ASD FR"
      wavelengths="splib07a_Wavelengths_ASD_0.35-2.5_microns_2151_ch.txt"
      d_min=0.075 d_max=0.150
      endmembers=("calcite|Calcite_GDS304_75-150um_ASDFRb|2.71" "epidote|Epidote_GDS301_75-150um_ASDFRb|3.45"
                  "chlorite|Clinochlore_Fe_GDS157.b_ASDFRa|3.0")
      mixtures=("GDS310|Calcite.67+Epidote.33_GDS310_ASDFRa|calcite=67,epidote=33"
                "GDS311|Calcite.33+Epidote.67_GDS311_ASDFRa|calcite=33,epidote=67"
                "GDS312|Chlor.2+Epid.6+Calc.2_GDS312_ASDFRa|calcite=20,epidote=60,chlorite=20"
                "GDS313|Chlor.6+Epid.2+Calc.2_GDS313_ASDFRa|calcite=20,epidote=20,chlorite=60"
                "GDS314|Chlor.2+Epid.2+Calc.6_GDS314_ASDFRa|calcite=60,epidote=20,chlorite=20"
                "GDS319|Chl.33+Epid.33+Cal.33_GDS319_ASDFRa|calcite=33,epidote=33,chlorite=33"
                "GDS315|Chlorit.33+Calcite.67_GDS315_ASDFRa|calcite=67,chlorite=33"
                "GDS316|Chlorite.67+Calcit.33_GDS316_ASDFRa|calcite=33,chlorite=67"
                "GDS317|Chlorite.67+Epidot.33_GDS317_ASDFRa|epidote=33,chlorite=67"
                "GDS318|Chlorite.33+Epidot.67_GDS318_ASDFRa|epidote=67,chlorite=33") ;;
    calcite-clay)
      # ASD NG (the Beckman copies lack their channels below 0.57 um); size class unknown (see above).
      title="Calcite WS272 + clay (80/20 wt %), ASD NG"
      wavelengths="splib07a_Wavelengths_ASD_0.35-2.5_microns_2151_ch.txt"
      d_min=0.075 d_max=0.150
      endmembers=("calcite|Calcite_WS272_ASDNGa|2.71" "montmorillonite|Montmorillonite_SWy-1_ASDNGb|2.35"
                  "kaolinite|Kaolinite_CM9_ASDNGb|2.63")
      mixtures=("GDS212|Calcite.80+Mont_Swy-1_GDS212_ASDNGa|calcite=80,montmorillonite=20"
                "GDS213|Calcite.80wt+Kaol_CM9_GDS213_ASDNGa|calcite=80,kaolinite=20") ;;
    ironoxide-quartz)
      # Quartz GDS31 is not the mixtures' quartz and the goethite fraction is unknown (PROVENANCE.md).
      title="2 wt % iron oxide + quartz (approximate end-members), Beckman"
      wavelengths="splib07a_Wavelengths_BECK_Beckman_0.2-3.0_microns.txt"
      d_min=0.075 d_max=0.150
      endmembers=("hematite|Hematite_GDS27_BECKa|5.26" "goethite|Goethite_WS222_Medium_Gr._BECKa|4.27"
                  "quartz|Quartz_GDS31_0-74um_fr_BECKa|2.65")
      mixtures=("GDS76|Hematite.02+Quartz.98_GDS76_BECKa|hematite=2,quartz=98"
                "GDS240|Goethite0.02+Quartz_GDS240_BECKa|goethite=2,quartz=98") ;;
  esac
}

# A formulation (roadbrdf-formulation, data/examples/formulations/README.md) of one mixture.
write_formulation() {  # NAME FRACTIONS FILE
  local name="$1" fractions="$2" file="$3" first=1 em part component wt density
  {
    printf '{\n  "format": "roadbrdf-formulation",\n  "version": 1,\n  "name": "%s",\n' "$name"
    printf '  "source": "USGS splib07a %s (Kokaly et al. 2017, doi:10.5066/F7RR1WDJ)",\n' "$name"
    printf '  "assumptions": ["geometry %s (not recorded in splib07a)", "densities: Handbook of Mineralogy",\n' "$geometry"
    printf '                  "one size class %s-%s mm for every component"],\n' "$d_min" "$d_max"
    # Published fractions are rounded (GDS319: 33+33+33 = 99 %).
    printf '  "fraction_tolerance_percent": 1.5,\n  "components": [\n'
    IFS=, read -ra parts <<< "$fractions"
    for part in "${parts[@]}"; do
      component="${part%%=*}"
      wt="${part#*=}"
      density=""
      for em in "${endmembers[@]}"; do
        IFS='|' read -r n _ d <<< "$em"
        [ "$n" = "$component" ] && density="$d"
      done
      [ -n "$density" ] || { echo "$0: $name: unknown end-member $component" >&2; exit 2; }
      [ $first -eq 1 ] || printf ',\n'
      first=0
      printf '    {"name": "%s", "kind": "aggregate", "mass_percent": %s, "density_g_cm3": %s, ' "$component" "$wt" "$density"
      printf '"d_min_mm": %s, "d_max_mm": %s, "fit": "../fits/%s.fit.json"}' "$d_min" "$d_max" "$component"
    done
    printf '\n  ]\n}\n'
  } > "$file.tmp"
  mv "$file.tmp" "$file"
}

status=0
for set in "${sets[@]}"; do
  define_set "$set"
  dir="$out/$set"
  mkdir -p "$dir/data" "$dir/fits" "$dir/formulations" "$dir/mix"
  echo "== $set: $title (geometry $geometry)"
  to_dataset() {  # FILE-STEM OUTPUT
    "$roadbrdf" convert --from usgs --usgs-wavelengths "$data/$wavelengths" --geometry "$geometry" \
        "$data/spectra/splib07a_$1_AREF.txt" -o "$2"
  }
  for em in "${endmembers[@]}"; do
    IFS='|' read -r name stem _ <<< "$em"
    to_dataset "$stem" "$dir/data/$name.csv"
    "$roadbrdf" fit "$dir/data/$name.csv" "${hapke_fit[@]}" -o "$dir/fits/$name.fit.json" > "$dir/fits/$name.log" 2>&1 ||
      { cat "$dir/fits/$name.log" >&2; exit 1; }
  done
  manifest="$dir/manifest.csv"
  names=()
  for em in "${endmembers[@]}"; do names+=("${em%%|*}"); done
  { printf 'mixture,measured,hapke,areal'; printf ',wt_%s' "${names[@]}"; printf '\n'; } > "$manifest.tmp"
  for mix in "${mixtures[@]}"; do
    IFS='|' read -r name stem fractions <<< "$mix"
    to_dataset "$stem" "$dir/data/$name.csv"
    write_formulation "$name" "$fractions" "$dir/formulations/$name.json"
    for method in hapke areal; do
      "$roadbrdf" mix "$dir/formulations/$name.json" --method "$method" --quiet -o "$dir/mix/$name.$method.mix.json" \
          > "$dir/mix/$name.$method.log" 2>&1 || { cat "$dir/mix/$name.$method.log" >&2; exit 1; }
    done
    row="$name,$dir/data/$name.csv,$dir/mix/$name.hapke.mix.json,$dir/mix/$name.areal.mix.json"
    for n in "${names[@]}"; do
      wt=0
      IFS=, read -ra parts <<< "$fractions"
      for part in "${parts[@]}"; do [ "${part%%=*}" = "$n" ] && wt="${part#*=}"; done
      row="$row,$wt"
    done
    echo "$row" >> "$manifest.tmp"
  done
  mv "$manifest.tmp" "$manifest"
  # Calibrated hapke (docs/mixing.md "Calibrated intimate mixing"): cross-section factors per end-member
  # fitted with `mix-calibrate`, (a) on every mixture of the set (in-sample: the best the factors can do),
  # (b) leave-one-out: on all mixtures but one, then predicting that one. A mixture whose end-members the
  # other mixtures do not link (e.g. the only mixture with montmorillonite) cannot be predicted: "n/a".
  # The factors are fitted to the measured spectra's 10 nm band means at the end-member fits' wavelengths
  # (400-2400 nm every 10 nm, `resample`): the same information as the 2001 channels there for three smooth
  # factors, at a tenth of the cost; the RMS of the table is still taken against the measured channels.
  mkdir -p "$dir/calibration"
  pairs=()
  for mix in "${mixtures[@]}"; do
    IFS='|' read -r name _ _ <<< "$mix"
    "$roadbrdf" resample "$dir/data/$name.csv" --wavelengths 395:2405:10 -o "$dir/data/$name.bands.csv"
    pairs+=("$dir/formulations/$name.json" "$dir/data/$name.bands.csv")
  done
  "$roadbrdf" mix-calibrate "${pairs[@]}" -o "$dir/calibration/all.json" > "$dir/calibration/all.log" 2>&1 ||
    { cat "$dir/calibration/all.log" >&2; exit 1; }
  { head -1 "$manifest" | sed 's/^mixture,measured,hapke,areal/mixture,measured,hapke,areal,insample,calibrated/'; } > "$manifest.tmp"
  i=0
  for mix in "${mixtures[@]}"; do
    IFS='|' read -r name _ _ <<< "$mix"
    "$roadbrdf" mix "$dir/formulations/$name.json" --method hapke --cross-sections "$dir/calibration/all.json" --quiet \
        -o "$dir/mix/$name.insample.mix.json" > "$dir/mix/$name.insample.log" 2>&1 ||
      { cat "$dir/mix/$name.insample.log" >&2; exit 1; }
    others=()
    for ((j = 0; j < ${#pairs[@]}; j += 2)); do
      [ $j -eq $((2 * i)) ] || others+=("${pairs[$j]}" "${pairs[$((j + 1))]}")
    done
    loo=""
    if "$roadbrdf" mix-calibrate "${others[@]}" -o "$dir/calibration/loo-$name.json" > "$dir/calibration/loo-$name.log" 2>&1 &&
       "$roadbrdf" mix "$dir/formulations/$name.json" --method hapke --cross-sections "$dir/calibration/loo-$name.json" \
           --quiet -o "$dir/mix/$name.calibrated.mix.json" > "$dir/mix/$name.calibrated.log" 2>&1; then
      loo="$dir/mix/$name.calibrated.mix.json"
    else
      echo "$name: no leave-one-out prediction: $(cat "$dir/calibration/loo-$name.log" "$dir/mix/$name.calibrated.log" \
          2>/dev/null | grep -h 'error' | head -1)" >&2
    fi
    line="$(grep "^$name," "$manifest")"
    echo "$line" | awk -F, -v ins="$dir/mix/$name.insample.mix.json" -v loo="$loo" \
        'BEGIN{OFS=","} {out=$1 OFS $2 OFS $3 OFS $4 OFS ins OFS loo; for (k = 5; k <= NF; k++) out = out OFS $k; print out}' >> "$manifest.tmp"
    i=$((i + 1))
  done
  mv "$manifest.tmp" "$manifest"
  "$python" "$repo/examples/usgs_rms.py" "$manifest" --geometry "$angles" --range 400:2400 \
      --table "$dir/rms.csv" --figure "$dir/spectra.png" --title "$title" "${check[@]}" || status=1
  echo "wrote $dir/rms.csv $dir/spectra.png $dir/calibration/"
done
exit $status
