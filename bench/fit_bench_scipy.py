"""Per-wavelength fit of bench data with scipy.optimize.least_squares (the usual Python loop), same
model, free parameters, bounds and starting point as `roadbrdf fit` in bench/fit_bench.sh.
Usage: fit_bench_scipy.py DATA.csv OUT.json [STRIDE]   (STRIDE > 1 fits every STRIDE-th wavelength)"""
import json
import sys
import time
import numpy as np
from scipy.optimize import least_squares
from fit_bench_model import Geometry, composite

START = {"albedo": 0.5, "sigma": 0.3, "ks": 0.5, "roughness": 0.3}
LOWER = [0.0, 0.0, 0.0, 0.002]
UPPER = [1.0, 0.65, 1.0, 2.0]


def read(path):
    with open(path) as fh:
        lines = [l for l in fh if not l.startswith("#")]
    header = lines[0].strip().split(",")
    data = np.array([[float(c) for c in l.split(",")] for l in lines[1:]])
    wl = np.array([float(h) for h in header[4:]])
    return data[:, :4], wl, data[:, 4:]


def main():
    ang, wl, y = read(sys.argv[1])
    stride = int(sys.argv[3]) if len(sys.argv) > 3 else 1
    g = Geometry(*ang.T)

    def residual(q, yw):
        return composite(g, (1.0, q[0], q[1], 1.0, q[2], q[3], 1.5)) - yw

    x0 = np.array([START["albedo"], START["sigma"], START["ks"], START["roughness"]])
    out = {"wavelengths": [], "cost": [], "parameters": [], "nfev": []}
    t0 = time.perf_counter()
    c0 = time.process_time()
    for w in range(0, len(wl), stride):
        r = least_squares(residual, x0, bounds=(LOWER, UPPER), args=(y[:, w],))
        out["wavelengths"].append(float(wl[w]))
        out["cost"].append(float(r.cost))
        out["parameters"].append([float(v) for v in r.x])
        out["nfev"].append(int(r.nfev))
    out["seconds"] = time.perf_counter() - t0
    out["cpu_seconds"] = time.process_time() - c0
    out["stride"] = stride
    with open(sys.argv[2], "w") as fh:
        json.dump(out, fh)
    print("scipy: %d wavelengths in %.2f s wall, %.2f s CPU" % (len(out["cost"]), out["seconds"], out["cpu_seconds"]))


if __name__ == "__main__":
    main()
