"""Synthetic datasets for bench/fit_bench.sh: 400 geometries x 2151 wavelengths (350..2500 nm), smooth
spectra, 1 % relative + 1e-4 sr^-1 noise, seeded, written as a wide CSV (io/dataset_io.h) with 7
significant digits (an instrument file's precision; the noise is at the 3rd digit).
  oren-nayar+torrance-sparrow (default): albedo(lambda), sigma 0.35 rad, ks(lambda), roughness 0.25, ior 1.5
  oren-nayar: albedo(lambda), sigma 0.35 rad
  hapke: w(lambda), B0 0.6, h 0.08, xi -0.25 (H function of Hapke 2002)
  hapke-bound: w(lambda), B0 1 (the upper bound of its fitting range), h 0.05, xi -0.3 (Hapke 2002 H)
  every other model: the parameters of bench/fit_bench_cases.py
Usage: fit_bench_data.py OUT.csv [N_WAVELENGTHS] [MODEL]"""
import sys
import numpy as np
from fit_bench_model import Geometry, HapkeGeometry, composite, hapke, oren_nayar_only
from fit_bench_cases import CASES


def grid():
    rows = []
    for ti in range(0, 80, 10):              # 8 incidence angles
        for tr in (10, 25, 40, 55, 70):      # 5 view zenith angles
            for pr in range(0, 200, 20):     # 10 azimuths
                rows.append((ti, 0.0, tr, float(pr)))
    return np.array(rows)


def main():
    out = sys.argv[1]
    m = int(sys.argv[2]) if len(sys.argv) > 2 else 2151
    model = sys.argv[3] if len(sys.argv) > 3 else "oren-nayar+torrance-sparrow"
    wl = np.linspace(350.0, 2500.0, m) if m > 1 else np.array([550.0])
    ang = grid()
    g = Geometry(*ang.T)
    hg = HapkeGeometry(g)
    rng = np.random.default_rng(12345)
    x = (wl - 350.0) / 2150.0
    albedo = 0.08 + 0.25 * x + 0.03 * np.sin(6.0 * x)
    ks = 0.15 + 0.1 * x
    w_ssa = 0.35 + 0.4 * x + 0.05 * np.sin(6.0 * x)
    if model == "oren-nayar+torrance-sparrow":
        f_of = lambda w: composite(g, (1.0, albedo[w], 0.35, 1.0, ks[w], 0.25, 1.5))
        note = "albedo(lambda), sigma 0.35 rad, ks(lambda), roughness 0.25, ior 1.5"
    elif model == "oren-nayar":
        f_of = lambda w: oren_nayar_only(g, (albedo[w], 0.35))
        note = "albedo(lambda), sigma 0.35 rad"
    elif model == "hapke":
        f_of = lambda w: hapke(hg, (w_ssa[w], 0.6, 0.08, -0.25))
        note = "w(lambda), B0 0.6, h 0.08, xi -0.25, H of Hapke 2002"
    elif model == "hapke-bound":
        # B0 on its upper fitting bound 1 (as fits of real sands end): with the noise, about half of the
        # wavelengths have their least-squares optimum on the bound.
        f_of = lambda w: hapke(hg, (w_ssa[w], 1.0, 0.05, -0.3))
        note = "w(lambda), B0 1 (on its bound), h 0.05, xi -0.3, H of Hapke 2002"
    elif model in CASES:
        case = CASES[model]
        pg = case.prepare(g)
        f_of = lambda w: case.model(pg, case.truth(x[w]))
        t0, t1 = case.truth(0.0), case.truth(1.0)
        note = ", ".join("%s %.4g" % (n, a) if a == b else "%s %.4g..%.4g (lambda)" % (n, a, b)
                         for n, a, b in zip(case.names, t0, t1))
    else:
        raise SystemExit("unknown model " + model)
    table = np.empty((len(ang), m))
    for w in range(m):
        f = f_of(w)
        table[:, w] = f + (0.01 * f + 1e-4) * rng.standard_normal(len(f))
    with open(out, "w") as fh:
        fh.write("# synthetic benchmark data (bench/fit_bench_data.py): %s, %s, noise 1 %% + 1e-4 sr^-1\n"
                 % (model, note))
        fh.write("# units: sr^-1\n")
        fh.write("theta_i,phi_i,theta_r,phi_r," + ",".join("%.6g" % v for v in wl) + "\n")
        for i in range(len(ang)):
            fh.write(",".join("%g" % a for a in ang[i]) + "," + ",".join("%.7g" % v for v in table[i]) + "\n")


if __name__ == "__main__":
    main()
