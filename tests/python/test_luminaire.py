"""roadbrdf.luminaire (the request contract's Result), `roadbrdf luminaire --json` (the same JSON), and the
figure `roadbrdf plot luminaire` (the data behind it), on the synthetic files of tests/data/lighting, whose
intensities follow closed forms (make_synthetic.py there):
  I(C, gamma) = (200 + 40 g(C)) (1 + gamma / 90) [cd/klm], lamp flux 2000 lm, LORL 80 %.
The rotational file (g = 0) is linear in gamma between its angles, so its flux is exact in closed form:
  Phi = 2 pi 2 [cd/(cd/klm)] 200 int_0^pi (1 + 2 gamma / pi) sin(gamma) d gamma = 2 pi 400 (2 + 2) = 3200 pi,
downward 2 pi 400 (1 + 2 / pi)."""
import json
import math
import warnings

import matplotlib.pyplot as plt
import numpy as np
import pytest

import roadbrdf
from roadbrdf import plot as rplot


@pytest.fixture(autouse=True)
def close_figures():
    yield
    plt.close("all")


@pytest.fixture
def lighting_data(root):
    return root / "tests" / "data" / "lighting"


def test_rotational_file_flux_and_ratios_in_closed_form(lighting_data):
    with pytest.warns(roadbrdf.RoadbrdfWarning, match="differs by"):
        r = roadbrdf.luminaire(lighting_data / "isym1.ldt")
    assert isinstance(r, roadbrdf.Result)
    assert r["integrated_flux_lm"] == pytest.approx(3200 * math.pi, rel=1e-12)
    assert r["downward_flux_lm"] == pytest.approx(2 * math.pi * 400 * (1 + 2 / math.pi), rel=1e-12)
    assert r["dlor"] == pytest.approx(r["downward_flux_lm"] / 2000.0, rel=1e-12)
    assert r["ulor"] == pytest.approx(r["upward_flux_lm"] / 2000.0, rel=1e-12)
    # The header says 2000 lm x 80 %: the integral disagrees, a structured warning says so.
    assert [w.kind for w in r.warnings] == ["flux_mismatch"]
    assert r["header_flux_lm"] == pytest.approx(1600.0)
    assert r["symmetry"] == "rotational"
    assert r["max_intensity_cd"] == pytest.approx(200 * 3 * 2.0)  # gamma 180: (1 + 2) x 200 cd/klm x 2 klm
    assert r["max_intensity_direction_deg"]["gamma"] == 180
    assert "maximum intensity" in r.summary


def test_principal_planes_in_cd_per_klm(lighting_data):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", roadbrdf.RoadbrdfWarning)
        r = roadbrdf.luminaire(str(lighting_data / "isym3.ldt"))  # symmetric about C90-C270: g = sin C
    planes = r["principal_planes"]
    gamma = np.array(planes["gamma_deg"])
    for name, g in (("C0", 0.0), ("C90", 1.0), ("C180", 0.0), ("C270", -1.0)):
        np.testing.assert_allclose(planes[name], (200 + 40 * g) * (1 + gamma / 90), rtol=1e-9)
    assert planes["unit"] == "cd/klm"


def test_cli_json_is_the_result_value(lighting_data, cli):
    path = lighting_data / "quadrants_2002.ies"
    out = cli("luminaire", path, "--json")
    value = json.loads(out.stdout)
    with pytest.warns(roadbrdf.RoadbrdfWarning, match="exceeds the lamps"):
        r = roadbrdf.luminaire(path)
    assert value == json.loads(r.to_json())
    assert value["symmetry"] == "quadrants"
    assert value["format"] == "ies"
    text = cli("luminaire", path).stdout
    assert text == r.summary


def test_errors_name_file_and_line_and_the_argument(lighting_data, tmp_path, cli):
    bad = tmp_path / "bad.ies"
    bad.write_text("IESNA:LM-63-2002\nTILT=NONE\n1 1000 1 3 1 2 2 0 0 0\n1 1 10\n0 45 90\n0\n1 2 3\n")
    with pytest.raises(roadbrdf.InputError, match=r"bad.ies:3:.*photometric type B"):
        roadbrdf.luminaire(bad)
    result = cli("luminaire", bad, check=False)
    assert result.returncode == 2
    assert "bad.ies:3:" in result.stderr and "photometric type B" in result.stderr
    with pytest.raises(TypeError, match="did you mean 'file'"):
        roadbrdf.luminaire(fil=bad)
    with pytest.raises(roadbrdf.InputError, match="file"):
        roadbrdf.luminaire(3)


def test_polar_figure_data_and_file(lighting_data, tmp_path, cli):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", roadbrdf.RoadbrdfWarning)
        fig = rplot.luminaire(lighting_data / "isym2.ldt", output=tmp_path / "lum.png")  # g = cos C
    data = fig.roadbrdf_data
    gamma = np.asarray(data["gamma_deg"])
    for name, g in (("C0", 1.0), ("C90", 0.0), ("C180", -1.0), ("C270", 0.0)):
        np.testing.assert_allclose(data[name], (200 + 40 * g) * (1 + gamma / 90), rtol=1e-9)
    assert (tmp_path / "lum.png").stat().st_size > 1000
    out = cli("plot", "luminaire", lighting_data / "full_2019.ies", "-o", tmp_path / "cli.svg")
    assert (tmp_path / "cli.svg").read_text().lstrip().startswith("<?xml")
    assert out.returncode == 0
    # The figure must not replace its input.
    copy = tmp_path / "in.ldt"
    copy.write_bytes((lighting_data / "isym0.ldt").read_bytes())
    refused = cli("plot", "luminaire", copy, "-o", copy, check=False)
    assert refused.returncode == 2
    assert copy.read_bytes() == (lighting_data / "isym0.ldt").read_bytes()


def test_real_files_flux_against_headers(real_data):
    folder = real_data / "luminaires"
    if not folder.is_dir():
        pytest.skip(f"{folder} is absent")
    # Its 360 deg plane differs from its 0 deg plane by up to 12 cd: warned, the 0 deg plane used.
    with pytest.warns(roadbrdf.RoadbrdfWarning, match="360 deg differ"):
        r = roadbrdf.luminaire(folder / "eulumdat-rs-AGPL3" / "outdoor-roadway-60W-4000K.ies")
    assert r["integrated_flux_lm"] == pytest.approx(9155.7, rel=0.02)
    assert [w.kind for w in r.warnings] == ["c360_differs"]
