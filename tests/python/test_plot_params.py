"""`roadbrdf plot params` / roadbrdf.plot_params.params: the data behind the figure are the fit file's
parameters and standard errors, against wavelength or against the group column of a grouped fit."""
import json

import matplotlib.pyplot as plt
import numpy as np
import pytest

from roadbrdf.plot_params import params

DATA = "data/examples/single/lazard.csv"


@pytest.fixture
def grouped(cli, root, tmp_path):
    out = tmp_path / "grouped.fit.json"
    cli("fit", root / DATA, "--model", "oren-nayar", "--group-by", "theta_i", "--where", "theta_i>0",
        "--wavelengths", "510:710:100", "-o", out)
    return out


def _fit(content, theta_i):
    return next(f for f in content["fits"] if f["group"]["theta_i"] == theta_i)


def test_against_the_group_column_at_one_wavelength(grouped):
    content = json.loads(grouped.read_text())
    fig = params(grouped, against="theta_i", wavelength=600)  # 600 is between 510 and 710: 610 is nearest
    assert fig.roadbrdf_data["wavelength_nm"] == 610
    x, y, e = fig.roadbrdf_data["albedo"]["oren-nayar"]
    assert list(x) == [20, 40, 60, 80]
    assert list(y) == [_fit(content, t)["parameters"]["albedo"][1] for t in x]
    assert list(e) == [_fit(content, t)["stderr"]["albedo"][1] for t in x]
    assert [a.get_ylabel() for a in fig.axes] == ["albedo [1]", "sigma [rad]"]
    plt.close(fig)


def test_against_wavelength_one_line_per_group_into_given_axes(grouped):
    content = json.loads(grouped.read_text())
    fig, ax = plt.subplots()
    out = params(grouped, parameters=["sigma"], ax=ax)
    assert out is fig
    x, y, _ = out.roadbrdf_data["sigma"]["oren-nayar, theta_i=40"]
    assert list(x) == [510, 610, 710]
    assert list(y) == _fit(content, 40)["parameters"]["sigma"]
    assert len(out.roadbrdf_data["sigma"]) == 4
    plt.close(fig)


def test_command_and_errors(cli, grouped, tmp_path):
    png = tmp_path / "p.png"
    cli("plot", "params", grouped, "--against", "theta_i", "-o", png)
    assert png.stat().st_size > 1000
    r = cli("plot", "params", grouped, "--parameter", "sigm", "-o", png, check=False)
    assert r.returncode == 2 and "no parameter 'sigm'" in r.stderr and "did you mean 'sigma'" in r.stderr, r.stderr
    r = cli("plot", "params", grouped, "--against", "phi_i", "-o", png, check=False)
    assert r.returncode == 2 and "'phi_i' is not one of wavelength, theta_i" in r.stderr, r.stderr


def test_a_parameter_fixed_in_every_fit_that_has_it_gets_no_panel(root, tmp_path):
    """sigma held at 0.3 in the Oren-Nayar fit of a file that also holds a Lambertian fit (which has no sigma) is
    a constant, not a result: no panel, as in a file of that fit alone."""
    import roadbrdf
    path = tmp_path / "two.fit.json"
    roadbrdf.fit(root / DATA, ["oren-nayar", "lambert"], fixed={"sigma": 0.3}, wavelengths="510,610", output=path)
    fig = params(path)
    assert [a.get_ylabel() for a in fig.axes] == ["albedo [1]"]
    assert set(fig.roadbrdf_data["albedo"]) == {"oren-nayar", "lambert"}
    plt.close(fig)
