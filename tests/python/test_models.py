import math

import numpy as np
import pytest

import roadbrdf


def test_model_metadata_matches_cli(cli):
    import json
    from_cli = json.loads(cli("models", "--json").stdout)
    from_python = roadbrdf.models()
    assert [m["name"] for m in from_cli] == [m["name"] for m in from_python]
    for a, b in zip(from_cli, from_python):
        assert [p["name"] for p in a["parameters"]] == [p["name"] for p in b["parameters"]]
        assert [(p["lower"], p["upper"], p["default"]) for p in a["parameters"]] == \
               [(p["lower"], p["upper"], p["default"]) for p in b["parameters"]]


def test_lambert_closed_form_and_broadcasting():
    m = roadbrdf.Model("lambert")
    theta_r = np.linspace(0, 89, 7)
    albedo = np.array([[0.1], [0.5]])
    f = m.evaluate(30, 0, theta_r, 180, albedo=albedo)
    assert f.shape == (2, 7)
    np.testing.assert_allclose(f, np.broadcast_to(albedo / math.pi, (2, 7)), rtol=0, atol=1e-15)
    assert isinstance(m(0, 0, 0, 0), float)


@pytest.mark.parametrize("name", roadbrdf.model_names())
def test_python_equals_cli(cli, name):
    m = roadbrdf.Model(name)
    for ti, pi, tr, pr in [(0, 0, 0, 0), (30, 0, 45, 180), (60, 10, 20, 100), (80, 0, 80, 0)]:
        expected = float(cli("eval", name, "--theta-i", ti, "--phi-i", pi, "--theta-r", tr, "--phi-r", pr).stdout)
        assert m.evaluate(ti, pi, tr, pr) == pytest.approx(expected, rel=1e-9, abs=1e-12)


def test_composite_parameters_by_dict():
    m = roadbrdf.Model("lambert+lambert")
    f = m.evaluate(10, 0, 10, 180, params={"lambert.albedo": 0.2, "lambert#2.albedo": 0.4,
                                           "lambert#2.weight": 0.5})
    assert f == pytest.approx((0.2 + 0.5 * 0.4) / math.pi, abs=1e-15)


def test_errors_raise_with_cli_messages(cli):
    with pytest.raises(roadbrdf.InputError, match="unknown model 'nope'"):
        roadbrdf.Model("nope")
    with pytest.raises(ValueError, match="outside its bounds"):
        roadbrdf.Model("lambert").evaluate(0, 0, 0, 0, albedo=2.0)
    with pytest.raises(roadbrdf.InputError, match="no parameter 'rho'"):
        roadbrdf.Model("lambert").evaluate(0, 0, 0, 0, rho=0.5)
    with pytest.raises(roadbrdf.InputError, match="outside the zenith range"):
        roadbrdf.Model("lambert").evaluate(95, 0, 0, 0)
    r = cli("eval", "nope", "--theta-i", 0, "--phi-i", 0, "--theta-r", 0, "--phi-r", 0, check=False)
    assert "unknown model 'nope'" in r.stderr


def test_road_angle_conversion_matches_core():
    ti, pi, tr, pr = roadbrdf.road_to_zenith_azimuth(60, 1, 0, 0)
    assert (float(ti), float(tr)) == (60.0, 89.0)
    assert float(pr) - float(pi) == pytest.approx(180.0)
    assert roadbrdf._roadbrdf.road_to_zenith_azimuth(35, 12, 45, 20) == pytest.approx(
        tuple(float(x) for x in roadbrdf.road_to_zenith_azimuth(35, 12, 45, 20)))


def test_cook_torrance_alias_fits_reloads_and_errors_alike(cli, root, tmp_path):
    """`cook-torrance` (torrance-sparrow with Cook & Torrance's 1982 choices) works wherever a model
    name does: the fit file carries the alias, `albedo` reloads it, Python gives the same numbers and
    changing a fixed option is the same error from both front ends."""
    aliases = {a["name"]: a for a in roadbrdf.model_aliases()}
    assert aliases["cook-torrance"]["model"] == "torrance-sparrow"
    assert aliases["cook-torrance"]["options"] == {"profile": "v-cavity", "distribution": "beckmann",
                                                   "fresnel": "exact-dielectric"}
    data = root / "data/examples/single/lazard.csv"
    out = tmp_path / "ct.fit.json"
    cli("fit", data, "--model", "lambert+cook-torrance", "--wavelengths", "610", "-o", out)
    import json
    content = json.loads(out.read_text())
    assert content["fits"][0]["model"] == "lambert+cook-torrance"
    result = roadbrdf.fit(data, "lambert+cook-torrance", wavelengths="610")
    fit = result.model_fit("lambert+cook-torrance")
    for name, values in content["fits"][0]["parameters"].items():
        assert fit.parameter(name)[0] == pytest.approx(values[0], rel=1e-12), name
    # The alias equals torrance-sparrow with its options written out.
    ct = roadbrdf.Model("cook-torrance")
    ts = roadbrdf.Model("torrance-sparrow", options=aliases["cook-torrance"]["options"])
    p = {"ks": 0.3, "roughness": 0.25, "ior": 1.6}
    assert ct.evaluate(30, 0, 50, 170, params=p) == ts.evaluate(30, 0, 50, 170, params=p)
    albedo = cli("albedo", out, "--wavelengths", "610")
    assert albedo.returncode == 0
    bad = cli("fit", data, "--model", "cook-torrance", "--option", "distribution=ggx", "-o", tmp_path / "x.json",
              check=False)
    assert bad.returncode != 0
    with pytest.raises(roadbrdf.InputError) as error:
        roadbrdf.fit(data, "cook-torrance", options={"distribution": "ggx"})
    assert "use model 'torrance-sparrow'" in str(error.value)
    # The library names the field (options.distribution), the CLI its flag (--option distribution).
    assert str(error.value).startswith("options.distribution: model 'cook-torrance' fixes")
    assert str(error.value).removeprefix("options.") in bad.stderr.replace("--option ", "")


def test_hapke_roughness_and_legendre_terms_fit_alike_from_cli_and_python(cli, tmp_path):
    """Hapke's options legendre_terms and roughness (Hapke 1984, parameter theta_bar [rad]): a synthetic
    noise-free dataset from the rough model with a 3-term Legendre phase function is fitted back, from a
    start away from theta_bar = 0 (where its derivative is 0), to the values that made it, by Python and
    by the command line alike; theta_bar = 0 is the smooth model."""
    import json
    options = {"phase": "legendre", "legendre_terms": "3", "roughness": "hapke1984"}
    rough = roadbrdf.Model("hapke", options=options)
    smooth = roadbrdf.Model("hapke", options={"phase": "legendre", "legendre_terms": "3"})
    truth = {"w": 0.6, "b0": 0.3, "h": 0.1, "legendre_b": 0.2, "legendre_c": 0.1, "legendre_a3": -0.1,
             "theta_bar": math.radians(20)}
    angles = np.array([(ti, 0.0, tr, pr) for ti in (10, 30, 50, 65) for tr in (5, 20, 35, 50, 65, 75)
                       for pr in (0, 45, 90, 135, 180)], dtype=float)
    columns = (angles[:, 0], angles[:, 1], angles[:, 2], angles[:, 3])
    flat = {name: value for name, value in truth.items() if name != "theta_bar"}
    assert np.array_equal(rough.evaluate(*columns, params=dict(truth, theta_bar=0.0)),
                          smooth.evaluate(*columns, params=flat))
    brdf = rough.evaluate(*columns, params=truth)
    data = tmp_path / "rough.csv"
    roadbrdf.Dataset(angles, [550.0], brdf.reshape(-1, 1)).write(data)
    fit = roadbrdf.fit(data, "hapke", options=options, start={"theta_bar": 0.2}).model_fit("hapke")
    for name, value in truth.items():
        assert fit.parameter(name)[0] == pytest.approx(value, rel=1e-8, abs=1e-10), name
    out = tmp_path / "rough.fit.json"
    cli("fit", data, "--model", "hapke", "--option", "phase=legendre", "--option", "legendre_terms=3",
        "--option", "roughness=hapke1984", "--start", "theta_bar=0.2", "-o", out)
    content = json.loads(out.read_text())
    for name, values in content["fits"][0]["parameters"].items():
        assert fit.parameter(name)[0] == pytest.approx(values[0], rel=1e-12, abs=1e-15), name
    with pytest.raises(roadbrdf.InputError, match="legendre_terms applies only to phase=legendre"):
        roadbrdf.Model("hapke", options={"legendre_terms": "4"})
