"""The sections of the sample report (``roadbrdf report``): each function turns the results gathered by
:mod:`roadbrdf.report` (an object ``r`` with the dataset, the check, the fits, albedo, r-table, mixing
and the rendered figures) into a :class:`~roadbrdf.report_html.Section`.

Numbers are shown rounded and carried exactly in ``data-value`` (report_html); ``data-key`` names them:
``file.*``, ``data.*``, ``check.*``, ``coverage.*``, ``group.MODEL.theta_i=T.PARAM`` (per-incidence fits),
``rank.MODEL.*`` (all configurations), ``all.MODEL.PARAM`` (their parameters at the band),
``albedo.*``, ``rtable.*``, ``mix.METHOD.*``.
"""

from __future__ import annotations

import math
import re

import numpy as np

from .report_html import Cell, Section, caveats, cell, definition_list, esc, figure, number, table

__all__ = ["summary", "provenance", "quality", "coverage", "spectra", "per_incidence", "ranking", "albedo",
           "rtable", "mixing", "FIT_COLUMNS"]

# The statistics columns of roadbrdf.params(...) shown after the parameters: (column, header, digits).
FIT_COLUMNS = [("rmse_per_sr", "RMSE [sr⁻¹]", 4), ("relative_rmse_percent", "rel. RMSE [%]", 3),
               ("max_relative_error_percent", "max rel. error [%]", 3), ("aic", "AIC", 6), ("bic", "BIC", 6)]


def _figure(r, key):
    """The embedded figure ``key`` (or the reason it is missing)."""
    if key in r.figures:
        png, caption = r.figures[key]
        return figure(png, caption, caption, key)
    if key in r.figure_errors:
        return caveats([f"figure not drawn: {r.figure_errors[key]}"])
    return ""


def _angles(values):
    return ", ".join(f"{v:g}" for v in values) + " °" if len(values) else "–"


def _fixed_text(r):
    return ", ".join(f"{k} = {v:g}" for k, v in r.fixed.items()) or "none"


# ---- summary ------------------------------------------------------------------------------------
def summary(r) -> str:
    """The boxes at the top of the page: the result a reader looks for first."""
    items = [("sample", esc(r.sample), None), ("best model (BIC, all configurations)", esc(r.best.model), None)]
    bb = (r.albedo or {}).get("broadband") if r.albedo else None
    if bb:
        items.append(("white-sky albedo (solar)", number(bb["white_sky"], 3), ("summary.white_sky", bb["white_sky"])))
        z = r.albedo["sun_zenith_deg"]
        if bb.get("blue_sky") is not None:
            items.append((f"blue-sky albedo, sun at {z[0]:g}°", number(bb["blue_sky"][0], 3), None))
    if r.rtable is not None:
        items.append(("r-table: Q0 [sr⁻¹] / S1", f"{number(r.rtable['Q0'], 3)} / {number(r.rtable['S1'], 3)}", None))
        items.append(("road surface class", esc(f"{r.rtable['class']} (N: {r.rtable['classes'].get('N', '–')}, "
                                                f"C: {r.rtable['classes'].get('C', '–')})"), None))
    flags = len(r.check.get("outliers", [])) + int(r.check["reciprocity"]["flagged"]) + \
        len(r.check["noise"]["noisy_bands"])
    items.append(("quality flags (outliers, reciprocity, noisy bands)", str(flags), None))
    plausibility = _plausibility_warnings(r)
    items.append(("plausibility warnings (scale, BRDF × cos θ_i)", str(len(plausibility)),
                  ("summary.plausibility_warnings", len(plausibility))))
    out = ['<div class="summary-grid">']
    for label, value, key in items:
        attr = f' data-key="{key[0]}" data-value="{float(key[1])!r}"' if key else ""
        out.append(f'<div><span class="label">{esc(label)}</span><span class="value"{attr}>{value}</span></div>')
    out.append("</div>")
    extrapolated = [n for n in r.all_caveats if n.lower().startswith("mostly extrapolation")]
    out.append(caveats(extrapolated))
    return "".join(out)


def _plausibility_warnings(r) -> list:
    """The plausibility warnings of the check (``plausibility.warnings``: a scale implausible for a BRDF in
    sr^-1, data that look like BRDF × cos θ_i), one line each."""
    return [str(w) for w in (r.check.get("plausibility") or {}).get("warnings") or []]


# ---- 1. provenance ------------------------------------------------------------------------------
def provenance(r) -> Section:
    d, f = r.dataset, r.file
    wl = d.wavelengths
    steps = np.unique(np.round(np.diff(wl), 6)) if wl.size > 1 else np.array([])
    step = ("–" if steps.size == 0 else f"{steps[0]:g} nm" if steps.size == 1
            else f"{steps.min():g}–{steps.max():g} nm (uneven)")
    items = [
        ("file", esc(f["name"])),
        ("path given", esc(f["path"])),
        ("size [bytes]", cell(f["size"], "file.size", digits=0, fixed=True)),
        ("SHA-256", Cell(esc(f["sha256"]), "file.sha256")),
        ("last modified (UTC)", esc(f["modified"])),
        ("data rows (after the header)", cell(f["rows"], "file.rows", digits=0, fixed=True)),
        ("angle columns", esc("road (gamma, alpha, beta, delta)" if d.convention == "road"
                              else "zenith/azimuth (theta_i, phi_i, theta_r, phi_r)")),
        ("geometries", cell(len(d), "data.geometries", digits=0, fixed=True)),
        ("wavelengths", cell(wl.size, "data.wavelengths", digits=0, fixed=True)),
        ("wavelength range [nm]", f"{number(wl[0], 6)} – {number(wl[-1], 6)}" if wl.size else "–"),
        ("wavelength step", esc(step)),
        ("standard uncertainties (sigma)", "yes" if d.sigma is not None else "no"),
        ("missing values", cell(int(np.isnan(d.brdf).sum()), "data.missing", digits=0, fixed=True)),
    ]
    html = definition_list(items)
    if d.metadata:
        html += "<h3>Metadata of the file</h3>" + table(["key", "value"], sorted(d.metadata.items()))
    else:
        html += "<p>The file has no metadata lines (<code># key: value</code>).</p>"
    if d.comments:
        html += "<h3>Comments of the file</h3><pre>" + esc("\n".join(d.comments)) + "</pre>"
    html += caveats(r.warnings.get("read", []))
    return Section("provenance", "1. Data provenance", html)


# ---- 2. quality ---------------------------------------------------------------------------------
def _geometry_text(g):
    """A geometry of the check's JSON, in the file's angles (road or zenith/azimuth), numbered from 1."""
    names = ([("γ", "gamma"), ("α", "alpha"), ("β", "beta"), ("δ", "delta")] if "gamma" in g else
             [("θ_i", "theta_i"), ("φ_i", "phi_i"), ("θ_r", "theta_r"), ("φ_r", "phi_r")])
    return f"#{g['index']}: " + ", ".join(f"{label} {g[key]:g}" for label, key in names) + "°"


def quality(r) -> Section:
    c = r.check
    rec = c["reciprocity"]

    def status(bad):
        return '<span class="flag">attention</span>' if bad else '<span class="ok">ok</span>'

    bands = c["noise"]["noisy_bands"]
    band_text = "; ".join(f"{b['from_nm']:g}–{b['to_nm']:g} nm (min SNR {number(b['min_snr'], 3)})" for b in bands)
    outliers = c.get("outliers", [])
    outlier_text = "; ".join(f"{_geometry_text(o['geometry'])} ({number(o['ratio_to_neighbours'], 2)}× its "
                             f"neighbours, score {number(o['score'], 2)})" for o in outliers)
    peaks = c.get("specular_peaks_not_counted_as_outliers", [])
    plausibility = _plausibility_warnings(r)
    rows = [
        ["negative values", cell(c["negative_values"], "check.negative_values", 0, True), status(c["negative_values"])],
        ["missing values", cell(c["missing_values"], "check.missing_values", 0, True),
         status(c["missing_values"])],
        ["reciprocity pairs (isotropic matching)", cell(rec["pairs"], "check.reciprocity.pairs", 0, True), ""],
        ["reciprocity: mean / max disagreement",
         Cell(f"{number(rec['mean_disagreement'], 3)} / {number(rec['max_disagreement'], 3)}",
              "check.reciprocity.max", rec["max_disagreement"], True), ""],
        ["reciprocity pairs flagged (> 10 %)", cell(rec["flagged"], "check.reciprocity.flagged", 0, True),
         status(rec["flagged"])],
        ["noisy bands (SNR < 20)", cell(len(bands), "check.noisy_bands", 0, True),
         status(bands) + (f"<br>{esc(band_text)}" if bands else "")],
        ["outlier geometries", cell(len(outliers), "check.outliers", 0, True),
         status(outliers) + (f"<br>{esc(outlier_text)}" if outliers else "")],
        ["specular peaks (bright near the mirror direction, not outliers)", cell(len(peaks), "check.peaks", 0, True),
         ""],
        ["plausibility warnings (implausible scale, BRDF × cos θ_i)",
         cell(len(plausibility), "check.plausibility.warnings", 0, True),
         status(plausibility) + (f"<br>{esc('; '.join(plausibility))}" if plausibility else "")],
    ]
    rows = [[Cell(esc(a)), b, Cell(s)] for a, b, s in rows]
    html = ("<p>The checks of <code>roadbrdf check</code> (<code>roadbrdf.check</code>) with their default "
            "thresholds.</p>" + table(["check", "result", "status"], rows))
    html += "<details><summary>the text report of <code>roadbrdf check</code></summary><pre>" + \
        esc(c["text"]) + "</pre></details>"
    return Section("quality", "2. Quality check", html)


# ---- 3. coverage --------------------------------------------------------------------------------
def coverage(r) -> Section:
    c = r.check["coverage"]
    items = [("incidence zenith angles θ_i", esc(_angles(c["incidence_zenith_deg"]))),
             ("viewing zenith angles θ_r", esc(_angles(c["viewing_zenith_deg"]))),
             ("azimuth planes β = 180° − |Δφ|", esc(_angles(c["azimuth_planes_beta_deg"]))),
             ("forward (specular side) / backward (retro side)", f"{c['forward']} / {c['backward']}"),
             ("perpendicular / in the plane of incidence", f"{c['perpendicular']} / {c['in_plane']}"),
             ("azimuth undefined (a direction along the normal)", str(c["azimuth_undefined"]))]
    html = definition_list(items)
    rows = []
    for g in r.groups:
        rows.append([cell(g["theta_i"], f"coverage.group.{g['theta_i']:g}.theta_i", 6),
                     cell(g["geometries"], f"coverage.group.{g['theta_i']:g}.geometries", 0, True),
                     esc(_angles(g["theta_r"])), cell(g["planes"], None, 0, True),
                     "yes" if g["fitted"] else f"no ({esc(g['reason'])})"])
    html += "<h3>Geometries per incidence</h3>" + table(
        ["θ_i [°]", "geometries", "θ_r [°]", "azimuth planes", f"fitted per incidence at {r.band:g} nm"], rows)
    cov = r.best.totals.get("coverage") or {}
    if cov:
        html += ("<h3>Measured directions known to the fits</h3><p>The fit file records the directions its data "
                 "covered; the albedo and the r-table integrate or tabulate the fitted model over every "
                 "direction and report the share that lies outside them (more than "
                 f"{number(((r.albedo or {}).get('coverage') or {}).get('tolerance_deg', 5.0), 2)}° from a "
                 "measured direction), i.e. where the model extrapolates.</p>")
        html += definition_list([("θ_i range", esc(_angles(cov.get("theta_i_deg", [])))),
                                 ("θ_r range", esc(_angles(cov.get("theta_r_deg", [])))),
                                 ("azimuth planes", esc(_angles(cov.get("azimuth_planes_deg", [])))),
                                 ("geometries", str(cov.get("geometries", "–")))])
    rows = []
    acov = (r.albedo or {}).get("coverage") or {}
    for z, share in zip(r.albedo["sun_zenith_deg"] if r.albedo else [], acov.get("black_sky_outside_fraction", [])):
        rows.append([f"black-sky albedo, sun zenith {z:g}°", cell(100 * share, f"coverage.black_sky.{z:g}", 3)])
    if "white_sky_outside_fraction" in acov:
        rows.append(["white-sky albedo", cell(100 * acov["white_sky_outside_fraction"], "coverage.white_sky", 3)])
    if r.albedo and (r.albedo.get("broadband") or {}).get("solar_fraction_outside_range") is not None:
        rows.append(["solar energy outside the data's wavelength range",
                     cell(100 * r.albedo["broadband"]["solar_fraction_outside_range"], "coverage.solar_outside", 3)])
    tcov = (r.rtable or {}).get("coverage") or {}
    if tcov.get("standard_cells") and "standard_cells_outside" in tcov:
        rows.append(["r-table, standard region (Q0, S1)", cell(100 * tcov["standard_cells_outside"] /
                                                              tcov["standard_cells"], "coverage.rtable_standard", 3)])
    if tcov.get("cells") and "cells_outside" in tcov:
        rows.append(["r-table, every cell", cell(100 * tcov["cells_outside"] / tcov["cells"], "coverage.rtable", 3)])
    if rows:
        html += "<h3>Extrapolated shares</h3>" + table(["result", "share outside the measured directions [%]"], rows)
    html += caveats([n for n in r.all_caveats if n.startswith("coverage") or "extrapolation" in n])
    return Section("coverage", "3. Geometry coverage", html)


# ---- 4. spectra ---------------------------------------------------------------------------------
def spectra(r) -> Section:
    html = "<p>BRDF against wavelength at measured geometries (the nearest measured one to each request; " \
           "bands: ±1 σ where the file gives σ).</p>"
    for key in r.spectral_keys:
        html += _figure(r, key)
    html += caveats(r.warnings.get("spectra", []))
    html += _figure(r, "hemisphere") + _figure(r, "plane")
    return Section("spectra", "4. Spectral and angular figures", html)


# ---- 5. per-incidence fits ----------------------------------------------------------------------
def _parameter_table(df, model, prefix, key_columns, fixed):
    """Rows of one model in a roadbrdf.params DataFrame: key columns, each free parameter ± its standard
    error, the statistics; data-key ``PREFIX.MODEL[.group].PARAM``."""
    rows_df = df[df["model"] == model]
    params = [c for c in df.attrs["units"] if c in df.columns and rows_df[c].notna().any() and c not in fixed]
    units = df.attrs["units"]
    headers = [h for _, h in key_columns] + [f"{esc(p).replace('.', '.<wbr>')} [{esc(units[p])}]" for p in params] + \
        [h for _, h, _ in FIT_COLUMNS] + ["converged", "on a bound"]
    rows = []
    for _, row in rows_df.iterrows():
        group = "".join(f".{c[:-4]}={row[c]:g}" for c, _ in key_columns if c.endswith("_deg"))
        base = f"{prefix}.{model}{group}"
        line = [cell(row[c], None, 6) for c, _ in key_columns]
        for p in params:
            v, e = row[p], row[p + "_stderr"]
            text = number(v, 4) + (f" ±\u00a0{number(e, 2)}" if e is not None and np.isfinite(e) else "")
            line.append(Cell(text, f"{base}.{p}", float(v), True))
        for c, _, digits in FIT_COLUMNS:
            line.append(cell(row[c], f"{base}.{c}", digits))
        line.append("yes" if bool(row["converged"]) else Cell('<span class="flag">no</span>'))
        line.append(esc(str(row["at_bounds"] or "–").replace(";", "; ")))
        rows.append(line)
    return headers, rows


def per_incidence(r) -> Section:
    if r.fit_groups is None:
        html = caveats([r.group_note or "no incidence has enough points for the models' free parameters"])
        return Section("per-incidence", f"5. Fits per incidence at {r.band:g} nm", html)
    df = r.group_params
    html = (f"<p>Each model fitted separately to the geometries of each incidence angle θ_i at "
            f"{r.band:g} nm (<code>roadbrdf fit --group-by theta_i --wavelengths {r.wavelength_asked:g}"
            f"</code>{esc(r.where_note)}), {r.multistart} starting points; fixed: {esc(_fixed_text(r))}. "
            "Parameters ± one standard error (none where the covariance is undefined, e.g. on a bound).</p>")
    html += caveats(r.fit_groups.notes + ([r.group_note] if r.group_note else []), info=True)
    for model in r.models:
        headers, rows = _parameter_table(df, model, "group", [("theta_i_deg", "θ_i [°]")], r.fixed)
        html += f"<h3>{esc(model)}</h3>" + table(headers, rows)
    html += "<h3>Ranking within each incidence</h3>"
    rows, classes = [], []
    for ti in sorted(df["theta_i_deg"].unique()):
        sub = df[df["theta_i_deg"] == ti].sort_values("bic")
        best_bic = float(sub["bic"].min())
        for rank, (_, row) in enumerate(sub.iterrows(), start=1):
            key = f"group-rank.theta_i={ti:g}.{row['model']}"
            rows.append([cell(ti, None, 6), cell(rank, f"{key}.rank", 0, True), esc(row["model"]),
                         cell(row["bic"], f"{key}.bic", 6), cell(row["bic"] - best_bic, f"{key}.delta_bic", 3),
                         cell(row["aic"], f"{key}.aic", 6), cell(row["rmse_per_sr"], f"{key}.rmse", 4)])
            classes.append("best" if rank == 1 else "")
    html += table(["θ_i [°]", "rank", "model", "BIC", "ΔBIC", "AIC", "RMSE [sr⁻¹]"], rows, classes)
    totals = df.groupby("model", sort=False)["bic"].sum()
    html += "<p>BIC summed over the incidences: " + ", ".join(
        f'{esc(m)} <span data-key="group-total.{esc(m)}.bic" data-value="{float(b)!r}">{number(b, 6)}</span>'
        for m, b in totals.items()) + f"; lowest: <strong>{esc(totals.idxmin())}</strong>.</p>"
    html += _figure(r, "params-by-incidence")
    html += _warnings_details(r.warnings.get("fit-groups", []))
    return Section("per-incidence", f"5. Fits per incidence at {r.band:g} nm", html)


def grouped_messages(items):
    """[(first message, count)]: messages that differ only in their numbers (the same finding at each
    incidence or wavelength) as one entry, in order of first appearance."""
    groups = {}
    for item in items:
        key = re.sub(r"[-+]?\d+(?:\.\d+)?(?:[eE][-+]?\d+)?", "#", str(item))
        first, count = groups.get(key, (item, 0))
        groups[key] = (first, count + 1)
    return list(groups.values())


def _warnings_details(items):
    if not items:
        return ""
    grouped = grouped_messages(items)
    return (f"<details><summary>{len(items)} message{'s' if len(items) > 1 else ''} of the fit"
            + (f" ({len(grouped)} kinds)" if len(grouped) < len(items) else "") + "</summary><ul>" +
            "".join(f"<li>{esc(i)}" + (f" <em>(and {n - 1} more like it)</em>" if n > 1 else "") + "</li>"
                    for i, n in grouped) + "</ul></details>")


# ---- 6. ranking over all configurations --------------------------------------------------------
def ranking(r) -> Section:
    fr = r.fit_all
    wl = fr.wavelengths
    html = (f"<p>Each model fitted to every geometry ({len(r.dataset)}) at each of the {wl.size} wavelengths "
            f"({number(wl[0], 6)}–{number(wl[-1], 6)} nm) separately, {r.multistart} starting points; fixed: "
            f"{esc(_fixed_text(r))}. Ranked by the BIC summed over the wavelengths (lower is better; a "
            "difference above 10 is decisive); AIC for comparison.</p>")
    ranked = [fr.fits[i] for i in fr.ranking]
    best_bic, best_aic = ranked[0].totals["bic"], min(f.totals["aic"] for f in ranked)
    rows, classes = [], []
    for rank, f in enumerate(ranked, start=1):
        t, key = f.totals, f"rank.{f.model}"
        rows.append([cell(rank, f"{key}.rank", 0, True), esc(f.model), cell(t["free_parameters"], None, 0, True),
                     cell(t["points"], None, 0, True), cell(t["rmse"], f"{key}.rmse", 4),
                     cell(100 * t["relative_rmse"], f"{key}.relative_rmse_percent", 3),
                     cell(t["aic"], f"{key}.aic", 7), cell(t["aic"] - best_aic, f"{key}.delta_aic", 4),
                     cell(t["bic"], f"{key}.bic", 7), cell(t["bic"] - best_bic, f"{key}.delta_bic", 4),
                     f"{t['converged_count']}/{wl.size}", str(t["at_bound_count"])])
        classes.append("best" if rank == 1 else "")
    html += table(["rank", "model", "free parameters", "values", "RMSE [sr⁻¹]", "rel. RMSE [%]", "AIC", "ΔAIC",
                   "BIC", "ΔBIC", "converged", "wavelengths on a bound"], rows, classes)
    html += f"<h3>Parameters at {r.band:g} nm</h3>"
    for model in r.models:
        headers, rows = _parameter_table(r.all_params, model, "all", [], r.fixed)
        html += f"<p><strong>{esc(model)}</strong></p>" + table(headers, rows)
    html += _figure(r, "params-by-wavelength") + _figure(r, "fit-quality")
    html += _warnings_details(r.warnings.get("fit-all", []))
    return Section("ranking", "6. Model ranking (all configurations)", html)


# ---- 7. albedo ----------------------------------------------------------------------------------
def _at(values, k):
    return None if values is None else values[k]


def albedo(r) -> Section:
    a = r.albedo
    if a is None:
        return Section("albedo", "7. Albedo", caveats([r.albedo_note]))
    z = a["sun_zenith_deg"]
    html = (f"<p>Albedo of the best-ranked fit ({esc(r.best.model)}), sun zenith {esc(_angles(z))}, "
            f"{esc(r.atmosphere_text)} (<code>roadbrdf albedo</code> / <code>roadbrdf.albedo</code>). "
            "Black-sky: directional-hemispherical; white-sky: bi-hemispherical; blue-sky: their mix for the "
            "sky's diffuse fraction.</p>")
    u = a.get("uncertainty") or {}

    def with_u(value, uncertainty, key):
        text = number(value, 4)
        if uncertainty is not None and np.isfinite(uncertainty):
            text += f" ±\u00a0{number(uncertainty, 2)}"
        return Cell(text, key, float(value), True)

    bb = a.get("broadband")
    if bb:
        # The solar-weighted uncertainties (albedo/uncertainty.h): the bound for errors correlated across
        # wavelengths is shown, since a per-wavelength covariance cannot exclude a common error (a reference
        # panel's calibration is common to every band); the independent value, hundreds of bands averaging
        # their noise away, is given beside it.
        ub = u.get("broadband") or {}
        part = lambda items, k, which: (_at(items, k) or {}).get(which)  # noqa: E731

        def with_both(value, items, k, key):
            c = with_u(value, part(items, k, "correlated"), key)
            i = part(items, k, "independent")
            if i is not None and np.isfinite(i):
                c = c._replace(text=c.text + f" (independent {number(i, 2)})")
            return c

        html += f"<h3>Solar-weighted ({esc(bb.get('weighting', ''))})</h3>"
        rows = []
        for k, zen in enumerate(z):
            rows.append([cell(zen, None, 4),
                         with_both(bb["black_sky"][k], ub.get("black_sky"), k, f"albedo.broadband.black_sky.{zen:g}"),
                         with_both(bb["blue_sky"][k], ub.get("blue_sky"), k, f"albedo.broadband.blue_sky.{zen:g}")
                         if bb.get("blue_sky") is not None else "–"])
        html += table(["sun zenith [°]", "black-sky", "blue-sky"], rows)
        white = ub.get("white_sky") or {}
        white_u, white_i = white.get("correlated"), white.get("independent")
        html += "<p>White-sky (solar-weighted): " + \
            f'<strong data-key="albedo.broadband.white_sky" data-value="{bb["white_sky"]!r}">' \
            f'{number(bb["white_sky"], 4)}</strong>' + \
            (f" ±\u00a0{number(white_u, 2)}" if white_u is not None else "") + \
            (f" (independent {number(white_i, 2)})" if white_i is not None else "") + "</p>"
        html += ("<p>± the bound for errors fully correlated across wavelengths (k = 1); in brackets the value "
                 "for independent wavelengths, which averages the bands' noise away and understates. Both come "
                 "from the fit's covariance only: they leave out the calibration (reference panel), the sample's "
                 "non-uniformity and the repeatability between scans (repeated scans of one sample can differ by "
                 "several per cent), the model's own error and the solar spectrum.</p>")
    wl = np.asarray(a["wavelengths"], dtype=float)
    k = int(np.argmin(np.abs(wl - r.band)))
    rows = []
    for j, zen in enumerate(z):
        rows.append([cell(zen, None, 4),
                     with_u(a["black_sky"][j][k], _at(_at(u.get("black_sky"), j), k), f"albedo.band.black_sky.{zen:g}"),
                     with_u(a["blue_sky"][j][k], _at(_at(u.get("blue_sky"), j), k), f"albedo.band.blue_sky.{zen:g}")
                     if a.get("blue_sky") is not None else "–"])
    html += f"<h3>At {wl[k]:g} nm</h3>" + table(["sun zenith [°]", "black-sky", "blue-sky"], rows)
    html += "<p>White-sky: " + \
        f'<strong data-key="albedo.band.white_sky" data-value="{a["white_sky"][k]!r}">{number(a["white_sky"][k], 4)}' \
        f"</strong>" + (f" ±\u00a0{number(u['white_sky'][k], 2)}" if u.get("white_sky") and
                        u["white_sky"][k] is not None else "") + \
        " (± standard uncertainty from the fit's covariance, where defined).</p>"
    html += caveats([w["message"] for w in a.get("warnings", [])] +
                    [n for n in a.get("notes", []) if n.startswith("coverage")])
    html += caveats([n for n in a.get("notes", []) if not n.startswith("coverage")], info=True)
    html += _figure(r, "albedo")
    return Section("albedo", "7. Albedo", html)


# ---- 8. r-table ---------------------------------------------------------------------------------
def _with_u(t, name, key):
    """An r-table figure ``t[name]`` ± its standard uncertainty (``t["uncertainty"][name]``, from the fit's or
    the mixture's covariance: photometry/rtable_uncertainty.h) where defined; ``data-value`` is the figure."""
    u = t.get("uncertainty") or {}
    text = number(t[name], 4)
    if t.get("extrapolated"):
        text += " (extrapolated)"
    elif u.get(name) is not None and np.isfinite(u[name]):
        text += f" ±\u00a0{number(u[name], 2)}"
    return Cell(text, key, float(t[name]), True)


def rtable(r) -> Section:
    t = r.rtable
    if t is None:
        return Section("rtable", "8. Road r-table", caveats([r.rtable_note]))
    w = t.get("weighting") or {}
    kind = str(w.get("kind", "photometric"))
    if kind.startswith("photometric"):
        kind += f", illuminant {w.get('illuminant', r.illuminant)}"
    html = (f"<p>The standard r-table (29 tan γ × 20 β, observation angle α = {t['alpha_deg']:g}°) of the "
            f"best-ranked fit ({esc(r.best.model)}), {esc(kind)} "
            "(<code>roadbrdf rtable</code> / <code>roadbrdf.rtable</code>).</p>")
    cls = t["classes"]
    u = t.get("uncertainty") or {}
    items = [("Q0 (average luminance coefficient) [sr⁻¹]", _with_u(t, "Q0", "rtable.Q0")),
             ("S1 = r(0, 2) / r(0, 0)", _with_u(t, "S1", "rtable.S1")),
             ("S2", _with_u(t, "S2", "rtable.S2")),
             ("Qd [sr⁻¹]", _with_u(t, "Qd", "rtable.Qd")),
             ("class (R system)", Cell(esc(t["class"]), "rtable.class")),
             ("classes N / C", esc(f"{cls.get('N', '–')} / {cls.get('C', '–')}"))]
    if t.get("extrapolated"):
        items.append(("class probability", "none: extrapolated (no standard-region cell was measured)"))
    elif u.get("class_probabilities"):
        items.append(("class probability (S1 normal with its uncertainty; ≥ 1 %)",
                      esc(", ".join(f"{c['class']} {c['probability']:.2f}" for c in u["class_probabilities"]))))
    html += definition_list(items)
    if t.get("extrapolated"):
        html += ("<p>Every cell of the standard region lies outside the measured directions: the figures are "
                 "the model's extrapolation, and the fit's covariance, which only describes the measured "
                 "directions, gives them no uncertainty.</p>")
    elif u:
        html += "<p>± standard uncertainty from the fit's covariance (wavelengths independent, where defined).</p>"
    html += caveats(list(t.get("warnings") or []) + [n for n in t.get("notes") or [] if n.startswith("coverage")])
    html += caveats([n for n in t.get("notes") or [] if not n.startswith("coverage")], info=True)
    html += _figure(r, "rtable")
    rr = np.asarray(t["r"], dtype=float) * 1e4
    rows = [[cell(tg, None, 3)] + [cell(v, None, 4) for v in line] for tg, line in zip(t["tan_gamma"], rr)]
    html += ("<details><summary>the r-table (10⁴ r [sr⁻¹]; rows tan γ, columns β)</summary>" +
             table(["tan γ \\ β [°]"] + [f"{b:g}" for b in t["beta_deg"]], rows, dense=True) + "</details>")
    return Section("rtable", "8. Road r-table", html)


# ---- 9. mixing ----------------------------------------------------------------------------------
def _mixture_uncertainty(r) -> str:
    """The r-table of one mixing prediction with the standard uncertainties propagated from its end-members'
    fits (report._mixture_uncertainty chose the method), and what is not shown."""
    method = getattr(r, "mix_u_method", None)
    html = "<h3>Uncertainty of the prediction</h3>"
    covariance_methods = "<code>areal</code>, <code>mastic</code> and <code>hapke</code>"
    none_text = ("<code>fitted</code> and <code>shadowed</code> carry none: their weights are fitted to this "
                 "measured sample, and the uncertainty of those weights is not propagated")
    if method is None:
        skipped = "; ".join(f"{esc(k)}: {esc(v)}" for k, v in (getattr(r, "mix_u_skipped", None) or {}).items())
        return html + (f"<p>No mixing prediction here carries a standard uncertainty. Only {covariance_methods} "
                       f"propagate their end-members' fit covariances ({skipped or 'none applied'}); "
                       f"{none_text}.</p>")
    t = r.mix_rtable
    html += (f'<p>Shown for <strong data-key="mix.uncertainty.method">{esc(method)}</strong>, the method with the '
             f"lowest held-out RMSE among those that carry an uncertainty ({covariance_methods}: the covariances "
             "of their end-members' fits propagated into the mixture, <code>roadbrdf mix --uncertainty</code>, "
             f"docs/mixing.md); {none_text}, so the best method above may have none. The r-table of the "
             f"prediction (illuminant {esc(r.illuminant)}), ± the standard uncertainty, as "
             f"<code>roadbrdf rtable MIX.json --fit {esc(method)}</code> gives it:</p>")
    cls = t["classes"]
    u = t.get("uncertainty") or {}
    items = [("Q0 [sr⁻¹]", _with_u(t, "Q0", "mix.rtable.Q0")), ("S1", _with_u(t, "S1", "mix.rtable.S1")),
             ("S2", _with_u(t, "S2", "mix.rtable.S2")), ("Qd [sr⁻¹]", _with_u(t, "Qd", "mix.rtable.Qd")),
             ("class (R system)", Cell(esc(t["class"]), "mix.rtable.class")),
             ("classes N / C", esc(f"{cls.get('N', '–')} / {cls.get('C', '–')}"))]
    if u.get("class_probabilities"):
        items.append(("class probability (S1 normal with its uncertainty; ≥ 1 %)",
                      Cell(esc(", ".join(f"{c['class']} {c['probability']:.2f}" for c in u["class_probabilities"])),
                           "mix.rtable.class_probabilities")))
    html += definition_list(items)
    html += ("<p>This uncertainty comes from the components' measurements only (their fits' covariances, "
             "wavelengths independent); it says nothing of how well the method describes the mixture, which is "
             "what the held-out RMSE above measures and which is usually far larger. The albedo of a mixture with "
             "its uncertainty is not computed here because of its cost (two black-sky integrals per end-member "
             "parameter and sun zenith: minutes of CPU): <code>roadbrdf mix F.json --uncertainty -o F.mix.json"
             f"</code>, then <code>roadbrdf albedo F.mix.json --fit {esc(method)}</code>.</p>")
    return html


def mixing(r) -> Section:
    title = "9. Mixing prediction"
    if r.mix is None:
        html = ("<p>Not requested. With <code>--formulation F.json</code> the report predicts this sample from its "
                "components with every mixing method of <code>roadbrdf mix</code> and compares each prediction "
                "with this dataset on held-out geometries. It needs: this dataset as the measured mixture, and a "
                "formulation file (docs/mixing.md) whose components (and mastic, for the <code>mastic</code> "
                "method) point to existing fit files of their own measured samples "
                "(<code>roadbrdf fit COMPONENT.csv ... -o COMPONENT.fit.json</code>; "
                "<code>examples/fit_components.sh</code> makes those of the bundled examples).</p>")
        return Section("mixing", title, html)
    m, form = r.mix, r.formulation
    html = (f"<p>Formulation <strong>{esc(form.get('name', ''))}</strong> ({esc(r.formulation_name)}): "
            f"{esc(form.get('description', ''))}. Every method of <code>roadbrdf mix --method all --data</code>, "
            f"{r.folds}-fold cross-validation over this dataset's geometries; albedo difference against the fit of "
            f"this sample ({esc(r.best.model)}).</p>")
    rows = [[esc(c.get("name", "")), esc(c.get("kind", "")), cell(c.get("mass_percent"), None, 4),
             esc(c.get("fit", ""))] for c in form.get("components", [])]
    html += table(["component", "kind", "mass [%]", "fit file"], rows)
    best = m.best.method if m.best is not None else None
    rows, classes = [], []
    for meth in m.methods:
        c, key = meth.comparison or {}, f"mix.{meth.method}"
        weights = ", ".join(f"{esc(k)} {number(v, 3)}" for k, v in meth.weights.items())
        rows.append([esc(meth.method), Cell(weights), cell(c.get("rmse"), f"{key}.rmse", 4),
                     cell(c.get("relative_rmse"), f"{key}.relative_rmse", 4),
                     cell(c.get("chi2_reduced"), f"{key}.chi2_reduced", 4), cell(c.get("albedo"), f"{key}.albedo", 4),
                     cell(c.get("albedo_difference"), f"{key}.albedo_difference", 3)])
        classes.append("best" if meth.method == best else "")
    html += table(["method", "weights", "held-out RMSE [sr⁻¹]", "held-out rel. RMSE", "χ²/n", "white-sky albedo",
                   "albedo − this sample's"], rows, classes)
    if best:
        html += f'<p>Best (lowest held-out RMSE): <strong data-key="mix.best">{esc(best)}</strong>.</p>'
    html += _mixture_uncertainty(r)
    html += caveats(m.notes, info=True)
    html += _figure(r, "mixing")
    return Section("mixing", title, html)
