"""Helpers of the design-study tests: Lambertian fit files, a small fast study, a small physical study."""

import json


def lambert_fit(path, albedo, wavelengths=(400, 550, 700, 900)):
    path.write_text(json.dumps({"format": "roadbrdf-fit", "version": 1, "best": "lambert",
                                "fits": [{"model": "lambert", "options": {}, "wavelengths": list(wavelengths),
                                          "parameters": {"albedo": [albedo] * len(wavelengths)}}]}))
    return path


def two_rock_study(tmp_path, design=None, variables=None):
    """Two coarse Lambertian rocks (no binder, no mastic): the areal mixture is a Lambertian of albedo
    sum a_k rho_k with a_k proportional to M_k / (rho_k D_k) (docs/mixing.md)."""
    (tmp_path / "fits").mkdir(exist_ok=True)
    lambert_fit(tmp_path / "fits" / "grey.fit.json", 0.3)
    lambert_fit(tmp_path / "fits" / "dark.fit.json", 0.1)
    lambert_fit(tmp_path / "fits" / "light.fit.json", 0.6)
    (tmp_path / "base.json").write_text(json.dumps({
        "format": "roadbrdf-formulation", "version": 1, "name": "two rocks",
        "components": [
            {"name": "Grey 2/6", "kind": "aggregate", "mass_percent": 40, "density_g_cm3": 2.65, "d_min_mm": 2,
             "d_max_mm": 6, "fit": "fits/grey.fit.json"},
            {"name": "Other 6/10", "kind": "aggregate", "mass_percent": 60, "density_g_cm3": 2.7, "d_min_mm": 6,
             "d_max_mm": 10, "fit": "fits/dark.fit.json"}]}))
    study = {"format": "roadbrdf-study", "version": 1, "name": "two rocks", "base": "base.json",
             "library": {"dark": {"fit": "fits/dark.fit.json"},
                         "light": {"fit": "fits/light.fit.json", "density_g_cm3": 2.5}},
             "variables": variables if variables is not None else [
                 {"name": "grey", "kind": "mass_percent", "component": "Grey 2/6", "values": [20, 50, 80],
                  "balance": "Other 6/10"},
                 {"name": "rock", "kind": "component", "component": "Other 6/10", "choices": ["dark", "light"]}],
             "design": design or {"type": "grid"},
             "predictions": {"path": "fast", "methods": ["areal"], "sun_zenith_deg": [0, 60],
                             "diffuse_fraction": 0.25}}
    path = tmp_path / "study.json"
    path.write_text(json.dumps(study))
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


def buggy_run_task(task, fits):
    """evaluate.run_task with a bug (a ZeroDivisionError) in the candidates where Grey 2/6 makes up 50 % of the
    mass: a module-level function, so that local worker processes started by fork or by a fork server can run
    it."""
    from roadbrdf.studies import evaluate
    from roadbrdf.studies.worker import guarded

    def run(task, fits):
        if any(c["name"] == "Grey 2/6" and c["mass_percent"] == 50 for c in task["formulation"]["components"]):
            return 1 / 0
        return evaluate._run(task, fits)
    return guarded(run, task, fits)


def candidate_file(task, fits, folder, name="candidate.json"):
    """A task's candidate formulation written as the file ``name`` in ``folder``, its fit files (``fits``: SHA-256
    -> text) beside it as ``<digest>.json``: the path through files that the tests compare the study's values
    with."""
    from roadbrdf.studies import evaluate
    folder.mkdir(parents=True, exist_ok=True)
    for digest, text in fits.items():
        if not (folder / (digest + ".json")).exists():  # once: a rewritten file is read again by the cache
            (folder / (digest + ".json")).write_text(text)
    path = folder / name
    path.write_text(json.dumps(evaluate._materialise(task["formulation"])))
    return str(path)
