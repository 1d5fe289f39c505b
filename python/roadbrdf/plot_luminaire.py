"""Luminaire polar curves (``roadbrdf plot luminaire FILE -o FIG.png``): the luminous intensity in the
C0-C180 and C90-C270 planes in cd/klm (per 1000 lm of the lamps, or of the luminaire for absolute
photometry), gamma = 0 (nadir) at the bottom, C0 and C90 on the right, C180 and C270 on the left."""

from __future__ import annotations

import os

import numpy as np

from .plot_common import finish, panels

__all__ = ["luminaire"]


def luminaire(source, title=None, output=None, *, ax=None, fig=None, dpi=None):
    """Polar curves of a luminaire's C0-C180 and C90-C270 planes [cd/klm].

    ``source``: a luminaire file (EULUMDAT or IES LM-63) or the :class:`roadbrdf.Result` of
    :func:`roadbrdf.luminaire`. ``ax``: one polar axes, or ``fig``.

    ``fig.roadbrdf_data``: ``gamma_deg`` and the curves ``C0``, ``C90``, ``C180``, ``C270`` [cd/klm] as drawn,
    ``name`` and ``unit``."""
    from . import luminaire as read
    result = source if hasattr(source, "value") and hasattr(source, "warnings") else read(os.fspath(source))
    value = result.value
    planes = value["principal_planes"]
    gamma = np.asarray(planes["gamma_deg"], dtype=float)
    curves = {k: np.asarray(planes[k], dtype=float) for k in ("C0", "C90", "C180", "C270")}
    figure, (axis,) = panels(["polar"], ax=ax, fig=fig, size=(5.5, 5.5), what="polar axes")
    axis.set_theta_zero_location("S")  # nadir at the bottom
    axis.set_theta_direction(1)  # gamma counter-clockwise: C0 / C90 to the right
    for (right, left), style in ((("C0", "C180"), "-"), (("C90", "C270"), "--")):
        theta = np.concatenate([-gamma[::-1], gamma])
        radius = np.concatenate([curves[left][::-1], curves[right]])
        axis.plot(np.radians(theta), radius, style, label=f"{left}-{right}")
    axis.set_thetamin(-180)  # the whole circle: C180 / C270 at negative angles on the left
    axis.set_thetamax(180)
    axis.set_thetagrids(np.arange(-150, 181, 30), [f"{abs(a)}°" for a in range(-150, 181, 30)])
    axis.set_rlim(0, None)
    axis.set_rlabel_position(100)
    axis.legend(loc="upper right", bbox_to_anchor=(1.15, 1.1), frameon=False)
    name = value.get("name") or os.path.basename(value.get("file", ""))
    axis.set_title(title if title is not None else f"{name} [{planes['unit']}]")
    data = {"gamma_deg": gamma, **curves, "name": name, "unit": planes["unit"]}
    return finish(figure, output, data, [axis], dpi)
