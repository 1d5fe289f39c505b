"""Checks the NumPy models of bench/fit_bench_cases.py against `roadbrdf eval` at 40 geometries (5 fixed:
backscatter, mirror, normal incidence, ...; 35 random) with the data parameters at both ends of the spectrum.
Prints the largest relative difference per model; fails above TOLERANCE (default 1e-9: eval prints 10
significant digits), except Kelemen & Szirmay-Kalos (1e-6: roadbrdf's tabulated specular albedo against the
NumPy quadrature).
Usage: fit_bench_check_models.py ROADBRDF [MODEL...]"""
import os
import subprocess
import sys
import tempfile
import numpy as np
from fit_bench_model import Geometry
from fit_bench_cases import CASES


def main():
    cli = sys.argv[1]
    models = sys.argv[2:] or list(CASES)
    rng = np.random.default_rng(7)
    n = 40
    ang = np.column_stack([rng.uniform(0, 80, n), rng.uniform(0, 360, n), rng.uniform(1, 80, n),
                           rng.uniform(0, 360, n)])
    ang[:5] = [[30, 0, 30, 0], [30, 0, 30, 180], [0, 0, 45, 90], [60, 0, 20, 180], [10, 0, 70, 40]]
    g = Geometry(*ang.T)
    failed = False
    with tempfile.TemporaryDirectory() as tmp:
        geo, out = os.path.join(tmp, "geo.csv"), os.path.join(tmp, "eval.csv")
        np.savetxt(geo, ang, delimiter=",", header="theta_i,phi_i,theta_r,phi_r", comments="", fmt="%.17g")
        for name in models:
            c = CASES[name]
            pg = c.prepare(g)
            worst = 0.0
            for x in (0.0, 1.0):
                p = c.truth(x)
                args = [cli, "eval", name, "--geometry", geo, "-o", out]
                for k, v in zip(c.names, p):
                    args += ["-p", "%s=%.17g" % (k, v)]
                subprocess.run(args, check=True)
                ref = np.genfromtxt(out, delimiter=",", names=True)["brdf"]
                worst = max(worst, float(np.max(np.abs(c.model(pg, p) - ref) / np.abs(ref))))
            tol = 1e-6 if name == "kelemen-szirmay-kalos" else 1e-9
            ok = worst <= tol
            failed |= not ok
            print("%-22s NumPy against roadbrdf eval: max relative difference %.1e %s"
                  % (name, worst, "ok" if ok else "ABOVE %.0e" % tol))
    sys.exit(1 if failed else 0)


if __name__ == "__main__":
    main()
