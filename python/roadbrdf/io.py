"""Measured datasets: reading and writing CSV, CUReT and ALTA files (``src/roadbrdf/io``)."""

from __future__ import annotations

import os
from typing import Any, Iterable, Mapping, Optional, Sequence, Union

import numpy as np

from . import _roadbrdf
from .core import ArrayLike, as_float, as_float_array, as_int, as_text

PathLike = Union[str, "os.PathLike[str]"]

__all__ = ["Dataset", "read_dataset", "write_dataset", "read_curet", "read_alta", "check", "convert"]


class Dataset:
    """A spectral BRDF dataset: N geometries x M wavelengths.

    Attributes
    ----------
    angles : ndarray (N, 4)
        theta_i, phi_i, theta_r, phi_r [deg] of each geometry.
    wavelengths : ndarray (M,)
        [nm], strictly increasing.
    brdf : ndarray (N, M)
        [sr^-1].
    sigma : ndarray (N, M) or None
        standard uncertainty [sr^-1].
    metadata : dict
        "sample", "instrument", "units" and free keys (the "# key: value" lines of a CSV file).
    convention : "zenith" or "road"
        angle columns used when the dataset is written.
    comments : list of str
        the free comment lines of the source file (any "# ..." line that is not "key: value"), kept
        in order and written back.
    """

    def __init__(self, angles: ArrayLike, wavelengths: ArrayLike, brdf: ArrayLike, sigma: Optional[ArrayLike] = None,
                 metadata: Optional[Mapping[str, Any]] = None, convention: str = "zenith",
                 comments: Optional[Iterable[str]] = None, average_duplicates: bool = False) -> None:
        """Repeated geometries follow the readers' duplicate policy: an InputError naming both rows,
        or, with ``average_duplicates``, averaged (values and sigma as duplicate rows of a file)."""
        self._set(angles, wavelengths, brdf, sigma, metadata, convention, comments)
        if self.angles.shape[0] > 1:
            checked = _roadbrdf.dataset_duplicate_policy(
                np.ascontiguousarray(self.angles), np.ascontiguousarray(self.wavelengths),
                np.ascontiguousarray(self.brdf), None if self.sigma is None else np.ascontiguousarray(self.sigma),
                {str(k): str(v) for k, v in self.metadata.items()}, self.convention,
                as_bool(average_duplicates, "average_duplicates"))
            if checked["angles"].shape[0] != self.angles.shape[0]:
                self._set(checked["angles"], checked["wavelengths"], checked["brdf"], checked["sigma"],
                          checked["metadata"], self.convention, self.comments)

    def _set(self, angles, wavelengths, brdf, sigma, metadata, convention, comments) -> None:
        self.angles = as_float_array(angles, "angles").reshape(-1, 4)
        self.wavelengths = as_float_array(wavelengths, "wavelengths").reshape(-1)
        self.brdf = as_float_array(brdf, "brdf").reshape(self.angles.shape[0], self.wavelengths.size)
        self.sigma = None if sigma is None else as_float_array(sigma, "sigma").reshape(self.brdf.shape)
        self.metadata = dict(metadata or {})
        self.convention = convention
        self.comments = [str(c) for c in (comments or [])]

    @classmethod
    def _from_dict(cls, d):
        # Read by the library, which applied the duplicate policy already.
        dataset = cls.__new__(cls)
        dataset._set(d["angles"], d["wavelengths"], d["brdf"], d["sigma"], d["metadata"], d["convention"],
                     d["comments"])
        return dataset

    @property
    def theta_i(self) -> np.ndarray:
        return self.angles[:, 0]

    @property
    def phi_i(self) -> np.ndarray:
        return self.angles[:, 1]

    @property
    def theta_r(self) -> np.ndarray:
        return self.angles[:, 2]

    @property
    def phi_r(self) -> np.ndarray:
        return self.angles[:, 3]

    def __len__(self):
        return self.angles.shape[0]

    def __repr__(self):
        name = self.metadata.get("sample", "")
        return (f"roadbrdf.Dataset({name!r}: {len(self)} geometries x {self.wavelengths.size} wavelengths "
                f"{self.wavelengths[0]:g}-{self.wavelengths[-1]:g} nm)") if self.wavelengths.size else "roadbrdf.Dataset()"

    def write(self, path: PathLike, format: str = "wide") -> None:
        """Write as wide (default) or long CSV, atomically (see :func:`write_dataset`)."""
        write_dataset(self, path, format)


def as_bool(value, name: str) -> bool:
    if isinstance(value, (bool, np.bool_)):
        return bool(value)
    raise TypeError(f"{name}: expected True or False, got {type(value).__name__}")


def _items(value, name: str) -> list:
    """``columns`` / ``set`` as the command line's [FILE:]FIELD=VALUE items: a mapping {field: value}
    (a key may be "FILE:field"), or a list of "FIELD=VALUE" strings."""
    if value is None:
        return []
    if isinstance(value, Mapping):
        return [f"{as_text(k, name)}={v if isinstance(v, str) else repr(as_float(v, name))}" for k, v in value.items()]
    if isinstance(value, str):
        return [value]
    return [as_text(item, name) for item in value]


def _paths(path) -> list:
    if isinstance(path, (str, os.PathLike)):
        return [as_text(path, "path")]
    return [as_text(p, "path") for p in path]


def read_dataset(path: Union[PathLike, Sequence[PathLike]], average_duplicates: bool = False,
                 allow_missing: bool = True, delimiter: str = "auto", decimal: str = "auto", quantity: str = "brdf",
                 columns: Optional[Union[Mapping[str, str], Sequence[str]]] = None,
                 set: Optional[Union[Mapping[str, float], Sequence[str]]] = None) -> Dataset:
    """Read a wide or long CSV dataset (the format is detected from the header).

    Duplicate geometries are an error unless ``average_duplicates`` (which averages the measured
    values of each cell). Missing values (empty, nan, NA) are measurements not made: kept as NaN,
    counted in a :class:`UserWarning` (``allow_missing=False`` makes them an error); the fit, mixing,
    resampling and calibration mask them out, never fill them in. Negative values are kept and
    reported with a :class:`UserWarning`. Malformed files raise InputError naming file:line:column.
    ``delimiter`` ("auto", ",", ";", "tab") and ``decimal`` ("auto", ".", ",") are the command line's
    ``--delimiter`` / ``--decimal``: by default the dialect is detected (docs/data.md). A file whose name
    ends in ``.xompt`` is read as an ASAM OpenMATERIAL 3D BRDF look-up table (docs/data.md).

    Laboratory tables (docs/data.md, "Any laboratory table"): ``quantity`` is what the values are
    ("brdf", "brf" = pi BRDF, "brdf-cos" = BRDF cos theta_i, "percent-brf"), converted to BRDF;
    ``columns`` maps dataset fields to header names (``{"theta_r": "True_Average_View_Zenith"}``);
    ``set`` gives angles the file has no column for (``{"theta_i": 30, "phi_i": 0}``; a key
    ``"run2.csv:theta_i"`` applies to that file only). Other columns are then not read (a warning
    lists them). ``path`` may be a list of files: runs of one sample combined into one dataset (the
    same wavelengths; a geometry in several runs follows ``average_duplicates``).
    """
    return Dataset._from_dict(_roadbrdf.read_dataset(
        _paths(path), as_bool(allow_missing, "allow_missing"),
        average_duplicates=as_bool(average_duplicates, "average_duplicates"), delimiter=str(delimiter),
        decimal=str(decimal), quantity=as_text(quantity, "quantity"), columns=_items(columns, "columns"),
        set=_items(set, "set")))


def write_dataset(dataset: Dataset, path: PathLike, format: str = "wide") -> None:
    """Write a dataset as ``"wide"`` or ``"long"`` CSV, atomically (temporary file, then rename)."""
    if not isinstance(dataset, Dataset):
        raise TypeError(f"dataset: expected a roadbrdf.Dataset, got {type(dataset).__name__}")
    _roadbrdf.write_dataset(np.ascontiguousarray(dataset.angles), np.ascontiguousarray(dataset.wavelengths),
                            np.ascontiguousarray(dataset.brdf),
                            None if dataset.sigma is None else np.ascontiguousarray(dataset.sigma),
                            {str(k): str(v) for k, v in dataset.metadata.items()}, dataset.convention,
                            list(dataset.comments), as_text(path, "path"), format)


def read_curet(abrdf_path: PathLike, table_path: PathLike, sample: int) -> Dataset:
    """One sample of the CUReT BRDF database (``abrdf.dat`` + ``table.txt``), grey, stored at a
    nominal wavelength recorded in the metadata (``roadbrdf convert abrdf.dat --from curet``, the same
    request)."""
    return convert(as_text(abrdf_path, "abrdf_path"), source="curet", curet_table=as_text(table_path, "table_path"),
                   sample=as_int(sample, "sample"))


def read_alta(path: PathLike, wavelength: float, assumed_output: str = "", exclude_grazing: bool = False) -> Dataset:
    """An ALTA text-format BRDF file (BRDF x cos theta_v output is divided by cos theta_v).
    ``wavelength`` [nm] is required (ALTA files carry none). ``roadbrdf convert FILE --from alta``, the
    same request (``assumed_output`` is its ``alta_output``)."""
    return convert(as_text(path, "path"), source="alta", wavelength=as_float(wavelength, "wavelength"),
                   alta_output=assumed_output, exclude_grazing=exclude_grazing)


def check(path: Union[PathLike, Dataset], **kwargs: Any) -> dict:
    """The quality report of a dataset file, as ``roadbrdf check DATA.csv --json`` gives it (one library
    request, the same rules): ``geometries``, ``wavelengths`` (count, min_nm, max_nm), ``coverage``
    (incidence and viewing zenith angles, azimuth planes, forward/backward/perpendicular/in-plane counts),
    ``negative_values``, ``missing_values``, ``reciprocity``, ``noise`` (noisy bands, SNR per wavelength),
    ``outliers``, ``specular_peaks_not_counted_as_outliers``, ``units``, ``file``, and ``text``: the report
    ``roadbrdf check`` prints. Missing values are counted, not an error. ``path`` may be a
    :class:`Dataset` in memory (``file`` is then None; the reading keywords do not apply to it and are
    refused). The keywords are the request's fields (listed below, the command line's options; ``None``
    leaves a field at its default); ``columns`` and ``set`` may also be mappings {field: value}.
    """
    kwargs = {key: value for key, value in kwargs.items() if value is not None}
    for key in ("columns", "set"):
        if key in kwargs:
            kwargs[key] = _items(kwargs[key], key)
    if isinstance(path, Dataset):
        d = path
        return _roadbrdf.check_dataset_object(
            np.ascontiguousarray(d.angles), np.ascontiguousarray(d.wavelengths), np.ascontiguousarray(d.brdf),
            None if d.sigma is None else np.ascontiguousarray(d.sigma), {str(k): str(v) for k, v in d.metadata.items()},
            d.convention, **kwargs)
    return _roadbrdf.check_dataset(path, **kwargs)


def resample(*args: Any, **kwargs: Any) -> Dataset:
    """A dataset band-averaged onto new wavelength intervals, as ``roadbrdf resample`` makes it (one library
    request, the same rules): ``wavelengths`` are the band edges [nm] (``"400:1000:10"`` or a list), each
    band reported at its centre; the bands overlapping ``drop`` intervals, or with ``drop_noisy`` the noisy
    bands of :func:`check`, are left out. Written to ``output`` (``format``) when given. The keywords are
    the request's fields (listed below, the command line's options; ``None`` leaves a field at its
    default); ``columns`` and ``set`` may also be mappings {field: value}.
    """
    kwargs = {key: value for key, value in kwargs.items() if value is not None}
    for key in ("columns", "set"):
        if key in kwargs:
            kwargs[key] = _items(kwargs[key], key)
    return Dataset._from_dict(_roadbrdf.resample(*args, **kwargs))


def _with_request_arguments(function, request):
    """Appends the keywords of the request's field table (the command line's options) to the docstring."""
    doc = request.__doc__ or ""
    if "Arguments" in doc:
        function.__doc__ += "\n    " + doc[doc.index("Arguments"):doc.rindex("Returns")].strip().replace("\n", "\n    ")
        function.__doc__ += "\n"
    return function


def evaluate(*args: Any, **kwargs: Any) -> Union[float, list]:
    """A model's BRDF [sr^-1] as ``roadbrdf eval`` computes it (one library request, the same rules).

    ``model`` (the one positional argument) is a model name (with ``parameters``, NAME=VALUE texts, and ``options``), a fit file or a
    MIX.json (``fit`` chooses its entry, ``wavelength`` [nm] its band unless it has one). The geometry is
    the four angles ``theta_i``, ``phi_i``, ``theta_r``, ``phi_r`` [deg] (a float is returned), or a
    ``geometry`` CSV file (a list, one value per row; written with a ``brdf`` column to ``output`` when
    given). ``None`` leaves a field at its default.
    """
    kwargs = {key: value for key, value in kwargs.items() if value is not None}
    return _roadbrdf.eval(*args, **kwargs)


def simulate(*args: Any, **kwargs: Any) -> Dataset:
    """A simulated measurement (virtual gonioreflectometer) as ``roadbrdf simulate`` makes it: the model
    sampled on the ``grid`` file's geometries at ``wavelengths`` [nm] with the ``noise`` model, reproducible
    by ``seed``; written to ``output`` (``format``) when given. ``None`` leaves a field at its default.
    """
    kwargs = {key: value for key, value in kwargs.items() if value is not None}
    return Dataset._from_dict(_roadbrdf.simulate(*args, **kwargs))


_with_request_arguments(evaluate, _roadbrdf.eval)
_with_request_arguments(simulate, _roadbrdf.simulate)


def convert(*args: Any, **kwargs: Any) -> Dataset:
    """A dataset converted as ``roadbrdf convert`` makes it (one library request, the same rules): from
    ``inputs`` (the one positional argument: a file, or several dataset CSV files, runs of one sample, as a
    list) in the format ``source`` (the command's ``--from``: dataset CSV, CUReT, ALTA, instrument files, run manifests, USGS splib07a);
    written to ``output`` (``to``) when given. ``None`` leaves a field at its default.
    """
    kwargs = {key: value for key, value in kwargs.items() if value is not None}
    return Dataset._from_dict(_roadbrdf.convert(*args, **kwargs))


_with_request_arguments(convert, _roadbrdf.convert)
_with_request_arguments(check, _roadbrdf.check_dataset)
_with_request_arguments(resample, _roadbrdf.resample)
