"""Publication figures for roadbrdf (matplotlib).

Every function returns the matplotlib Figure it drew, with the data behind it as ``fig.roadbrdf_data``
(numpy arrays and lists: check the data, not the pixels), and, when ``output`` is given, saves it (PNG, SVG
or PDF from the extension; written atomically with normal permissions; ``dpi`` for the raster parts). Each
takes ``ax=`` (the axes to draw into) or, for several panels, ``fig=`` (a Figure or SubFigure), so that
figures can be composed. The same figures are available from the command line as
``roadbrdf plot KIND ... -o FILE`` (``python3 -m roadbrdf.plot KIND ...``); docs/figures.md shows each kind.

Kinds (one module each):

* :func:`spectral` - BRDF against wavelength at one geometry: measured datasets with uncertainty bands, and
  the predictions of fit files and mixtures (plot_spectral.py);
* :func:`hemisphere` - BRDF over the viewing hemisphere per incidence: polar heat map and 3-D lobe (equal
  axes) of a model, with measured points marked (plot_hemisphere.py);
* :func:`plane` - BRDF in the plane of incidence (negative theta_r on the backward side), measured points
  against models, polar from 0 or logarithmic, or cartesian (plot_plane.py);
* :func:`fit_quality` - measured vs fitted values per geometry with residuals, and RMSE vs wavelength
  (plot_fit.py);
* :func:`albedo` - black-sky albedo vs sun zenith with white-sky and the blue-sky albedo of each atmosphere,
  spectral albedo (plot_albedo.py);
* :func:`rtable` - r-table heat map, and the sample's (S1, Q0) among the standard classes (plot_rtable.py);
* :func:`luminaire` - a luminaire's polar curves C0-C180 and C90-C270 in cd/klm (plot_luminaire.py);
* :func:`lighting` - plan of an installation with the luminance map of `roadbrdf lighting` (plot_lighting.py);
* :func:`params` - fitted parameters +- standard error against wavelength or a group column (plot_params.py);
* :func:`study_plane`, :func:`study_sensitivity` - design-study results (plot_study.py).

Angles in degrees, BRDF in sr^-1, wavelengths in nm.
"""

from __future__ import annotations

from .plot_common import _finish, plt, save  # noqa: F401  (_finish, plt: for modules written before the split)
from .plot_spectral import spectral
from .plot_hemisphere import hemisphere
from .plot_plane import plane
from .plot_fit import fit_quality
from .plot_albedo import albedo
from .plot_rtable import rtable
from .plot_params import params
from .plot_luminaire import luminaire
from .plot_lighting import lighting
from .plot_study import plane as study_plane, sensitivity as study_sensitivity
from .plot_cli import main, run

__all__ = ["spectral", "hemisphere", "plane", "fit_quality", "albedo", "rtable", "params", "luminaire", "lighting", "study_plane",
           "study_sensitivity", "save", "main"]

if __name__ == "__main__":
    import sys
    sys.exit(run())
