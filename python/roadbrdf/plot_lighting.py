"""Plan of a road-lighting installation (``roadbrdf plot lighting RESULT.json -o FIG.png``): the field of
calculation with the luminance map seen by one observer (filled, with iso-lines labelled in cd/m^2), the
carriageway's edges and lane lines, the luminaires around the field and the observer's lane and distance."""

from __future__ import annotations

import json
import os

import numpy as np

from .plot_common import finish, panels

__all__ = ["lighting"]


def _value(source):
    if hasattr(source, "value") and hasattr(source, "warnings"):
        return source.value
    if isinstance(source, dict):
        return source
    with open(os.fspath(source), encoding="utf-8") as f:
        return json.load(f)


def lighting(source, title=None, output=None, *, lane=1, ax=None, fig=None, dpi=None):
    """Luminance map of ``roadbrdf lighting`` seen by the observer of ``lane`` (1 = the right-hand lane).

    ``source``: the JSON file of ``roadbrdf lighting --json``, its dict, or the :class:`roadbrdf.Result` of
    :func:`roadbrdf.lighting`. ``ax``: one axes, or ``fig``.

    ``fig.roadbrdf_data``: ``x_m``, ``y_m``, ``L_cd_m2`` (rows along x) as drawn, ``luminaires_m`` and ``lane``."""
    value = _value(source)
    grid = value["grid"]
    lanes = value["lanes"]
    if not 1 <= lane <= len(lanes):
        raise ValueError(f"lane: {lane} is not one of 1-{len(lanes)}")
    x = np.asarray(grid["x_m"], dtype=float)
    y = np.asarray(grid["y_m"], dtype=float)
    luminance = np.asarray(grid["L_cd_m2"][lane - 1], dtype=float)
    figure, (axis,) = panels([None], ax=ax, fig=fig, size=(8.0, 3.8), what="axes")
    filled = axis.contourf(x, y, luminance.T, levels=12, cmap="viridis")
    lines = axis.contour(x, y, luminance.T, levels=filled.levels[::2], colors="white", linewidths=0.7)
    axis.clabel(lines, fmt="%.2f", fontsize=7)
    figure.colorbar(filled, ax=axis, label="luminance [cd/m²]")
    axis.plot(*np.meshgrid(x, y), ".", color="0.85", markersize=2)
    spacing = float(grid["spacing_m"])
    width = len(lanes) and float(y[-1] + y[0])  # the outer points are d/2 inside the edges
    for edge in (0.0, width):
        axis.axhline(edge, color="black", linewidth=1.2)
    lane_width = width / len(lanes)
    for k in range(1, len(lanes)):
        axis.axhline(k * lane_width, color="0.4", linewidth=0.8, linestyle="--")
    positions = np.asarray(value.get("luminaires_m", []), dtype=float).reshape(-1, 2)
    if len(positions):
        axis.plot(positions[:, 0], positions[:, 1], "*", color="orange", markersize=12, markeredgecolor="black",
                  label="luminaires")
    observer = lanes[lane - 1]["observer_m"]
    # The label stands below the road, inside the axes (outside them it ran into the y-axis label).
    axis.annotate(f"observer at x = {observer[0]:g} m", xy=(0.0, observer[1]), xytext=(-0.19 * spacing, -0.3 * width),
                  arrowprops=dict(arrowstyle="->"), va="center", ha="left", fontsize=8)
    axis.set_xlim(-0.2 * spacing, 1.05 * spacing)
    axis.set_ylim(-0.15 * width, 1.15 * width)
    axis.set_xlabel("x along the road [m]")
    axis.set_ylabel("y from the right-hand edge [m]")
    axis.set_aspect("equal", adjustable="datalim")
    name = os.path.basename(value.get("installation", ""))
    axis.set_title(title if title is not None else
                   f"{name}: L_av {value['L_av']:.2f} cd/m², U_o {value['U_o']:.2f}, lane {lane} observer")
    data = {"x_m": x, "y_m": y, "L_cd_m2": luminance, "luminaires_m": positions, "lane": lane}
    return finish(figure, output, data, [axis], dpi)
