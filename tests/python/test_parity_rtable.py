"""roadbrdf rtable and roadbrdf.rtable: one library request (photometry/rtable_request.h), the same
errors (the CLI naming its flag, Python the keyword), the same numbers and the same warnings."""
import json
import math

import pytest

import roadbrdf
from conftest import assert_same_error

ERRORS = [
    (["--alpha", "0"], dict(alpha=0.0), "--alpha", "alpha"),
    (["--wavelength", "550", "--band", "500:600"], dict(wavelength=550.0, band=(500.0, 600.0)), "--band", "band"),
    (["--band", "600:500"], dict(band=(600.0, 500.0)), "--band", "band"),
    (["--wavelength", "550", "--illuminant", "D65"], dict(wavelength=550.0, illuminant="D65"), "--illuminant",
     "illuminant"),
    (["--q0-region", "all"], dict(q0_region="all"), "--q0-region", "q0_region"),
    (["--class-system", "Q"], dict(class_system="Q"), "--class-system", "class_system"),
]


@pytest.mark.parametrize("flags,kwargs,cli_field,py_field", ERRORS, ids=[e[3] for e in ERRORS])
def test_rtable_errors_are_the_same(cli, flags, kwargs, cli_field, py_field):
    r = cli("rtable", "lambert", "-p", "albedo=0.3", *flags, check=False)
    with pytest.raises(roadbrdf.InputError) as e:
        roadbrdf.rtable(roadbrdf.Model("lambert"), {"albedo": 0.3}, **kwargs)
    assert_same_error(r, e.value, cli_field, py_field)


def test_rtable_numbers_and_warnings_are_the_same(cli):
    # Lambertian: Q0 = rho/pi, S1 = cos^3(atan 2) = 5^-1.5 (class N1 in the N system).
    r = cli("rtable", "lambert", "-p", "albedo=0.3", "--wavelength", "550", "--class-system", "N", "--json")
    j = json.loads(r.stdout)
    with pytest.warns(UserWarning, match="do not depend on wavelength"):
        t = roadbrdf.rtable(roadbrdf.Model("lambert"), {"albedo": 0.3}, wavelength=550.0, class_system="N")
    assert j["Q0"] == t["Q0"] == pytest.approx(0.3 / math.pi, rel=1e-12)
    assert j["S1"] == t["S1"] == pytest.approx(5 ** -1.5, rel=1e-12)
    assert j["class"] == t["class"] == "N1"
    assert j["warnings"] == t["warnings"]
    assert "roadbrdf: warning: " + t["warnings"][0] in r.stderr


def _fit_file(path, model, parameters, stderr, correlation):
    path.write_text(json.dumps({
        "format": "roadbrdf-fit", "version": 1, "best": model, "fits": [{
            "model": model, "options": {}, "wavelengths": [550],
            "parameters": {k: [v] for k, v in parameters.items()},
            "stderr": {k: [v] for k, v in stderr.items()},
            "parameter_order": list(parameters), "fixed": [], "correlation": [correlation]}]}))
    return path


def test_rtable_uncertainty_is_the_same_and_follows_the_lambert_closed_form(cli, tmp_path):
    # Lambertian fit, albedo 0.3 +- 0.02: Q0 = Qd = rho/pi are linear in rho, so u(Q0) = u(Qd) = 0.02/pi;
    # S1 and S2 do not depend on rho (u = 0) and the class is certain.
    fit = _fit_file(tmp_path / "lambert.fit.json", "lambert", {"albedo": 0.3}, {"albedo": 0.02}, [[1]])
    j = json.loads(cli("rtable", str(fit), "--json").stdout)
    t = roadbrdf.rtable(fit)
    assert j["uncertainty"] == t["uncertainty"]
    u = t["uncertainty"]
    assert u["Q0"] == pytest.approx(0.02 / math.pi, rel=1e-9)
    assert u["Qd"] == pytest.approx(0.02 / math.pi, rel=1e-9)
    assert u["S1"] == pytest.approx(0.0, abs=1e-12)
    assert u["S2"] == pytest.approx(0.0, abs=1e-12)
    assert u["class_probabilities"] == [{"class": t["class"], "probability": 1.0}]
    assert u["correlated"]["Q0"] == pytest.approx(u["Q0"], rel=1e-12)  # one wavelength: the same
    # Rough diffuse with a correlated roughness: S1 moves too; the text names the uncertainties.
    fit = _fit_file(tmp_path / "on.fit.json", "oren-nayar", {"albedo": 0.4, "sigma": 0.3},
                    {"albedo": 0.01, "sigma": 0.05}, [[1, 0.6], [0.6, 1]])
    t = roadbrdf.rtable(fit, class_system="N")
    assert t["uncertainty"] == json.loads(cli("rtable", str(fit), "--class-system", "N", "--json").stdout)["uncertainty"]
    assert t["uncertainty"]["S1"] > 0
    assert sum(c["probability"] for c in t["uncertainty"]["class_probabilities"]) <= 1.0 + 1e-12
    assert t["uncertainty"]["class_probabilities"][0]["class"].startswith("N")
    assert f"u(S1) = {t['uncertainty']['S1']:.3g}" in cli("rtable", str(fit), "-o", str(tmp_path / "t.csv")).stdout
    # A model given by its parameters has no covariance.
    assert roadbrdf.rtable(roadbrdf.Model("lambert"), {"albedo": 0.3})["uncertainty"] is None
