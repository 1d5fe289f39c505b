"""roadbrdf plot lighting: the plan of an installation draws the luminance map of roadbrdf lighting as computed."""

import json
import pathlib

import matplotlib
import numpy as np
import pytest

matplotlib.use("Agg")

import roadbrdf  # noqa: E402
import roadbrdf.plot  # noqa: E402

DATA = pathlib.Path(__file__).resolve().parents[1] / "data" / "lighting"


def test_plan_draws_the_computed_luminances(cli, tmp_path):
    result_file = tmp_path / "r3.json"
    run = cli("lighting", DATA / "installation-r3.json", "--json", check=False)
    if "cannot be read yet" in run.stderr:
        pytest.skip("the luminaire file reader is not merged into this branch yet")
    assert run.returncode == 0, run.stderr
    result_file.write_text(run.stdout)
    value = json.loads(run.stdout)
    figure = roadbrdf.plot.lighting(result_file, lane=2)
    np.testing.assert_array_equal(figure.roadbrdf_data["L_cd_m2"], np.asarray(value["grid"]["L_cd_m2"][1]))
    assert len(figure.roadbrdf_data["luminaires_m"]) == len(value["luminaires_m"]) > 0
    out = tmp_path / "plan.png"
    cli("plot", "lighting", result_file, "-o", out, "--lane", "1")
    assert out.stat().st_size > 0
    with pytest.raises(ValueError, match="lane"):
        roadbrdf.plot.lighting(value, lane=4)
