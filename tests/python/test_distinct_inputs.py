"""Every file a command reads through another file (a formulation's component fits, a manifest's
instrument files) is an input that no output may replace: the library lists them
(formulation_input_files, manifest_input_files) and `roadbrdf report` checks its output against them."""
import os
import pathlib
import shutil
import subprocess

import pytest

import roadbrdf
from roadbrdf import _roadbrdf
from roadbrdf.report import write_report

ROOT = pathlib.Path(__file__).resolve().parents[2]
LAMBERT_FIT = ('{"format": "roadbrdf-fit", "version": 1, "best": "lambert", "fits": [{"model": "lambert", '
               '"options": {}, "wavelengths": [400, 500, 600, 700, 800], '
               '"parameters": {"albedo": [0.2, 0.25, 0.3, 0.3, 0.3]}}]}')
FORMULATION = ('{"format": "roadbrdf-formulation", "version": 1, "name": "T", "components": [{"name": "Grey", '
               '"kind": "binder", "mass_percent": 100, "density_g_cm3": 1.0, "fit": "lambert.fit.json"}]}')


@pytest.fixture
def folder(tmp_path):
    shutil.copy(ROOT / "tests" / "data" / "io" / "wide_small.csv", tmp_path / "data.csv")
    (tmp_path / "lambert.fit.json").write_text(LAMBERT_FIT)
    (tmp_path / "F.json").write_text(FORMULATION)
    return tmp_path


def _contents(folder):
    return {p.name: p.read_bytes() for p in folder.iterdir()}


def test_formulation_input_files_lists_the_component_fits(folder):
    assert _roadbrdf.formulation_input_files(str(folder / "F.json")) == [
        ("fit of component 'Grey'", str(folder / "lambert.fit.json"))]


def test_manifest_input_files_lists_every_entry(instruments):
    files = _roadbrdf.manifest_input_files(str(instruments / "run.csv"))
    assert [os.path.basename(path) for _, path in files] == [
        "run_white.asd", "run_dark.asd", "run_001.asd", "run_002.asd", "run_003.asd"]
    assert files[0][0].startswith("white reference file 'run_white.asd'")


def test_report_refuses_to_replace_a_component_fit(folder, cli):
    before = _contents(folder)
    result = cli("report", folder / "data.csv", "--model", "lambert", "--formulation", folder / "F.json",
                 "-o", folder / "lambert.fit.json", check=False)
    assert result.returncode == 2, result.stderr
    assert (f"-o '{folder / 'lambert.fit.json'}' is the same file as the input fit of component 'Grey'"
            in result.stderr), result.stderr
    assert "Traceback" not in result.stderr
    assert _contents(folder) == before
    with pytest.raises(roadbrdf.InputError, match="fit of component 'Grey'"):
        write_report(folder / "data.csv", folder / "lambert.fit.json", models=["lambert"],
                     formulation=str(folder / "F.json"))
    assert _contents(folder) == before
