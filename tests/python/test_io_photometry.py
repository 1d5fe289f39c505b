import math

import numpy as np
import pytest

import roadbrdf


def test_dataset_round_trip(tmp_path):
    angles = np.array([[0, 0, 0, 0], [30, 0, 45, 180], [60, 0, 60, 0]], dtype=float)
    wl = np.array([400.0, 500.0, 600.0])
    brdf = np.array([[0.1, 0.2, 0.3], [0.11, 0.21, -0.01], [0.5, 0.6, 0.7]])
    sigma = np.full_like(brdf, 0.01)
    d = roadbrdf.Dataset(angles, wl, brdf, sigma, {"sample": "test"})
    for fmt in ("wide", "long"):
        path = tmp_path / f"d_{fmt}.csv"
        d.write(path, fmt)
        with pytest.warns(UserWarning, match="negative"):
            back = roadbrdf.read_dataset(path)
        np.testing.assert_array_equal(back.brdf, brdf)
        np.testing.assert_array_equal(back.sigma, sigma)
        np.testing.assert_allclose(back.angles, angles, atol=1e-9)
        assert back.metadata["sample"] == "test"


def test_dataset_errors_name_file_line_column(tmp_path):
    path = tmp_path / "bad.csv"
    path.write_text("theta_i,phi_i,theta_r,phi_r,500\n0,0,0,0,0.1\n0,0,10,0,x\n")
    with pytest.raises(roadbrdf.InputError, match=r"bad\.csv:3:\d+"):
        roadbrdf.read_dataset(path)


def test_curet_sample_has_205_geometries(root):
    d = roadbrdf.read_curet(root / "data/third-party/curet/abrdf.dat", root / "data/third-party/curet/table.txt", 45)
    assert d.brdf.shape == (205, 1)


def test_lambert_rtable_closed_form():
    rho = 0.3
    t = roadbrdf.rtable(roadbrdf.Model("lambert"), {"albedo": rho})
    tan_gamma = np.asarray(t["tan_gamma"])
    expected = rho / math.pi * np.cos(np.arctan(tan_gamma)) ** 3
    np.testing.assert_allclose(t["r"], np.broadcast_to(expected[:, None], (29, 20)), rtol=1e-12)
    assert t["S1"] == pytest.approx(math.cos(math.atan(2.0)) ** 3, rel=1e-12)
    assert t["Q0"] == pytest.approx(rho / math.pi, rel=1e-12)


def test_standard_rtable_s1_and_round_trip(root, tmp_path, cli):
    published = {"r1": 0.25, "r2": 0.58, "r3": 1.11, "r4": 1.55}
    for name, s1 in published.items():
        t = roadbrdf.read_rtable(root / f"data/third-party/rtables/{name}-table.dat")
        assert round(t["S1"], 2) == s1
        assert t["class"] == name.upper()
    t = roadbrdf.read_rtable(root / "data/third-party/rtables/r3-table.dat")
    assert np.isnan(t["r"]).sum() == 580 - 396
    for fmt in ("csv", "rtb", "radiance"):
        path = tmp_path / f"r3.{fmt if fmt != 'radiance' else 'dat'}"
        t.write(path, fmt)
        back = roadbrdf.read_rtable(path, fmt)
        np.testing.assert_array_equal(np.isnan(back["r"]), np.isnan(t["r"]))
        np.testing.assert_allclose(back["r"][~np.isnan(t["r"])], t["r"][~np.isnan(t["r"])], rtol=1e-12)
    import json
    from_cli = json.loads(cli("rtable", "--import", root / "data/third-party/rtables/r3-table.dat", "--json").stdout)
    assert from_cli["S1"] == pytest.approx(t["S1"], rel=1e-12)
    assert from_cli["Q0"] == pytest.approx(t["Q0"], rel=1e-12)


def test_albedo_lambert_and_cli_agreement(cli, tmp_path):
    r = roadbrdf.albedo(roadbrdf.Model("lambert"), {"albedo": 0.3}, sun_zenith=[0, 60], diffuse_fraction=0.25)
    assert r["black_sky"][0][0] == pytest.approx(0.3, abs=1e-12)
    assert r["white_sky"][0] == pytest.approx(0.3, abs=1e-12)
    assert r["blue_sky"][1][0] == pytest.approx(0.3, abs=1e-12)
    import json
    from_cli = json.loads(cli("albedo", "oren-nayar", "-p", "sigma=0.5", "--sun-zenith", "0,40", "--json").stdout)
    from_py = roadbrdf.albedo(roadbrdf.Model("oren-nayar"), {"sigma": 0.5}, sun_zenith=[0, 40])
    assert from_py["black_sky"] == from_cli["black_sky"]
    assert from_py["white_sky"] == from_cli["white_sky"]


def test_albedo_and_fit_figures_render(root, tmp_path):
    import roadbrdf.plot as rplot
    data = root / "data/examples/single/lazard.csv"
    fit_path = tmp_path / "lazard.fit.json"
    roadbrdf.fit(data, ["oren-nayar", "lambert"], output=fit_path)
    fig = rplot.fit_quality(data, fit_path, output=tmp_path / "fit.png")
    assert (tmp_path / "fit.png").stat().st_size > 10000
    d = roadbrdf.read_dataset(data)
    k = int(np.argmin(np.abs(d.wavelengths - 550)))
    np.testing.assert_array_equal(fig.roadbrdf_data["measured"], d.brdf[:, k])
    result = roadbrdf.albedo(fit_path, sun_zenith=[0, 30, 60], atmosphere="spectrl2", wavelengths=[450, 550, 650])
    fig = rplot.albedo(result, output=tmp_path / "albedo.png")
    assert (tmp_path / "albedo.png").stat().st_size > 10000
    # Black-sky of a rough diffuse surface changes little with sun zenith; all values are albedos.
    assert all(0 < v < 1 for row in result["black_sky"] for v in row)
