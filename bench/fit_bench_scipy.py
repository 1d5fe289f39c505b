"""Per-wavelength fit of bench data with scipy.optimize.least_squares (the usual Python loop: a fixed
start at every wavelength, 2-point finite-difference Jacobian, default 'trf' method), with the
models of bench/fit_bench_model.py and the free parameters and bounds of `roadbrdf fit` in
bench/fit_bench.sh (bench/fit_bench_cases.py for the models of bench/fit_bench_all.sh).
Usage: fit_bench_scipy.py DATA.csv OUT.json [STRIDE] [MODEL]   (STRIDE > 1 fits every STRIDE-th wavelength)"""
import json
import sys
import time
import numpy as np
from scipy.optimize import least_squares
from fit_bench_model import Geometry, HapkeGeometry, composite, hapke, oren_nayar_only
from fit_bench_cases import CASES

# Free parameters: start, lower, upper (the bounds of `roadbrdf models`).
SETUPS = {
    # albedo, sigma, ks, roughness (weights 1, ior 1.5 fixed)
    "oren-nayar+torrance-sparrow": ([0.5, 0.3, 0.5, 0.3], [0.0, 0.0, 0.0, 0.002], [1.0, 0.65, 1.0, 2.0]),
    # albedo, sigma
    "oren-nayar": ([0.5, 0.3], [0.0, 0.0], [1.0, 0.65]),
    # w, b0, h, xi
    "hapke": ([0.5, 0.3, 0.05, 0.0], [0.0, 0.0, 1e-3, -0.95], [1.0, 1.0, 2.0, 0.95]),
}


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
    model = sys.argv[4] if len(sys.argv) > 4 else "oren-nayar+torrance-sparrow"
    g = Geometry(*ang.T)
    if model == "oren-nayar+torrance-sparrow":
        f = lambda q: composite(g, (1.0, q[0], q[1], 1.0, q[2], q[3], 1.5))
    elif model == "oren-nayar":
        f = lambda q: oren_nayar_only(g, q)
    elif model == "hapke":
        hg = HapkeGeometry(g)
        f = lambda q: hapke(hg, q)
    else:  # bench/fit_bench_cases.py: the free parameters, the others fixed at the data's values
        case = CASES[model]
        pg = case.prepare(g)
        f = lambda q: case.model(pg, case.full(q))
        SETUPS[model] = (case.start, case.lower, case.upper)
    start, lower, upper = SETUPS[model]

    def residual(q, yw):
        return f(q) - yw

    x0 = np.array(start)
    out = {"wavelengths": [], "cost": [], "parameters": [], "nfev": []}
    t0 = time.perf_counter()
    c0 = time.process_time()
    for w in range(0, len(wl), stride):
        r = least_squares(residual, x0, bounds=(lower, upper), args=(y[:, w],))
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
