"""The render request's field table (RenderRequest::fields, surface/render_request.cpp) seen from both front
ends, row by row: `roadbrdf render --help` shows each row's flag, the docstrings of `roadbrdf.render` and
`roadbrdf.render_albedo` each setting's keyword and help, and a bad value is refused with the same text by
both (the command line naming the flag, Python the keyword). The rows come from the table itself, so a new
field without a bad value here fails. The command's files (`grid`, `format`) are its own: Python passes
a surface and directions, and refuses them by name."""
import re

import numpy as np
import pytest
from request_table import check_refused_alike, fields

import roadbrdf

FIELDS = fields("render")

# A bad value per field: (command-line value, Python keyword value); None for a field without a value the
# library refuses (every seed is valid): only Python's type check is compared with the table then.
BAD = {
    "surface": None,  # a file: see test_a_bad_surface_or_output_is_refused_alike
    "grid": None,  # the command's own: see test_the_command_files_are_refused_by_python
    "sun_zenith": ("95", 95),
    "white_sky_nodes": ("100", 100),
    "wavelengths": ("500:600:30", "500:600:30"),
    "samples": ("1", 1),
    "target_error": ("2", 2.0),
    "max_samples": ("1", 1),
    "error_floor": ("-1", -1.0),
    "sampling": ("cosin", "cosin"),
    "acceptance_deg": ("50", 50.0),
    "seed": None,
    "threads": ("-1", -1),
    "max_bounces": ("5000", 5000),
    "format": None,
    "output": None,
}


@pytest.fixture
def flat(tmp_path):
    path = tmp_path / "flat.surface.json"
    roadbrdf.flat_surface("lambert", {"albedo": 0.4}, cells=8).write(path)
    grid = tmp_path / "grid.csv"
    grid.write_text("theta_i,phi_i,theta_r,phi_r\n30,0,30,180\n")
    return path, grid


def test_every_row_has_a_bad_value():
    assert sorted(row["name"] for row in FIELDS) == sorted(BAD)


def test_every_row_is_an_option_and_a_keyword(cli):
    help_text = cli("render", "--help").stdout
    render_doc = " ".join(roadbrdf.render.__doc__.split())
    albedo_doc = " ".join(roadbrdf.render_albedo.__doc__.split())
    for row in FIELDS:
        assert re.search(r"(^|[\s,\[])" + re.escape(row["long_flag"]) + r"\b", help_text), row
        if row["name"] in ("surface", "grid", "format"):
            continue  # the command's files: Python passes a surface and directions
        doc = albedo_doc if row["name"] in ("sun_zenith", "output") else render_doc
        if row["name"] == "sun_zenith":
            continue  # render_albedo's own positional argument
        assert f" {row['name']}: " in doc or f" {row['name']} [" in doc, row["name"]
        assert " ".join(row["help"].split())[:40] in doc, row["name"]


@pytest.mark.parametrize("row", FIELDS, ids=[row["name"] for row in FIELDS])
def test_a_bad_value_is_refused_alike(cli, flat, tmp_path, row):
    name = row["name"]
    surface, grid = flat
    out = tmp_path / "x.csv"
    if BAD[name] is None:
        if row["kind"] == "integer":  # Python's type check
            with pytest.raises(roadbrdf.InputError, match=f"^{name}: expected an integer, got str"):
                roadbrdf.render(surface, 30, 0, 30, 180, **{name: "1"})
        return
    cli_value, py_value = BAD[name]
    if name == "sun_zenith":
        result = cli("render", surface, "--albedo", cli_value, "-o", out, check=False)
        with pytest.raises(roadbrdf.InputError) as error:
            roadbrdf.render_albedo(surface, py_value)
    else:
        result = cli("render", surface, "--grid", grid, row["long_flag"], cli_value, "-o", out, check=False)
        with pytest.raises(roadbrdf.InputError) as error:
            roadbrdf.render(surface, 30, 0, 30, 180, **{name: py_value})
    check_refused_alike("render", row, result, error.value)
    assert not out.exists()


def test_a_bad_surface_or_output_is_refused_alike(cli, flat, tmp_path):
    surface, grid = flat
    rows = {row["name"]: row for row in FIELDS}
    missing = tmp_path / "missing.surface.json"
    result = cli("render", missing, "--grid", grid, "-o", tmp_path / "x.csv", check=False)
    with pytest.raises(roadbrdf.InputError) as error:
        roadbrdf.render(missing, 30, 0, 30, 180)
    check_refused_alike("render", rows["surface"], result, error.value)
    # The albedo table written over the surface it reads.
    result = cli("render", surface, "--albedo", "30", "-o", surface, check=False)
    with pytest.raises(roadbrdf.InputError) as error:
        roadbrdf.render_albedo(surface, 30, output=surface)
    check_refused_alike("render", rows["output"], result, error.value)


def test_the_command_files_are_refused_by_python(cli, flat, tmp_path):
    surface, grid = flat
    assert cli("render", surface, "--grid", grid, "--format", "tall", "-o", tmp_path / "x.csv",
               check=False).stderr.startswith("roadbrdf: error: --format: ")
    assert cli("render", surface, "--grid", grid, "--albedo", "30", "-o", tmp_path / "x.csv",
               check=False).stderr == "roadbrdf: error: give either --grid GRID.csv or --albedo ZENITHS\n"
    for name, value in (("grid", grid), ("format", "long"), ("output", tmp_path / "x.csv")):
        with pytest.raises(roadbrdf.InputError, match=f"^{name}: does not apply here"):
            roadbrdf.render(surface, 30, 0, 30, 180, **{name: value})


def test_render_with_settings_is_identical(cli, flat, tmp_path):
    """One request from both front ends: the same paths, so bit-identical estimates."""
    surface, grid = flat
    out = tmp_path / "cli.csv"
    cli("render", surface, "--grid", grid, "--samples", "512", "--sampling", "cosine", "--acceptance", "5",
        "--seed", "9", "--max-bounces", "2", "--wavelengths", "500,600", "-o", out)
    d = roadbrdf.read_dataset(out)
    py = roadbrdf.render(surface, 30, 0, 30, 180, samples=512, sampling="cosine", acceptance_deg=5, seed=9,
                         max_bounces=2, wavelengths="500,600")
    np.testing.assert_array_equal(py.brdf, d.brdf)
    np.testing.assert_array_equal(py.sigma, d.sigma)

