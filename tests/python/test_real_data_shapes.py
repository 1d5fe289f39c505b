"""Real-data shapes through Python and the command line alike: rows at exactly 90 deg left out of a fit
with the same note, the nested-model flag in the totals, and the check report's repeatability and
plausibility warnings."""
import numpy as np

import roadbrdf


def _lambert_with_grazing_rows(path):
    rows = ["theta_i,phi_i,theta_r,phi_r,500,600"]
    for ti in (0, 20, 40, 60, 80):
        for tr in (0, 20, 40, 60, 80):
            for dphi in (0, 180) if ti and tr else (0,):  # the azimuth of the normal is undefined
                v = 0.3 / np.pi
                rows.append(f"{ti},0,{tr},{dphi},{v!r},{v!r}")
    rows += ["90,0,90,0,0,0", "90,0,30,180,0,0", "45,0,90,180,0,0"]
    path.write_text("\n".join(rows) + "\n")
    return path


def test_grazing_rows_are_left_out_with_the_same_note(cli, tmp_path):
    data = _lambert_with_grazing_rows(tmp_path / "grazing.csv")
    result = roadbrdf.fit(data, ["oren-nayar", "lambert"])
    notes = [n for n in result.notes if "direction at 90 deg" in n]
    assert len(notes) == 1
    assert notes[0].startswith("3 of 44 geometries have a direction at 90 deg")
    printed = cli("fit", data, "-m", "oren-nayar", "-m", "lambert", "-o", tmp_path / "f.json").stderr
    assert f"roadbrdf: note: {notes[0]}" in printed
    for f in result["fits"]:
        # albedo of the data (Oren-Nayar at sigma = 0 is Lambert): closed form 0.3
        assert abs(f["parameters"]["albedo"][0] - 0.3) < 1e-4
        assert f["worse_than_nested"] == []


def test_check_reports_repeatability_and_a_too_dark_scale(tmp_path):
    path = tmp_path / "dark_dup.csv"
    rows = ["theta_i,phi_i,theta_r,phi_r,500,600"]
    for ti in (0, 20, 40, 60):
        for tr in (10, 30, 50):
            rows.append(f"{ti},0,{tr},180,2e-5,2e-5")
    rows.append("20,0,30,180,3e-5,2e-5")  # a repeat of one geometry: spread 1e-5 / 2.5e-5 at 500 nm
    path.write_text("\n".join(rows) + "\n")
    report = roadbrdf.check(path, average_duplicates=True)
    rep = report["repeatability"]
    assert rep["duplicated_geometries"] == 1
    assert abs(rep["max_relative_spread"][0] - 1e-5 / 2.5e-5) < 1e-12
    assert rep["max_relative_spread"][1] == 0.0
    warnings = report["plausibility"]["warnings"]
    assert any("below 0.005" in w for w in warnings)
    assert "warning: the Lambertian-equivalent albedo" in report["text"]
