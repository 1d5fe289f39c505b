"""The design studies' fast path in process (studies/evaluate.py, mixing/end_member_cache.h) against the path it
replaces: ``roadbrdf.mix`` writing MIX.json, read back for ``roadbrdf.albedo`` and ``roadbrdf.rtable``."""

import json

import roadbrdf
from roadbrdf.studies import evaluate
from roadbrdf.studies.run import make_tasks
from roadbrdf.studies.spec import read_study
from study_support import candidate_file
from test_study import two_rock_study


def oren_nayar_fit(path, albedo, sigma, wavelengths=(400, 550, 700, 900)):
    path.write_text(json.dumps({"format": "roadbrdf-fit", "version": 1, "best": "oren-nayar",
                                "fits": [{"model": "oren-nayar", "options": {"form": "full"},
                                          "wavelengths": list(wavelengths),
                                          "parameters": {"albedo": [albedo + 0.05 * i for i in range(len(wavelengths))],
                                                         "sigma": [sigma] * len(wavelengths)}}]}))


def through_mix_file(task, path, work):
    """The former fast path of evaluate.py: MIX.json written and read back per method."""
    p = task["predictions"]
    rows = []
    for method in p["methods"]:
        mix_path = str(work / f"{method}.mix.json")
        roadbrdf.mix(path, method=method, output=mix_path)
        model = roadbrdf.read_fit(mix_path, method)
        a = roadbrdf.albedo(model, sun_zenith=p["sun_zenith_deg"], diffuse_fraction=p["diffuse_fraction"],
                            atmosphere=p["atmosphere"], spectrum=p["spectrum"])
        row = {"method": method}
        row.update(evaluate._albedo_outputs(a, p["sun_zenith_deg"]))
        row.update(evaluate._rtable_outputs(roadbrdf.rtable(model, illuminant=p["illuminant"])))
        rows.append(row)
    return rows


def test_in_process_fast_path_matches_the_mix_file_path(tmp_path):
    study_path = two_rock_study(tmp_path)
    # Rough (Oren-Nayar) rocks, so that the quadratures have something to refine; areal (linear) and hapke.
    oren_nayar_fit(tmp_path / "fits" / "grey.fit.json", 0.25, 0.4)
    oren_nayar_fit(tmp_path / "fits" / "dark.fit.json", 0.08, 0.2)
    oren_nayar_fit(tmp_path / "fits" / "light.fit.json", 0.5, 0.3)
    s = read_study(str(study_path))
    s.predictions["methods"] = ["areal", "hapke"]
    tasks = make_tasks(s, roadbrdf._roadbrdf.__version__)
    evaluate._END_MEMBERS = None
    for number, (*_, task) in enumerate(tasks):
        work = tmp_path / f"task{number}"
        work.mkdir()
        path = candidate_file(task, s.fits, tmp_path / "candidates", f"task{number}.json")
        for before, now in zip(through_mix_file(task, path, work), evaluate._fast(task, path)):
            linear = before["method"] == "areal"
            for key, value in before.items():
                if key.endswith("_error"):
                    continue
                if key in ("method", "class", "Q0", "S1", "Qd") or not linear:
                    assert now[key] == value, (before["method"], key)  # the same numbers, bit for bit
                else:
                    # The end-members' integrals combined: within both quadratures' error estimates.
                    bound = before[key + "_error"] + now[key + "_error"]
                    assert abs(now[key] - value) <= bound, (key, now[key], value, bound)
    # Each fit file read once in this process, whatever the number of candidates and methods.
    assert evaluate._END_MEMBERS.fits_read == len(s.fits)
