"""The benchmark cases of every model for bench/fit_bench_all.sh: the NumPy model (bench/fit_bench_model*.py),
the parameters the synthetic data are made with (per wavelength), which parameters are fitted (the rest fixed
at the data's values with `roadbrdf fit --fix`), the fixed start (the model defaults of `roadbrdf models`) and
the bounds (those of `roadbrdf models`).
Usage: fit_bench_cases.py fix MODEL   -> the --fix arguments of `roadbrdf fit` for MODEL"""
import sys
import numpy as np
import fit_bench_model as m0
import fit_bench_model_more as m1


class Case:
    def __init__(self, names, model, truth, free, start, lower, upper, prepare=None, note=""):
        self.names = names        # parameter names, in the order of `roadbrdf models`
        self.model = model        # model(geometry, full parameter vector) -> BRDF
        self.truth = truth        # truth(x) -> full parameter vector of the data, x = (wl - 350)/2150 in [0, 1]
        self.free = free          # indices of the fitted parameters
        self.start, self.lower, self.upper = start, lower, upper  # of the free parameters
        self.prepare = prepare or (lambda g: g)  # geometry -> what model() takes
        self.note = note

    def fixed(self):
        t = self.truth(0.0)
        return {self.names[i]: t[i] for i in range(len(self.names)) if i not in self.free}

    def full(self, q, x=0.0):
        p = list(self.truth(x))
        for k, i in enumerate(self.free):
            p[i] = q[k]
        return p


def smooth(x, a, b, c=0.0):
    return a + b * x + c * np.sin(6.0 * x)


CASES = {
    "lambert": Case(["albedo"], m1.lambert, lambda x: [smooth(x, 0.08, 0.25, 0.03)], [0], [0.5], [0.0], [1.0],
                    note="free albedo"),
    "ross-li": Case(["f_iso", "f_vol", "f_geo"], m1.ross_li,
                    lambda x: [smooth(x, 0.1, 0.3, 0.03), smooth(x, 0.05, 0.1), smooth(x, 0.02, 0.02)],
                    [0, 1, 2], [0.1, 0.05, 0.01], [0.0] * 3, [2.0] * 3, note="free f_iso, f_vol, f_geo"),
    "retro-phong": Case(["kd", "n", "k1", "k2", "k3", "k4"], m1.retro_phong,
                        lambda x: [smooth(x, 0.3, 0.4, 0.03), 30.0, smooth(x, 0.2, 0.1), 0.02, 0.002, 5.0],
                        [0, 1, 2, 3, 4, 5], [0.62, 24.0, 0.158, 0.0145, 0.00133, 5.47],
                        [0.0, 0.0, 0.0, 0.0, 0.0, -20.0], [1.0, 1000.0, 1.0, 1.0, 1.0, 20.0],
                        note="free kd, n, k1, k2, k3, k4"),
    "lafortune": Case(["kd", "rho1", "cx1", "cz1", "n1"], m1.lafortune,
                      lambda x: [smooth(x, 0.08, 0.25, 0.03), smooth(x, 0.4, 0.3), -0.9, 1.0, 8.0],
                      [0, 1, 2, 4], [0.2, 0.3, -1.0, 5.0], [0.0, 0.0, -1.5, 0.0], [1.0, 1000.0, 1.5, 1000.0],
                      note="free kd, rho1, cx1, n1; cz1 = 1 fixed (rho (s C.p)^n = rho s^n (C.p)^n: the lobe's "
                           "scale is not identifiable)"),
    "torrance-sparrow": Case(["ks", "roughness", "ior"], m1.torrance_sparrow_only,
                             lambda x: [smooth(x, 0.15, 0.1), 0.25, 1.5], [0, 1], [1.0, 0.2], [0.0, 0.002],
                             [1.0, 2.0], note="free ks, roughness; ior = 1.5 fixed (as in ON+TS)"),
    "ashikhmin-shirley": Case(["rd", "rs", "nu", "nv"], m1.ashikhmin_shirley,
                              lambda x: [smooth(x, 0.1, 0.3, 0.03), smooth(x, 0.04, 0.02), 40.0, 15.0],
                              [0, 1, 2, 3], [0.3, 0.05, 20.0, 20.0], [0.0, 0.0, 0.0, 0.0],
                              [1.0, 1.0, 10000.0, 10000.0], note="free rd, rs, nu, nv"),
    "burley": Case(["albedo", "roughness", "specular", "ior"], m1.burley,
                   lambda x: [smooth(x, 0.08, 0.25, 0.03), 0.6, smooth(x, 0.5, 0.3), 1.5], [0, 1, 2],
                   [0.5, 0.5, 1.0], [0.0, 0.02, 0.0], [1.0, 1.0, 1.0],
                   note="free albedo, roughness, specular; ior = 1.5 fixed (specular x Schlick(F0) leaves it "
                        "nearly degenerate with specular, as ks and ior in ON+TS)"),
    "simonot": Case(["albedo", "ior"], m1.simonot, lambda x: [smooth(x, 0.1, 0.5, 0.03), 1.55 - 0.05 * x],
                    [0, 1], [0.5, 1.5], [0.0, 1.0], [1.0, 3.0], note="free albedo, ior"),
    "kelemen-szirmay-kalos": Case(["albedo", "roughness", "ior"], m1.kelemen_szirmay_kalos,
                                  lambda x: [smooth(x, 0.1, 0.4, 0.03), 0.25, 1.6 - 0.05 * x], [0, 1, 2],
                                  [0.5, 0.3, 1.5], [0.0, 0.01, 1.0], [1.0, 1.0, 3.0],
                                  prepare=lambda g: m1.KskGeometry(g), note="free albedo, roughness, ior"),
}


if __name__ == "__main__":
    if sys.argv[1] == "fix":
        model = sys.argv[2]
        print(" ".join("--fix %s=%.17g" % (k, v) for k, v in CASES[model].fixed().items()) if model in CASES
              else "")
