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
    # The value it was held at is in the heading.
    assert "held fixed in oren-nayar: sigma = 0.3" in fig._suptitle.get_text()
    plt.close(fig)


def test_a_fit_holding_a_parameter_others_fit_draws_it_dashed_without_a_band(root, tmp_path):
    import roadbrdf
    path = tmp_path / "two.fit.json"
    roadbrdf.fit(root / DATA, ["oren-nayar", "lambert"], fixed={"albedo": 0.2}, wavelengths="510,610,710",
                 output=path)
    content = json.loads(path.read_text())
    lambert = next(f for f in content["fits"] if f["model"] == "lambert")
    lambert["fixed"] = []  # as if Lambert's albedo had been fitted (to 0.2): only Oren-Nayar holds it
    lambert["stderr"]["albedo"] = [0.01, 0.01, 0.01]
    path.write_text(json.dumps(content))
    fig = params(path, parameters=["albedo"])
    axis = fig.axes[0]
    styles = {line.get_label(): line.get_linestyle() for line in axis.get_lines()}
    assert styles == {"oren-nayar (fixed)": "--", "lambert": "-"}
    assert len(axis.collections) == 1  # the one band: Lambert's
    plt.close(fig)


def test_own_figure_one_x_range_labelled_under_each_column_one_key_and_nothing_cut(root, tmp_path):
    """Five panels (Lambert's albedo, Hapke's w, b0, h, xi) on three columns: one x range, its tick labels and
    label under the lowest panel of each column only, one key for the figure whose colours are the lines' in
    every panel, and every text inside the figure, which is saved as laid out (not cropped)."""
    import roadbrdf
    from matplotlib.colors import to_rgba
    path = tmp_path / "two.fit.json"
    roadbrdf.fit(root / DATA, ["lambert", "hapke"], wavelengths="510,610,710", output=path)
    fig = params(path)
    assert [a.get_ylabel() for a in fig.axes] == ["albedo [1]", "w [1]", "b0 [1]", "h [1]", "xi [1]"]
    fig.canvas.draw()
    renderer = fig.canvas.get_renderer()
    assert len({a.get_xlim() for a in fig.axes}) == 1
    for k, a in enumerate(fig.axes):
        shown = [t.get_text() for t in a.get_xticklabels() if t.get_text()]
        lowest = k + 3 >= 5  # no panel below in its column
        assert bool(shown) == lowest and (a.get_xlabel() == "wavelength [nm]") == lowest, k
    key = fig.legends[0]
    colour = {t.get_text(): to_rgba(h.get_color()) for t, h in zip(key.get_texts(), key.get_lines())}
    assert set(colour) == {"lambert", "hapke"}
    for a in fig.axes:
        for line in a.get_lines():
            assert to_rgba(line.get_color()) == colour[line.get_label()]
    box = fig.bbox
    texts = [fig._suptitle, *key.get_texts()]
    for a in fig.axes:
        texts += [a.xaxis.label, a.yaxis.label]
        for which in (a.xaxis, a.yaxis):  # the tick labels drawn: those inside the view range
            low, high = sorted(which.get_view_interval())
            texts += [t for t, v in zip(which.get_ticklabels(), which.get_ticklocs()) if low <= v <= high]
    for t in texts:
        if t.get_text():
            e = t.get_window_extent(renderer)
            assert box.x0 <= e.x0 and e.x1 <= box.x1 and box.y0 <= e.y0 and e.y1 <= box.y1, t.get_text()
    png = tmp_path / "p.png"
    params(path, output=png)
    import matplotlib.image
    height, width = matplotlib.image.imread(png).shape[:2]
    expected = fig.get_size_inches() * 150  # 150 dpi, as laid out
    assert abs(width - expected[0]) <= 1 and abs(height - expected[1]) <= 1
    plt.close("all")


def test_a_parameter_on_its_bound_is_said_so_in_its_panel(cli, tmp_path):
    # A Lambertian sample brighter than albedo 1 can be (BRDF 0.5 sr^-1 = albedo pi/2) at two of three
    # wavelengths: the fit stops on the albedo's upper bound there, where no standard error exists.
    data = tmp_path / "bright.csv"
    rows = [f"{ti},0,{tr},180,{0.3 / np.pi:.6g},0.5,0.5" for ti in (0, 20, 40) for tr in (10, 30, 50)]
    data.write_text("theta_i,phi_i,theta_r,phi_r,500,600,700\n" + "\n".join(rows) + "\n")
    fit = tmp_path / "bright.fit.json"
    cli("fit", data, "--model", "lambert", "-o", fit)
    fig = params(fit)
    texts = [t.get_text() for t in fig.axes[0].texts]
    assert texts == ["at its upper bound at 2 of 3 wavelengths"], texts
    plt.close(fig)
