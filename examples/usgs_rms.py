"""Measured intimate mixtures against their predictions (examples/usgs_mixtures.sh).

    usgs_rms.py MANIFEST.csv --geometry theta_i,phi_i,theta_r,phi_r --range 400:2400
                --table RMS.csv [--figure FIG.png] [--title T] [--check-ratio 2]
                [--check-loo-mean 0.025] [--check-calibration-improves]

MANIFEST.csv has one row per mixture: ``mixture, measured`` (dataset CSV of the measured mixture,
BRDF = R/pi at the assumed geometry), ``hapke``, ``areal`` (MIX.json of `roadbrdf mix --method ...`), optionally
``insample`` (hapke with cross-section factors calibrated on every mixture of the set) and ``calibrated``
(hapke with factors calibrated on the other mixtures: leave-one-out; empty when not predictable), then
``wt_<end-member>`` columns (mass %, copied to the table). For each mixture and method the prediction is
evaluated at the MIX.json's wavelengths inside the range, at the geometry, turned into a reflectance factor
(R = pi f, the inverse of the dataset's R/pi) and compared with the measured R, interpolated linearly onto
those wavelengths (exact for the 1 nm ASD channels): RMS = sqrt(mean (R_pred - R_meas)^2).

The table (written atomically): mixture, the wt % columns, rms_hapke, rms_areal, ratio = rms_areal /
rms_hapke (> 1: hapke better), then rms_insample and rms_calibrated when present ("n/a": no prediction).
--check-ratio K exits 1 unless hapke is at least K times better than areal for more than half of the mixtures
(the target of the validation), after printing the table either way. --check-loo-mean X exits 1 unless the mean of
rms_calibrated over the mixtures is <= X (every mixture must have a prediction); --check-calibration-improves
exits 1 unless that mean is below the mean of rms_hapke over the same mixtures.
"""
import argparse
import csv
import io
import math
import sys

import numpy as np

import roadbrdf
from roadbrdf.core import write_figure_atomic, write_text_atomic

METHODS = ("hapke", "areal")
CALIBRATED = ("insample", "calibrated")


def rms_of(row, angles, lo, hi):
    measured = roadbrdf.read_dataset(row["measured"])
    if measured.brdf.shape[0] != 1:
        raise SystemExit(f"{row['measured']}: expected one geometry, found {measured.brdf.shape[0]}")
    out = {}
    curves = {}
    for method in METHODS + CALIBRATED:
        if not row.get(method):
            continue
        model = roadbrdf.read_fit(row[method], "hapke" if method in CALIBRATED else method)
        wl = model.wavelengths[(model.wavelengths >= lo) & (model.wavelengths <= hi)]
        if wl.size == 0:
            raise SystemExit(f"{row[method]}: no wavelength in {lo}-{hi} nm")
        if wl[0] < measured.wavelengths[0] or wl[-1] > measured.wavelengths[-1]:
            raise SystemExit(f"{row['measured']}: does not cover {wl[0]}-{wl[-1]} nm")
        r_pred = math.pi * np.asarray(model.evaluate(*angles, wl), dtype=float)
        r_meas = math.pi * np.interp(wl, measured.wavelengths, measured.brdf[0])
        out[method] = float(np.sqrt(np.mean((r_pred - r_meas) ** 2)))
        curves[method] = (wl, r_pred)
    curves["measured"] = (measured.wavelengths, math.pi * measured.brdf[0])
    return out, curves


def draw(results, path, title):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    n = len(results)
    cols = min(n, 4)
    rows = (n + cols - 1) // cols
    fig, axes = plt.subplots(rows, cols, figsize=(3.4 * cols, 2.8 * rows), sharex=True, squeeze=False)
    for ax, (name, rms, curves) in zip(axes.flat, results):
        wl, r = curves["measured"]
        ax.plot(wl, r, color="k", lw=1.2, label="measured")
        ax.plot(*curves["hapke"], color="tab:red", lw=1, label=f"hapke ({rms['hapke']:.3f})")
        ax.plot(*curves["areal"], color="tab:blue", lw=1, ls="--", label=f"areal ({rms['areal']:.3f})")
        if "calibrated" in curves:
            ax.plot(*curves["calibrated"], color="tab:green", lw=1,
                    label=f"calibrated, LOO ({rms['calibrated']:.3f})")
        ax.set_title(name, fontsize=9)
        ax.set_ylim(0, 1)
        ax.legend(fontsize=6, loc="lower right")
    for ax in list(axes.flat)[n:]:
        ax.set_visible(False)
    for ax in axes[-1]:
        ax.set_xlabel("wavelength [nm]")
    for ax in axes[:, 0]:
        ax.set_ylabel("reflectance factor")
    fig.suptitle(title, fontsize=10)
    fig.tight_layout()
    write_figure_atomic(fig, path, dpi=110)
    plt.close(fig)


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("manifest")
    p.add_argument("--geometry", required=True, help="theta_i,phi_i,theta_r,phi_r [deg]")
    p.add_argument("--range", default="400:2400", help="LO:HI [nm]")
    p.add_argument("--table", required=True)
    p.add_argument("--figure")
    p.add_argument("--title", default="USGS intimate mixtures")
    p.add_argument("--check-ratio", type=float)
    p.add_argument("--check-loo-mean", type=float)
    p.add_argument("--check-calibration-improves", action="store_true")
    a = p.parse_args(argv)
    angles = [float(x) for x in a.geometry.split(",")]
    lo, hi = (float(x) for x in a.range.split(":"))
    with open(a.manifest, newline="") as f:
        rows = list(csv.DictReader(f))
    if not rows:
        raise SystemExit(f"{a.manifest}: no mixture")
    wt = [k for k in rows[0] if k.startswith("wt_")]
    results = []
    text = io.StringIO()
    w = csv.writer(text, lineterminator="\n")
    extra = [m for m in CALIBRATED if m in rows[0]]
    w.writerow(["mixture", *wt, "rms_hapke", "rms_areal", "ratio", *(f"rms_{m}" for m in extra)])
    for row in rows:
        rms, curves = rms_of(row, angles, lo, hi)
        ratio = rms["areal"] / rms["hapke"] if rms["hapke"] > 0 else math.inf
        w.writerow([row["mixture"], *(row[k] for k in wt), f"{rms['hapke']:.4f}", f"{rms['areal']:.4f}",
                    f"{ratio:.2f}", *(f"{rms[m]:.4f}" if m in rms else "n/a" for m in extra)])
        results.append((row["mixture"], rms, curves))
    means = {}
    for m in ("hapke", "areal", *extra):
        values = [r[m] for _, r, _ in results if m in r]
        means[m] = (float(np.mean(values)) if values else math.nan, len(values))
    w.writerow(["mean", *("" for _ in wt), f"{means['hapke'][0]:.4f}", f"{means['areal'][0]:.4f}", "",
                *(f"{means[m][0]:.4f}" if means[m][1] else "n/a" for m in extra)])
    write_text_atomic(a.table, text.getvalue())
    sys.stdout.write(text.getvalue())
    if a.figure:
        draw(results, a.figure, a.title)
    ratios = [r["areal"] / r["hapke"] if r["hapke"] > 0 else math.inf for _, r, _ in results]
    better = sum(x > 1 for x in ratios)
    print(f"hapke better than areal on {better} of {len(ratios)} mixtures; "
          f"at least 2x better on {sum(x >= 2 for x in ratios)}")
    status = 0
    if a.check_ratio is not None:
        good = sum(x >= a.check_ratio for x in ratios)
        if 2 * good <= len(ratios):
            print(f"CHECK FAILED: hapke is at least {a.check_ratio:g}x better than areal on only {good} of "
                  f"{len(ratios)} mixtures (needs more than half)")
            status = 1
        else:
            print(f"check passed: hapke at least {a.check_ratio:g}x better than areal on {good} of {len(ratios)}")
    if "calibrated" in extra:
        loo = [(r["calibrated"], r["hapke"]) for _, r, _ in results if "calibrated" in r]
        n_loo = len(loo)
        mean_loo = float(np.mean([x for x, _ in loo])) if loo else math.nan
        mean_unc = float(np.mean([y for _, y in loo])) if loo else math.nan
        if n_loo:
            print(f"leave-one-out calibrated hapke: {n_loo} of {len(results)} mixtures predicted; mean RMS "
                  f"{mean_loo:.4f} (uncalibrated hapke on the same mixtures {mean_unc:.4f})")
        else:
            print(f"leave-one-out calibrated hapke: none of the {len(results)} mixtures can be predicted from the others")
        if a.check_loo_mean is not None:
            if n_loo < len(results) or not mean_loo <= a.check_loo_mean:
                print(f"CHECK FAILED: leave-one-out mean RMS {mean_loo:.4f} over {n_loo} of {len(results)} "
                      f"mixtures; target <= {a.check_loo_mean:g} on all")
                status = 1
            else:
                print(f"check passed: leave-one-out mean RMS {mean_loo:.4f} <= {a.check_loo_mean:g}")
        if a.check_calibration_improves:
            if not n_loo or not mean_loo < mean_unc:
                print(f"CHECK FAILED: calibration does not improve on uncalibrated hapke "
                      f"({mean_loo:.4f} vs {mean_unc:.4f})")
                status = 1
            else:
                print(f"check passed: calibration improves the mean RMS from {mean_unc:.4f} to {mean_loo:.4f}")
    elif a.check_loo_mean is not None or a.check_calibration_improves:
        print("CHECK FAILED: no leave-one-out predictions in the manifest")
        status = 1
    return 1 if status else 0


if __name__ == "__main__":
    sys.exit(main())
