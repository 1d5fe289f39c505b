"""Choosing the measured geometry a figure shows (``roadbrdf plot spectral --geometry``).

A geometry is asked for as ``theta_i,phi_i,theta_r,phi_r`` [deg] or in road-photometry angles
``gamma=..,alpha=..,beta=..,delta=..`` (core.road_to_zenith_azimuth). The samples are taken as azimuthally
isotropic, so two geometries are compared after turning each about the normal until phi_i = 0: the
distance is the larger of the angles between the two incidence directions and between the two
viewing directions. A file measured at (40, 180, 40, 180) therefore answers a request for
(40, 0, 40, 0) exactly.
"""

from __future__ import annotations

import numpy as np

from .core import road_to_zenith_azimuth

#: A nearest geometry farther than this [deg] is reported on the figure and on standard error.
TOLERANCE_DEG = 1.0

_ROAD = ("gamma", "alpha", "beta", "delta")


def parse_geometry(text: str) -> tuple:
    """``"40,0,40,180"`` or ``"gamma=40,alpha=50,beta=0,delta=0"`` as (theta_i, phi_i, theta_r, phi_r) [deg]."""
    items = [t.strip() for t in text.split(",")]
    if all("=" in t for t in items):
        road = {}
        for t in items:
            key, _, value = t.partition("=")
            if key.strip() not in _ROAD:
                raise ValueError(f"geometry: '{key.strip()}' is not a road angle ({', '.join(_ROAD)})")
            road[key.strip()] = _number(value, key)
        missing = [k for k in _ROAD if k not in road]
        if missing:
            raise ValueError(f"geometry: give all four road angles gamma, alpha, beta, delta (missing {', '.join(missing)})")
        return tuple(float(x) for x in road_to_zenith_azimuth(*(road[k] for k in _ROAD)))
    if len(items) != 4:
        raise ValueError(f"geometry: expected theta_i,phi_i,theta_r,phi_r [deg] or gamma=..,alpha=..,beta=..,delta=.., "
                         f"got '{text}'")
    return tuple(_number(x, "geometry") for x in items)


def _number(text, what):
    try:
        x = float(text)
    except ValueError:
        raise ValueError(f"{what}: '{text}' is not a number") from None
    if not np.isfinite(x):
        raise ValueError(f"{what}: '{text}' is not finite")
    return x


def _directions(theta_i, phi_i, theta_r, phi_r):
    """Unit vectors of incidence and viewing after turning the geometry until phi_i = 0."""
    ti, tr = np.radians(theta_i), np.radians(theta_r)
    dphi = np.radians(np.asarray(phi_r, float) - np.asarray(phi_i, float))
    wi = np.stack([np.sin(ti), np.zeros_like(ti), np.cos(ti)], axis=-1)
    wr = np.stack([np.sin(tr) * np.cos(dphi), np.sin(tr) * np.sin(dphi), np.cos(tr)], axis=-1)
    return wi, wr


def nearest_geometry(angles, geometry) -> tuple:
    """(index, distance [deg]) of the row of ``angles`` (N x 4, deg) nearest to ``geometry``."""
    a = np.asarray(angles, float)
    wi, wr = _directions(a[:, 0], a[:, 1], a[:, 2], a[:, 3])
    qi, qr = _directions(*(np.asarray(x, float) for x in geometry))
    angle_i = np.degrees(np.arccos(np.clip(wi @ qi, -1.0, 1.0)))
    angle_r = np.degrees(np.arccos(np.clip(wr @ qr, -1.0, 1.0)))
    distance = np.maximum(angle_i, angle_r)
    k = int(np.argmin(distance))
    return k, float(distance[k])
