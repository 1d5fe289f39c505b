import json

import pytest

import roadbrdf


def test_mix_errors(tmp_path):
    bad = tmp_path / "bad.json"
    bad.write_text('{"format": "roadbrdf-formulation", "version": 1, "name": "x", "components": []}')
    with pytest.raises(roadbrdf.InputError):
        roadbrdf.mix(bad)


def _lambert_fit(path, albedo, wavelengths):
    path.write_text(json.dumps({"format": "roadbrdf-fit", "version": 1, "best": "lambert",
                                "fits": [{"model": "lambert", "options": {}, "wavelengths": wavelengths,
                                          "parameters": {"albedo": albedo}}]}))


def test_mix_sigma_weighting_and_residuals(cli, tmp_path):
    # Lambertian end-members and a perturbed mixture with sigma (1 % on two thirds of the values,
    # 10 % on the rest): the weighted and unweighted fits differ; the residual file is the CLI's.
    import math
    wavelengths = [400, 500, 600, 700]
    spectra = {"bitumen": [0.05, 0.06, 0.05, 0.07], "mastic": [0.10, 0.15, 0.12, 0.11],
               "gravel": [0.40, 0.35, 0.50, 0.45]}
    (tmp_path / "fits").mkdir()
    for name, albedo in spectra.items():
        _lambert_fit(tmp_path / "fits" / f"{name}.fit.json", albedo, wavelengths)
    formulation = tmp_path / "F.json"
    formulation.write_text(json.dumps({
        "format": "roadbrdf-formulation", "version": 1, "name": "T",
        "mastic": {"fit": "fits/mastic.fit.json"},
        "components": [
            {"name": "Bitumen", "kind": "binder", "mass_percent": 5, "density_g_cm3": 1.03,
             "fit": "fits/bitumen.fit.json"},
            {"name": "Sand 0/2", "kind": "aggregate", "mass_percent": 40, "density_g_cm3": 2.65, "d_min_mm": 0,
             "d_max_mm": 2, "fit": "fits/mastic.fit.json"},
            {"name": "Gravel 6/10", "kind": "aggregate", "mass_percent": 55, "density_g_cm3": 2.7,
             "d_min_mm": 6, "d_max_mm": 10, "fit": "fits/gravel.fit.json"}]}))
    lines = ["theta_i,phi_i,theta_r,phi_r," + ",".join(map(str, wavelengths)) + ","
             + ",".join(f"sigma_{w}" for w in wavelengths)]
    i = 0
    for ti in (0, 30, 60):
        for tr in (10, 40, 70):
            for pr in (0, 90, 180):
                values = []
                for m in range(4):
                    i += 1
                    rho = 0.1 * spectra["bitumen"][m] + 0.3 * spectra["mastic"][m] + 0.6 * spectra["gravel"][m]
                    values.append(rho / math.pi * (1 + 0.05 * math.sin(2.3 * i)))
                sigmas = [(0.01 if i % 3 else 0.1) * v for v in values]
                lines.append(f"{ti},0,{tr},{pr}," + ",".join(repr(v) for v in values + sigmas))
    data = tmp_path / "mixed.csv"
    data.write_text("\n".join(lines) + "\n")

    weighted = roadbrdf.mix(formulation, data=data, method="fitted", folds=3, residuals=tmp_path / "py-res.csv")
    plain = roadbrdf.mix(formulation, data=data, method="fitted", folds=3, use_sigma=False)
    mw, mp = weighted["methods"][0], plain["methods"][0]
    assert mw["settings"]["sigma_weighted"] == 1.0 and mp["settings"]["sigma_weighted"] == 0.0
    assert abs(mw["weights"]["gravel"] - mp["weights"]["gravel"]) > 1e-6
    assert mw["comparison"]["chi2_reduced"] > 0
    cli("mix", formulation, "--data", data, "--method", "fitted", "--folds", "3", "--residuals",
        tmp_path / "cli-res.csv", "-o", tmp_path / "cli.mix.json")
    assert (tmp_path / "py-res.csv").read_text() == (tmp_path / "cli-res.csv").read_text()
    rows = [r.split(",") for r in (tmp_path / "py-res.csv").read_text().splitlines() if not r.startswith("#")]
    header, body = rows[0], rows[1:]
    residual = [float(r[header.index("residual")]) for r in body]
    rmse = math.sqrt(sum(r * r for r in residual) / len(residual))
    assert rmse == pytest.approx(mw["comparison"]["rmse"], rel=1e-12)
    with pytest.raises(roadbrdf.InputError):
        roadbrdf.mix(formulation, method="areal", residuals=tmp_path / "x.csv")
