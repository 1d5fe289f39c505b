import json

import numpy as np
import pytest

import roadbrdf


def test_fit_through_python_equals_cli(cli, root, tmp_path):
    data = root / "data/examples/single/lazard.csv"
    cli_out = tmp_path / "cli.fit.json"
    cli("fit", data, "--model", "oren-nayar", "--wavelengths", "510:710:40", "-o", cli_out)
    py_out = tmp_path / "py.fit.json"
    result = roadbrdf.fit(data, "oren-nayar", wavelengths="510:710:40", output=py_out)
    from_cli = json.loads(cli_out.read_text())
    a, b = from_cli["fits"][0], result["fits"][0]
    assert a["wavelengths"] == b["wavelengths"]
    for name in ("albedo", "sigma"):
        np.testing.assert_allclose(a["parameters"][name], b["parameters"][name], rtol=1e-12)
    np.testing.assert_allclose(a["rmse"], b["rmse"], rtol=1e-12)
    # The fit round-trips through the JSON file and evaluates as a spectral model.
    m = roadbrdf.read_fit(py_out)
    p = m.parameters_at(510.0)
    assert p["albedo"] == pytest.approx(b["parameters"]["albedo"][0], rel=1e-12)
    d = roadbrdf.read_dataset(data)
    direct = roadbrdf.Model("oren-nayar").evaluate(30, 0, 40, 180, albedo=p["albedo"], sigma=p["sigma"])
    assert m.evaluate(30, 0, 40, 180, 510.0) == pytest.approx(direct, rel=1e-12)
    assert roadbrdf.spectral_model_from_fit(result).evaluate(30, 0, 40, 180, 510.0) == pytest.approx(direct, rel=1e-12)


def test_fit_recovers_lambert_albedo_closed_form():
    # Least squares of a constant: albedo = pi * mean(y) (no sigma weights).
    rng = np.random.default_rng(3)
    angles = np.column_stack([rng.uniform(0, 80, 50), np.zeros(50), rng.uniform(0, 80, 50), rng.uniform(0, 360, 50)])
    y = 0.3 / np.pi + rng.normal(0, 0.002, (50, 1))
    d = roadbrdf.Dataset(angles, [550.0], y)
    result = roadbrdf.fit(d, "lambert")
    assert result["fits"][0]["parameters"]["albedo"][0] == pytest.approx(np.pi * y.mean(), rel=1e-9)


def test_fit_errors_are_input_errors():
    d = roadbrdf.Dataset([[0, 0, 0, 0]], [550.0], [[0.1]])
    with pytest.raises(roadbrdf.InputError):
        roadbrdf.fit(d, "no-such-model")
