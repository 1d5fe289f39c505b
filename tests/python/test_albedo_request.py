"""The albedo request's field table (AlbedoRequest::fields, albedo/albedo_request.cpp) seen from both front
ends, row by row: `roadbrdf albedo --help` shows each row's flag, `roadbrdf.albedo`'s docstring its keyword
and help, and a bad value is refused with the same text by both (the command line naming the flag, Python
the keyword). The rows come from the table itself, so a new field without a bad value here fails."""
import json

import numpy as np
import pytest
from request_table import check_every_row_is_shown, check_refused_alike, fields

import roadbrdf

FIELDS = fields("albedo")

# A bad value per field: (Python keyword value, command-line value). None for a switch: a flag has no
# value on the command line to get wrong, so Python's type check alone is compared with the table.
BAD = {
    "model": ("no-such-model", "no-such-model"),
    "parameters": (["albedo=2"], "albedo=2"),
    "options": (["bogus=1"], "bogus=1"),
    "fit": ("no-such-fit", "no-such-fit"),
    "sun_zenith": (95.0, "95"),
    "sun_azimuth": (float("inf"), "inf"),
    "azimuth_mean": None,
    "diffuse_fraction": ("1.5", "1.5"),
    "atmosphere": ("spectrl2:bogus=1", "spectrl2:bogus=1"),
    "spectrum": ("astm-g173-nothing", "astm-g173-nothing"),
    "wavelengths": ("600:500:50", "600:500:50"),
    "illuminant": ("Z", "Z"),
    "tolerance": (0.0, "0"),
    "uncertainty": None,
    "threads": (-1, "-1"),
}


def _fit(path):
    """A Lambertian fit over 400-700 nm (albedo 0.1 to 0.4), for the rows that need a fit file."""
    wavelengths = list(range(400, 701, 50))
    path.write_text(json.dumps({
        "format": "roadbrdf-fit", "version": 1, "best": "lambert", "fits": [{
            "model": "lambert", "options": {}, "wavelengths": wavelengths,
            "parameters": {"albedo": [0.1 + 0.3 * (w - 400) / 300 for w in wavelengths]},
            "parameter_order": ["albedo"], "fixed": []}]}))
    return path


def test_every_row_has_a_bad_value():
    assert sorted(row["name"] for row in FIELDS) == sorted(BAD)


def test_every_row_is_an_option_and_a_keyword(cli):
    check_every_row_is_shown(cli, "albedo", roadbrdf.albedo)


@pytest.mark.parametrize("row", FIELDS, ids=[row["name"] for row in FIELDS])
def test_a_bad_value_is_refused_alike(cli, tmp_path, row):
    name = row["name"]
    if BAD[name] is None:  # a switch: only True or False from Python
        with pytest.raises(roadbrdf.InputError, match=f"^{name}: expected True or False, got str"):
            roadbrdf.albedo("lambert", {"albedo": 0.3}, **{name: "yes"})
        return
    py_value, cli_value = BAD[name]
    fit = str(_fit(tmp_path / "lambert.fit.json"))
    if name == "model":
        cli_args, source, kwargs = [cli_value], py_value, {}
    elif name in ("parameters", "options"):
        cli_args, source, kwargs = ["lambert", row["long_flag"], cli_value], "lambert", {name: py_value}
    else:
        cli_args, source, kwargs = [fit, row["long_flag"], cli_value], fit, {name: py_value}
    result = cli("albedo", *cli_args, "--quiet", check=False)
    with pytest.raises(roadbrdf.InputError) as error:
        roadbrdf.albedo(source, **kwargs)
    check_refused_alike("albedo", row, result, error.value)


def test_numbers_and_writer_are_the_command_lines(cli, tmp_path):
    """One request, one writer: the same document and table from both front ends."""
    fit = _fit(tmp_path / "lambert.fit.json")
    from_cli = json.loads(cli("albedo", fit, "--sun-zenith", "0:60:30", "--diffuse-fraction", "0.25",
                              "--no-uncertainty", "--json").stdout)
    result = roadbrdf.albedo(fit, sun_zenith="0:60:30", diffuse_fraction=0.25, uncertainty=False)
    assert dict(result) == from_cli
    cli("albedo", fit, "--sun-zenith", "20,50", "-o", tmp_path / "cli.csv")
    roadbrdf.albedo(fit, sun_zenith=[20, 50]).write(tmp_path / "py.csv", format="table")
    assert (tmp_path / "py.csv").read_bytes() == (tmp_path / "cli.csv").read_bytes()


def test_warnings_are_typed_and_issued(cli):
    """A white-sky albedo of 1e-4 is below the 0.005 of any natural material (docs/data.md)."""
    with pytest.warns(roadbrdf.RoadbrdfWarning, match="^implausible: a white-sky albedo of 0.0001"):
        result = roadbrdf.albedo(roadbrdf.Model("lambert"), {"albedo": 1e-4})
    assert [w["kind"] for w in result["warnings"]] == ["implausibly_dark"]
    assert not any("WARNING" in note for note in result["notes"])
    printed = cli("albedo", "lambert", "-p", "albedo=1e-4", "--quiet").stderr
    assert printed == f"roadbrdf: warning: {result['warnings'][0]['message']}\n"


def test_objects_and_names_give_the_same_albedo():
    """A Model object with params and the model name with parameters: one request."""
    by_object = roadbrdf.albedo(roadbrdf.Model("lambert"), {"albedo": 0.3}, sun_zenith=[0, 60])
    by_name = roadbrdf.albedo("lambert", parameters=["albedo=0.3"], sun_zenith=[0, 60])
    assert dict(by_object) == dict(by_name)
    assert by_object.white_sky[0] == pytest.approx(0.3, rel=1e-12)  # Lambert: the albedo itself
    with pytest.raises(roadbrdf.InputError, match="^fit: is given by the model argument"):
        roadbrdf.albedo(roadbrdf.Model("lambert"), {"albedo": 0.3}, fit="lambert")


def test_albedo_result_arrays_follow_the_lambert_closed_form(tmp_path):
    # A Lambertian surface reflects its albedo whatever the sun and sky: black-sky = white-sky = blue-sky
    # = rho(lambda) at every zenith (the quadrature's errors are far below 1e-9 for a constant BRDF).
    fit = _fit(tmp_path / "lambert.fit.json")
    wavelengths = list(range(400, 701, 50))
    albedos = [0.1 + 0.3 * (w - 400) / 300 for w in wavelengths]
    result = roadbrdf.albedo(fit, sun_zenith=[0, 45], diffuse_fraction=0.3)
    assert result.wavelengths.tolist() == wavelengths
    assert result.black_sky.shape == (2, len(wavelengths))
    np.testing.assert_allclose(result.black_sky, [albedos, albedos], rtol=1e-9)
    np.testing.assert_allclose(result.white_sky, albedos, rtol=1e-9)
    np.testing.assert_allclose(result.blue_sky, [albedos, albedos], rtol=1e-9)
    df = result.to_dataframe()
    assert list(df["wavelength_nm"]) == wavelengths
    assert list(df["black_sky_45deg"]) == pytest.approx(albedos, rel=1e-9)
    assert "black_sky_45deg_error" in df and "blue_sky_0deg" in df
    assert repr(result).startswith("roadbrdf.AlbedoResult(\n# albedo of lambert")
