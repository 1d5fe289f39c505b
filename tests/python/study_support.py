"""Helpers of the design-study tests: Lambertian fit files and a small physical study."""

import json


def lambert_fit(path, albedo, wavelengths=(400, 550, 700, 900)):
    path.write_text(json.dumps({"format": "roadbrdf-fit", "version": 1, "best": "lambert",
                                "fits": [{"model": "lambert", "options": {}, "wavelengths": list(wavelengths),
                                          "parameters": {"albedo": [albedo] * len(wavelengths)}}]}))
    return path


def physical_study(folder, shares=(0.0, 0.5, 1.0), mastic=(0.2, 0.4), rtable=True, samples=16):
    """A binder + sand mastic (Lambert 0.05) around grey 2/6 grains (Lambert 0.3), part of which a share moves
    to a light rock (Lambert 0.6); tiny virtual samples (12 mm, 0.4 mm cells) so that it runs in seconds."""
    (folder / "fits").mkdir(parents=True, exist_ok=True)
    lambert_fit(folder / "fits" / "mastic.fit.json", 0.05)
    lambert_fit(folder / "fits" / "grey.fit.json", 0.3)
    lambert_fit(folder / "fits" / "light.fit.json", 0.6)
    (folder / "base.json").write_text(json.dumps({
        "format": "roadbrdf-formulation", "version": 1, "name": "virtual", "mastic": {"fit": "fits/mastic.fit.json"},
        "components": [
            {"name": "Binder", "kind": "binder", "mass_percent": 5, "density_g_cm3": 1.03,
             "fit": "fits/mastic.fit.json"},
            {"name": "Sand 0/2", "kind": "aggregate", "mass_percent": 35, "density_g_cm3": 2.65, "d_min_mm": 0,
             "d_max_mm": 2, "fit": "fits/mastic.fit.json"},
            {"name": "Grey 2/6", "kind": "aggregate", "mass_percent": 60, "density_g_cm3": 2.65, "d_min_mm": 2,
             "d_max_mm": 6, "fit": "fits/grey.fit.json"}]}))
    study = folder / "study.json"
    study.write_text(json.dumps({
        "format": "roadbrdf-study", "version": 1, "name": "virtual", "base": "base.json",
        "library": {"light": {"fit": "fits/light.fit.json"}},
        "variables": [{"name": "light_share", "kind": "share", "component": "Grey 2/6", "material": "light",
                       "values": list(shares)},
                      {"name": "mastic", "kind": "mastic_fraction", "values": list(mastic)}],
        "predictions": {"path": "physical", "sun_zenith_deg": [30], "diffuse_fraction": 0.2,
                        "physical": {"size_mm": 12, "cell_mm": 0.4, "samples": samples, "wavelengths": [550],
                                     "white_sky_nodes": 2, "rtable": rtable}}}))
    return study


def store_keys(path):
    """Keys of the records of a results store (after its header line), in file order."""
    lines = path.read_text().splitlines()
    return [json.loads(line)["key"] for line in lines[1:]]
