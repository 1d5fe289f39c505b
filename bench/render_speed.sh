#!/usr/bin/env bash
# Virtual gonioreflectometer speed (goal: 400 geometries x 20 wavelength bands at 1 %
# standard error in under 5 minutes on the 2-core machine).
# Usage: nice bash bench/render_speed.sh BUILD_DIR [SAMPLING]   (SAMPLING: brdf (default) | cosine)
#
# The sample is the F1 formulation of data/examples/formulations built as in the demo (section 7),
# but 60 mm wide at 0.1 mm cells. F1 refers to fit files; they are made here with the demo's own `fit`
# commands (section 3) from the bundled measurements, so the materials are the real fitted ones
# (Hapke / Oren-Nayar / Torrance-Sparrow, whichever BIC selects), not stand-in models. The fits are
# cached in BUILD_DIR/render-speed/ and not part of the timing.
# The grid: theta_i in {0,15,...,75} x theta_r in {0,10,...,80} x dphi in {0,30,60,90,120,150,165,180}
# = 432 geometries (>= 400; theta_r + the 1 deg cone <= 90 deg); wavelengths 390:770:20 (20 bands).
# Timing: /usr/bin/time around `roadbrdf render` alone; CPU time (user + system) is the main figure
# because the machine is shared (wall time depends on the load).
set -euo pipefail
cd "$(dirname "$0")/.."
build="${1:?usage: bench/render_speed.sh BUILD_DIR [brdf|cosine]}"
sampling="${2:-brdf}"
rb="$build/roadbrdf"
[ -x "$rb" ] || { echo "no $rb: build it first (cmake --build $build -j1 --target roadbrdf)" >&2; exit 1; }
out="$build/render-speed"
mkdir -p "$out/fits" "$out/formulations"

# Fits used by F1 (same commands as examples/demo.sh section 3).
for name in garonne bitumen mastic-garonne-bitumen; do
  [ -s "$out/fits/$name.fit.json" ] && continue
  file="data/examples/single/$name.csv"
  [ -f "$file" ] || file="data/examples/mastics/$name.csv"
  echo "fitting $name (once, cached)"
  "$rb" fit "$file" --model oren-nayar --model oren-nayar+torrance-sparrow --model hapke \
      --fix oren-nayar.weight=1 --fix torrance-sparrow.weight=1 --multistart 8 -o "$out/fits/$name.fit.json" >/dev/null 2>&1
done
cp data/examples/formulations/F1.json "$out/formulations/"
[ -s "$out/F1-60mm.surface.json" ] ||
  "$rb" surface "$out/formulations/F1.json" --size 60mm --cell 0.1 --seed 1 -o "$out/F1-60mm.surface.json" >/dev/null

grid="$out/grid-432.csv"
{
  echo "theta_i,phi_i,theta_r,phi_r"
  for ti in 0 15 30 45 60 75; do
    for tr in 0 10 20 30 40 50 60 70 80; do
      for dp in 0 30 60 90 120 150 165 180; do echo "$ti,0,$tr,$dp"; done
    done
  done
} > "$grid"

log="$out/render-$sampling.log"
/usr/bin/time -f "TIME wall %e s user %U s system %S s" \
  "$rb" render "$out/F1-60mm.surface.json" --grid "$grid" --wavelengths 390:770:20 --acceptance 1 \
  --target-error 0.01 --sampling "$sampling" --threads 2 -o "$out/F1-$sampling.csv" >"$log" 2>&1 || { cat "$log"; exit 1; }
cat "$log"

/usr/bin/python3 - "$log" "$out/F1-$sampling.csv" <<'PY'
import re, sys
import numpy as np
log = open(sys.argv[1]).read()
wall, user, system = map(float, re.search(r"TIME wall ([\d.]+) s user ([\d.]+) s system ([\d.]+) s", log).groups())
paths = int(re.search(r"(\d+) paths in total", log).group(1))
rows = [l for l in open(sys.argv[2]) if not l.startswith("#")]
head = rows[0].strip().split(",")
data = np.array([[float(x) for x in l.strip().split(",")] for l in rows[1:]])
b = [k for k, h in enumerate(head) if h.replace(".", "").isdigit()]  # BRDF columns are named by wavelength
s = [k for k, h in enumerate(head) if h.startswith("sigma_")]
assert len(b) == len(s) > 0, head
rel = data[:, s] / np.abs(data[:, b])
cpu = user + system
print(f"geometries {data.shape[0]}, wavelengths {len(b)}, total paths {paths}")
print(f"wall {wall:.1f} s, CPU {cpu:.1f} s (user {user:.1f} + system {system:.1f}) on 2 threads")
print(f"paths/s/core (CPU time) {paths / cpu / 1e6:.3f} M; paths/s (wall) {paths / wall / 1e6:.3f} M")
q = np.percentile(rel, [50, 90, 99, 100])
print("relative standard error over all values: median {:.4f}, 90% {:.4f}, 99% {:.4f}, max {:.4f}".format(*q))
print(f"values above 1 %: {np.sum(rel > 0.01)} of {rel.size}")
PY
