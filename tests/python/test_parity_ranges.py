"""One grammar for lists of numbers and one vocabulary, on the command line and in Python: the same
values and the same errors (the field named as each front end names it: --sun-zenith / sun_zenith)."""
import json

import numpy as np
import pytest

import roadbrdf


def _detail(message, field):
    """The error message without the leading field name."""
    prefix = f"{field}: "
    assert message.startswith(prefix) or f"error: {prefix}" in message, message
    return message.split(prefix, 1)[1].strip()


def _cli_error(cli, *args):
    r = cli(*args, check=False)
    assert r.returncode == 2, r.stderr
    assert r.stderr.startswith("roadbrdf: error: "), r.stderr
    return r.stderr[len("roadbrdf: error: "):].strip()


def test_parse_range_values():
    assert roadbrdf._roadbrdf.parse_range("0:60:30") == [0.0, 30.0, 60.0]
    assert roadbrdf._roadbrdf.parse_range("400:420:10,500") == [400.0, 410.0, 420.0, 500.0]
    assert roadbrdf._roadbrdf.values(30, "x") == [30.0]
    assert roadbrdf._roadbrdf.values(np.array([1.0, 2.0]), "x") == [1.0, 2.0]
    assert roadbrdf._roadbrdf.values(None, "x") == []


@pytest.mark.parametrize("text", ["0:50:30", "0:1e30:1", "0:10:0", "10:0:5", "0,0", "a:b:c", "30,,60"])
def test_albedo_sun_zenith_errors_are_the_same(cli, text):
    cli_message = _cli_error(cli, "albedo", "lambert", "-p", "albedo=0.3", "--sun-zenith", text, "--json")
    with pytest.raises(roadbrdf.InputError) as e:
        roadbrdf.albedo(roadbrdf.Model("lambert"), {"albedo": 0.3}, sun_zenith=text)
    assert _detail(cli_message, "--sun-zenith") == _detail(str(e.value), "sun_zenith")


def test_albedo_sun_zenith_range_includes_both_ends(cli):
    out = json.loads(cli("albedo", "lambert", "-p", "albedo=0.3", "--sun-zenith", "0:60:30", "--json").stdout)
    assert out["sun_zenith_deg"] == [0, 30, 60]
    py = roadbrdf.albedo(roadbrdf.Model("lambert"), {"albedo": 0.3}, sun_zenith="0:60:30")
    assert py["sun_zenith_deg"] == out["sun_zenith_deg"]
    assert py["black_sky"] == out["black_sky"]
    # Lambert: black-sky albedo = albedo at every sun zenith angle (closed form).
    np.testing.assert_allclose(np.asarray(out["black_sky"]).ravel(), 0.3, atol=1e-5)


def test_simulate_takes_a_wavelength_list(cli, root, tmp_path):
    out = tmp_path / "sim.csv"
    cli("simulate", "lambert", "-p", "albedo=0.25", "--grid", root / "data/examples/grid/cerema-like-grid.csv",
        "--wavelengths", "400,500:600:100", "-o", out)
    d = roadbrdf.read_dataset(out)
    assert list(d.wavelengths) == [400.0, 500.0, 600.0]
    np.testing.assert_allclose(d.brdf, 0.25 / np.pi, rtol=1e-12)  # Lambert: albedo / pi
    message = _cli_error(cli, "simulate", "lambert", "--grid", root / "data/examples/grid/cerema-like-grid.csv",
                         "--wavelengths", "500,400", "-o", tmp_path / "x.csv")
    assert message.startswith("--wavelengths: values must increase"), message


def test_fit_member_is_chosen_with_fit_everywhere(cli, root, tmp_path):
    fit = tmp_path / "two.fit.json"
    cli("fit", root / "data/examples/single/lazard.csv", "--model", "lambert", "--model", "oren-nayar",
        "--wavelengths", "510:710:100", "-o", fit)
    for command in (["albedo", fit, "--json"], ["rtable", fit, "--wavelength", "610", "--json"]):
        out = cli(*command, "--fit", "lambert").stdout
        assert out
        message = _cli_error(cli, *command, "--fit-model", "lambert")
        assert message.startswith("--fit-model: renamed: use --fit NAME"), message
    message = _cli_error(cli, "albedo", "lambert", "--fit", "lambert")
    assert "--fit: selects a fit of a fit file" in message
    grid = root / "data/examples/grid/cerema-like-grid.csv"
    cli("simulate", fit, "--fit", "oren-nayar", "--grid", grid, "-o", tmp_path / "s.csv")
    message = _cli_error(cli, "simulate", fit, "--fit", "no-such", "--grid", grid, "-o", tmp_path / "s.csv")
    assert "no-such" in message


def test_mistyped_command_or_option_names_the_nearest(cli):
    assert _cli_error(cli, "simulte").startswith("unknown command 'simulte' (did you mean 'simulate'?)")
    assert _cli_error(cli, "fti").startswith("unknown command 'fti' (did you mean 'fit'?)")
    message = _cli_error(cli, "albedo", "lambert", "--sun-zenit", "30")
    assert message.startswith("unknown option '--sun-zenit' of 'roadbrdf albedo' (did you mean '--sun-zenith'?)")
    message = _cli_error(cli, "albedo", "lambert", "--sun-zenit=30")
    assert "did you mean '--sun-zenith'?" in message
    assert _cli_error(cli).startswith("a command is required")
    # Negative numbers are values, not options.
    assert cli("eval", "lambert", "--theta-i", "30", "--phi-i", "-20", "--theta-r", "10", "--phi-r", "160").stdout
    message = _cli_error(cli, "plot", "hemisphre", "lambert", "-o", "x.png")
    assert "unknown kind of figure 'hemisphre'" in message and "did you mean 'hemisphere'?" in message
    message = _cli_error(cli, "plot", "hemisphere", "lambert", "--thta-i", "30", "-o", "x.png")
    assert "did you mean '--theta-i'?" in message, message


@pytest.mark.parametrize("cli_args, py_kwargs, flag, field", [
    (["--sun-zenith", "95"], {"sun_zenith": 95}, "--sun-zenith", "sun_zenith"),
    (["--tolerance", "0"], {"tolerance": 0.0}, "--tolerance", "tolerance"),
    (["--diffuse-fraction", "1.5"], {"diffuse_fraction": 1.5}, "--diffuse-fraction", "diffuse_fraction"),
    (["--diffuse-fraction", "0.2", "--atmosphere", "spectrl2"], {"diffuse_fraction": 0.2, "atmosphere": "spectrl2"},
     "--diffuse-fraction", "diffuse_fraction"),
])
def test_albedo_request_errors_are_the_same(cli, cli_args, py_kwargs, flag, field):
    """AlbedoRequest::validate names the field once; each front end names it its own way."""
    cli_message = _cli_error(cli, "albedo", "lambert", "-p", "albedo=0.3", *cli_args, "--json")
    with pytest.raises(roadbrdf.InputError) as e:
        roadbrdf.albedo(roadbrdf.Model("lambert"), {"albedo": 0.3}, **py_kwargs)
    assert _detail(cli_message, flag) == _detail(str(e.value), field)
