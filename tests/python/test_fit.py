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


def test_spectral_model_from_a_fit_dict_is_read_as_its_file(root, tmp_path):
    """A fit file's content as a dict goes to the library's fit file reader directly: the same model,
    and the same errors (JSON key paths included), the dict named fit_result instead of the file."""
    path = tmp_path / "l.fit.json"
    roadbrdf.fit(root / "data/examples/single/lazard.csv", "lambert", wavelengths="510:710:100", output=path)
    content = json.loads(path.read_text())
    from_dict, from_file = roadbrdf.spectral_model_from_fit(content), roadbrdf.read_fit(path)
    np.testing.assert_array_equal(from_dict.wavelengths, from_file.wavelengths)
    assert from_dict.evaluate(30, 0, 40, 180, 610.0) == from_file.evaluate(30, 0, 40, 180, 610.0)
    content["fits"][0]["wavelengths"] = [610.0, 510.0]
    bad = tmp_path / "bad.fit.json"
    bad.write_text(json.dumps(content))
    with pytest.raises(roadbrdf.InputError) as from_file_error:
        roadbrdf.read_fit(bad)
    with pytest.raises(roadbrdf.InputError) as from_dict_error:
        roadbrdf.spectral_model_from_fit(content)
    assert "wavelengths" in str(from_dict_error.value)
    assert str(from_dict_error.value) == str(from_file_error.value).replace(str(bad), "fit_result")
    with pytest.raises(roadbrdf.InputError, match="fit"):
        roadbrdf.spectral_model_from_fit(content, "no-such-model")
