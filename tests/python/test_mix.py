import json
import shutil

import pytest

import roadbrdf


def test_mix_through_python_equals_cli(cli, root, tmp_path):
    # Component fits for F2 (Oren-Nayar only: quick), laid out as the formulation expects (../fits/).
    (tmp_path / "fits").mkdir()
    (tmp_path / "formulations").mkdir()
    for name, folder in [("bitumen", "single"), ("soreze-limestone", "single"), ("lazard", "single"),
                         ("mastic-soreze-bitumen", "mastics")]:
        roadbrdf.fit(root / f"data/examples/{folder}/{name}.csv", "oren-nayar",
                     output=tmp_path / "fits" / f"{name}.fit.json")
    formulation = tmp_path / "formulations" / "F2.json"
    shutil.copy(root / "data/examples/formulations/F2.json", formulation)
    from_python = roadbrdf.mix(formulation, method="areal", output=tmp_path / "py.mix.json")
    cli("mix", formulation, "--method", "areal", "-o", tmp_path / "cli.mix.json")
    from_cli = json.loads((tmp_path / "cli.mix.json").read_text())
    assert from_python["methods"][0]["weights"] == from_cli["methods"][0]["weights"]
    # The mixture evaluates as a spectral model, from Python and from the command line.
    m = roadbrdf.read_fit(tmp_path / "py.mix.json", "areal")
    assert m.evaluate(30, 0, 30, 180, 550.0) > 0


def test_mix_errors(tmp_path):
    bad = tmp_path / "bad.json"
    bad.write_text('{"format": "roadbrdf-formulation", "version": 1, "name": "x", "components": []}')
    with pytest.raises(roadbrdf.InputError):
        roadbrdf.mix(bad)
