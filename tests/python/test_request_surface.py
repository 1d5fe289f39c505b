"""The surface request's field table (SurfaceRequest::fields, surface/surface_request.cpp) seen from both front
ends, row by row: `roadbrdf surface --help` shows each row's flag, the docstring of `roadbrdf.surface` each
keyword and its help, and a bad value is refused with the same text by both (the command line naming the flag,
Python the keyword). The rows come from the table itself, so a new field without a bad value here fails.
The material functions (flat_surface, gaussian_slope_surface) fill the same request and give the same errors."""
import re
import warnings

import numpy as np
import pytest
from request_table import check_refused_alike, fields
from study_support import physical_study

import roadbrdf
from roadbrdf import _roadbrdf

FIELDS = fields("surface")

# A bad value per field, on a validation surface of the model `lambert`: (command-line arguments after
# `roadbrdf surface lambert`, the keywords of the same request in Python); None for a field whose bad values
# are checked below (`input`) or that takes every value (`seed`: only Python's type check is compared).
OUT = "OUT"  # the output file of the call
BAD = {
    "input": None,  # test_a_bad_formulation_is_refused_alike
    "size_mm": (["--flat", "--size", "60mm"], dict(flat=True, size_mm=60.0)),
    "cell_mm": (["--flat", "--cell", "20"], dict(flat=True, cell_mm=20.0)),
    "seed": None,
    "matrix_level": (["--flat", "--matrix-level", "0.5"], dict(flat=True, matrix_level=0.5)),
    "target_mpd": (["--flat", "--target-mpd", "0.5"], dict(flat=True, target_mpd=0.5)),
    "mastic_fraction": (["--flat", "--mastic-fraction", "0.5"], dict(flat=True, mastic_fraction=0.5)),
    "preview": (["--flat", "--preview", OUT], dict(flat=True, preview=OUT, output=OUT)),
    "flat": (["--flat", "--gaussian-slopes", "0.2"], dict(flat=True, sigma_rad=0.2)),
    "sigma_rad": (["--gaussian-slopes", "2"], dict(sigma_rad=2.0)),
    "cells": (["--flat", "--cells", "1"], dict(flat=True, cells=1)),
    "parameters": (["--flat", "-p", "rho=0.5"], dict(flat=True, parameters={"rho": 0.5})),
    "options": (["--flat", "--option", "shadowing=none"], dict(flat=True, options={"shadowing": "none"})),
    "fit": (["--flat", "--fit", "lambert"], dict(flat=True, fit="lambert")),
    "output": (["--preview", OUT], dict(preview=OUT, output=OUT)),
}


def test_every_row_has_a_bad_value():
    assert sorted(row["name"] for row in FIELDS) == sorted(BAD)


def test_every_row_is_an_option_and_a_keyword(cli):
    help_text = cli("surface", "--help").stdout
    for function in (roadbrdf.surface, _roadbrdf.surface):
        doc = " ".join(function.__doc__.split())
        for row in FIELDS:
            assert re.search(r"(^|[\s,\[])" + re.escape(row["long_flag"]) + r"\b", help_text), row
            assert f" {row['name']}: " in doc or f" {row['name']} [" in doc, row["name"]
            assert " ".join(row["help"].split())[:40] in doc, row["name"]


@pytest.mark.parametrize("row", FIELDS, ids=[row["name"] for row in FIELDS])
def test_a_bad_value_is_refused_alike(cli, tmp_path, monkeypatch, row):
    monkeypatch.chdir(tmp_path)
    name = row["name"]
    out = tmp_path / "s.json"
    if BAD[name] is None:
        if row["kind"] == "integer":  # Python's type check
            with pytest.raises(roadbrdf.InputError, match=f"^{name}: expected an integer, got str"):
                _roadbrdf.surface("lambert", flat=True, **{name: "1"})
        return
    cli_args, keywords = BAD[name]
    if name == "output":
        cli_args = ["--flat", *cli_args]
        keywords = dict(keywords, flat=True)
    cli_args = [str(out) if a == OUT else a for a in cli_args]
    keywords = {k: str(out) if v == OUT else v for k, v in keywords.items()}
    result = cli("surface", "lambert", *cli_args, "-o", out, check=False)
    with pytest.raises(roadbrdf.InputError) as error:
        _roadbrdf.surface("lambert", **keywords)
    check_refused_alike("surface", row, result, error.value)
    assert not out.exists()


def test_the_material_functions_fill_the_same_request(cli, tmp_path):
    """flat_surface and gaussian_slope_surface are the request's `flat` and `sigma_rad` with its material."""
    for flags, function, kwargs, cli_field, py_field in [
            (["--gaussian-slopes", "2"], "gaussian_slope_surface", dict(sigma_rad=2.0), "--gaussian-slopes",
             "sigma_rad"),
            (["--flat", "--cells", "1"], "flat_surface", dict(cells=1), "--cells", "cells"),
            (["--flat", "--cell", "20"], "flat_surface", dict(cell_mm=20.0), "--cell", "cell_mm")]:
        out = tmp_path / "s.json"
        r = cli("surface", "lambert", "-p", "albedo=0.3", *flags, "-o", out, check=False)
        args = ("lambert",) if function == "flat_surface" else ("lambert", kwargs.pop("sigma_rad"))
        with pytest.raises(roadbrdf.InputError) as e:
            getattr(roadbrdf, function)(*args, {"albedo": 0.3}, **kwargs)
        prefix = f"roadbrdf: error: {cli_field}: "
        assert r.returncode == 2 and r.stderr.startswith(prefix), r.stderr
        assert str(e.value).startswith(py_field + ": ") and r.stderr.strip()[len(prefix):] == \
            str(e.value)[len(py_field) + 2:]
        assert not out.exists()


MATERIAL_ERRORS = [
    # (CLI material argument and flags, Python material, params, fit_model)
    (["lambert", "-p", "rho=0.5"], "lambert", {"rho": 0.5}, None),
    (["lambertt"], "lambertt", None, None),
    (["lambert", "--fit", "lambert"], "lambert", None, "lambert"),
    (["missing.fit.json"], "missing.fit.json", None, None),
]


@pytest.mark.parametrize("cli_args,material,params,fit_model", MATERIAL_ERRORS,
                         ids=["parameter", "model", "fit", "file"])
def test_a_bad_material_is_refused_alike(cli, tmp_path, monkeypatch, cli_args, material, params, fit_model):
    """A material is built and checked once (surface/materials.h material_spec): same message from both."""
    monkeypatch.chdir(tmp_path)
    out = tmp_path / "s.json"
    r = cli("surface", *cli_args, "--flat", "-o", out, check=False)
    assert r.returncode == 2 and r.stderr.startswith("roadbrdf: error: "), r.stderr
    with pytest.raises(roadbrdf.InputError) as e:
        roadbrdf.flat_surface(material, params, fit_model=fit_model)
    cli_message, py_message = r.stderr.strip()[len("roadbrdf: error: "):], str(e.value)
    if fit_model:  # a field error: the CLI names its flag, Python the field
        assert cli_message.startswith("--fit: ") and py_message.startswith("fit: "), (cli_message, py_message)
        cli_message, py_message = cli_message[len("--fit: "):], py_message[len("fit: "):]
    assert cli_message == py_message
    assert not out.exists()


def test_a_bad_formulation_is_refused_alike(cli, tmp_path):
    """The formulation file is read by the library (formulation.h read_formulation) for both front ends."""
    bad = tmp_path / "bad.formulation.json"
    bad.write_text("{\"components\": [")
    for path in (bad, tmp_path / "missing.formulation.json"):
        r = cli("surface", path, "-o", tmp_path / "s.json", check=False)
        assert r.returncode == 2, r.stderr
        with pytest.raises(roadbrdf.InputError) as e:
            roadbrdf.surface(path)
        assert r.stderr.strip() == "roadbrdf: error: " + str(e.value)


def test_parameters_with_a_fit_file_are_refused_by_the_library(cli, root, tmp_path):
    fit = tmp_path / "l.fit.json"
    cli("fit", root / "data/examples/single/lazard.csv", "--model", "lambert", "--wavelengths", "510:710:100",
        "-o", fit)
    r = cli("surface", fit, "--flat", "-p", "albedo=0.3", "-o", tmp_path / "s.json", check=False)
    assert r.returncode == 2 and r.stderr.startswith("roadbrdf: error: --parameter: "), r.stderr
    with pytest.raises(roadbrdf.InputError) as e:
        roadbrdf.flat_surface(fit, {"albedo": 0.3})
    assert str(e.value).startswith("parameters: ")
    assert r.stderr.strip()[len("roadbrdf: error: --parameter: "):] == str(e.value)[len("parameters: "):]


def test_a_length_with_its_unit_is_the_same_sample(cli, tmp_path):
    """`--size 1.2cm` on the command line is `size_mm=12` in Python (1 cm = 10 mm): the same periodic sample of
    12 mm / 0.4 mm = 30 cells a side, identical heights from the same seed (both written to a SURFACE file, which
    rounds the heights the same way)."""
    physical_study(tmp_path)
    out = tmp_path / "cli.surface.json"
    cli("surface", tmp_path / "base.json", "--size", "1.2cm", "--cell", "0.4", "--seed", "3", "--quiet", "-o", out)
    from_cli = roadbrdf.read_surface(out)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # generator notes (UserWarning) may come for this tiny sample
        roadbrdf.surface(tmp_path / "base.json", size_mm=12, cell_mm=0.4, seed=3, output=tmp_path / "py.json")
    from_python = roadbrdf.read_surface(tmp_path / "py.json")
    assert from_cli.shape == (30, 30) == from_python.shape
    assert np.array_equal(from_cli.heights, from_python.heights)
    assert np.array_equal(from_cli.material_map, from_python.material_map)
    bad = cli("surface", tmp_path / "base.json", "--size", "12 parsecs", "-o", out, check=False)
    assert bad.returncode == 2 and bad.stderr.startswith("roadbrdf: error: --size: "), bad.stderr

