"""The plain per-wavelength scipy loop a user writes, as the speed goal states it: for each wavelength
scipy.optimize.least_squares(residual, x0, bounds, method='trf', jac='2-point') from the SAME plain start
(no warm start), with the models of bench/fit_bench_model.py (NumPy, written from the papers).
  hapke       2002 H, Henyey-Greenstein, SHOE; x0 w 0.5, b0 0.1, h 0.05, xi 0;
              bounds w [0, 1], b0 [0, 1], h [0.001, 2], xi [-0.95, 0.95]
  oren-nayar  x0 albedo 0.5, sigma 0.3; bounds albedo [0, 1], sigma [0, 0.65]
Writes the per-wavelength final costs 1/2 sum r^2 and the CPU time of the loop (process_time) and of
the whole process (reading the CSV and importing scipy included) as JSON.
Usage: fit_bench_plain.py DATA.csv OUT.json MODEL [STRIDE]   (STRIDE > 1 fits every STRIDE-th
wavelength; fit_bench_compare.py extrapolates the time)"""
import json
import sys
import time

import numpy as np
from scipy.optimize import least_squares

from fit_bench_model import Geometry, HapkeGeometry, hapke, oren_nayar_only
from fit_bench_scipy import read

PLAIN = {
    "hapke": ([0.5, 0.1, 0.05, 0.0], [0.0, 0.0, 1e-3, -0.95], [1.0, 1.0, 2.0, 0.95]),
    "oren-nayar": ([0.5, 0.3], [0.0, 0.0], [1.0, 0.65]),
}


def main():
    data, out_path, model = sys.argv[1], sys.argv[2], sys.argv[3]
    stride = int(sys.argv[4]) if len(sys.argv) > 4 else 1
    ang, wl, y = read(data)
    g = Geometry(*ang.T)
    if model.startswith("hapke"):
        hg = HapkeGeometry(g)
        f = lambda q: hapke(hg, q)
    else:
        f = lambda q: oren_nayar_only(g, q)
    x0, lower, upper = (np.array(v) for v in PLAIN[model.split("-")[0] if model.startswith("hapke") else model])
    out = {"wavelengths": [], "cost": [], "parameters": [], "nfev": []}
    t0, c0 = time.perf_counter(), time.process_time()
    for w in range(0, len(wl), stride):
        r = least_squares(lambda q: f(q) - y[:, w], x0, bounds=(lower, upper), method="trf", jac="2-point")
        out["wavelengths"].append(float(wl[w]))
        out["cost"].append(float(r.cost))
        out["parameters"].append([float(v) for v in r.x])
        out["nfev"].append(int(r.nfev))
    out["seconds"] = time.perf_counter() - t0
    out["cpu_seconds"] = time.process_time() - c0
    out["process_cpu_seconds"] = time.process_time()
    out["stride"] = stride
    with open(out_path, "w") as fh:
        json.dump(out, fh)
    print("plain scipy loop, %s: %d wavelengths, loop %.2f s CPU (%.2f s wall), whole process %.2f s CPU"
          % (model, len(out["cost"]), out["cpu_seconds"], out["seconds"], out["process_cpu_seconds"]))


if __name__ == "__main__":
    main()
