"""The figures (roadbrdf.plot and `roadbrdf plot`): the data behind each figure
(fig.roadbrdf_data) against values computed here independently - Lambert closed forms (BRDF = rho/pi, every
albedo = rho, r-table S1 = cos^3(atan 2)), the CSV values of small datasets written in tmp_path, areal mixing
weights from the formulation's densities - and the properties the issue asks for: axes the caller gives,
radial axes from 0 or an explicit log scale, equal 3-D boxes, one panel per incidence, no empty panels,
normal file permissions, a clear error for a missing folder, a small hemisphere SVG."""
import json
import math
import os
import pathlib
import struct

import matplotlib.pyplot as plt
import numpy as np
import pytest

import roadbrdf
from roadbrdf import plot as rplot
from roadbrdf import plot_albedo, plot_params, plot_study

WAVELENGTHS = [500.0, 590.0, 700.0]
RHO = [0.2, 0.3, 0.4]


@pytest.fixture(autouse=True)
def close_figures():
    yield
    plt.close("all")


def lambert_fit(path, rho=RHO, wavelengths=WAVELENGTHS):
    path.write_text(json.dumps({"format": "roadbrdf-fit", "version": 1, "best": "lambert",
                                "fits": [{"model": "lambert", "options": {}, "wavelengths": list(wavelengths),
                                          "parameters": {"albedo": list(rho)}}]}))
    return path


def tiny_angles():
    rows = []
    for ti in (0.0, 20.0, 40.0):
        rows.append((ti, 0.0, 0.0, 0.0))
        for tr in (15.0, 30.0, 45.0, 60.0):
            for pr in (0.0, 90.0, 180.0):
                rows.append((ti, 0.0, tr, pr))
    return np.array(rows)


@pytest.fixture
def tiny(tmp_path):
    """A small zenith-convention dataset whose every value is distinct: row k, band j -> 0.01 (k + 1) + 0.001 j."""
    angles = tiny_angles()
    brdf = 0.01 * (np.arange(len(angles))[:, None] + 1) + 0.001 * np.arange(len(WAVELENGTHS))[None, :]
    path = tmp_path / "tiny.csv"
    roadbrdf.write_dataset(roadbrdf.Dataset(angles, WAVELENGTHS, brdf, metadata={"sample": "tiny sample"}), path)
    return path, angles, brdf


def lambert_mix(folder):
    """A mixture of two Lambertian components, areal method: weights = volume fractions."""
    (folder / "fits").mkdir()
    lambert_fit(folder / "fits" / "binder.fit.json", [0.05, 0.05, 0.06])
    lambert_fit(folder / "fits" / "rock.fit.json", [0.3, 0.35, 0.4])
    (folder / "F.json").write_text(json.dumps({
        "format": "roadbrdf-formulation", "version": 1, "name": "F", "components": [
            {"name": "Binder", "kind": "binder", "mass_percent": 10, "density_g_cm3": 1.0,
             "fit": "fits/binder.fit.json"},
            {"name": "Rock", "kind": "aggregate", "mass_percent": 90, "density_g_cm3": 2.7, "d_min_mm": 2,
             "d_max_mm": 6, "fit": "fits/rock.fit.json"}]}))
    out = folder / "F.mix.json"
    roadbrdf.mix(folder / "F.json", method="areal", output=out)
    binder, rock = 10 / 1.0, 90 / 2.7
    w = binder / (binder + rock)
    return out, w * np.array([0.05, 0.05, 0.06]) + (1 - w) * np.array([0.3, 0.35, 0.4])


def png_width(path):
    head = pathlib.Path(path).read_bytes()[:24]
    assert head[:8] == b"\x89PNG\r\n\x1a\n"
    return struct.unpack(">I", head[16:20])[0]


# ---- 1. the split: one topic per module, the public entry unchanged ---------------------------------------
def test_every_plot_module_is_small_and_the_entry_keeps_its_names(root):
    for path in (root / "python/roadbrdf").glob("plot*.py"):
        assert len(path.read_text().splitlines()) <= 600, path
    for name in ("spectral", "hemisphere", "plane", "fit_quality", "albedo", "rtable", "save", "main", "params"):
        assert callable(getattr(rplot, name)), name


# ---- 3. spectral: datasets, fit files and mixtures in one figure ------------------------------------------
def test_spectral_draws_measured_fitted_and_mixed_curves(tiny, tmp_path):
    path, angles, brdf = tiny
    fit = lambert_fit(tmp_path / "tiny.fit.json")
    mix, expected_mix = lambert_mix(tmp_path)
    fig = rplot.spectral([path, fit, mix], geometry=(20, 0, 30, 180))
    data, kinds = fig.roadbrdf_data, fig.roadbrdf_kinds
    k = int(np.where((angles[:, 0] == 20) & (angles[:, 2] == 30) & (angles[:, 3] == 180))[0][0])
    np.testing.assert_array_equal(data["tiny sample"][1], brdf[k])
    fitted = next(label for label, kind in kinds.items() if kind == "fit")
    mixed = next(label for label, kind in kinds.items() if kind == "mix")
    assert "lambert" in fitted and "areal" in mixed
    np.testing.assert_allclose(data[fitted][0], WAVELENGTHS)
    np.testing.assert_allclose(data[fitted][1], np.array(RHO) / math.pi, rtol=1e-12)
    np.testing.assert_allclose(data[mixed][1], expected_mix / math.pi, rtol=1e-9)
    # The prediction of tiny.fit.json is drawn in the colour of tiny.csv.
    lines = {line.get_label().split("  (")[0]: line for line in fig.axes[0].get_lines()}
    assert lines[fitted].get_color() == lines["tiny sample measured"].get_color()


def test_spectral_command_takes_csv_fit_and_mix(cli, tiny, tmp_path):
    path, _, _ = tiny
    mix, _ = lambert_mix(tmp_path)
    out = tmp_path / "s.png"
    cli("plot", "spectral", path, lambert_fit(tmp_path / "t.fit.json"), mix, "--geometry", "20,0,30,180", "-o", out)
    assert png_width(out) > 300


# ---- 4. measured data on the hemisphere and in the plane --------------------------------------------------
def test_hemisphere_of_a_dataset_draws_its_points(tiny):
    path, angles, brdf = tiny
    fig = rplot.hemisphere(path, theta_i=20, wavelength=600)
    m = fig.roadbrdf_data["measured"]
    rows = angles[:, 0] == 20
    assert m["wavelength"] == 590.0  # nearest band to 600 nm, said on the figure
    assert "nearest band to 600 nm" in fig._suptitle.get_text() and "tiny sample" in fig._suptitle.get_text()
    np.testing.assert_array_equal(m["brdf"], brdf[rows, 1])
    np.testing.assert_allclose(m["theta_r"], angles[rows, 2], atol=1e-12)
    np.testing.assert_allclose(m["phi_r"], angles[rows, 3], atol=1e-12)
    labels = [t.get_text() for t in fig.axes[0].get_legend().get_texts()]
    assert labels == [f"measured ({rows.sum()} points)"]
    with pytest.raises(ValueError, match=r"no measured geometry at theta_i = 30 deg \(measured incidences: 0, 20, 40\)"):
        rplot.hemisphere(path, theta_i=30)


def test_plane_of_a_dataset_draws_its_in_plane_points(tiny):
    path, angles, brdf = tiny
    fig = rplot.plane(samples=[path], theta_i=40, wavelength=700)
    (label, (x, y)), = fig.roadbrdf_data.items()
    assert label == "tiny sample measured (700 nm)"
    expected = sorted((tr if pr == 180.0 else -tr, brdf[k, 2]) for k, (ti, pi, tr, pr) in enumerate(angles)
                      if ti == 40 and pr in (0.0, 180.0))
    np.testing.assert_allclose(x, [a for a, _ in expected], atol=1e-12)
    np.testing.assert_array_equal(y, [v for _, v in expected])


def test_hemisphere_and_plane_commands_on_a_dataset(cli, tiny, tmp_path):
    path, _, _ = tiny
    cli("plot", "hemisphere", path, "--theta-i", "40", "--wavelength", "600", "-o", tmp_path / "h.png")
    cli("plot", "plane", path, "-o", tmp_path / "p.png", "--theta-i", "20")
    cli("plot", "plane", path, "--cartesian", "--log", "-o", tmp_path / "c.png", "--theta-i", "20")
    for name in ("h.png", "p.png", "c.png"):
        assert png_width(tmp_path / name) > 300
    r = cli("plot", "plane", "-o", tmp_path / "x.png", check=False)
    assert r.returncode == 2 and "give a dataset" in r.stderr


# ---- 5. radial axes from 0 or logarithmic, cartesian, equal 3-D axes --------------------------------------
def test_the_polar_radius_starts_at_zero():
    fig = rplot.plane(models=["lambert"], params={"albedo": 0.5}, theta_i=30)
    ax = fig.axes[0]
    assert ax.name == "polar" and ax.get_ylim()[0] == 0.0
    x, y = fig.roadbrdf_data["lambert"]
    np.testing.assert_allclose(y, 0.5 / math.pi, rtol=1e-14)
    assert ax.get_ylim()[1] >= 0.5 / math.pi


def test_a_logarithmic_radius_is_labelled_in_decades():
    fig = rplot.plane(models=["oren-nayar+torrance-sparrow"], theta_i=40, log=True)
    ax = fig.axes[0]
    label, (x, y) = next(iter(fig.roadbrdf_data.items()))
    floor = 10.0 ** (math.floor(math.log10(y.min())) - 1)
    assert ax.get_ylim()[0] == 0.0
    ticks = [t.get_text() for t in ax.get_yticklabels()]
    assert ticks[:3] == [f"{floor:g}", f"{floor * 10:g}", f"{floor * 100:g}"]
    assert f"logarithmic (centre {floor:g})" in ax.get_xlabel()
    # The radius of each point is its number of decades above the centre.
    r = ax.get_lines()[0].get_ydata()
    np.testing.assert_allclose(r, np.log10(y / floor), rtol=1e-12)


def test_cartesian_plane_uses_signed_theta_r():
    fig = rplot.plane(models=["oren-nayar"], theta_i=40, cartesian=True)
    ax = fig.axes[0]
    assert ax.name == "rectilinear" and ax.get_ylim()[0] == 0.0 and ax.get_xlim() == (-90.0, 90.0)
    x, y = fig.roadbrdf_data["oren-nayar"]
    k = int(np.argmin(np.abs(x + 30)))  # -30 deg: the source side, phi_r = phi_i
    assert y[k] == pytest.approx(roadbrdf.Model("oren-nayar").evaluate(40, 0, -x[k], 0))
    k = int(np.argmin(np.abs(x - 30)))
    assert y[k] == pytest.approx(roadbrdf.Model("oren-nayar").evaluate(40, 0, x[k], 180))
    fig = rplot.plane(models=["oren-nayar"], theta_i=40, cartesian=True, log=True)
    assert fig.axes[0].get_yscale() == "log"


def test_the_lobe_has_equal_axes():
    fig = rplot.hemisphere("lambert", {"albedo": 0.6}, theta_i=30)
    ax3 = next(a for a in fig.axes if a.name == "3d")
    spans = np.array([np.ptp(ax3.get_xlim()), np.ptp(ax3.get_ylim()), np.ptp(ax3.get_zlim())])
    box = np.asarray(ax3.get_box_aspect())
    np.testing.assert_allclose(box / box[0], spans / spans[0], rtol=1e-9)
    # A Lambertian lobe is a half ball of radius rho/pi: twice as wide as high.
    radius = 0.6 / math.pi
    # (theta_r runs to 89.5 deg: z from rho/pi cos 89.5 deg to rho/pi)
    assert spans[2] == pytest.approx(radius * (1 - math.cos(math.radians(89.5))), rel=1e-6)
    assert spans[0] == pytest.approx(2 * radius * math.sin(math.radians(89.5)), rel=1e-6)


# ---- 6. one panel per incidence -----------------------------------------------------------------------------
def test_one_panel_per_incidence(tmp_path):
    fit = lambert_fit(tmp_path / "l.fit.json")
    fig = rplot.hemisphere(fit, theta_i="0,20,40,60", wavelength=590)
    assert [a.name for a in fig.axes if a.name in ("polar", "3d")].count("polar") == 4
    assert sorted(fig.roadbrdf_data) == [0.0, 20.0, 40.0, 60.0]
    for item in fig.roadbrdf_data.values():
        np.testing.assert_allclose(item["brdf"], 0.3 / math.pi, rtol=1e-12)
    fig = rplot.plane(models=[fit], theta_i=[0, 20, 40, 60], wavelength=700)
    assert len([a for a in fig.axes if a.name == "polar"]) == 4
    assert sorted(fig.roadbrdf_data) == [0.0, 20.0, 40.0, 60.0]
    (label, (x, y)), = fig.roadbrdf_data[60.0].items()
    np.testing.assert_allclose(y, 0.4 / math.pi, rtol=1e-12)


def test_incidence_panels_on_the_command_line(cli, tiny, tmp_path):
    path, _, _ = tiny
    fit = lambert_fit(tmp_path / "l.fit.json")
    cli("plot", "hemisphere", fit, "--data", path, "--theta-i", "0,20,40", "-o", tmp_path / "h.png", "--dpi", "40")
    cli("plot", "plane", path, fit, "--theta-i", "0,20,40", "-o", tmp_path / "p.png", "--dpi", "40")
    r = cli("plot", "plane", path, "--theta-i", "0,95", "-o", tmp_path / "x.png", check=False)
    assert r.returncode == 2 and "95 deg is outside [0, 90)" in r.stderr


# ---- 2. ax= / fig= everywhere -----------------------------------------------------------------------------
def test_every_function_draws_into_the_callers_axes(tiny, tmp_path):
    path, _, _ = tiny
    fit = lambert_fit(tmp_path / "l.fit.json")
    fig = plt.figure(layout="constrained")
    top, bottom = fig.subfigures(2, 1)
    ax = top.add_subplot(1, 2, 1)
    polar = top.add_subplot(1, 2, 2, projection="polar")
    assert rplot.spectral([path], geometry=(0, 0, 0, 0), ax=ax) is top and ax.roadbrdf_data
    assert rplot.plane(models=["lambert"], ax=polar) is top and "lambert" in polar.roadbrdf_data
    drawn = rplot.rtable(fit, wavelength=590, fig=bottom)
    assert drawn is bottom and len(bottom.axes) >= 2 and drawn.roadbrdf_data["Q0"] == pytest.approx(0.3 / math.pi)
    rplot.save(fig, tmp_path / "composed.png", dpi=40)  # a SubFigure's figure is saved whole
    assert png_width(tmp_path / "composed.png") > 100
    one = lambert_fit(tmp_path / "one.fit.json", [0.3], [590.0])
    fig, axes = plt.subplots(1, 2)
    assert rplot.fit_quality(path, one, ax=axes) is fig  # a single band: no RMSE panel needed
    with pytest.raises(ValueError, match="ax: 1 axes given for 2"):
        rplot.fit_quality(path, one, ax=axes[0])
    fig = plt.figure()
    hemi = [fig.add_subplot(1, 2, 1, projection="polar"), fig.add_subplot(1, 2, 2, projection="3d")]
    assert rplot.hemisphere("lambert", ax=hemi) is fig
    with pytest.raises(ValueError, match="needs polar axes"):
        rplot.hemisphere("lambert", ax=plt.subplots(1, 2)[1])
    fig, ax = plt.subplots()
    assert rplot.albedo(roadbrdf.albedo(fit, sun_zenith="0:60:30"), ax=[ax, plt.subplots()[1]]) is fig


def test_params_figure_into_a_subfigure(cli, root, tmp_path):
    out = tmp_path / "g.fit.json"
    cli("fit", root / "data/examples/single/lazard.csv", "--model", "oren-nayar", "--group-by", "theta_i",
        "--where", "theta_i>0", "--wavelengths", "510:710:100", "-o", out)
    fig = plt.figure()
    sub = fig.subfigures(1, 1)
    drawn = plot_params.params(out, parameters=["albedo"], against="theta_i", fig=sub)
    assert drawn is sub and list(drawn.roadbrdf_data["albedo"]["oren-nayar"][0]) == [20, 40, 60, 80]


def test_study_figures_carry_their_data(tmp_path):
    results = tmp_path / "r.csv"
    results.write_text("candidate,status,method,rock,black_sky_30deg [1],white_sky [1],Q0 [sr^-1],S1 [1],class [R]\n"
                       "1,ok,areal,grey,0.10,0.11,0.090,0.30,R1\n"
                       "2,ok,areal,light,0.20,0.21,0.080,0.50,R2\n"
                       "3,ok,areal,grey,0.15,0.16,0.060,0.90,R3\n"
                       "4,ok,areal,light,0.30,0.31,0.050,1.40,R4\n")
    fig, ax = plt.subplots()
    drawn = plot_study.plane(str(results), "Q0", ax=ax)
    assert drawn is fig
    # (0.15, 0.06) is beaten by (0.20, 0.08); the others trade albedo for Q0.
    assert drawn.roadbrdf_data["pareto"] == [0, 1, 3]
    np.testing.assert_array_equal(drawn.roadbrdf_data["albedo"], [0.10, 0.20, 0.15, 0.30])
    assert drawn.roadbrdf_data["fronts"] == {"areal": [0, 1, 3]}
    fig = plot_study.sensitivity(str(results), outputs=["Q0 [sr^-1]"])
    s = fig.roadbrdf_data["Q0 [sr^-1]"]["rock"]["areal"]
    assert s["x"] == ["grey", "light"]
    np.testing.assert_allclose(s["mean"], [0.075, 0.065])
    np.testing.assert_allclose(s["min"], [0.060, 0.050])


def test_study_figures_draw_each_method_apart(tmp_path):
    """Two methods predicting the same candidates are not pooled: a front and a sensitivity line each."""
    results = tmp_path / "r.csv"
    results.write_text("candidate,status,method,rock,black_sky_30deg [1],white_sky [1],Q0 [sr^-1],S1 [1],class [R]\n"
                       "1,ok,areal,grey,0.10,0.11,0.090,0.30,R1\n"
                       "1,ok,mastic,grey,0.30,0.31,0.085,0.20,R1\n"
                       "2,ok,areal,light,0.20,0.21,0.080,0.50,R2\n"
                       "2,ok,mastic,light,0.40,0.41,0.082,0.15,R1\n"
                       "3,failed,,grey,,,,,\n")
    fig = plot_study.plane(str(results), "Q0")
    data = fig.roadbrdf_data
    assert data["methods"] == ["areal", "mastic", "areal", "mastic"]
    # Pooled, mastic's (0.30, 0.085) would push areal's (0.20, 0.08) off the front: the same candidate predicted
    # by another method is no competitor.
    assert plot_study.pareto(data["albedo"], data["lighting"]) == [0, 1, 3]
    assert data["fronts"] == {"areal": [0, 2], "mastic": [1, 3]}
    assert data["pareto"] == [0, 2, 1, 3]
    labels = fig.axes[0].get_legend_handles_labels()[1]
    # The legend's keys: a colour per class, a marker per method, a front per method.
    assert labels == ["R1", "R2", "areal", "mastic", "Pareto front, areal", "Pareto front, mastic"]
    fig = plot_study.plane(str(results), "S1", method="mastic")
    assert fig.roadbrdf_data["fronts"] == {"mastic": [1]} and fig.roadbrdf_data["methods"] == ["mastic", "mastic"]
    fig = plot_study.sensitivity(str(results), outputs=["Q0 [sr^-1]"])
    s = fig.roadbrdf_data["Q0 [sr^-1]"]["rock"]
    np.testing.assert_allclose(s["areal"]["mean"], [0.090, 0.080])
    np.testing.assert_allclose(s["mastic"]["mean"], [0.085, 0.082])
    assert len(fig.axes[0].lines) == 2
    with pytest.raises(ValueError, match="no successful candidates to draw with method 'hapke'"):
        plot_study.plane(str(results), "Q0", method="hapke")


# ---- 7. albedo, r-table, names, no empty panels, layout -----------------------------------------------------
def test_albedo_figure_of_a_lambert_fit_per_atmosphere(tmp_path):
    fit = lambert_fit(tmp_path / "l.fit.json")
    atmospheres = ["spectrl2:aod=0.05", "spectrl2:aod=0.5"]
    fig = rplot.albedo(fit, atmospheres=atmospheres, sun_zenith="0:60:20")
    assert len(fig.axes) == 2  # against sun zenith, and spectral
    panel = fig.roadbrdf_data["zenith_panel"]
    assert list(panel) == [f"l, {a}" for a in atmospheres]
    for c in panel.values():
        np.testing.assert_array_equal(c["sun_zenith_deg"], [0, 20, 40, 60])
        # Every solar-weighted albedo of a Lambertian surface lies within its albedo spectrum's range.
        assert np.all((c["black_sky"] > 0.2) & (c["black_sky"] < 0.4))
        assert np.all((c["blue_sky"] > 0.2) & (c["blue_sky"] < 0.4)) and 0.2 < c["white_sky"] < 0.4
    spectral = fig.roadbrdf_data["spectral_panel"]
    for values in spectral["black_sky"].values():
        np.testing.assert_allclose(values, RHO, atol=1e-9)
    np.testing.assert_allclose(spectral["white_sky"], RHO, atol=1e-9)
    assert len(spectral["blue_sky"]) == 2
    for blue in spectral["blue_sky"].values():
        np.testing.assert_allclose(blue, RHO, atol=1e-9)


def test_albedo_blue_sky_is_the_diffuse_weighted_mean_and_single_values_are_bars(tmp_path):
    result = roadbrdf.albedo(roadbrdf.Model("oren-nayar"), {"sigma": 0.5}, sun_zenith=[0, 40, 70],
                             diffuse_fraction=0.3)
    fig = rplot.albedo(result)
    c, = fig.roadbrdf_data["zenith_panel"].values()
    assert c["weighting"] == "solar-weighted" or c["weighting"].startswith("at ")
    bb = result["broadband"]
    np.testing.assert_allclose(c["black_sky"], bb["black_sky"])
    np.testing.assert_allclose(c["blue_sky"], 0.7 * np.array(bb["black_sky"]) + 0.3 * bb["white_sky"], rtol=1e-6)
    single = lambert_fit(tmp_path / "one.fit.json", [0.25], [550.0])
    fig = rplot.albedo(roadbrdf.albedo(single, sun_zenith=30, diffuse_fraction=0.2))
    assert len(fig.axes) == 1 and fig.axes[0].get_title().startswith("albedo at 550 nm")
    heights = [p.get_height() for p in fig.axes[0].patches]
    np.testing.assert_allclose(heights, [0.25, 0.25, 0.25], atol=1e-9)


def test_albedo_error_bars_are_the_uncertainties_of_the_result(cli, root, tmp_path):
    """A fit file with its covariance: the figure draws the result's standard uncertainties, the solar-weighted
    ones (by default the bound for errors correlated across wavelengths, on request the independent ones)
    against sun zenith and the per-wavelength ones as bands."""
    fit = tmp_path / "on.fit.json"
    cli("fit", root / "data" / "examples" / "single" / "lazard.csv", "--model", "oren-nayar", "--wavelengths",
        "400:700:50", "-o", fit)
    result = json.loads(cli("albedo", fit, "--sun-zenith", "0,30,60", "--diffuse-fraction", "0.2", "--json").stdout)
    fig = rplot.albedo(result)
    c, = fig.roadbrdf_data["zenith_panel"].values()
    u = result["uncertainty"]["broadband"]
    np.testing.assert_array_equal(c["black_sky_u"], [b["correlated"] for b in u["black_sky"]])
    np.testing.assert_array_equal(c["blue_sky_u"], [b["correlated"] for b in u["blue_sky"]])
    assert c["white_sky_u"] == u["white_sky"]["correlated"] > u["white_sky"]["independent"] > 0
    independent, = rplot.albedo(result, uncertainty="independent").roadbrdf_data["zenith_panel"].values()
    np.testing.assert_array_equal(independent["black_sky_u"], [b["independent"] for b in u["black_sky"]])
    assert independent["white_sky_u"] == u["white_sky"]["independent"]
    zenith_axis = fig.axes[0]
    bars = [child for child in zenith_axis.containers if hasattr(child, "has_yerr") and child.has_yerr]
    assert len(bars) == 2  # black-sky and blue-sky
    spectral = fig.roadbrdf_data["spectral_panel"]
    np.testing.assert_array_equal(spectral["white_sky_u"], result["uncertainty"]["white_sky"])
    np.testing.assert_array_equal(spectral["black_sky_u"][0.0], result["uncertainty"]["black_sky"][0])
    # Without uncertainties (a model with given parameters) there are no bars.
    fig = rplot.albedo(roadbrdf.albedo(roadbrdf.Model("lambert"), {"albedo": 0.3}, sun_zenith=[0, 40]))
    c, = fig.roadbrdf_data["zenith_panel"].values()
    assert c["black_sky_u"] is None and not fig.axes[0].containers


def test_albedo_computed_by_the_figure_is_to_its_tolerance(cli, root, tmp_path):
    """From a fit file the figure computes the albedo to FIGURE_TOLERANCE (1e-4, a tenth of a pixel) unless
    told otherwise, the same values as `roadbrdf albedo` within it; an albedo result is read, not recomputed,
    even when it mentions a fit file's format in a note."""
    fit = tmp_path / "on.fit.json"
    cli("fit", root / "data" / "examples" / "single" / "lazard.csv", "--model", "oren-nayar", "--wavelengths",
        "400:700:50", "-o", fit)
    reference = json.loads(cli("albedo", fit, "--sun-zenith", "0,40,80", "--json").stdout)
    assert reference["tolerance"] == 1e-5
    for tolerance in (None, 1e-6):
        kwargs = {} if tolerance is None else {"tolerance": tolerance}
        data = rplot.albedo(fit, sun_zenith="0,40,80", **kwargs).roadbrdf_data
        assert data["tolerance"] == (tolerance or plot_albedo.FIGURE_TOLERANCE) == (tolerance or 1e-4)
        for key in ("black_sky", "white_sky"):
            np.testing.assert_allclose(data[key], reference[key], rtol=0, atol=(tolerance or 1e-4) + 1e-5)
    out = tmp_path / "a.png"
    cli("plot", "albedo", fit, "--sun-zenith", "0,40", "--tolerance", "1e-3", "-o", out)
    assert png_width(out) > 300
    reference["notes"].append('a note quoting "format": "roadbrdf-fit"')  # escaped inside a JSON string
    result = tmp_path / "r.json"
    result.write_text(json.dumps(reference))
    assert rplot.albedo(result).roadbrdf_data["tolerance"] == 1e-5


def test_albedo_command_with_atmospheres(cli, tmp_path):
    fit = lambert_fit(tmp_path / "l.fit.json")
    out = tmp_path / "a.png"
    cli("plot", "albedo", fit, "--atmosphere", "spectrl2:aod=0.05", "--atmosphere", "spectrl2:aod=0.4",
        "--sun-zenith", "0:60:30", "-o", out)
    assert png_width(out) > 300
    report = tmp_path / "r.json"
    report.write_text(cli("albedo", fit, "--sun-zenith", "0,40", "--json").stdout)
    r = cli("plot", "albedo", report, "--atmosphere", "spectrl2", "-o", out, check=False)
    assert r.returncode == 2 and "atmospheres apply to a fit file" in r.stderr


def test_rtable_of_lambert_and_a_class_diagram_that_follows_s1():
    fig = rplot.rtable(roadbrdf.Model("lambert"), {"albedo": 0.3})
    t = fig.roadbrdf_data
    assert t["Q0"] == pytest.approx(0.3 / math.pi, rel=1e-3)
    # r(beta, gamma) = f cos^3(gamma) for a Lambertian surface: S1 = r(0, tan 2) / r(0, 0) = cos^3(atan 2).
    assert t["S1"] == pytest.approx(math.cos(math.atan(2.0)) ** 3, rel=1e-6)
    diagram = next(a for a in fig.axes if a.get_xlabel().startswith("S1"))
    assert diagram.get_xlim() == (0.0, 2.5)
    fig = rplot.rtable(roadbrdf.Model("torrance-sparrow"), {"roughness": 0.1})
    s1 = fig.roadbrdf_data["S1"]
    assert s1 > 2.5
    diagram = next(a for a in fig.axes if a.get_xlabel().startswith("S1"))
    assert diagram.get_xlim()[1] >= s1 and fig.roadbrdf_data["diagram_range"][0] >= s1
    star = [line for line in diagram.get_lines() if line.get_marker() == "*"][0]
    assert star.get_xdata()[0] == pytest.approx(s1)


def test_figures_name_sample_model_wavelength_and_units(tiny, tmp_path):
    path, _, _ = tiny
    fit = lambert_fit(tmp_path / "tiny.fit.json")
    fig = rplot.hemisphere(fit, theta_i=40, wavelength=590)
    title = fig._suptitle.get_text()
    assert "tiny" in title and "lambert" in title and "590 nm" in title
    assert any("sr$^{-1}$" in a.get_ylabel() for a in fig.axes)  # the colour bar
    fig = rplot.fit_quality(path, fit, wavelength=700)
    assert "tiny sample" in fig._suptitle.get_text() and "lambert" in fig._suptitle.get_text()
    assert "700 nm" in fig.axes[0].get_title() and "sr$^{-1}$" in fig.axes[0].get_xlabel()
    fig = rplot.plane(samples=[path], models=[fit], theta_i=20)
    labels = [t.get_text() for t in fig.axes[-1].get_legend().get_texts()]
    assert labels == ["tiny (lambert fit) (590 nm)", "tiny sample measured (590 nm)"]


def test_no_empty_panels_and_constrained_layout(tiny, tmp_path):
    path, _, _ = tiny
    one = lambert_fit(tmp_path / "one.fit.json", [0.3], [590.0])
    fig = rplot.fit_quality(path, one)
    assert len(fig.axes) == 2 and all(a.has_data() for a in fig.axes)
    fig = rplot.fit_quality(path, lambert_fit(tmp_path / "by-hand.fit.json"))
    assert len(fig.axes) == 2  # a fit file without RMSE (written by hand): no RMSE panel either
    fitted = roadbrdf.fit(path, "lambert", output=tmp_path / "three.fit.json")
    fig = rplot.fit_quality(path, tmp_path / "three.fit.json")
    assert len(fig.axes) == 3 and fig.axes[2].get_title() == "RMSE vs wavelength"
    (x, y), = fig.roadbrdf_data["rmse"].values()
    np.testing.assert_array_equal(x, WAVELENGTHS)
    np.testing.assert_allclose(y, fitted.best.statistics["rmse"])
    assert type(fig.get_layout_engine()).__name__ == "ConstrainedLayoutEngine"


# ---- 8. files: permissions, missing folder, atomic ----------------------------------------------------------
def test_files_have_normal_permissions(tmp_path):
    fig = rplot.plane(models=["lambert"])
    old = os.umask(0o002)
    try:
        rplot.save(fig, tmp_path / "new.png", dpi=30)
    finally:
        os.umask(old)
    assert (tmp_path / "new.png").stat().st_mode & 0o777 == 0o666 & ~0o002
    existing = tmp_path / "existing.png"
    existing.write_bytes(b"old")
    existing.chmod(0o640)
    link = tmp_path / "link.png"
    link.symlink_to(existing)
    rplot.save(fig, link, dpi=30)
    assert link.is_symlink() and existing.stat().st_mode & 0o777 == 0o640 and png_width(existing) > 10
    assert [p.name for p in tmp_path.iterdir() if p.name.startswith(".roadbrdf-plot-")] == []


def test_the_command_writes_with_the_umask(root, tmp_path):
    import subprocess
    import sys
    out = tmp_path / "u.png"
    env = dict(os.environ, MPLBACKEND="Agg")
    code = "import os, sys; os.umask(0o027); from roadbrdf import plot; sys.exit(plot.run(sys.argv[1:]))"
    r = subprocess.run([sys.executable, "-c", code, "hemisphere", "lambert", "--dpi", "30", "-o", str(out)],
                       capture_output=True, text=True, env=env)
    assert r.returncode == 0, r.stderr
    assert out.stat().st_mode & 0o777 == 0o640


def test_a_missing_output_folder_is_a_clear_error(cli, tmp_path):
    missing = tmp_path / "nowhere"
    r = cli("plot", "hemisphere", "lambert", "-o", missing / "h.png", check=False)
    assert r.returncode == 2
    assert r.stderr == f"roadbrdf plot: error: output folder '{missing}' does not exist\n"
    from roadbrdf.plot_common import OutputFolderError
    with pytest.raises(OutputFolderError):
        rplot.save(plt.figure(), missing / "x.png")


# ---- 9. a small hemisphere SVG, --dpi ---------------------------------------------------------------------
def test_the_hemisphere_svg_is_small_and_its_mesh_raster(cli, tmp_path):
    out = tmp_path / "h.svg"
    cli("plot", "hemisphere", "oren-nayar+torrance-sparrow", "--theta-i", "45", "-o", out)
    text = out.read_text()
    assert out.stat().st_size < 1_500_000
    assert text.count("<image") >= 2  # the heat map and the lobe, raster inside the vector figure
    small, large = tmp_path / "a.png", tmp_path / "b.png"
    cli("plot", "hemisphere", "lambert", "--dpi", "40", "-o", small)
    cli("plot", "hemisphere", "lambert", "--dpi", "80", "-o", large)
    assert png_width(large) / png_width(small) == pytest.approx(2.0, rel=0.05)
    r = cli("plot", "hemisphere", "lambert", "--dpi", "0", "-o", small, check=False)
    assert r.returncode == 2 and "--dpi" in r.stderr
