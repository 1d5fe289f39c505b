"""Campaign fitting (`roadbrdf study CAMPAIGN.json`): every sample fitted as `roadbrdf fit` + `roadbrdf params`
would, failures recorded per sample, re-runs free, errors naming the file and the JSON key."""
import csv
import io
import json
import os
import shutil

import pandas
import pytest

import roadbrdf
from roadbrdf.studies import campaign as campaign_module

SAMPLES = ("garonne", "lazard")
FIT = {"models": ["lambert", "oren-nayar"], "wavelengths": "450:650:100"}


def _campaign(tmp_path, root, samples=SAMPLES, fit=FIT, **extra):
    folder = tmp_path / "samples"
    folder.mkdir(exist_ok=True)
    for s in samples:
        shutil.copy(root / "data" / "examples" / "single" / f"{s}.csv", folder / f"{s}.csv")
    path = tmp_path / "campaign.json"
    path.write_text(json.dumps({"format": "roadbrdf-campaign", "version": 1, "samples": "samples", "fit": fit,
                                **extra}))
    return path


def _csv(text):
    return list(csv.reader(io.StringIO(text)))


def _without_timing(text):
    content = json.loads(text)
    for f in content["fits"]:
        f.pop("seconds", None)
        f.pop("cpu_seconds", None)
    return content


def test_rows_are_those_of_fit_and_params(cli, root, tmp_path):
    fits = tmp_path / "fits"
    fits.mkdir()
    path = _campaign(tmp_path, root, fits_folder="fits")
    out = tmp_path / "params.csv"
    r = cli("study", path, "-o", out, "--workers", "2")
    assert "campaign 'campaign': 2 samples, 0 already in the store, 2 to compute" in r.stderr
    table = _csv(out.read_text())
    header, rows = table[0], table[1:]
    assert header[:4] == ["sample", "key", "status", "error"]
    assert "albedo [1]" in header and "sigma [rad]" in header and "sigma_stderr [rad]" in header
    for sample in SAMPLES:
        direct = tmp_path / f"{sample}.direct.json"
        cli("fit", root / "data" / "examples" / "single" / f"{sample}.csv", "--model", "lambert", "--model", "oren-nayar",
            "--wavelengths", "450:650:100", "-o", direct)
        # The fit file of the campaign is the one `roadbrdf fit -o` writes (apart from its timing).
        assert _without_timing((fits / f"{sample}.fit.json").read_text()) == _without_timing(direct.read_text())
        params = pandas.read_csv(io.StringIO(cli("params", direct, "--format", "csv").stdout), comment="#")
        mine = [dict(zip(header, row)) for row in rows if row[0] == sample]
        assert len(mine) == len(params) == 6  # 2 models x 3 wavelengths
        for row, (_, p) in zip(mine, params.iterrows()):
            assert row["status"] == "ok" and row["model"] == p["model"]
            assert float(row["wavelength_nm"]) == p["wavelength_nm"]
            for name in ("albedo", "albedo_stderr"):
                assert float(row[f"{name} [1]"]) == pytest.approx(p[name], rel=1e-9)
            if p["model"] == "oren-nayar":
                assert float(row["sigma [rad]"]) == pytest.approx(p["sigma"], rel=1e-9)
            else:
                assert row["sigma [rad]"] == ""  # a parameter the row's model lacks stays empty
            assert float(row["bic"]) == pytest.approx(p["bic"], rel=1e-9)
    # A re-run computes nothing and writes the same table.
    before = out.read_text()
    r = cli("study", path, "-o", out)
    assert "2 already in the store, 0 to compute" in r.stderr
    assert out.read_text() == before


def test_python_list_of_samples_with_attributes(root, tmp_path):
    data = root / "data" / "examples" / "single"
    rows = roadbrdf.study({"format": "roadbrdf-campaign", "version": 1, "fit": {"models": "lambert",
                                                                                 "wavelengths": [550]},
                           "samples": [{"data": str(data / "garonne.csv"), "name": "G", "attributes": {"site": "A"}},
                                       {"data": str(data / "lazard.csv"), "attributes": {"site": "B", "age": 3}}]},
                          progress=False)
    assert [(r["sample"], r["site"], r["age"]) for r in rows] == [("G", "A", None), ("lazard", "B", 3)]
    assert all(r["status"] == "ok" and r["model"] == "lambert" for r in rows)


def test_a_failing_sample_is_recorded_and_the_others_fitted(cli, root, tmp_path):
    path = _campaign(tmp_path, root)
    (tmp_path / "samples" / "broken.csv").write_text("theta_i,phi_i,theta_r,phi_r,550\n30,0,oops,180,0.1\n")
    out = tmp_path / "params.csv"
    r = cli("study", path, "-o", out)
    assert "1 failed" in r.stderr
    rows = [dict(zip(t[0], row)) for t in [_csv(out.read_text())] for row in t[1:]]
    broken = [row for row in rows if row["sample"] == "broken"]
    assert len(broken) == 1 and broken[0]["status"] == "failed"
    assert "broken.csv:2:" in broken[0]["error"]  # file and line of the bad value
    assert {row["sample"] for row in rows if row["status"] == "ok"} == set(SAMPLES)


def test_settings_errors_name_the_file_and_key(cli, root, tmp_path):
    path = _campaign(tmp_path, root, fit={"modles": ["lambert"]})
    r = cli("study", path, "-o", tmp_path / "out.csv", check=False)
    assert r.returncode == 2
    assert f"{path}: fit.modles: unknown key" in r.stderr
    path = _campaign(tmp_path, root, fit={"models": ["lambert"], "wavelengths": "1:2:0"})
    # The same bad setting for every sample is the campaign's error, not a table of failures.
    r = cli("study", path, "-o", tmp_path / "out.csv", check=False)
    assert r.returncode == 2 and "every sample failed" in r.stderr and "wavelengths" in r.stderr
    assert not (tmp_path / "out.csv").exists()
    with pytest.raises(roadbrdf.InputError, match=r"campaign: samples\[0\].data: cannot read"):
        roadbrdf.study({"format": "roadbrdf-campaign", "version": 1, "fit": {"models": "lambert"},
                        "samples": [{"data": str(tmp_path / "missing.csv")}]}, progress=False)


def test_a_worker_without_the_file_fits_the_shipped_bytes(root, tmp_path):
    """A Dask worker on another machine gets the dataset's bytes (texts_of) instead of the path."""
    path = _campaign(tmp_path, root, samples=("garonne",))
    c = campaign_module.read_campaign(path)
    (_, _, key, task), = campaign_module.make_tasks(c, roadbrdf.__version__)
    texts = campaign_module.texts_of(c)
    here = campaign_module.fit_sample(task, None)
    os.rename(task["path"], str(task["path"]) + ".moved")
    away = campaign_module.fit_sample(task, texts)
    assert here["error"] is None and away["rows"] == here["rows"]
    lost = campaign_module.fit_sample(task, None)
    assert "changed or unreadable since the campaign started" in lost["error"]
