"""Single-band fits are first class in Python and the figures. References: Lambert
closed forms (every albedo equals rho, Q0 = rho / pi)."""
import json
import math

import pytest

import roadbrdf
import roadbrdf.plot as rplot


def lambert_fit(path, wavelengths, rho):
    path.write_text(json.dumps({"format": "roadbrdf-fit", "version": 1, "best": "lambert",
                                "fits": [{"model": "lambert", "options": {}, "wavelengths": wavelengths,
                                          "parameters": {"albedo": rho}}]}))
    return path


def test_albedo_of_a_single_band_fit(tmp_path):
    fit = lambert_fit(tmp_path / "f.json", [550.0], [0.3])
    a = roadbrdf.albedo(fit, sun_zenith=[0, 45], illuminant="D65")
    assert a["white_sky"][0] == pytest.approx(0.3, abs=1e-9)
    assert a["black_sky"][1][0] == pytest.approx(0.3, abs=1e-9)
    assert a["broadband"] is None and a["luminous"] is None
    assert any("single-band fit (550 nm)" in n for n in a["notes"])


def test_rtable_of_a_single_band_fit_uses_its_band(tmp_path):
    fit = lambert_fit(tmp_path / "f.json", [550.0], [0.3])
    t = roadbrdf.rtable(fit)
    assert t["Q0"] == pytest.approx(0.3 / math.pi, abs=1e-9)
    assert "single-band" in t["note"]
    assert roadbrdf.rtable(fit, wavelength=550.0)["note"] is None
    few = lambert_fit(tmp_path / "few.json", [450.0, 550.0, 650.0], [0.2, 0.3, 0.4])
    with pytest.raises(roadbrdf.InputError, match="choose one band with `wavelength` NM"):
        roadbrdf.rtable(few)
    assert roadbrdf.rtable(few, wavelength=650.0)["Q0"] == pytest.approx(0.4 / math.pi, abs=1e-9)


def test_figures_of_a_single_band_fit(tmp_path, cli):
    fit = lambert_fit(tmp_path / "f.json", [550.0], [0.3])
    fig = rplot.albedo(roadbrdf.albedo(fit), output=tmp_path / "a.png")
    assert fig.roadbrdf_data["broadband"] is None and (tmp_path / "a.png").stat().st_size > 5000
    fig = rplot.rtable(fit, output=tmp_path / "r.png")
    assert fig.roadbrdf_data["Q0"] == pytest.approx(0.3 / math.pi, abs=1e-9)
    few = lambert_fit(tmp_path / "few.json", [450.0, 550.0, 650.0], [0.2, 0.3, 0.4])
    cli("plot", "rtable", few, "--wavelength", "450", "-o", tmp_path / "r450.png")
    assert (tmp_path / "r450.png").stat().st_size > 5000
    report = tmp_path / "albedo.json"
    report.write_text(cli("albedo", fit, "--json").stdout)
    cli("plot", "albedo", report, "-o", tmp_path / "a2.png")
    assert (tmp_path / "a2.png").stat().st_size > 5000
