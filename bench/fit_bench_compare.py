"""Compare roadbrdf and scipy fits of the benchmark (per-wavelength final costs 1/2 sum r^2, times).
Usage: fit_bench_compare.py ROADBRDF_FIT.json SCIPY.json [WHOLE_COMMAND_CPU_SECONDS]
With WHOLE_COMMAND_CPU_SECONDS (user + system CPU of the whole `roadbrdf fit` process: reading,
fitting, statistics, writing) the ratio of scipy's fit CPU to it is printed as well."""
import json
import sys


def main():
    rb = json.load(open(sys.argv[1]))["fits"][0]
    sp = json.load(open(sys.argv[2]))
    whole = float(sys.argv[3]) if len(sys.argv) > 3 else None
    index = {round(w, 6): i for i, w in enumerate(rb["wavelengths"])}
    worse, better, n = 0, 0, 0
    worst = 0.0
    for w, c in zip(sp["wavelengths"], sp["cost"]):
        cr = rb["cost"][index[round(w, 6)]]
        n += 1
        rel = (cr - c) / c
        worst = max(worst, rel)
        if rel > 1e-6:
            worse += 1
        elif rel < -1e-6:
            better += 1
    stride = sp.get("stride", 1)
    t_rb, c_rb = rb["seconds"], rb["cpu_seconds"]
    t_sp, c_sp = sp["seconds"] * stride, sp["cpu_seconds"] * stride  # extrapolated when STRIDE > 1
    note = " (extrapolated from every %d-th wavelength)" % stride if stride > 1 else ""
    print("roadbrdf fit: %.3f s wall, %.3f s CPU for %d wavelengths" % (t_rb, c_rb, len(rb["wavelengths"])))
    print("scipy fit:    %.3f s wall, %.3f s CPU%s" % (t_sp, c_sp, note))
    print("speed-up:     %.1fx wall, %.1fx CPU (fit only)" % (t_sp / t_rb, c_sp / c_rb))
    if whole is not None:
        print("speed-up:     %.1fx CPU, whole roadbrdf command (%.3f s CPU: read, fit, statistics, write)"
              % (c_sp / whole, whole))
    print("total cost roadbrdf %.6e, scipy %.6e (same wavelengths)" % (
        sum(rb["cost"][index[round(w, 6)]] for w in sp["wavelengths"]), sum(sp["cost"])))
    print("wavelengths where roadbrdf's cost is worse by > 1e-6 relative: %d of %d, better: %d, "
          "max relative excess %.2e" % (worse, n, better, worst))


if __name__ == "__main__":
    main()
