#!/usr/bin/env python3
"""Helpers of the virtual-sample ground-truth study (examples/virtual_study.sh, docs/virtual-study.md).

  virtual_study.py relabel IN.surface.json OUT.surface.json SPEC [SPEC ...]
      Same height field and material map, materials replaced: one SPEC for every material, or one
      SPEC per material (index order). SPEC = a fit file (path as given, written relative to OUT's
      folder) or lambert:ALBEDO.
  virtual_study.py formulation IN.json OUT.json --mastic FIT [--rock STEM=FIT ...]
      The formulation with every fit replaced: coarse aggregates by the fit given for the stem of
      their original fit file (e.g. garonne=V/garonne.fit.json), every other component and the
      "mastic" key by --mastic. Paths are written relative to OUT's folder.
  virtual_study.py report OUT_DIR
      The tables of docs/virtual-study.md from the files written by virtual_study.sh (markdown on
      standard output).

Angles in degrees, BRDF in sr^-1, wavelengths in nm. Relative RMSE = RMSE / mean |virtual BRDF|
(the definition used by `roadbrdf mix`).
"""
from __future__ import annotations

import json
import os
import sys

import numpy as np


def _relative(path: str, folder: str) -> str:
    return os.path.relpath(os.path.abspath(path), os.path.abspath(folder))


def _material(spec: str, out_folder: str) -> dict:
    if spec.startswith("lambert:"):
        albedo = float(spec.split(":", 1)[1])
        return {"name": f"lambert {albedo:g}", "model": "lambert", "parameters": {"albedo": albedo}, "options": {}}
    if not os.path.isfile(spec):
        raise SystemExit(f"virtual_study.py: material fit file not found: {spec}")
    return {"name": os.path.basename(spec).replace(".fit.json", ""), "fit": _relative(spec, out_folder),
            "fit_model": ""}


def relabel(src: str, dst: str, specs: list[str]) -> None:
    with open(src) as f:
        s = json.load(f)
    n = len(s["materials"])
    if len(specs) not in (1, n):
        raise SystemExit(f"virtual_study.py: {src} has {n} materials: give 1 or {n} SPECs, not {len(specs)}")
    folder = os.path.dirname(os.path.abspath(dst))
    new = [_material(x, folder) for x in (specs * n if len(specs) == 1 else specs)]
    s["description"] = (s.get("description", "") + " | materials replaced by virtual_study.py: " +
                        ", ".join(f"{old['name']} -> {m['name']}" for old, m in zip(s["materials"], new)))
    s["materials"] = new
    s.pop("statistics", None)  # the exposed fractions are those of the original file
    with open(dst, "w") as f:
        json.dump(s, f)


def formulation(src: str, dst: str, mastic: str, rocks: list[str]) -> None:
    with open(src) as f:
        d = json.load(f)
    rock_fit = dict(r.split("=", 1) for r in rocks)
    folder = os.path.dirname(os.path.abspath(dst))
    coarse_min = d.get("coarse_min_size_mm", 2.0)
    for c in d["components"]:
        stem = os.path.basename(c["fit"]).replace(".fit.json", "")
        coarse = c["kind"] == "aggregate" and c.get("d_min_mm", 0.0) >= coarse_min
        if coarse:
            if stem not in rock_fit:
                raise SystemExit(f"virtual_study.py: no --rock {stem}=FIT for coarse component {c['name']}")
            c["fit"] = _relative(rock_fit[stem], folder)
        else:
            c["fit"] = _relative(mastic, folder)
        c.pop("fit_model", None)
    d["mastic"]["fit"] = _relative(mastic, folder)
    d["mastic"].pop("fit_model", None)
    d["name"] = d["name"] + " (virtual components)"
    d.setdefault("assumptions", []).append(
        "Virtual study: every fit is that of a virtual single-component sample rendered by the same virtual "
        "gonioreflectometer as the virtual mixture (examples/virtual_study.sh).")
    with open(dst, "w") as f:
        json.dump(d, f, indent=2)


# ---- analysis ---------------------------------------------------------------------------------

def _rb():
    import roadbrdf  # noqa: PLC0415 (needs PYTHONPATH=<build>/python)
    return roadbrdf


def _dirs(ds):
    t_i, p_i, t_r, p_r = (np.radians(np.asarray(a, dtype=float)) for a in (ds.theta_i, ds.phi_i, ds.theta_r, ds.phi_r))
    wi = np.stack([np.sin(t_i) * np.cos(p_i), np.sin(t_i) * np.sin(p_i), np.cos(t_i)], axis=1)
    wr = np.stack([np.sin(t_r) * np.cos(p_r), np.sin(t_r) * np.sin(p_r), np.cos(t_r)], axis=1)
    phase = np.degrees(np.arccos(np.clip(np.sum(wi * wr, axis=1), -1.0, 1.0)))
    return np.asarray(ds.theta_i, dtype=float), np.asarray(ds.theta_r, dtype=float), phase


PHASE_BINS = [(0, 30), (30, 60), (60, 90), (90, 120), (120, 181)]
THETA_BINS = [(0, 30), (30, 50), (50, 70), (70, 91)]


def _bin_rows(label, key, bins, rel):
    """Mean signed and rms relative residual [%] of the geometries whose `key` falls in each bin."""
    out = []
    for lo, hi in bins:
        sel = (key >= lo) & (key < hi)
        if not sel.any():
            continue
        r = rel[sel]
        out.append((f"{label} {lo}-{min(hi, 180) if hi != 91 else 90}", int(sel.sum()), 100 * r.mean(),
                    100 * np.sqrt((r ** 2).mean())))
    return out


def _model_on(ds, path, which=""):
    rb = _rb()
    m = rb.read_fit(path, which or None)
    wl = np.asarray(ds.wavelengths, dtype=float)
    a = [np.asarray(x, dtype=float)[:, None] for x in (ds.theta_i, ds.phi_i, ds.theta_r, ds.phi_r)]
    return np.asarray(m.evaluate(*a, wl[None, :]), dtype=float)


def _relative_rmse(pred, y):
    return float(np.sqrt(np.mean((pred - y) ** 2)) / np.mean(np.abs(y)))


def _nnls(columns, y):
    from scipy.optimize import nnls  # noqa: PLC0415
    a = np.stack([c.reshape(-1) for c in columns], axis=1)
    w, _ = nnls(a, y.reshape(-1))
    return w


def _table(header, rows, fmt):
    lines = ["| " + " | ".join(header) + " |", "|" + "---|" * len(header)]
    for r in rows:
        lines.append("| " + " | ".join(f.format(v) for f, v in zip(fmt, r)) + " |")
    return "\n".join(lines)


def _binned_table(rel_by_name, ds):
    t_i, t_r, phase = _dirs(ds)
    names = list(rel_by_name)
    rows = {}
    for name in names:
        rel = rel_by_name[name]
        for label, key, bins in (("phase", phase, PHASE_BINS), ("theta_i", t_i, THETA_BINS),
                                 ("theta_r", t_r, THETA_BINS)):
            for b, n, mean, rms in _bin_rows(label, key, bins, rel):
                rows.setdefault(b, [b, n]).extend([mean, rms])
    header = ["bin [deg]", "n"] + [f"{n}: {s}" for n in names for s in ("mean %", "rms %")]
    return _table(header, rows.values(), ["{}", "{}"] + ["{:+.1f}", "{:.1f}"] * len(names))


def _mix_methods(path):
    with open(path) as f:
        d = json.load(f)
    return d, {m["method"]: m for m in d["methods"]}


def _area_fractions(surface_path):
    with open(surface_path) as f:
        s = json.load(f)
    mat = np.asarray(s["material"])
    fits = [m.get("fit", m["name"]) for m in s["materials"]]
    distinct = list(dict.fromkeys(fits))  # component j = j-th distinct fit (virtual_study.sh)
    names = [os.path.basename(f).replace(".fit.json", "") for f in distinct]
    return names, np.array([sum((mat == i).mean() for i, f in enumerate(fits) if f == d) for d in distinct])


def report(out: str) -> None:
    rb = _rb()
    p = lambda *a: os.path.join(out, *a)  # noqa: E731
    print("<!-- generated by examples/virtual_study.py report " + out + " -->\n")

    # 1. Diagnosis on the virtual F1 texture.
    print("### D1. Flat sample (renderer check): rendered / fit - 1\n")
    flat = rb.read_dataset(p("data", "flat-mastic.csv"))
    fit = _model_on(flat, p("fits", "mastic-garonne-bitumen.fit.json"))
    y, s = np.asarray(flat.brdf), np.asarray(flat.sigma)
    print(f"ideal detector (acceptance 0): max relative difference |rendered / fit - 1| = "
          f"{np.max(np.abs(y / fit - 1)):.2e} over {y.size} values (geometries x bands), max sigma {np.max(s):.1e} "
          f"sr^-1\n")

    print("### D2. One material on the F1 macro-texture: rendered / material BRDF - 1 (all bands)\n")
    rel = {}
    for label, data, model in (("mastic fit", "F1-all-mastic.csv", p("fits", "mastic-garonne-bitumen.fit.json")),
                               ("garonne fit", "F1-all-garonne.csv", p("fits", "garonne.fit.json")),
                               ("lambert 0.5", "F1-all-lambert.csv", None)):
        ds = rb.read_dataset(p("data", data))
        y = np.asarray(ds.brdf)
        f = _model_on(ds, model) if model else np.full_like(y, 0.5 / np.pi)
        rel[label] = (y / f - 1).mean(axis=1)
        print(f"- {label}: relative RMSE of the material's own BRDF as a model of the textured sample "
              f"{_relative_rmse(f, y):.3f}")
    print()
    print(_binned_table(rel, ds))
    print()

    print("### D3. Where each material of the virtual F1 is seen: single-scattering share of the mastic\n")
    _share(p, "F1")

    print("### D4. Mixing methods with the measured (real-sample) fits against the virtual F1\n")
    d, methods = _mix_methods(p("mix", "F1-real-fits.mix.json"))
    print(_table(["method", "held-out rel. RMSE", "in-sample rel. RMSE", "weights"],
                 [(m, v["comparison"]["relative_rmse"], v["comparison"]["relative_rmse_in_sample"],
                   ", ".join(f"{k} {w:.3f}" for k, w in v["weights"].items())) for m, v in methods.items()],
                 ["{}", "{:.3f}", "{:.3f}", "{}"]))
    print()
    ds = rb.read_dataset(p("data", "F1.csv"))
    y = np.asarray(ds.brdf)
    rel = {}
    for m in ("fitted", "mastic", "shadowed"):
        rel[m] = ((_model_on(ds, p("mix", "F1-real-fits.mix.json"), m) - y) / y).mean(axis=1)
    print("Relative residual (prediction / virtual - 1, mean over bands) by geometry:\n")
    print(_binned_table(rel, ds))
    print()

    # 2. The self-consistent study.
    tags = ["F1", "F2", "F3", "F4", "F1-60mm-seed2"]
    print("### G1. Virtual components, virtual mixtures: held-out relative RMSE (5 folds) of each method\n")
    _g1(p, tags)
    print("### G2. Mixing the rendered component datasets directly (no model fit in between)\n")
    _g2(p, tags)
    print("### G3. Best fitted-linear prediction with the virtual-component fits, residual by geometry\n")
    _g3(p, tags[:4])

    # 2b. The same at 25 % exposed mastic (surface --mastic-fraction 0.25).
    m25 = ["F1-m25", "F2-m25", "F3-m25", "F4-m25"]
    print("### G1-m25. As G1 with the mastic raised to 25 % of the plan (--mastic-fraction 0.25)\n")
    print(_table(["mixture", "mastic level [mm]", "MPD [mm]", "exposed mastic (counted)"],
                 [(t,) + _level_mpd(p, t) for t in m25], ["{}", "{:.3f}", "{:.3f}", "{:.4f}"]))
    print()
    _g1(p, m25)
    print("### G2-m25. As G2 at 25 % mastic\n")
    _g2(p, m25)
    print("### G3-m25. As G3 at 25 % mastic\n")
    _g3(p, m25)
    print("### D3-m25. Single-scattering share of the mastic on F1-m25\n")
    _share(p, "F1-m25")

    print("### G4. Laboratory-like components (flat mastic = its fit, rock trays), virtual mixtures: held-out "
          "relative RMSE\n")
    print(_lab_table(p))
    print()

    print("### G5. Quality of the fits of the virtual single-component samples\n")
    rows = []
    for name in sorted(os.listdir(p("vfits"))):
        with open(p("vfits", name)) as f:
            fd = json.load(f)
        for ft in fd["fits"]:
            if ft["model"] == fd["best"]:
                rows.append((name.replace(".fit.json", ""), ft["model"], float(np.mean(ft["relative_rmse"]))))
    print(_table(["virtual sample", "best model (BIC)", "relative RMSE (mean over bands)"], rows,
                 ["{}", "{}", "{:.3f}"]))
    print()


def _share(p, tag):
    """D3: the mastic's share of the single-scattered light of a white Lambertian version of `tag`."""
    rb = _rb()
    ds_m = rb.read_dataset(p("data", f"{tag}-share-mastic.csv"))
    ds_1 = rb.read_dataset(p("data", f"{tag}-share-all.csv"))
    share = np.asarray(ds_m.brdf)[:, 0] / np.asarray(ds_1.brdf)[:, 0]
    names, fr = _area_fractions(p("surfaces", f"{tag}.surface.json"))
    print(f"projected area fraction of the mastic: {fr[0]:.3f}; its share of the single-scattered light of a "
          f"Lambertian sample (lit and seen fraction, cosine-weighted): median {np.median(share):.3f}, "
          f"range {share.min():.3f}-{share.max():.3f}\n")
    t_i, t_r, phase = _dirs(ds_1)
    rows = []
    for lo, hi in THETA_BINS:
        for lo2, hi2 in THETA_BINS:
            sel = (t_i >= lo) & (t_i < hi) & (t_r >= lo2) & (t_r < hi2)
            if sel.any():
                rows.append((f"{lo}-{min(hi, 90)}", f"{lo2}-{min(hi2, 90)}", int(sel.sum()), share[sel].mean(),
                             share[sel].min(), share[sel].max()))
    print(_table(["theta_i", "theta_r", "n", "mastic share (mean)", "min", "max"], rows,
                 ["{}", "{}", "{}", "{:.3f}", "{:.3f}", "{:.3f}"]))
    print()
    # The shadowed method's form: share = a exp(-s (tan theta_i + tan theta_r)); a, s by least squares on ln(share)
    # over theta_i, theta_r <= 70 deg (beyond, tan diverges).
    sel = (t_i <= 70) & (t_r <= 70) & (share > 0)
    tsum = np.tan(np.radians(t_i[sel])) + np.tan(np.radians(t_r[sel]))
    slope, intercept = np.polyfit(tsum, np.log(share[sel]), 1)
    pred = np.exp(intercept + slope * tsum)
    print(f"\nFit share = a exp(-s (tan theta_i + tan theta_r)) over the {int(sel.sum())} geometries with theta_i, "
          f"theta_r <= 70 deg: a = {np.exp(intercept):.3f}, s = {-slope:.3f}, rms relative deviation "
          f"{100 * np.sqrt(np.mean((pred / share[sel] - 1) ** 2)):.0f} %\n")


def _g1(p, tags):
    rows = []
    all_methods = None
    for tag in tags:
        d, methods = _mix_methods(p("mix", f"{tag}.mix.json"))
        all_methods = list(methods)
        rows.append([tag] + [methods[m]["comparison"]["relative_rmse"] for m in all_methods] + [d["best"]])
    print(_table(["mixture"] + all_methods + ["best"], rows, ["{}"] + ["{:.3f}"] * len(all_methods) + ["{}"]))
    print()
    print("Weights (fitted method) against the projected area fractions of the virtual mixture:\n")
    rows = []
    for tag in tags:
        _, methods = _mix_methods(p("mix", f"{tag}.mix.json"))
        names, fr = _area_fractions(p("surfaces", f"{tag}.surface.json"))
        rows.append((tag, ", ".join(f"{n} {w:.3f}" for n, w in methods["fitted"]["weights"].items()),
                     ", ".join(f"{n} {a:.3f}" for n, a in zip(names, fr)),
                     ", ".join(f"{w:.3f}" for w in methods["shadowed"]["weights"].values()),
                     methods["shadowed"]["settings"].get("shadowing", float("nan"))))
    print(_table(["mixture", "fitted weights", "projected area fractions (surface)", "shadowed: weights", "s"], rows,
                 ["{}", "{}", "{}", "{}", "{:.3f}"]))
    print()


def _g2(p, tags):
    rb = _rb()
    rows = []
    residuals = {}
    for tag in tags:
        mix = rb.read_dataset(p("data", f"{tag}.csv"))
        y = np.asarray(mix.brdf)
        names, fr = _area_fractions(p("surfaces", f"{tag}.surface.json"))
        comps = [np.asarray(rb.read_dataset(p("data", f"{tag}-comp{j}.csv")).brdf) for j in range(len(names))]
        areal = sum(a * c for a, c in zip(fr, comps))
        w = _nnls(comps, y)
        nn = sum(a * c for a, c in zip(w, comps))
        rows.append((tag, _relative_rmse(areal, y), _relative_rmse(nn, y),
                     ", ".join(f"{a:.3f}" for a in w), ", ".join(f"{a:.3f}" for a in fr)))
        if "60mm" not in tag:
            residuals[f"{tag} areal"] = ((areal - y) / y).mean(axis=1)
    print(_table(["mixture", "areal (projected fractions) rel. RMSE", "NNLS rel. RMSE (in-sample)",
                  "NNLS weights", "projected fractions"], rows, ["{}", "{:.3f}", "{:.3f}", "{}", "{}"]))
    print()
    print("Areal mixing of the rendered components: relative residual (prediction / virtual - 1) by geometry:\n")
    print(_binned_table(residuals, mix))
    print()


def _g3(p, tags):
    rb = _rb()
    rel = {}
    for tag in tags:
        mix = rb.read_dataset(p("data", f"{tag}.csv"))
        y = np.asarray(mix.brdf)
        rel[f"{tag} fitted"] = ((_model_on(mix, p("mix", f"{tag}.mix.json"), "fitted") - y) / y).mean(axis=1)
    print(_binned_table(rel, mix))
    print()


def _level_mpd(p, tag):
    with open(p("surfaces", f"{tag}.surface.json")) as f:
        s = json.load(f)
    z = np.asarray(s["heights_mm"])
    return (float(z.min()), float(s["statistics"]["mpd_mm"]), float((np.asarray(s["material"]) == 0).mean()))


def _lab_table(p):
    rows = []
    all_methods = None
    for k in (1, 2, 3, 4):
        d, methods = _mix_methods(p("mix", f"F{k}-lab.mix.json"))
        all_methods = list(methods)
        rows.append([f"F{k}"] + [methods[m]["comparison"]["relative_rmse"] for m in all_methods] + [d["best"]] +
                    [", ".join(f"{n} {w:.3f}" for n, w in methods["fitted"]["weights"].items())])
    return _table(["mixture"] + all_methods + ["best", "fitted weights"], rows,
                  ["{}"] + ["{:.3f}"] * len(all_methods) + ["{}", "{}"])


def main(argv):
    if len(argv) < 2:
        raise SystemExit(__doc__)
    cmd = argv[1]
    if cmd == "relabel" and len(argv) >= 5:
        relabel(argv[2], argv[3], argv[4:])
    elif cmd == "formulation" and len(argv) >= 6:
        args = argv[4:]
        mastic, rocks = None, []
        while args:
            if args[0] == "--mastic":
                mastic = args[1]
            elif args[0] == "--rock":
                rocks.append(args[1])
            else:
                raise SystemExit(f"virtual_study.py: unknown argument {args[0]}")
            args = args[2:]
        if mastic is None:
            raise SystemExit("virtual_study.py formulation: --mastic FIT is required")
        formulation(argv[2], argv[3], mastic, rocks)
    elif cmd == "report" and len(argv) == 3:
        report(argv[2])
    else:
        raise SystemExit(__doc__)


if __name__ == "__main__":
    main(sys.argv)
