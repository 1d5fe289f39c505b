"""The sample report's road-lighting section (``roadbrdf report DATA.csv --installation INSTALLATION.json
[--lighting-class M3]``; Python ``write_report(..., installation=..., lighting_class=...)``).

The installation of the user's file with the sample's best-ranked fit as its pavement: exactly
``roadbrdf lighting INSTALLATION.json --surface FIT.json [--class M]`` on the report's fit of all configurations
(the installation's own surface is replaced). The section shows the EN 13201 quality figures and the M class met,
the energy indicators and the power per km of road (the least power that meets the asked class), the light sent
to the sky (direct and reflected by the road, the latter from the BRDF's hemispherical reflectance) and how far
the luminance at each point's true observation angle differs from the r-table's; the plan of the luminance
map is drawn by ``roadbrdf.plot.lighting``. Without an installation the report has no such section (docs/report.md).
"""

from __future__ import annotations

import os

from .core import InputError
from .report_html import Cell, Section, caveats, cell, definition_list, esc, figure, figure_png

__all__ = ["check_arguments", "gather", "section"]

_CLASSES = ("M1", "M2", "M3", "M4", "M5", "M6")  # EN 13201-2:2015 Table 1


def check_arguments(installation, lighting_class):
    """Errors seen before the long steps: a missing installation file, a class without an installation."""
    if installation is None:
        if lighting_class is not None:
            raise InputError("--lighting-class: needs --installation (the installation the class is met with)")
        return
    if not os.path.isfile(installation):
        raise InputError(f"--installation: '{installation}': no such file")
    if lighting_class is not None and lighting_class not in _CLASSES:
        raise InputError(f"--lighting-class: '{lighting_class}' is not an M lighting class ({', '.join(_CLASSES)})")


def gather(r, installation, lighting_class, fit_path):
    """``r.lighting``: the lighting result (a roadbrdf.Result) of ``installation`` over the fit file's best model,
    ``r.lighting_warnings`` its warnings and ``r.lighting_figure`` the plan's PNG (or ``r.lighting_note``: why
    there is none, e.g. a fit without the visible range the r-table needs)."""
    from . import lighting
    r.lighting = r.lighting_figure = None
    r.lighting_note = ""
    r.lighting_installation = os.path.basename(installation)
    try:
        r.lighting = lighting(installation, surface=fit_path, target_class=lighting_class or "")
    except InputError as e:
        r.lighting_note = f"No lighting calculation: {e}"
        r.steps.say(f"warning: no lighting calculation: {e}")
        return
    try:
        from .plot import lighting as plan
        r.lighting_figure = figure_png(plan(r.lighting.value))
    except Exception as e:  # noqa: BLE001 - the figure must not lose the section
        r.figure_errors["lighting"] = f"{type(e).__name__}: {e}"


def _messages(items):
    return [i["message"] if isinstance(i, dict) else str(i) for i in items or []]


def section(r) -> Section:
    """The lighting section (numbered after the report's last section)."""
    title = "10. Road lighting (EN 13201)"
    v = r.lighting.value if r.lighting is not None else None
    if v is None:
        return Section("lighting", title, caveats([r.lighting_note]))
    lum = v["luminaire"]
    html = (f"<p>The installation <code>{esc(r.lighting_installation)}</code> ({esc(lum['name'])}, "
            f"{esc(lum['arrangement'])}, {lum['flux_lm']:g} lm and {lum['power_w']:g} W per luminaire, maintenance "
            f"factor {lum['maintenance_factor']:g}) with this sample's best-ranked fit ({esc(r.best.model)}) as "
            "its pavement: <code>roadbrdf lighting INSTALLATION --surface FIT.json</code> (docs/lighting.md). "
            "The r-table is the fit's at α = 1° (photometric, illuminant A); the flux reflected upward comes from "
            "the BRDF's hemispherical reflectance.</p>")
    cls = v["M_class"] or "none"
    limited = ", ".join(v.get("limited_by") or [])
    quality = [("M class met (EN 13201-2)", Cell(esc(cls), "lighting.M_class")),
               ("next class limited by", esc(f"{v.get('next_class')}: {limited}") if limited else "–"),
               ("L_av [cd/m²]", cell(v["L_av"], "lighting.L_av")),
               ("U_o", cell(v["U_o"], "lighting.U_o", 3)),
               ("U_l", cell(v["U_l"], "lighting.U_l", 3)),
               ("f_TI [%]", cell(v["f_TI"], "lighting.f_TI", 3)),
               ("R_EI", cell(v["R_EI"], "lighting.R_EI", 3)),
               ("E_av [lx]", cell(v["E_av"], "lighting.E_av")),
               ("U_o of E", cell(v["U_o_E"], "lighting.U_o_E", 3))]
    e = v["energy"]
    energy = [("D_P [W lx⁻¹ m⁻²]", cell(v["D_P"], "lighting.D_P")),
              (f"D_E [Wh m⁻² per year] ({e['operating_hours']:g} h)", cell(v["D_E"], "lighting.D_E")),
              ("installed power [W/km]", cell(e["power_per_km_w"], "lighting.power_per_km_w"))]
    least = v.get("least_flux")
    if least is not None:
        if least["feasible"]:
            energy += [(f"least flux for {least['class']} (× installed)",
                        cell(least["dimming_factor"], "lighting.least_dimming_factor")),
                       (f"least power for {least['class']} [W/km]",
                        cell(least["power_per_km_w"], "lighting.least_power_per_km_w"))]
        else:
            energy.append((f"least power for {least['class']}",
                           esc(f"none: no flux meets {', '.join(least['blocking'])}")))
    up = v["upward"]
    sky = [("ULOR as installed", cell(up["ULOR"], "lighting.ULOR", 3)),
           ("direct upward [lm/km]", cell(up["direct_upward_lm_per_km"], "lighting.direct_upward_lm_per_km")),
           ("flux onto the carriageway [lm/km]",
            cell(up["flux_on_carriageway_lm_per_km"], "lighting.flux_on_carriageway_lm_per_km")),
           ("reflected upward by the road [lm/km]",
            cell(up["reflected_upward_lm_per_km"], "lighting.reflected_upward_lm_per_km")),
           ("hemispherical reflectance (photometric)", cell(up["reflectance"], "lighting.reflectance", 3))]
    a = v.get("alpha_variation")
    if a is not None:
        sky.append((f"L_av at the true observation angles ({a['alpha_min_deg']:.2f}–{a['alpha_max_deg']:.2f}°) "
                    "vs α = 1°", cell(100 * a["L_av_difference"], "lighting.L_av_difference_percent", 3,
                                      suffix=" %")))
    html += "<h3>Quality</h3>" + definition_list(quality)
    html += "<h3>Energy (EN 13201-5)</h3>" + definition_list(energy)
    html += "<h3>Light to the sky</h3>" + definition_list(sky)
    html += caveats(_messages(v.get("warnings")))
    html += caveats(_messages(v.get("notes")), info=True)
    if r.lighting_figure is not None:
        caption = "Plan of the field of calculation: luminance seen by the observer of lane 1 [cd/m²]."
        html += figure(r.lighting_figure, caption, caption, "lighting")
    elif "lighting" in r.figure_errors:
        html += caveats([f"figure not drawn: {r.figure_errors['lighting']}"])
    return Section("lighting", title, html)
