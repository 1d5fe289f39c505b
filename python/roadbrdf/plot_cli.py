"""``roadbrdf plot KIND ... -o FILE`` (``python3 -m roadbrdf.plot``): the command line of the figures.

Errors in the input are ``roadbrdf: error: ...`` with exit status 2; a missing output folder is
``roadbrdf plot: error: output folder 'X' does not exist`` (status 2), found before anything is drawn."""

from __future__ import annotations

import argparse
import os
import re
import sys

import numpy as np

from . import Model, read_fit
from .plot_albedo import FIGURE_TOLERANCE
from .plot_common import DEFAULT_DPI, OutputFolderError, check_output_folder, is_model_file

__all__ = ["main", "run"]


class _Parser(argparse.ArgumentParser):
    """argparse with the errors of the roadbrdf program: ``roadbrdf: error: ...`` naming the nearest
    valid sub-command or option (the same edit-distance helper as the C++ program)."""

    def error(self, message):
        from . import _roadbrdf
        hint = ""
        unknown = re.search(r"unrecognized arguments: (\S+)", message)
        choice = re.search(r"invalid choice: '([^']*)' \(choose from (.*)\)", message)
        if unknown:
            word = unknown.group(1).split("=")[0]
            names = [o for a in self._all_actions() for o in a.option_strings]
            message = f"unknown option '{word}' of '{self.prog}'"
            hint = _roadbrdf.did_you_mean(word, names)
        elif choice:
            word = choice.group(1)
            names = re.findall(r"'([^']*)'", choice.group(2))
            message = f"unknown kind of figure '{word}' (one of {', '.join(names)})"
            hint = _roadbrdf.did_you_mean(word, names)
        self.exit(2, f"roadbrdf: error: {message}{hint}; see '{self.prog} --help'\n")

    def _all_actions(self):
        actions = list(self._actions)
        for a in self._actions:
            if isinstance(a, argparse._SubParsersAction):
                for parser in a.choices.values():
                    actions += parser._actions
        return actions


def _assignments(items, what, number):
    """``NAME=VALUE`` items of a repeatable option; ``number``: values are finite floats."""
    out = {}
    for item in items or []:
        name, eq, value = item.partition("=")
        if not eq or not name:
            raise ValueError(f"{what} expects NAME=VALUE, got '{item}'")
        if name in out:
            raise ValueError(f"{what} {name} is given twice")
        if number:
            try:
                v = float(value)
            except ValueError:
                v = float("nan")
            if not np.isfinite(v):
                raise ValueError(f"{what} {name}: '{value}' is not a finite number")
            value = v
        out[name] = value
    return out


def _model_argument(text, a, read=True):
    """A model name (with -p/--option) or a fit file (with --fit) as the object the figures take. ``read``
    False: a fit file is only checked against -p/--option and returned as its path (the figure reads it, and
    checks --fit, once: an 8 MB fit file takes a few tenths of a second to parse)."""
    params = _assignments(getattr(a, "parameter", None), "-p", True)
    options = _assignments(getattr(a, "option", None), "--option", False)
    if is_model_file(text):
        if params or options:
            raise ValueError(f"-p/--option cannot be combined with a fit file ('{text}')")
        return (read_fit(text, a.fit) if read else text), {}
    if a.fit:
        raise ValueError(f"--fit selects a fit of a fit file; '{text}' is a model name")
    return Model(text, options), params


def _renamed(new):
    """An old option spelling, refused with a message naming the new one."""
    class Renamed(argparse.Action):
        def __call__(self, parser, namespace, values, option_string=None):
            raise ValueError(f"{option_string}: renamed: use {new}")
    return Renamed


def _dpi(text):
    try:
        value = float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"'{text}' is not a number") from None
    if not (np.isfinite(value) and 10 <= value <= 2400):
        raise argparse.ArgumentTypeError(f"{text} is outside [10, 2400]")
    return value


def _geometry(text):
    from .plot_geometry import parse_geometry
    try:
        return parse_geometry(text)
    except ValueError as e:
        raise argparse.ArgumentTypeError(str(e)) from None


def _output(p):
    p.add_argument("-o", "--output", required=True, help="figure file (.png, .svg, .pdf)")
    p.add_argument("--title", help="figure title (default: from the inputs)")
    p.add_argument("--dpi", type=_dpi, help=f"resolution of the raster parts [dots per inch] (default {DEFAULT_DPI}; "
                                            "vector files keep their lines and text as vectors)")


def _dataset_flags(p):
    """The dataset-reading and BRDF-axis options of the figures that draw datasets and models."""
    p.add_argument("--average-duplicates", action="store_true",
                   help="average dataset rows with the same geometry (else an error), as every command does")
    p.add_argument("--units", choices=["brdf", "brf"], default="brdf",
                   help="BRDF axes as BRDF [sr^-1] (default) or as the reflectance factor BRF = pi x BRDF")


def _model_flags(p, options=True):
    p.add_argument("-p", "--parameter", action="append", metavar="NAME=VALUE",
                   help="model parameter (repeatable); defaults otherwise")
    if options:
        p.add_argument("--option", action="append", metavar="NAME=VALUE",
                       help="model option (repeatable), e.g. distribution=ggx")
    p.add_argument("--fit", metavar="NAME", help="which fit of FIT.json (its model name) or which method of a "
                   "MIX.json (default: the best-ranked)")


_INCIDENCES = "incidence zenith angle [deg], or several for one panel each: 0,20,40,60 (default 45)"


def _parser():
    parser = _Parser(prog="roadbrdf plot", description="roadbrdf figures (PNG, SVG or PDF); docs/figures.md shows "
                                                       "each kind with the command that made it.")
    sub = parser.add_subparsers(dest="kind", required=True, parser_class=_Parser)
    p = sub.add_parser("spectral", help="BRDF vs wavelength at one geometry: datasets, fit files and mixtures")
    p.add_argument("data", nargs="+", metavar="FILE",
                   help="dataset CSV files, and fit files / MIX.json whose prediction is drawn at the geometry")
    p.add_argument("--geometry", type=_geometry, default=(30.0, 0.0, 30.0, 0.0),
                   help="theta_i,phi_i,theta_r,phi_r [deg] or gamma=G,alpha=A,beta=B,delta=D (road angles): the "
                        "nearest measured geometry, up to a turn about the normal (default 30,0,30,0)")
    p.add_argument("--fit", metavar="NAME", help="which fit (model name) or mixing method of each JSON file "
                                                 "(default: its best)")
    _dataset_flags(p)
    _output(p)
    p = sub.add_parser("hemisphere", help="BRDF over the viewing hemisphere (heat map and lobe) of a model, fit "
                                          "file, mixture or dataset")
    p.add_argument("model", help="model name (with -p/--option), fit file / MIX.json (with --fit), or a dataset "
                                 "CSV (its measured points)")
    _model_flags(p)
    p.add_argument("--data", help="dataset whose measured points are drawn over the model")
    p.add_argument("--theta-i", default="45", help=_INCIDENCES)
    p.add_argument("--wavelength", type=float, help="wavelength [nm] (default: 550 or the middle; a dataset: its "
                                                    "nearest band)")
    p.add_argument("--log", action="store_true", help="logarithmic colour scale")
    p.add_argument("--no-lobe", action="store_true", help="only the polar maps, no 3-D lobe")
    _dataset_flags(p)
    _output(p)
    p = sub.add_parser("plane", help="BRDF in the plane of incidence: measured points and model curves")
    p.add_argument("inputs", nargs="*", metavar="FILE", help="datasets (measured points) and fit files / MIX.json")
    p.add_argument("--model", action="append", default=[], help="model name or fit file (repeatable)")
    p.add_argument("--data", action="append", default=[], help="dataset (repeatable)")
    _model_flags(p)
    p.add_argument("--theta-i", default="45", help=_INCIDENCES)
    p.add_argument("--wavelength", type=float, help="wavelength [nm] (default: 550 or the middle; datasets: their "
                                                    "nearest band, at which the fit files are evaluated too)")
    p.add_argument("--log", action="store_true", help="logarithmic radius (y axis) with labelled decades; "
                                                      "otherwise the radius starts at 0")
    p.add_argument("--cartesian", action="store_true", help="BRDF against signed theta_r instead of a polar plot")
    _dataset_flags(p)
    _output(p)
    p = sub.add_parser("fit", help="fit quality: measured vs fitted, residuals, RMSE vs wavelength")
    p.add_argument("data", help="the dataset CSV that was fitted")
    p.add_argument("fit_file", metavar="FIT.json", help="fit file written by roadbrdf fit")
    p.add_argument("--fit", metavar="NAME", help="which fit of FIT.json (its model name; default: the best-ranked)")
    p.add_argument("--model", action=_renamed("--fit NAME"), help=argparse.SUPPRESS)
    p.add_argument("--wavelength", type=float, help="wavelength [nm] of the left panels (default: 550 or the middle)")
    _dataset_flags(p)
    _output(p)
    p = sub.add_parser("albedo", help="black-sky vs sun zenith, white-sky, blue-sky per atmosphere, spectral albedo")
    p.add_argument("result", nargs="+", metavar="FILE",
                   help="JSON of `roadbrdf albedo --json` (one per atmosphere), or a fit file / MIX.json")
    p.add_argument("--atmosphere", action="append", help="fit file: compute the blue-sky albedo under this "
                   "atmosphere, e.g. spectrl2:aod=0.05 (repeatable: one curve each)")
    p.add_argument("--sun-zenith", default="0:80:10", help="fit file: sun zenith angles [deg] (default 0:80:10)")
    p.add_argument("--wavelengths", help="fit file: wavelengths [nm] (default: the fit's)")
    p.add_argument("--fit", metavar="NAME", help="which fit of FIT.json or method of MIX.json (default: the best)")
    p.add_argument("--tolerance", type=float, default=FIGURE_TOLERANCE,
                   help="fit file: absolute quadrature tolerance of the albedo drawn (default "
                   f"{FIGURE_TOLERANCE:g}, a tenth of a pixel; `roadbrdf albedo` computes to 1e-5)")
    p.add_argument("--label", action="append", help="legend name of each input (repeatable; default: file names)")
    p.add_argument("--uncertainty", choices=["correlated", "independent"], default="correlated",
                   help="solar-weighted bars: the bound for errors correlated across wavelengths (default) or "
                   "the wavelengths taken as independent")
    _output(p)
    p = sub.add_parser("rtable", help="r-table heat map and class diagram")
    p.add_argument("table", help="r-table file, fit file (with --fit) or model name (with -p/--option)")
    _model_flags(p)
    p.add_argument("--wavelength", type=float, help="fit file: the r-table at one wavelength [nm]")
    p.add_argument("--band", help="fit file: unweighted mean over a band A:B [nm]")
    p.add_argument("--illuminant", default="", help="fit file: photometric weighting V(lambda) x A (default)|D65|FILE")
    _output(p)
    p = sub.add_parser("luminaire", help="luminaire polar curves: C0-C180 and C90-C270 in cd/klm")
    p.add_argument("file", metavar="FILE", help="luminaire photometry file: EULUMDAT (.ldt) or IES LM-63 (.ies)")
    _output(p)
    p = sub.add_parser("lighting", help="plan of a road-lighting installation with its luminance map in cd/m^2")
    p.add_argument("result", metavar="RESULT", help="JSON of roadbrdf lighting --json")
    p.add_argument("--lane", type=int, default=1, help="the observer's lane (1 = the right-hand lane)")
    _output(p)
    from .plot_study import add_parser as add_study_parser  # design studies (plot_study.py)
    from .plot_params import add_parser as add_params_parser  # plot_params.py
    add_study_parser(sub, _output)
    add_params_parser(sub, _output)
    return parser


def _draw(a):
    from . import plot
    out = dict(title=a.title, output=a.output, dpi=a.dpi)
    if a.kind in ("spectral", "hemisphere", "plane", "fit"):
        out.update(average_duplicates=a.average_duplicates, units=a.units)
    if a.kind == "spectral":
        plot.spectral(a.data, a.geometry, fit=a.fit, **out)
    elif a.kind == "hemisphere":
        data = a.data
        if not is_model_file(a.model) and os.path.isfile(a.model):
            if a.parameter or a.option or a.fit:
                raise ValueError(f"-p/--option/--fit cannot be combined with a dataset ('{a.model}')")
            model, params, data = None, {}, a.model
        elif is_model_file(a.model):
            model, params = _model_argument(a.model, a, read=False)
        else:
            model, params = _model_argument(a.model, a)
        plot.hemisphere(model, params, a.theta_i, a.wavelength, a.log, data=data, lobe=not a.no_lobe, fit=a.fit,
                        **out)
    elif a.kind == "plane":
        models = [m if is_model_file(m) else _model_argument(m, a)[0] for m in a.model]
        models += [f for f in a.inputs if is_model_file(f)]
        data = a.data + [f for f in a.inputs if not is_model_file(f)]
        if not models and not data:
            raise ValueError("plot plane: give a dataset (DATA.csv or --data) or a model (--model)")
        params = _assignments(a.parameter, "-p", True)
        plot.plane(models, data, a.theta_i, params, a.wavelength, log=a.log, cartesian=a.cartesian, fit=a.fit, **out)
    elif a.kind == "fit":
        plot.fit_quality(a.data, a.fit_file, a.fit, a.wavelength, **out)
    elif a.kind == "albedo":
        plot.albedo(a.result if len(a.result) > 1 else a.result[0], labels=a.label, atmospheres=a.atmosphere,
                    sun_zenith=a.sun_zenith, wavelengths=a.wavelengths, fit=a.fit, uncertainty=a.uncertainty,
                    tolerance=a.tolerance, **out)
    elif a.kind == "rtable":
        table = a.table
        if is_model_file(table) or not os.path.exists(table):
            # A fit file is passed by its name, which names the figure.
            table, params = _model_argument(table, a, read=False)
        else:
            if a.parameter or a.option or a.fit:
                raise ValueError(f"-p/--option/--fit cannot be combined with an r-table file ('{table}')")
            params = {}
        band = None
        if a.band is not None:
            lo, sep, hi = a.band.partition(":")
            if not sep:
                raise ValueError(f"--band expects A:B in nm, got '{a.band}'")
            band = (float(lo), float(hi))
        plot.rtable(table, params, wavelength=a.wavelength, band=band, illuminant=a.illuminant,
                    fit=a.fit if is_model_file(a.table) else None, **out)
    elif a.kind == "luminaire":
        plot.luminaire(a.file, **out)
    elif a.kind == "lighting":
        plot.lighting(a.result, lane=a.lane, **out)
    elif a.kind == "study":
        from .plot_study import run as run_study
        run_study(a)
    elif a.kind == "params":
        from .plot_params import run as run_params
        run_params(a)


def main(argv=None):
    """``python3 -m roadbrdf.plot KIND ... -o FILE`` (also ``roadbrdf plot``); errors raise ValueError."""
    a = _parser().parse_args(argv)
    check_output_folder(a.output)
    # As every roadbrdf command: the figure must not replace one of the files it is drawn from.
    inputs = []
    for role in ("data", "model", "fit_file", "result", "table", "inputs", "file"):
        value = getattr(a, role, None)
        for path in (value if isinstance(value, list) else [value]):
            if isinstance(path, str):
                inputs.append(("FIT.json" if role == "fit_file" else role.upper(), path))
    from . import _roadbrdf
    _roadbrdf.check_distinct_files(inputs, [("-o", a.output)])
    # A figure that takes long (an albedo with its uncertainty computed first, say) is not drawn in silence:
    # a line every 10 s in a log, a bar from 2 s on a terminal.
    from .heartbeat import Heartbeat
    with Heartbeat(f"roadbrdf plot {a.kind}"):
        _draw(a)
    print(a.output)
    return 0


def _warning(message, category, filename, lineno, file=None, line=None):
    from .heartbeat import say
    say(f"roadbrdf: warning: {message}")  # above the progress bar when one is drawn


def run(argv=None):
    """:func:`main` with the errors and warnings as the program reports them: ``roadbrdf: warning: ...``, and
    an error message on standard error with status 2."""
    import warnings
    warnings.showwarning = _warning
    try:
        return main(argv)
    except OutputFolderError as e:
        print(f"roadbrdf plot: error: {e}", file=sys.stderr)
    except ValueError as e:
        # The library names its fields; this command line spells the dataset options as flags.
        print(f"roadbrdf: error: {str(e).replace('`average_duplicates`', '--average-duplicates')}", file=sys.stderr)
    except OSError as e:
        where = f"{e.filename}: " if e.filename else ""
        print(f"roadbrdf: error: {where}{e.strerror or e}", file=sys.stderr)
    return 2
