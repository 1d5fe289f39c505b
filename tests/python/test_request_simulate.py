"""The simulate request's field table (SimulateRequest::fields, io/simulate_request.cpp; its model source rows
shared with eval, modelfile/model_source_fields.h) seen from both front ends, row by row: `roadbrdf simulate
--help` shows each row's flag, `roadbrdf.simulate`'s docstring its keyword and help, and a bad value is refused
with the same text by both (the command line naming the flag, Python the keyword). The rows come from the table
itself, so a new field without a bad value here fails. The values are checked against closed forms."""
import math

import numpy as np
import pytest
from request_table import check_every_row_is_shown, check_refused_alike, fields

import roadbrdf
from roadbrdf import _roadbrdf

FIELDS = fields("simulate")
GRID = "data/examples/grid/cerema-like-grid.csv"


def _bad_values(root, tmp_path):
    """For every field: (command line arguments after the model, Python keywords) of a bad value; None for a
    field that takes every value (only Python's type check is compared then)."""
    grid = str(root / GRID)
    lambert = ["-p", "albedo=0.3", "--grid", grid, "--wavelengths", "500"]
    ok = dict(parameters=["albedo=0.3"], grid=grid, wavelengths="500")
    return {
        "model": ("no-such-model", ["--grid", grid], dict(grid=grid)),
        "parameters": ("lambert", ["-p", "albedo=2", "--grid", grid], dict(parameters=["albedo=2"], grid=grid)),
        "options": ("lambert", [*lambert, "--option", "bogus=1"], dict(ok, options=["bogus=1"])),
        "fit": ("lambert", [*lambert, "--fit", "lambert"], dict(ok, fit="lambert")),
        "grid": ("lambert", ["--grid", str(tmp_path / "absent.csv")], dict(grid=str(tmp_path / "absent.csv"))),
        "wavelengths": ("lambert", ["--grid", grid, "--wavelengths", "500,400"], dict(grid=grid, wavelengths="500,400")),
        "spectral": ("lambert", [*lambert, "--spectral", "albedo"], dict(ok, spectral=["albedo"])),
        "noise": ("lambert", [*lambert, "--noise", "bogus=1"], dict(ok, noise="bogus=1")),
        "seed": None,
        "digits": ("lambert", [*lambert, "--digits", "18"], dict(ok, digits=18)),
        "sigma": None,
        "metadata": ("lambert", [*lambert, "--metadata", "site"], dict(ok, metadata=["site"])),
        "format": ("lambert", [*lambert, "--format", "xlsx"], dict(ok, format="xlsx")),
        "output": ("lambert", [*lambert, "-o", grid], dict(ok, output=grid)),
    }


def test_every_row_is_an_option_and_a_keyword(cli):
    check_every_row_is_shown(cli, "simulate", roadbrdf.simulate)


@pytest.mark.parametrize("row", FIELDS, ids=[row["name"] for row in FIELDS])
def test_a_bad_value_is_refused_alike(cli, root, tmp_path, row):
    bad = _bad_values(root, tmp_path)
    assert row["name"] in bad, f"the table's field {row['name']} needs a bad value in this test"
    if bad[row["name"]] is None:
        with pytest.raises(roadbrdf.InputError, match=f"^{row['name']}: expected"):
            _roadbrdf.simulate("lambert", grid=str(root / GRID), **{row["name"]: "1"})
        return
    model, cli_args, kwargs = bad[row["name"]]
    out = tmp_path / "s.csv"
    result = cli("simulate", model, *cli_args, *([] if "-o" in cli_args else ["-o", out]), check=False)
    with pytest.raises(roadbrdf.InputError) as error:
        roadbrdf.simulate(model, **kwargs)
    check_refused_alike("simulate", row, result, error.value)
    assert not out.exists()


def test_lambert_without_noise_is_its_albedo_over_pi_and_both_write_the_same_file(cli, root, tmp_path):
    # Noise-free Lambertian data: rho / pi at every geometry and wavelength (closed form).
    d = roadbrdf.simulate("lambert", parameters=["albedo=0.25"], grid=root / GRID, wavelengths="400:600:100",
                          output=tmp_path / "py.csv")
    assert list(d.wavelengths) == [400.0, 500.0, 600.0]
    np.testing.assert_allclose(d.brdf, 0.25 / math.pi, rtol=1e-12)
    cli("simulate", "lambert", "-p", "albedo=0.25", "--grid", root / GRID, "--wavelengths", "400:600:100",
        "-o", tmp_path / "cli.csv")
    assert (tmp_path / "py.csv").read_bytes() == (tmp_path / "cli.csv").read_bytes()


def test_the_same_seed_gives_the_same_noise_in_both(cli, root, tmp_path):
    # Relative noise of 5 %: the sample standard deviation of (value - rho/pi) / (rho/pi) over all values
    # estimates 0.05 (about 700 values: within 20 %); without sigma columns when switched off.
    args = dict(parameters=["albedo=0.25"], grid=root / GRID, wavelengths="400:700:50", noise="relative=0.05",
                seed=7, sigma=False)
    d = roadbrdf.simulate("lambert", output=tmp_path / "py.csv", **args)
    cli("simulate", "lambert", "-p", "albedo=0.25", "--grid", root / GRID, "--wavelengths", "400:700:50",
        "--noise", "relative=0.05", "--seed", "7", "--no-sigma", "-o", tmp_path / "cli.csv")
    assert (tmp_path / "py.csv").read_bytes() == (tmp_path / "cli.csv").read_bytes()
    relative = (np.asarray(d.brdf) - 0.25 / math.pi) / (0.25 / math.pi)
    assert np.std(relative) == pytest.approx(0.05, rel=0.2)
    assert "sigma_400" not in (tmp_path / "py.csv").read_text()
