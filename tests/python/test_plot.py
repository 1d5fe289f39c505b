"""Every figure kind renders to PNG on the bundled example data (headless), and the data it draws
is checked where that makes sense."""
import math

import numpy as np
import pytest

import roadbrdf
import roadbrdf.plot as rplot

EXAMPLES = "data/examples"


def test_spectral_figure_draws_the_dataset_values(root, tmp_path):
    files = [root / EXAMPLES / f"mixed/F{k}.csv" for k in (1, 2, 3, 4)]
    fig = rplot.spectral(files, geometry=(40, 0, 40, 180), output=tmp_path / "s.png")
    assert (tmp_path / "s.png").stat().st_size > 10000
    d = roadbrdf.read_dataset(files[0])
    k = int(np.where((d.angles[:, 0] == 40) & (d.angles[:, 2] == 40) & (np.abs(d.angles[:, 3] - d.angles[:, 1]) == 180))[0][0])
    label = d.metadata["sample"]
    np.testing.assert_array_equal(fig.roadbrdf_data[label][1], d.brdf[k])


def test_hemisphere_figure_of_lambert_is_flat(tmp_path):
    fig = rplot.hemisphere("lambert", {"albedo": 0.4}, theta_i=30, output=tmp_path / "h.png")
    np.testing.assert_allclose(fig.roadbrdf_data["brdf"], 0.4 / math.pi, rtol=1e-14)
    assert (tmp_path / "h.png").exists()


def test_plane_figure_uses_negative_angles_on_the_source_side(root, tmp_path):
    fig = rplot.plane(models=["oren-nayar"], samples=[root / EXAMPLES / "single/garonne.csv"], theta_i=40,
                      output=tmp_path / "p.svg")
    angles, values = fig.roadbrdf_data["oren-nayar"]
    m = roadbrdf.Model("oren-nayar")
    # theta_r = -30 is the backward (retro) side: phi_r = phi_i.
    k = int(np.argmin(np.abs(angles + 30)))
    assert values[k] == pytest.approx(m.evaluate(40, 0, abs(angles[k]), 0))
    assert (tmp_path / "p.svg").exists()


def test_rtable_figure_of_standard_table(root, tmp_path):
    fig = rplot.rtable(root / "data/third-party/rtables/r2-table.dat", output=tmp_path / "r.pdf")
    assert round(fig.roadbrdf_data["S1"], 2) == 0.58
    assert (tmp_path / "r.pdf").exists()


def test_plot_command_line(cli, root, tmp_path):
    out = tmp_path / "cli.png"
    cli("plot", "hemisphere", "oren-nayar", "-p", "sigma=0.4", "--theta-i", "60", "-o", out)
    assert out.stat().st_size > 10000
    r = cli("plot", "hemisphere", "no-such-model", "-o", tmp_path / "x.png", check=False)
    assert r.returncode != 0 and "unknown model 'no-such-model'" in r.stderr
