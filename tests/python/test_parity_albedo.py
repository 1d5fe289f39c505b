"""roadbrdf albedo and roadbrdf.albedo: one library request (albedo/report.h), the same errors (the CLI
naming its flag, Python the keyword), the same numbers with every option, and the same writer."""
import json
import math

import numpy as np
import pytest

import roadbrdf
from conftest import assert_same_error

ERRORS = [
    (["--sun-zenith", "95"], dict(sun_zenith=95.0), "--sun-zenith", "sun_zenith"),
    (["--tolerance", "0"], dict(tolerance=0.0), "--tolerance", "tolerance"),
    (["--diffuse-fraction", "0.2", "--atmosphere", "spectrl2"], dict(diffuse_fraction=0.2, atmosphere="spectrl2"),
     "--diffuse-fraction", "diffuse_fraction"),
]


@pytest.mark.parametrize("flags,kwargs,cli_field,py_field", ERRORS, ids=[e[3] for e in ERRORS])
def test_albedo_errors_are_the_same(cli, flags, kwargs, cli_field, py_field):
    r = cli("albedo", "lambert", "-p", "albedo=0.3", *flags, check=False)
    with pytest.raises(roadbrdf.InputError) as e:
        roadbrdf.albedo(roadbrdf.Model("lambert"), {"albedo": 0.3}, **kwargs)
    assert_same_error(r, e.value, cli_field, py_field)


def _spectral_fit(path):
    """A Lambertian fit over 400-700 nm whose albedo rises linearly from 0.1 to 0.4."""
    wavelengths = list(range(400, 701, 50))
    albedos = [0.1 + 0.3 * (w - 400) / 300 for w in wavelengths]
    path.write_text(json.dumps({
        "format": "roadbrdf-fit", "version": 1, "best": "lambert", "fits": [{
            "model": "lambert", "options": {}, "wavelengths": wavelengths,
            "parameters": {"albedo": albedos}, "parameter_order": ["albedo"], "fixed": []}]}))
    return path, wavelengths, albedos


OPTIONS = [
    ([], {}),
    (["--sun-zenith", "0:60:30"], dict(sun_zenith="0:60:30")),
    (["--diffuse-fraction", "0.25"], dict(diffuse_fraction=0.25)),
    (["--atmosphere", "spectrl2:aod=0.2"], dict(atmosphere="spectrl2:aod=0.2")),
    (["--spectrum", "astm-g173-direct"], dict(spectrum="astm-g173-direct")),
    (["--wavelengths", "450:650:100"], dict(wavelengths="450:650:100")),
    (["--illuminant", "D65"], dict(illuminant="D65")),
    (["--tolerance", "1e-7", "--sun-zenith", "10,70"], dict(tolerance=1e-7, sun_zenith=[10, 70])),
]


@pytest.mark.parametrize("flags,kwargs", OPTIONS, ids=[" ".join(o[0]) or "defaults" for o in OPTIONS])
def test_albedo_numbers_are_the_same_with_every_option(cli, tmp_path, flags, kwargs):
    fit, _, _ = _spectral_fit(tmp_path / "lambert.fit.json")
    from_cli = json.loads(cli("albedo", fit, *flags, "--json").stdout)
    result = roadbrdf.albedo(fit, **kwargs)
    assert isinstance(result, roadbrdf.AlbedoResult)
    assert dict(result) == from_cli  # every number and note, exactly


def test_albedo_result_arrays_follow_the_lambert_closed_form(tmp_path):
    # A Lambertian surface reflects its albedo whatever the sun and sky: black-sky = white-sky = blue-sky
    # = rho(lambda) at every zenith (the quadrature's errors are far below 1e-9 for a constant BRDF).
    fit, wavelengths, albedos = _spectral_fit(tmp_path / "lambert.fit.json")
    result = roadbrdf.albedo(fit, sun_zenith=[0, 45], diffuse_fraction=0.3)
    assert result.wavelengths.tolist() == wavelengths
    assert result.black_sky.shape == (2, len(wavelengths))
    np.testing.assert_allclose(result.black_sky, [albedos, albedos], rtol=1e-9)
    np.testing.assert_allclose(result.white_sky, albedos, rtol=1e-9)
    np.testing.assert_allclose(result.blue_sky, [albedos, albedos], rtol=1e-9)
    df = result.to_dataframe()
    assert list(df["wavelength_nm"]) == wavelengths
    np.testing.assert_allclose(df["black_sky_45deg"], albedos, rtol=1e-9)
    np.testing.assert_allclose(df["white_sky"], albedos, rtol=1e-9)
    assert "black_sky_45deg_error" in df and "blue_sky_0deg" in df
    assert repr(result).startswith("roadbrdf.AlbedoResult(\n# albedo of lambert")


def test_albedo_result_is_written_by_the_command_line_writer(cli, tmp_path):
    fit, _, _ = _spectral_fit(tmp_path / "lambert.fit.json")
    cli("albedo", fit, "--sun-zenith", "20,50", "--json", "-o", tmp_path / "cli.json")
    cli("albedo", fit, "--sun-zenith", "20,50", "-o", tmp_path / "cli.csv")
    result = roadbrdf.albedo(fit, sun_zenith=[20, 50])
    result.write(tmp_path / "py.json")
    result.write(tmp_path / "py.csv", format="table")
    assert (tmp_path / "py.json").read_bytes() == (tmp_path / "cli.json").read_bytes()
    assert (tmp_path / "py.csv").read_bytes() == (tmp_path / "cli.csv").read_bytes()
    assert result.summary == (tmp_path / "cli.csv").read_text()
    with pytest.raises(roadbrdf.InputError, match="format must be"):
        result.write(tmp_path / "x", format="xml")
    assert math.isclose(result.black_sky[0][0], 0.1, rel_tol=1e-9)


def test_albedo_without_uncertainty_gives_the_same_values(cli, tmp_path):
    """--no-uncertainty / uncertainty=False: the same values, no uncertainty (Lambert: u(A) = u(albedo))."""
    fit, wavelengths, albedos = _spectral_fit(tmp_path / "lambert.fit.json")
    document = json.loads(fit.read_text())
    document["fits"][0]["stderr"] = {"albedo": [0.01] * len(wavelengths)}
    document["fits"][0]["correlation"] = [[[1.0]]] * len(wavelengths)
    fit.write_text(json.dumps(document))
    full = roadbrdf.albedo(fit, sun_zenith="0:60:30", diffuse_fraction=0.2)
    assert np.allclose(full["uncertainty"]["white_sky"], 0.01, rtol=0, atol=1e-12)
    values = roadbrdf.albedo(fit, sun_zenith="0:60:30", diffuse_fraction=0.2, uncertainty=False)
    assert values["uncertainty"] is None
    for key in ("black_sky", "white_sky", "blue_sky", "broadband"):
        assert values[key] == full[key]
    from_cli = json.loads(cli("albedo", fit, "--sun-zenith", "0:60:30", "--diffuse-fraction", "0.2",
                              "--no-uncertainty", "--json").stdout)
    assert dict(values) == from_cli
