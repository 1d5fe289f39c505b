#!/bin/sh
# Regenerates the SYNTHETIC example datasets of data/examples/ (see data/examples/README.md for the
# models, their parameters and the nonlinear mixing model). Reproducible: fixed seeds, and awk is
# only used for arithmetic (no random numbers).
#   usage: examples/make_example_data.sh [path/to/roadbrdf]     (default: build/roadbrdf)
set -eu
cd "$(dirname "$0")/.."
R=${1:-build/roadbrdf}
E=data/examples
S=$E/spectra
WL=350:2490:20
NOISE=relative=0.01,absolute=2e-4,edge=6,edge-width=60,water=5
DIGITS=5
mkdir -p $E/grid $E/single $E/mastics $E/mixed $E/calibration

# ---- instrument grid, road angles (report section 5.3.1), like the Cerema gonioreflectometer --------
# incidence gamma 0-80 deg, observation alpha = 90 - theta_r, azimuth planes beta, delta = 0.
# The azimuth of a direction along the normal is undefined: gamma = 0 or alpha = 90 rows have beta = 0 only.
{
  echo "# Synthetic instrument grid like the Cerema gonioreflectometer (road angles, degrees)"
  echo "gamma,alpha,beta,delta"
  for g in 0 20 40 60 80; do
    for a in 10 30 50 70 90; do
      for b in 0 45 90 135 180; do
        if { [ $g = 0 ] || [ $a = 90 ]; } && [ $b != 0 ]; then continue; fi
        echo "$g,$a,$b,0"
      done
    done
  done
} > $E/grid/cerema-like-grid.csv

# ---- intimate mixing of fines with binder (mastic albedo) -------------------------------------------
# Each component's albedo rho is turned into a single-scattering albedo w through the isotropic
# multiple-scattering relation rho = (1 - g)/(1 + g), g = sqrt(1 - w) (Hapke 1981, eq. 25 form),
# the w are averaged with the volume fractions, and the mean w is turned back into rho.
intimate_mix() {  # fines.csv binder.csv fines_volume_fraction out.csv description
  awk -F, -v x="$3" -v desc="$5" '
    function load(file, xs, ys,   n, line, p) {
      n = 0
      while ((getline line < file) > 0) {
        if (line ~ /^#/ || line ~ /^wavelength/) continue
        split(line, p, ","); n++; xs[n] = p[1] + 0; ys[n] = p[2] + 0
      }
      close(file); return n
    }
    function interp(xs, ys, n, t,   k, u) {
      for (k = 1; k < n; k++) if (t <= xs[k + 1]) { u = (t - xs[k]) / (xs[k + 1] - xs[k]); return ys[k] * (1 - u) + ys[k + 1] * u }
      return ys[n]
    }
    function to_w(r,   g) { g = (1 - r) / (1 + r); return 1 - g * g }
    function to_rho(w,   g) { g = sqrt(1 - w); return (1 - g) / (1 + g) }
    BEGIN {
      nf = load(ARGV[1], fx, fy); nb = load(ARGV[2], bx, by); ARGV[1] = ""; ARGV[2] = ""
      print "# " desc
      print "# synthetic: yes; intimate mixing (single-scattering albedos averaged by volume, fines fraction " x ")"
      print "wavelength,value"
      for (t = 350; t <= 2500; t += 10) {
        w = x * to_w(interp(fx, fy, nf, t)) + (1 - x) * to_w(interp(bx, by, nb, t))
        printf "%d,%.5f\n", t, to_rho(w)
      }
    }' "$1" "$2" > "$4"
}
intimate_mix $S/garonne-fines-albedo.csv $S/bitumen-albedo.csv 0.69 $S/mastic-garonne-bitumen-albedo.csv \
  "mastic of F1/F4: Garonne fines 0/2 + bitumen"
intimate_mix $S/soreze-limestone-albedo.csv $S/bitumen-albedo.csv 0.675 $S/mastic-soreze-bitumen-albedo.csv \
  "mastic of F2: Soreze limestone fines 0/2 + bitumen"
intimate_mix $S/soreze-limestone-albedo.csv $S/synthetic-binder-albedo.csv 0.674 $S/mastic-soreze-synthetic-albedo.csv \
  "mastic of F3: Soreze limestone fines 0/2 + TiO2-pigmented synthetic binder"

# ---- single-material samples and mastics: the virtual gonioreflectometer ---------------------------
GRID=$E/grid/cerema-like-grid.csv
sim() {  # out seed model args...
  out=$1; seed=$2; model=$3; shift 3
  "$R" simulate "$model" --grid $GRID --wavelengths $WL --noise $NOISE --seed "$seed" --digits $DIGITS "$@" -o "$out"
}
ONTS=oren-nayar+torrance-sparrow
sim $E/single/bitumen.csv 101 $ONTS --spectral oren-nayar.albedo=$S/bitumen-albedo.csv \
  -p oren-nayar.sigma=0.15 -p torrance-sparrow.ks=1 -p torrance-sparrow.roughness=0.15 -p torrance-sparrow.ior=1.6 \
  --metadata sample="bitumen (synthetic)" --metadata behaviour="diffuse + specular"
sim $E/single/synthetic-binder.csv 102 $ONTS --spectral oren-nayar.albedo=$S/synthetic-binder-albedo.csv \
  -p oren-nayar.sigma=0.2 -p torrance-sparrow.ks=1 -p torrance-sparrow.roughness=0.25 -p torrance-sparrow.ior=1.5 \
  --metadata sample="TiO2-pigmented synthetic binder (synthetic)" --metadata behaviour="diffuse + specular"
sim $E/single/soreze-limestone.csv 103 oren-nayar --spectral albedo=$S/soreze-limestone-albedo.csv -p sigma=0.45 \
  --metadata sample="Soreze limestone, light aggregate (synthetic)" --metadata behaviour="rough diffuse"
sim $E/single/lazard.csv 104 oren-nayar --spectral albedo=$S/lazard-albedo.csv -p sigma=0.35 \
  --metadata sample="Lazard rock, medium aggregate (synthetic)" --metadata behaviour="rough diffuse"
sim $E/single/garonne.csv 105 hapke --spectral w=$S/garonne-w.csv -p b0=0.6 -p h=0.08 -p xi=-0.25 \
  --metadata sample="Garonne rock, dark aggregate (synthetic)" --metadata behaviour="backscattering (Hapke)"
sim $E/single/gouraudiere.csv 106 $ONTS --spectral oren-nayar.albedo=$S/gouraudiere-albedo.csv \
  -p oren-nayar.sigma=0.3 -p torrance-sparrow.ks=0.5 -p torrance-sparrow.roughness=0.3 -p torrance-sparrow.ior=1.55 \
  --metadata sample="Gouraudiere rock, dark aggregate (synthetic)" --metadata behaviour="diffuse + specular"
seed=200
for m in garonne-bitumen soreze-bitumen soreze-synthetic; do
  seed=$((seed + 1))
  sim $E/mastics/mastic-$m.csv $seed $ONTS --spectral oren-nayar.albedo=$S/mastic-$m-albedo.csv \
    -p oren-nayar.sigma=0.25 -p torrance-sparrow.ks=0.5 -p torrance-sparrow.roughness=0.3 -p torrance-sparrow.ior=1.55 \
    --metadata sample="mastic $m (synthetic: intimate mixing of fines with binder)" --metadata behaviour="diffuse + weak specular"
done

# ---- FORMER mixed samples F1-F4 (report Table 5.1): NONLINEAR geometric mixing ---------------------
# These used to be the bundled data/examples/mixed/F1-F4.csv. They are circular for the `shadowed`
# mixing method (it fits the same shadowing form), so the bundled mixtures are now path-traced virtual samples
# (examples/make_virtual_mixtures.sh, called at the end of this script). These geometric mixtures are still
# made here, but outside the source tree (not bundled: 644 KB, and reproducible from the bundled components
# in a second): into $GEOMETRIC (default build/mixed-geometric).
GEOMETRIC=${GEOMETRIC:-build/mixed-geometric}
mkdir -p "$GEOMETRIC"
# f = (1 - c) f_mastic + c sum_k s_k f_coarse_k with the coarse-aggregate cover fraction seen AND lit
#   c(theta_i, theta_r) = 1 - (1 - c0)^((1/mu_i + 1/mu_r)/2),  mu = max(cos theta, 0.1):
# the recessed mastic between protruding coarse aggregates is shadowed and masked more and more
# towards grazing angles. sigma combines as sqrt(((1-c) s_m)^2 + sum (c s_k sigma_k)^2).
mix() {  # out c0 sample-label mastic coarse1 share1 [coarse2 share2]
  out=$1; c0=$2; label=$3; mastic=$4; shift 4
  awk -F, -v c0="$c0" -v label="$label" -v n="$(($# / 2))" -v f1="${1:-}" -v s1="${2:-0}" -v f2="${3:-}" -v s2="${4:-0}" '
    function load(file, store,   line, row) {
      row = 0
      while ((getline line < file) > 0) {
        if (line ~ /^#/ || line ~ /^gamma/) continue
        row++; store[row] = line
      }
      close(file)
    }
    BEGIN { load(f1, A); if (n > 1) load(f2, B); row = 0 }
    /^#/ { next }
    /^gamma/ {
      print "# roadbrdf spectral BRDF dataset (wide CSV); angles in degrees, wavelengths in nm, BRDF and sigma in sr^-1"
      print "# sample: " label
      print "# synthetic: yes: NONLINEAR geometric mixture of synthetic mastic and coarse-aggregate datasets (see data/examples/README.md), not a measurement"
      print "# mixing: f = (1 - c) f_mastic + c sum_k s_k f_k, c = 1 - (1 - c0)^((1/mu_i + 1/mu_r)/2), mu = max(cos, 0.1)"
      print "# c0: " c0
      print "# units: sr^-1"
      print; m = (NF - 4) / 2; next
    }
    {
      row++; split(A[row], a, ","); if (n > 1) split(B[row], b, ",")
      pi = 3.141592653589793
      mi = cos($1 * pi / 180); mr = cos((90 - $2) * pi / 180)
      if (mi < 0.1) mi = 0.1; if (mr < 0.1) mr = 0.1
      c = 1 - exp(((1 / mi + 1 / mr) / 2) * log(1 - c0))
      line = $1 "," $2 "," $3 "," $4
      for (k = 5; k <= 4 + m; k++) {
        v = (1 - c) * $k + c * s1 * a[k]; if (n > 1) v += c * s2 * b[k]
        line = line "," sprintf("%.5g", v)
      }
      for (k = 5 + m; k <= 4 + 2 * m; k++) {
        q = ((1 - c) * $k)^2 + (c * s1 * a[k])^2; if (n > 1) q += (c * s2 * b[k])^2
        line = line "," sprintf("%.2g", sqrt(q))
      }
      print line
    }' "$mastic" > "$out"
}
mix "$GEOMETRIC"/F1.csv 0.667 "F1 (synthetic): bitumen + Garonne 0/2, 2/6, 6/10" \
  $E/mastics/mastic-garonne-bitumen.csv $E/single/garonne.csv 1
mix "$GEOMETRIC"/F2.csv 0.694 "F2 (synthetic): bitumen + Soreze limestone 0/2 + Lazard 2/6, 6/10" \
  $E/mastics/mastic-soreze-bitumen.csv $E/single/lazard.csv 1
mix "$GEOMETRIC"/F3.csv 0.703 "F3 (synthetic): TiO2 synthetic binder + Soreze limestone 0/2 + Lazard 2/6, 6/10" \
  $E/mastics/mastic-soreze-synthetic.csv $E/single/lazard.csv 1
mix "$GEOMETRIC"/F4.csv 0.682 "F4 (synthetic): bitumen + Garonne 0/2, 2/6 + Gouraudiere 6/10" \
  $E/mastics/mastic-garonne-bitumen.csv $E/single/garonne.csv 0.313 $E/single/gouraudiere.csv 0.687
for f in "$GEOMETRIC"/F*.csv; do "$R" convert "$f" -o "$f.tmp.csv" && mv "$f.tmp.csv" "$f"; done   # validates, normalises

# ---- calibration example with the real Spectralon calibration ------------------------------------
# Radiances of the Soreze limestone sample and of the Spectralon panel (Lambertian rho(lambda)/pi,
# rho from data/third-party/spectralon/Spectralon_Num4.txt) under a 3000 K halogen lamp
# (Planck shape, arbitrary units) at the same geometries, plus a constant dark signal.
PANEL=data/third-party/spectralon/Spectralon_Num4.txt
"$R" simulate lambert --grid $GRID --wavelengths $WL --spectral albedo=$PANEL --digits 8 \
  --metadata sample="Spectralon panel (rho from Spectralon_Num4.txt; synthetic Lambertian measurement)" \
  -o $E/calibration/panel-brdf.csv
to_radiance() {  # in out label
  awk -F, -v label="$3" '
    /^#/ { next }
    /^gamma/ {
      print "# synthetic radiance (arbitrary units): L = E_lamp(lambda) cos(gamma) f + dark, dark = 2; 3000 K halogen lamp"
      print "# sample: " label
      print "# units: arbitrary radiance units"
      m = 0; line = $1 "," $2 "," $3 "," $4
      for (k = 5; k <= NF; k++) { if ($k ~ /^sigma_/) break; m++; wl[k] = $k; line = line "," $k }
      print line; next
    }
    {
      line = $1 "," $2 "," $3 "," $4; mu = cos($1 * 3.141592653589793 / 180)
      for (k = 5; k < 5 + m; k++) {
        l = wl[k] * 1e-9; e = 1e-3 / (l^5 * (exp(0.014388 / (l * 3000)) - 1)) / 1e12
        line = line "," sprintf("%.6g", e * mu * $k + 2)
      }
      print line
    }' "$1" > "$2"
}
to_radiance $E/single/soreze-limestone.csv $E/calibration/sample-radiance.csv "Soreze limestone (synthetic radiance)"
to_radiance $E/calibration/panel-brdf.csv $E/calibration/reference-radiance.csv "Spectralon panel (synthetic radiance)"
awk -F, '/^#/ { next } /^gamma/ { print "# dark signal (arbitrary radiance units), one row used for every geometry"; print "# units: arbitrary radiance units"; print; next }
  !done { line = $1 "," $2 "," $3 "," $4; for (k = 5; k <= NF; k++) line = line ",2"; print line; done = 1 }' \
  $E/calibration/sample-radiance.csv > $E/calibration/dark.csv
"$R" calibrate $E/calibration/sample-radiance.csv --reference $E/calibration/reference-radiance.csv \
  --dark $E/calibration/dark.csv --panel-reflectance $PANEL -o $E/calibration/soreze-limestone-calibrated.csv
# ---- mixed samples F1-F4: path-traced virtual samples of the formulations ---------------
# made of the fits of the components above; about 45 s CPU (see data/examples/README.md).
bash examples/make_virtual_mixtures.sh "$(dirname "$R")" "$(dirname "$R")/virtual-mixtures" $E/mixed
echo "example data written to $E (former geometric mixtures: $GEOMETRIC)"
