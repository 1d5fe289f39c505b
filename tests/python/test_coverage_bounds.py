"""Coverage, extrapolation and non-physical flags in Python and on the command line, and fit bounds
within the physical range. References: closed forms for a Lambertian surface measured
in the principal plane only (4 azimuth sectors of 5 deg of 360 are covered) and the model metadata."""
import json
import math

import pytest

import roadbrdf


def principal_plane(path):
    with open(path, "w") as f:
        f.write("theta_i,phi_i,theta_r,phi_r,550\n")
        for ti in range(0, 61, 10):
            for tr in range(5, 46, 10):
                for pr in (0, 180):
                    f.write(f"{ti},0,{tr},{pr},{0.3 / math.pi * (1 + 0.01 * math.sin(ti + tr + pr)):.8f}\n")
    return path


def test_fit_records_coverage_and_albedo_and_rtable_report_it(tmp_path, cli):
    data = principal_plane(tmp_path / "pp.csv")
    r = roadbrdf.fit(data, "lambert", output=tmp_path / "f.json")
    cov = r.best.totals["coverage"]
    assert cov["theta_i_deg"] == pytest.approx([0, 60]) and cov["theta_r_deg"] == pytest.approx([5, 45])
    assert cov["azimuth_planes_deg"] == [0, 180] and cov["geometries"] == 70
    assert json.loads((tmp_path / "f.json").read_text())["fits"][0]["coverage"]["geometries"] == 70
    with pytest.warns(UserWarning, match="mostly extrapolation"):
        a = roadbrdf.albedo(tmp_path / "f.json", sun_zenith=[30])
    # theta_r covered to 50 deg, 1/18 of the azimuths, plus the cap theta_r <= 5 deg (4 or 6 on the 2-deg grid)
    to50 = math.sin(math.radians(50)) ** 2
    outside = [1 - (c + (to50 - c) / 18) for c in (math.sin(math.radians(6)) ** 2, math.sin(math.radians(4)) ** 2)]
    assert outside[0] - 1e-3 <= a["coverage"]["black_sky_outside_fraction"][0] <= outside[1] + 1e-3
    with pytest.warns(UserWarning, match="mostly extrapolation"):
        t = roadbrdf.rtable(tmp_path / "f.json")
    assert t["coverage"]["cells_outside"] == 580 and t["coverage"]["negative_cells"] == 0
    # The command line: the same numbers in the JSON, the warnings on standard error.
    out = cli("rtable", tmp_path / "f.json", "--json")
    assert json.loads(out.stdout)["coverage"]["cells_outside"] == 580
    assert "warning: mostly extrapolation" in out.stderr
    out = cli("albedo", tmp_path / "f.json", "--json")
    assert "warning: mostly extrapolation" in out.stderr
    assert json.loads(out.stdout)["coverage"]["geometries"] == 70


def test_model_without_coverage_has_none(tmp_path):
    a = roadbrdf.albedo(roadbrdf.Model("lambert"), {"albedo": 0.3})
    assert a["coverage"] is None


def test_bounds_within_the_physical_range(tmp_path, cli):
    data = principal_plane(tmp_path / "pp.csv")
    (p,) = [q for q in roadbrdf.Model("retro-phong").parameters if q["name"] == "n"]
    assert (p["lower"], p["upper"]) == (0, 1000) and p["physical_bounds"] == [0, 1e6]
    with pytest.raises(roadbrdf.InputError, match=r"bounds\.n: .*physical range \[0, 1000000\]"):
        roadbrdf.fit(data, "retro-phong", bounds={"n": (0, 2e6)})
    r = cli("fit", data, "-m", "retro-phong", "--bounds", "n=0:2e6", "-o", tmp_path / "x.json", check=False)
    assert r.returncode == 2 and "--bound n" in r.stderr and "physical range" in r.stderr
    # Wider than the default fitting range is accepted, and written to the fit file.
    fit = roadbrdf.fit(data, "retro-phong", bounds={"n": (0, 5e3)}, fixed={"k1": 0.1, "k2": 0.01, "k3": 0.001,
                                                                            "k4": 1.0})
    assert fit.to_dict()["fits"][0]["bounds"] == {"n": [0, 5000]}
