"""One study task: a candidate formulation predicted by the fast or the physical path.

:func:`run_task` is a pure function of the task (a dict that ``run.make_tasks`` builds) and of the fit files'
contents (``fits``: SHA-256 -> text): both paths pass the candidate's formulation and the fits to the library as
values (the fast path to the mixing, the physical path to the surface generator and renderer), so no file is
written. It returns the candidate's result rows. It uses one thread, so a process pool or a Dask worker runs one
task per core, and the same task gives the same numbers, bit for bit, everywhere.
"""

from __future__ import annotations

import hashlib
import json
import math
import os

import numpy as np

_REGION = None
_WEIGHTS = {}
_END_MEMBERS = None
_INSTALLATIONS = {}


def _materialise(formulation):
    """The formulation with its "sha256:..." fit references named as the fits given as values (``<digest>.json``,
    the keys of :func:`_fit_values`)."""
    f = json.loads(json.dumps(formulation))

    def fix(entry):
        ref = entry.get("fit")
        if isinstance(ref, str) and ref.startswith("sha256:"):
            entry["fit"] = ref[7:] + ".json"

    for c in f["components"]:
        fix(c)
    if isinstance(f.get("mastic"), dict):
        fix(f["mastic"])
    return f


def _rtable_outputs(rt):
    return {"Q0": rt["Q0"], "S1": rt["S1"], "Qd": rt["Qd"], "class": rt["class"]}


def _albedo_outputs(a, zeniths):
    """Broadband (solar-weighted) values of a ``roadbrdf.albedo`` result."""
    b = a["broadband"]
    if b is None:  # a single-band fit has no solar-weighted value (docs/albedo.md)
        from .spec import InputError
        raise InputError("no solar-weighted albedo: " + "; ".join(a.get("notes", [])))
    out = {}
    for i, z in enumerate(zeniths):
        out[f"black_sky_{z:g}deg"] = b["black_sky"][i]
        out[f"black_sky_{z:g}deg_error"] = b["black_sky_error"][i]
    out["white_sky"] = b["white_sky"]
    out["white_sky_error"] = b["white_sky_error"]
    if b.get("blue_sky") is not None:
        for i, z in enumerate(zeniths):
            out[f"blue_sky_{z:g}deg"] = b["blue_sky"][i]
            out[f"blue_sky_{z:g}deg_error"] = b["blue_sky_error"][i]
    return out


def _installation(lighting):
    """This process's reading of the study's installation and luminaire, checked against the SHA-256 the study
    recorded (the task key holds them: a file edited while the study runs would give results under another
    file's key)."""
    from .. import _roadbrdf
    from .spec import InputError
    path = lighting["installation"]
    key = (path, lighting["installation_sha256"], lighting["luminaire_sha256"])
    if key not in _INSTALLATIONS:
        prepared = _roadbrdf.read_lighting_installation(path)
        for what, file, digest in (("installation", path, lighting["installation_sha256"]),
                                   ("luminaire", prepared.luminaire_file, lighting["luminaire_sha256"])):
            try:
                with open(file, "rb") as f:
                    same = hashlib.sha256(f.read()).hexdigest() == digest
            except OSError as e:
                raise InputError(f"predictions.lighting: cannot read the {what} file {file}: {e.strerror}") from None
            if not same:
                raise InputError(f"predictions.lighting: the {what} file {file} changed since the study began "
                                 "(run the study again)")
        _INSTALLATIONS[key] = prepared
    return _INSTALLATIONS[key]


def _lighting_outputs(run, lighting):
    """The EN 13201 figures of the installation over the candidate mixture's BRDF (its r-table and, for the light
    reflected upward, its hemispherical reflectance): what ``roadbrdf lighting INSTALLATION --surface MIX.json
    --class C`` gives for the MIX.json of this mixture, the r-table and the reflectance from the end-members
    shared through the process's cache (docs/studies.md "Lighting predictions")."""
    import warnings
    from .. import _roadbrdf
    r = _roadbrdf.mixture_lighting(run, 0, _installation(lighting), _end_members(),
                                   target_class=lighting["class"] or "", operating_hours=lighting["operating_hours"])
    for w in r["warnings"]:
        warnings.warn(w["message"], UserWarning, stacklevel=2)
    least = r["least_flux"] or {}
    up = r["upward"]
    return {"M_class": r["M_class"], "L_av": r["L_av"], "U_o": r["U_o"], "U_l": r["U_l"], "f_TI": r["f_TI"],
            "R_EI": r["R_EI"], "E_av": r["E_av"], "U_o_E": r["U_o_E"], "D_P": r["D_P"], "D_E": r["D_E"],
            "power_per_km_w": r["energy"]["power_per_km_w"], "least_class": least.get("class"),
            "least_dimming_factor": least.get("dimming_factor"),
            "least_power_per_km_w": least.get("power_per_km_w"),
            "least_blocking": " ".join(least.get("blocking") or []) or None, "ULOR": up["ULOR"],
            "direct_upward_lm_per_km": up["direct_upward_lm_per_km"],
            "reflected_upward_lm_per_km": up["reflected_upward_lm_per_km"], "lighting_reflectance": up["reflectance"]}


def _end_members():
    """This process's end-member cache (mixing/end_member_cache.h): each fit file read once, and the
    end-members' albedo integrals and r-table values computed once for every candidate that mixes them."""
    global _END_MEMBERS
    if _END_MEMBERS is None:
        from .. import _roadbrdf
        _END_MEMBERS = _roadbrdf.EndMemberCache()
    return _END_MEMBERS


def _fast(task, candidate):
    """The candidate mixed by each method in this process, as ``roadbrdf mix`` + ``albedo`` + ``rtable`` on its
    MIX.json would give (the r-table bit for bit; the albedo of a linear method from its end-members' integrals,
    within the quadrature's error estimates: docs/studies.md "Speed")."""
    import warnings
    from .. import _roadbrdf
    from ..albedos import _warn_notes
    # The candidate's formulation: its file, or (its content, the fit files' texts by reference) as values.
    formulation, values = (candidate, {}) if isinstance(candidate, str) else (candidate[0], {"fits": candidate[1]})
    p = task["predictions"]
    cache = _end_members()
    diffuse = "" if p["diffuse_fraction"] is None else str(p["diffuse_fraction"])
    rows = []
    for method in p["methods"]:
        run = _roadbrdf.mix(formulation, method=method, cache=cache, **values)
        for note in run.notes:
            warnings.warn(note, UserWarning, stacklevel=2)
        a = _warn_notes(_roadbrdf.mixture_albedo(run, 0, cache, sun_zenith=p["sun_zenith_deg"],
                                                 diffuse_fraction=diffuse, atmosphere=p["atmosphere"],
                                                 spectrum=p["spectrum"]))
        row = {"method": method}
        row.update(_albedo_outputs(a, p["sun_zenith_deg"]))
        row.update(_rtable_outputs(_roadbrdf.mixture_rtable_report(run, 0, cache, illuminant=p["illuminant"] or "")))
        if p.get("lighting") is not None:
            row.update(_lighting_outputs(run, p["lighting"]))
        rows.append(row)
    return rows


def _table(path, columns):
    """Columns of a bundled CSV table as arrays: the header is the first line naming ``columns[0]`` (title and
    ``#`` lines before it are skipped)."""
    with open(path, encoding="utf-8") as f:
        lines = [line.strip() for line in f if line.strip() and not line.startswith("#")]
    start = next(i for i, line in enumerate(lines) if columns[0] in line.split(","))
    names = lines[start].split(",")
    index = [names.index(c) for c in columns]
    values = [[float(line.split(",")[i]) for i in index] for line in lines[start + 1:]]
    return [np.asarray(col, dtype=float) for col in zip(*values)]


def _band_weights(kind, wavelengths):
    """Weights of the rendered bands for a broadband value: trapezoid weights on the bands times the spectrum
    (the solar spectrum or V x illuminant) there; one band: weight 1."""
    key = (kind, tuple(wavelengths))
    if key not in _WEIGHTS:
        import roadbrdf
        data = roadbrdf.data_directory()
        w = np.asarray(wavelengths, dtype=float)
        if kind.startswith("astm"):
            x, y = _table(os.path.join(data, "third-party", "solar", "astm-g173-03.csv"),
                          ["wavelength", kind.split("-")[-1]])
            e = np.interp(w, x, y)
        else:
            x, v, s = _table(os.path.join(data, "third-party", "photometry", "cie-1931-v-lambda-illuminants.csv"),
                             ["wavelength_nm", "v_lambda", "illuminant_" + kind])
            e = np.interp(w, x, v * s, left=0.0, right=0.0)
        if w.size == 1:
            t = np.ones(1)
        else:
            t = np.zeros(w.size)
            t[1:] += np.diff(w) / 2
            t[:-1] += np.diff(w) / 2
        weights = t * e
        if not np.sum(weights) > 0:
            from .spec import InputError
            raise InputError(f"the rendered bands {list(wavelengths)} nm carry no {kind} weight")
        _WEIGHTS[key] = weights / np.sum(weights)
    return _WEIGHTS[key]


def _region():
    """(row, column) cells of the CIE standard r-table region (the defined cells of the bundled R1 table)."""
    global _REGION
    if _REGION is None:
        import roadbrdf
        r1 = roadbrdf.read_rtable(os.path.join(roadbrdf.data_directory(), "third-party", "rtables", "r1-table.dat"))
        rows, cols = np.nonzero(np.isfinite(np.asarray(r1["r"])))
        _REGION = (rows, cols, np.asarray(r1["tan_gamma"], dtype=float), np.asarray(r1["beta_deg"], dtype=float))
    return _REGION


def _fit_values(fits):
    """The fit files' texts by the references :func:`_materialise` writes."""
    return {digest + ".json": text for digest, text in fits.items()}


def _physical(task, formulation, fits):
    """The candidate rendered on a virtual sample generated from its formulation (given as a value, its fits
    too: ``fits`` by reference)."""
    import roadbrdf
    from .. import _roadbrdf
    from ..surfaces import Surface
    from .spec import InputError
    p = task["predictions"]
    q = p["physical"]
    seed = task["seed"]
    common = dict(samples=q["samples"], seed=seed, threads=1, max_bounces=q["max_bounces"])
    import warnings
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # generator notes (e.g. jamming): the row has the texture statistics
        try:
            handle, report = _roadbrdf.surface(formulation, size_mm=float(q["size_mm"]),
                                               cell_mm=float(q["cell_mm"]), seed=seed,
                                               mastic_fraction=task["mastic_fraction"], fits=fits)
            s = Surface(handle, dict(report))
        except ValueError as e:  # e.g. an exposed mastic fraction the sample cannot reach
            raise InputError(str(e)) from None
    row = {"method": "physical", "mpd_mm": s.mpd_mm,
           "exposed_mastic_fraction": float(s.exposed_area_fraction[0])}
    zen = p["sun_zenith_deg"]
    a = roadbrdf.render_albedo(s, zen, wavelengths=q["wavelengths"], white_sky_nodes=q["white_sky_nodes"], **common)
    w = _band_weights(p["spectrum"], q["wavelengths"])
    # Broadband = weighted sum over the bands; its error is the weighted sum of the band errors (the bands share
    # their paths, so their errors are correlated: this is the fully correlated bound).
    black = a["black_sky"] @ w
    black_err = a["black_sky_error"] @ w
    white = float(a["white_sky"] @ w)
    white_err = float(a["white_sky_error"] @ w)
    for i, z in enumerate(zen):
        row[f"black_sky_{z:g}deg"] = float(black[i])
        row[f"black_sky_{z:g}deg_error"] = float(black_err[i])
    row["white_sky"] = white
    row["white_sky_error"] = white_err
    d = p["diffuse_fraction"]
    if d is not None:
        for i, z in enumerate(zen):
            row[f"blue_sky_{z:g}deg"] = float((1 - d) * black[i] + d * white)
            row[f"blue_sky_{z:g}deg_error"] = float((1 - d) * black_err[i] + d * white_err)
    if q["rtable"]:
        rows, cols, tan_gamma, beta = _region()
        gamma = np.degrees(np.arctan(tan_gamma[rows]))
        # Road angles (core/geometry.h): theta_i = gamma, theta_r = 90 - alpha (alpha = 1 deg), phi_i = 0,
        # phi_r = 180 - beta.
        data = roadbrdf.render(s, gamma, 0.0, 89.0, 180.0 - beta[cols], wavelengths=q["wavelengths"],
                               acceptance_deg=q["acceptance_deg"], **common)
        wv = _band_weights(p["illuminant"], q["wavelengths"])
        cos3 = np.cos(np.radians(gamma)) ** 3
        r = np.full((tan_gamma.size, beta.size), np.nan)
        r[rows, cols] = (data.brdf @ wv) * cos3
        sigma = np.zeros_like(r)
        sigma[rows, cols] = (data.sigma @ wv) * cos3
        rt = roadbrdf._roadbrdf.rtable_summary(np.ascontiguousarray(r), "candidate", 1.0)
        row.update(_rtable_outputs(rt))
        # Q0 and Qd are linear in r: their standard errors follow from the same functional applied to the
        # unit cells (weights computed once); S1 = r(0, 2) / r(0, 0) by the ratio rule.
        c0, cd = _linear_weights(rows, cols, tan_gamma.size, beta.size)
        s_cells = sigma[rows, cols]
        row["Q0_error"] = float(math.sqrt(np.sum((c0 * s_cells) ** 2)))
        row["Qd_error"] = float(math.sqrt(np.sum((cd * s_cells) ** 2)))
        i0 = np.argmin(np.abs(tan_gamma - 0.0))
        i2 = np.argmin(np.abs(tan_gamma - 2.0))
        a0, a2 = r[i0, 0], r[i2, 0]
        row["S1_error"] = float(abs(a2 / a0) * math.hypot(sigma[i2, 0] / a2, sigma[i0, 0] / a0))
    return [row]


def _linear_weights(rows, cols, nr, nc):
    """Coefficients c with Q0 = sum c r and Qd = sum c r over the region's cells (from the summary itself)."""
    key = ("linear", nr, nc, len(rows))
    if key not in _WEIGHTS:
        import roadbrdf
        base = np.full((nr, nc), np.nan)
        base[rows, cols] = 1.0
        one = roadbrdf._roadbrdf.rtable_summary(np.ascontiguousarray(base), "", 1.0)
        c0 = np.zeros(len(rows))
        cd = np.zeros(len(rows))
        for k, (i, j) in enumerate(zip(rows, cols)):
            bumped = base.copy()
            bumped[i, j] = 2.0
            t = roadbrdf._roadbrdf.rtable_summary(np.ascontiguousarray(bumped), "", 1.0)
            c0[k] = t["Q0"] - one["Q0"]
            cd[k] = t["Qd"] - one["Qd"]
        _WEIGHTS[key] = (c0, cd)
    return _WEIGHTS[key]


def run_task(task, fits):
    """The result of one task: {"rows": [...], "error": None} or {"rows": [], "error": message}, with its CPU
    time and build (worker.guarded: a task of another build is refused; an unexpected exception is recorded as
    ``internal error: ...``).

    Input errors of the candidate (a formulation the mixing code refuses, a mastic fraction the generator cannot
    reach, ...) become the candidate's recorded error, as they are.
    """
    from .worker import guarded
    return guarded(_run, task, fits)


def _run(task, fits):
    from .spec import InputError
    if task.get("error"):
        return {"rows": [], "error": task["error"]}
    formulation, values = _materialise(task["formulation"]), _fit_values(fits)
    try:
        if task["predictions"]["path"] == "fast":
            rows = _fast(task, (formulation, values))
        else:
            rows = _physical(task, formulation, values)
    except InputError as e:
        return {"rows": [], "error": str(e).replace("<formulation>", "<candidate formulation>")}
    return {"rows": rows, "error": None}
