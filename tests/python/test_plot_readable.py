"""What an eye checks on each kind of figure, checked on the drawn figure: tick labels present on every
axis (a logarithmic axis inside one decade included), legend and title text that says only what is true
(no "result 1", no "+-1 sigma" without sigma), an axis range that contains the data with margins
proportional to them (a 1 % change is not drawn as a cliff), no panel for a constant (fixed) parameter,
standard-error bands inside the parameter's physical bounds, and the r-table's class diagram without a
class probability when the table is all extrapolation, the measured points on a Lambert fit's hemisphere.
Reference values are closed forms (Lambert: BRDF = rho / pi, every albedo = rho, S1 = 5^-1.5) and the
numbers written into the small files here."""
import json
import math

import matplotlib.pyplot as plt
import numpy as np
import pytest

import roadbrdf
from roadbrdf import plot as rplot
from roadbrdf import plot_params

WAVELENGTHS = [500.0, 590.0, 700.0]


@pytest.fixture(autouse=True)
def close_figures():
    yield
    plt.close("all")


def _labels(axis_obj):
    """The non-empty major tick labels of a drawn axis, inside its view range."""
    low, high = sorted(axis_obj.get_view_interval())
    return [t.get_text() for t, v in zip(axis_obj.get_ticklabels(), axis_obj.get_ticklocs())
            if t.get_text().strip() and low <= v <= high]


def _narrow_dataset(tmp_path):
    """Lambert-like data whose BRDF spans 0.10-0.14 sr^-1, inside one decade; no sigma columns."""
    rows = []
    for ti in (0.0, 30.0):
        for tr in (10.0, 30.0, 50.0):
            for pr in (0.0, 180.0):
                rows.append((ti, 0.0, tr, pr))
    angles = np.array(rows)
    brdf = 0.10 + 0.04 * np.arange(len(rows))[:, None] / (len(rows) - 1) + np.zeros((1, len(WAVELENGTHS)))
    path = tmp_path / "narrow.csv"
    roadbrdf.write_dataset(roadbrdf.Dataset(angles, WAVELENGTHS, brdf, metadata={"sample": "narrow"}), path)
    return path


def _lambert_fit(path, rho):
    path.write_text(json.dumps({"format": "roadbrdf-fit", "version": 1, "best": "lambert",
                                "fits": [{"model": "lambert", "options": {}, "wavelengths": WAVELENGTHS,
                                          "parameters": {"albedo": list(rho)}}]}))
    return path


def test_fit_log_axes_inside_one_decade_have_several_tick_labels(tmp_path):
    data = _narrow_dataset(tmp_path)
    fit = _lambert_fit(tmp_path / "l.fit.json", [0.12 * math.pi] * 3)  # BRDF 0.12 sr^-1
    fig = rplot.fit_quality(data, fit, wavelength=590)
    fig.canvas.draw()
    axis = fig.axes[0]
    for which in (axis.xaxis, axis.yaxis):
        labels = _labels(which)
        assert len(labels) >= 2, labels
        assert all(float(t.replace("−", "-")) > 0 for t in labels)  # plain numbers, not "10^-1" alone
    low, high = axis.get_xlim()
    assert low <= 0.10 and high >= 0.14  # the data inside


def test_spectral_title_promises_sigma_bands_only_when_the_data_have_sigma(tmp_path):
    data = _narrow_dataset(tmp_path)
    fig = rplot.spectral([data], geometry=(30, 0, 30, 180))
    assert "sigma" not in fig.axes[0].get_title()
    assert not fig.axes[0].collections  # no band drawn
    fig.canvas.draw()
    assert len(_labels(fig.axes[0].xaxis)) >= 2 and len(_labels(fig.axes[0].yaxis)) >= 2


def test_albedo_axis_keeps_a_small_change_small_and_the_legend_names_no_result_number(tmp_path):
    # A Lambertian surface: every albedo equals rho, here 0.371-0.378 across the bands, as in the sample report.
    fit = _lambert_fit(tmp_path / "l.fit.json", [0.371, 0.375, 0.378])
    result = roadbrdf.albedo(fit, sun_zenith="0:60:20")
    fig = rplot.albedo(result)
    fig.canvas.draw()
    axis = fig.axes[0]
    c, = fig.roadbrdf_data["zenith_panel"].values()
    values = np.r_[c["black_sky"], c["white_sky"]]
    low, high = axis.get_ylim()
    assert low <= values.min() and high >= values.max()
    # Margins proportional to the data: at least 5 % of the largest value each side.
    assert values.min() - low >= 0.05 * values.max() - 1e-12
    assert high - values.max() >= 0.05 * values.max() - 1e-12
    legend = [t.get_text() for t in axis.get_legend().get_texts()]
    assert legend and not any("result" in t for t in legend), legend
    assert len(_labels(axis.yaxis)) >= 2
    # Several results are still told apart.
    two = rplot.albedo([result, result])
    assert [t.get_text() for t in two.axes[0].get_legend().get_texts() if "result 2" in t.get_text()]


def _fit_with_a_fixed_parameter(root, tmp_path):
    """An Oren-Nayar fit of an example file with sigma fixed, whose albedo is then rewritten here: a standard
    error far beyond [0, 1] at one band, and on its upper bound at another."""
    path = tmp_path / "on.fit.json"
    roadbrdf.fit(root / "data/examples/single/lazard.csv", ["oren-nayar"], fixed={"sigma": 0.3},
                 wavelengths="510,590,710", output=path)
    content = json.loads(path.read_text())
    f = content["fits"][0]
    assert f["fixed"] == ["sigma"]
    f["parameters"]["albedo"] = [0.4, 0.95, 1.0]
    f["stderr"]["albedo"] = [0.01, 0.5, 53.0]
    f["at_bounds"] = [[], [], ["albedo=upper"]]  # as the fitter writes them
    path.write_text(json.dumps(content))
    return path


def test_params_no_panel_for_a_fixed_parameter_and_bands_inside_the_bounds(root, tmp_path):
    fit = _fit_with_a_fixed_parameter(root, tmp_path)
    # A standard error at a bound is not a standard error: none is given (b0 = 1 +- 53 on [0, 1]).
    table = roadbrdf.params(fit)
    assert table["albedo_stderr"].iloc[0] == 0.01 and table["albedo_stderr"].iloc[1] == 0.5
    assert np.isnan(table["albedo_stderr"].iloc[2])
    fig = plot_params.params(fit)
    assert [a.get_ylabel() for a in fig.axes] == ["albedo [1]"]  # sigma is fixed: no panel
    band = fig.axes[0].collections[0]
    y = np.concatenate([p.vertices[:, 1] for p in band.get_paths()])
    assert y.min() >= 0.0 - 1e-12 and y.max() <= 1.0 + 1e-12  # albedo's physical range [0, 1]
    assert fig.roadbrdf_data["bounds"]["albedo"] == (0.0, 1.0)
    fig.canvas.draw()
    assert len(_labels(fig.axes[0].yaxis)) >= 2
    # Asked for by name, the fixed parameter still gets its panel.
    assert len(plot_params.params(fit, parameters=["albedo", "sigma"]).axes) == 2


def test_rtable_of_an_extrapolated_table_has_no_class_probability():
    table = roadbrdf.rtable(roadbrdf.Model("lambert"), {"albedo": 0.3})
    table = dict(table, extrapolated=True,
                 uncertainty={"Q0": 0.001, "S1": 0.0, "S2": 0.0, "Qd": 0.001,
                              "class_probabilities": [{"class": "R1", "probability": 1.0}]})
    fig = rplot.rtable(table)
    legend = " ".join(t.get_text() for t in fig.axes[1].get_legend().get_texts())
    assert "P(class)" not in legend and "extrapolated" in legend
    assert fig.roadbrdf_data["error_bars"] is None
    # S1 of a Lambertian table: r(0, 2) / r(0, 0) = cos^3(atan 2) = 5^-1.5, inside the class diagram.
    assert table["S1"] == pytest.approx(5 ** -1.5, rel=1e-9)
    assert fig.axes[1].get_xlim()[1] > table["S1"]


def test_hemisphere_of_a_lambert_fit_shows_the_measured_points_on_its_colour_scale(tmp_path):
    """A Lambertian model alone is one flat colour; with the data (as the report draws it) the measured
    points carry the information, on a colour scale that contains them (0.10-0.14 sr^-1 written here)."""
    data = _narrow_dataset(tmp_path)
    fit = _lambert_fit(tmp_path / "l.fit.json", [0.12 * math.pi] * 3)
    fig = rplot.hemisphere(fit, theta_i=30, wavelength=590, data=data, lobe=False)
    measured = fig.roadbrdf_data["measured"]
    assert len(measured["brdf"]) == 6  # the six geometries at theta_i = 30 deg
    polar = fig.axes[0]
    points = [c for c in polar.collections if c.get_array() is not None and len(c.get_array()) == 6]
    assert points, "no measured points drawn"
    low, high = points[0].norm.vmin, points[0].norm.vmax
    assert low <= min(measured["brdf"]) and high >= max(measured["brdf"])
    np.testing.assert_allclose(fig.roadbrdf_data["brdf"], 0.12, rtol=1e-12)  # BRDF = rho / pi


@pytest.mark.parametrize("kind", ["spectral", "plane", "fit", "albedo", "rtable", "params"])
def test_every_cartesian_axis_has_tick_labels_on_both_sides(kind, root, tmp_path):
    data = _narrow_dataset(tmp_path)
    fit = _lambert_fit(tmp_path / "l.fit.json", [0.3, 0.35, 0.4])
    fig = {"spectral": lambda: rplot.spectral([data, fit], geometry=(30, 0, 30, 180)),
           "plane": lambda: rplot.plane([fit], [data], theta_i=30, wavelength=590, cartesian=True),
           "fit": lambda: rplot.fit_quality(data, fit, wavelength=590),
           "albedo": lambda: rplot.albedo(fit, sun_zenith="0:60:20"),
           "rtable": lambda: rplot.rtable(fit, wavelength=590),
           "params": lambda: plot_params.params(_fit_with_a_fixed_parameter(root, tmp_path))}[kind]()
    fig.canvas.draw()
    checked = 0
    for axis in fig.axes:
        if axis.name != "rectilinear" or not axis.get_visible() or axis.get_label() == "<colorbar>":
            continue
        for which in (axis.xaxis, axis.yaxis):
            if which.get_visible() and which.get_ticks_position() != "none":
                assert len(_labels(which)) >= 2, (kind, axis.get_title(), which.axis_name, _labels(which))
        checked += 1
    assert checked >= 1
