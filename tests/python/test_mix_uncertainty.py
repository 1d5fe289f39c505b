"""Uncertainties of a mixture from its end-members' fits (mixing/mixture_covariance.h) on every front end: the
MIX.json carries the mixture's covariance, and `roadbrdf albedo` / `roadbrdf rtable` on it, roadbrdf.albedo /
roadbrdf.rtable on the file or on the run's spectral model, and `plot rtable` give the same uncertainties.
Reference for the values: the closed form of an areal mixture of Lambertian end-members (white-sky albedo
sum_k a_k rho_k, so u = sqrt(sum_k a_k^2 u_k^2); Q0 = A / pi)."""
import json
import math

import matplotlib.pyplot as plt
import pytest

import roadbrdf
from roadbrdf import plot as rplot

WAVELENGTHS = [450.0, 550.0, 650.0]
END_MEMBERS = {"binder": ([0.05, 0.06, 0.07], [0.004, 0.005, 0.006]),
               "rock": ([0.35, 0.40, 0.45], [0.02, 0.03, 0.025])}


@pytest.fixture
def mixture(tmp_path):
    """Lambertian binder and rock fits with standard errors, their formulation, and its areal and hapke mixes."""
    (tmp_path / "fits").mkdir()
    for name, (albedo, u) in END_MEMBERS.items():
        (tmp_path / "fits" / f"{name}.fit.json").write_text(json.dumps({
            "format": "roadbrdf-fit", "version": 1, "best": "lambert",
            "fits": [{"model": "lambert", "options": {}, "wavelengths": WAVELENGTHS, "parameters": {"albedo": albedo},
                      "stderr": {"albedo": u}, "correlation": [[[1.0]]] * 3}]}))
    formulation = tmp_path / "F.json"
    formulation.write_text(json.dumps({
        "format": "roadbrdf-formulation", "version": 1, "name": "F", "components": [
            {"name": "Binder", "kind": "binder", "mass_percent": 10, "density_g_cm3": 1.0,
             "fit": "fits/binder.fit.json"},
            {"name": "Rock", "kind": "aggregate", "mass_percent": 90, "density_g_cm3": 2.7, "d_min_mm": 2,
             "d_max_mm": 6, "fit": "fits/rock.fit.json"}]}))
    out = tmp_path / "F.mix.json"
    run = roadbrdf.mix(formulation, output=out, uncertainty=True)
    return out, run


def test_the_mix_file_carries_the_covariance_and_albedo_gives_the_closed_form(cli, mixture):
    path, run = mixture
    areal = next(m for m in json.loads(path.read_text())["methods"] if m["method"] == "areal")
    assert areal["stderr"]["weight.binder"] == [0.0] * 3 and "weight.binder" in areal["fixed"]
    a = areal["weights"]["binder"]
    expected = [math.hypot(a * ub, (1 - a) * ur) for ub, ur in zip(END_MEMBERS["binder"][1], END_MEMBERS["rock"][1])]
    from_cli = json.loads(cli("albedo", path, "--fit", "areal", "--sun-zenith", "30", "--json").stdout)["uncertainty"]
    assert from_cli["white_sky"] == pytest.approx(expected, rel=1e-9)
    assert from_cli["black_sky"][0] == pytest.approx(expected, rel=1e-9)
    # Python: on the file, and on the run's model without writing it.
    for model in (roadbrdf.read_fit(path, "areal"), run.method("areal").spectral_model()):
        u = roadbrdf.albedo(model, sun_zenith=30)["uncertainty"]
        assert u["white_sky"] == pytest.approx(from_cli["white_sky"], rel=1e-12)
        assert u["broadband"]["white_sky"]["independent"] == pytest.approx(
            from_cli["broadband"]["white_sky"]["independent"], rel=1e-12)


def test_rtable_of_a_mixture_has_q0_and_class_uncertainties_on_every_front_end(cli, mixture):
    path, run = mixture
    for method in ("areal", "hapke"):
        from_cli = json.loads(cli("rtable", path, "--fit", method, "--wavelength", "550", "--json").stdout)
        u = from_cli["uncertainty"]
        assert u is not None and u["Q0"] > 0 and u["class_probabilities"]
        from_python = roadbrdf.rtable(run.method(method).spectral_model(), wavelength=550)["uncertainty"]
        assert from_python["Q0"] == pytest.approx(u["Q0"], rel=1e-9)
        assert from_python["S1"] == pytest.approx(u["S1"], rel=1e-9, abs=1e-15)
    # Areal Lambert at 550 nm: Q0 = A / pi, so u(Q0) = u(A) / pi.
    areal = json.loads(cli("rtable", path, "--fit", "areal", "--wavelength", "550", "--json").stdout)
    a = run.method("areal").weights["binder"]
    assert areal["uncertainty"]["Q0"] == pytest.approx(
        math.hypot(a * 0.005, (1 - a) * 0.03) / math.pi, rel=1e-9)


def test_plot_rtable_draws_the_uncertainty_of_the_figures(mixture, tmp_path):
    path, _ = mixture
    table = roadbrdf.rtable(roadbrdf.read_fit(path, "hapke"), wavelength=550)
    fig = rplot.rtable(table)
    bars = fig.roadbrdf_data["error_bars"]
    assert bars["S1"] == table["uncertainty"]["S1"] and bars["Q0"] == table["uncertainty"]["Q0"] > 0
    assert [c for c, _ in bars["class_probabilities"]] == [c["class"] for c in table["uncertainty"]["class_probabilities"]]
    diagram = next(a for a in fig.axes if a.get_xlabel().startswith("S1"))
    drawn = [c for c in diagram.containers if getattr(c, "has_yerr", False) and c.has_xerr]
    assert len(drawn) == 1
    # The legend gives each figure ± its uncertainty to two significant digits, the value to the same place.
    from roadbrdf.plot_rtable import _pm
    legend = diagram.get_legend().get_texts()[0].get_text()
    assert f"S1 = {_pm(table['S1'], bars['S1'], 2)}" in legend
    assert _pm(1.16287, 0.00294, 2) == "1.1629 ± 0.0029" and _pm(0.272508, 0.0451, 2) == "0.273 ± 0.045"
    assert _pm(0.0732614, 8.59e-5, 3) == "0.073261 ± 0.000086" and _pm(0.5, 0.0, 3) == "0.500 ± 0.000"
    # The r-table of a model given by its parameters has none, and no bars are drawn.
    fig = rplot.rtable(roadbrdf.Model("lambert"), {"albedo": 0.3})
    assert fig.roadbrdf_data["error_bars"] is None
    assert not next(a for a in fig.axes if a.get_xlabel().startswith("S1")).containers
    plt.close("all")
