"""Luminaire photometry and road lighting (``src/roadbrdf/lighting``; named ``lightings`` so as not to hide
the function :func:`roadbrdf.lighting`).

:func:`luminaire` reads an EULUMDAT (.ldt) or IES LM-63 (.ies) file and summarises it as
``roadbrdf luminaire FILE --json`` does (the same library request and JSON): a :class:`roadbrdf.Result`
whose value holds the name, the fluxes [lm] (lamps, header, integrated, downward, upward), DLOR and ULOR,
the maximum intensity [cd, cd/klm] and its direction (C, gamma) [deg], the symmetry, the luminous area,
the file's metadata and the principal planes C0, C90, C180, C270 in cd/klm at the file's gamma angles.
Conventions and formulas: docs/lighting.md ("Luminaire files").
"""

from __future__ import annotations

from ._roadbrdf import lighting, luminaire

__all__ = ["lighting", "luminaire"]
