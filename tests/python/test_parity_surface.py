"""roadbrdf surface and roadbrdf.surface / flat_surface / gaussian_slope_surface: surface settings and
materials are validated once, in the library, and give the same errors (the CLI naming its flag, Python the
argument)."""
import pytest

import roadbrdf
from conftest import assert_same_error


SURFACE_ERRORS = [
    (["--gaussian-slopes", "2"], "gaussian_slope_surface", dict(sigma_rad=2.0), "--gaussian-slopes", "sigma_rad"),
    (["--flat", "--cells", "1"], "flat_surface", dict(cells=1), "--cells", "cells"),
    (["--flat", "--cell", "20"], "flat_surface", dict(cell_mm=20.0), "--cell", "cell_mm"),
]


@pytest.mark.parametrize("flags,function,kwargs,cli_field,py_field", SURFACE_ERRORS, ids=[e[4] for e in SURFACE_ERRORS])
def test_surface_errors_are_the_same(cli, tmp_path, flags, function, kwargs, cli_field, py_field):
    """Surface settings are validated once (surface/surface_request.h): same message, flag vs keyword."""
    out = tmp_path / "s.json"
    r = cli("surface", "lambert", "-p", "albedo=0.3", *flags, "-o", out, check=False)
    args = ("lambert",) if function == "flat_surface" else ("lambert", kwargs.pop("sigma_rad"))
    with pytest.raises(roadbrdf.InputError) as e:
        getattr(roadbrdf, function)(*args, {"albedo": 0.3}, **kwargs)
    assert_same_error(r, e.value, cli_field, py_field)
    assert not out.exists()


MATERIAL_ERRORS = [
    # (CLI material argument and flags, Python material, params, fit_model)
    (["lambert", "-p", "rho=0.5"], "lambert", {"rho": 0.5}, None),
    (["lambertt"], "lambertt", None, None),
    (["lambert", "--fit", "lambert"], "lambert", None, "lambert"),
    (["missing.fit.json"], "missing.fit.json", None, None),
]


@pytest.mark.parametrize("cli_args,material,params,fit_model", MATERIAL_ERRORS, ids=["parameter", "model", "fit",
                                                                                    "file"])
def test_surface_material_errors_are_the_same(cli, tmp_path, monkeypatch, cli_args, material, params, fit_model):
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


def test_surface_formulation_errors_are_the_same(cli, tmp_path):
    """The formulation file is read by the library (formulation.h read_formulation) for both front ends."""
    bad = tmp_path / "bad.formulation.json"
    bad.write_text("{\"components\": [")
    for path in (bad, tmp_path / "missing.formulation.json"):
        r = cli("surface", path, "-o", tmp_path / "s.json", check=False)
        assert r.returncode == 2, r.stderr
        with pytest.raises(roadbrdf.InputError) as e:
            roadbrdf.surface(path)
        assert r.stderr.strip() == "roadbrdf: error: " + str(e.value)


def test_surface_parameters_with_a_fit_file_are_refused_by_the_library(cli, root, tmp_path):
    fit = tmp_path / "l.fit.json"
    cli("fit", root / "data/examples/single/lazard.csv", "--model", "lambert", "--wavelengths", "510:710:100",
        "-o", fit)
    r = cli("surface", fit, "--flat", "-p", "albedo=0.3", "-o", tmp_path / "s.json", check=False)
    assert r.returncode == 2 and r.stderr.startswith("roadbrdf: error: -p: "), r.stderr
    with pytest.raises(roadbrdf.InputError) as e:
        roadbrdf.flat_surface(fit, {"albedo": 0.3})
    assert str(e.value).startswith("parameters: ")
    assert r.stderr.strip()[len("roadbrdf: error: -p: "):] == str(e.value)[len("parameters: "):]
