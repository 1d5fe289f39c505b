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
