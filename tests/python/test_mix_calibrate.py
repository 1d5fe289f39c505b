"""roadbrdf.mix_calibrate and mix(cross_sections=...) (docs/mixing.md "Calibrated intimate mixing"): the same
calibration as `roadbrdf mix-calibrate`, the factors used by hapke mixing, errors naming the field."""
import json
import math

import pytest

import roadbrdf


def _lambert_fit(path, albedo, wavelengths):
    path.write_text(json.dumps({"format": "roadbrdf-fit", "version": 1, "best": "lambert",
                                "fits": [{"model": "lambert", "options": {}, "wavelengths": wavelengths,
                                          "parameters": {"albedo": albedo}}]}))


def _setup(tmp_path):
    wavelengths = [400, 500, 600, 700]
    spectra = {"calcite": [0.80, 0.85, 0.88, 0.90], "chlorite": [0.10, 0.20, 0.15, 0.30],
               "epidote": [0.30, 0.25, 0.40, 0.45]}
    (tmp_path / "fits").mkdir()
    for name, albedo in spectra.items():
        _lambert_fit(tmp_path / "fits" / f"{name}.fit.json", albedo, wavelengths)
    pairs = []
    for name, parts in (("A", {"calcite": 60, "chlorite": 40}), ("B", {"calcite": 30, "epidote": 70}),
                        ("C", {"chlorite": 50, "epidote": 50})):
        f = tmp_path / f"{name}.json"
        f.write_text(json.dumps({"format": "roadbrdf-formulation", "version": 1, "name": name, "components": [
            {"name": n, "kind": "aggregate", "mass_percent": wt, "density_g_cm3": 2.7, "d_min_mm": 0.075,
             "d_max_mm": 0.15, "fit": f"fits/{n}.fit.json"} for n, wt in parts.items()]}))
        # A measured mixture: the linear mixture of the albedos (not a hapke mixture: the fit is a compromise).
        lines = ["theta_i,phi_i,theta_r,phi_r," + ",".join(map(str, wavelengths))]
        for ti in (0, 30, 60):
            rho = [sum(wt / 100 * spectra[n][m] for n, wt in parts.items()) for m in range(4)]
            lines.append(f"{ti},0,10,0," + ",".join(repr(r / math.pi) for r in rho))
        d = tmp_path / f"{name}.csv"
        d.write_text("\n".join(lines) + "\n")
        pairs.append((f, d))
    return pairs


def test_mix_calibrate_matches_the_cli_and_feeds_mix(cli, tmp_path):
    pairs = _setup(tmp_path)
    cal = roadbrdf.mix_calibrate(pairs, reference="calcite", output=tmp_path / "py-cal.json")
    assert cal["reference"] == "calcite" and cal["factors"]["calcite"] == 1.0
    assert set(cal["factors"]) == {"calcite", "chlorite", "epidote"}
    assert sum(x * x for x in cal["rms_calibrated"]) < sum(x * x for x in cal["rms_uncalibrated"])
    cli("mix-calibrate", *[p for pair in pairs for p in pair], "--reference", "calcite", "-o", tmp_path / "cli-cal.json")
    file = json.loads((tmp_path / "cli-cal.json").read_text())
    for e in file["end_members"]:
        assert e["cross_section_factor"] == cal["factors"][e["name"]]
    assert json.loads((tmp_path / "py-cal.json").read_text())["end_members"] == file["end_members"]
    result = roadbrdf.mix(pairs[0][0], method="hapke", cross_sections=tmp_path / "cli-cal.json")
    settings = result["methods"][0]["settings"]
    assert settings["cross_section_factor.chlorite"] == cal["factors"]["chlorite"]


def test_mix_calibrate_errors(tmp_path):
    pairs = _setup(tmp_path)
    with pytest.raises(roadbrdf.InputError, match="reference"):
        roadbrdf.mix_calibrate(pairs, reference="granite")
    with pytest.raises(roadbrdf.InputError, match="mixtures"):
        roadbrdf.mix_calibrate([])
    with pytest.raises(roadbrdf.InputError, match="cross_sections"):
        roadbrdf.mix(pairs[0][0], method="areal", cross_sections=tmp_path / "none.json")
