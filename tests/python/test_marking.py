"""Road markings (roadbrdf marking / roadbrdf.marking) and model grids (roadbrdf export /
roadbrdf.export): the same numbers and errors from both front ends, closed forms of a Lambertian
marking, the 3M retroreflective tape from its data and from a retro-phong fit, OpenMATERIAL 3D files
validated against the schema, and the walkthrough blocks of docs/markings.md run as written."""
import json
import math
import pathlib
import re
import shutil
import subprocess

import pytest

import roadbrdf

ROOT = pathlib.Path(__file__).resolve().parents[2]


def test_lambertian_marking_closed_forms_in_both_front_ends(cli):
    rho = 0.6
    py = roadbrdf.marking("lambert", parameters=["albedo=0.6"])
    out = json.loads(cli("marking", "lambert", "-p", "albedo=0.6", "--json").stdout)
    for value in (py.value, out):
        # Q_d = 1000 rho/pi; R_L = 1000 (rho/pi) cos(88.76 deg); beta = rho (EN 1436 definitions).
        assert value["Qd"] == pytest.approx(1000 * rho / math.pi, abs=0.01)
        assert value["RL"] == pytest.approx(1000 * rho / math.pi * math.cos(math.radians(88.76)), rel=1e-12)
        assert value["beta"] == pytest.approx(rho, rel=1e-12)
        assert value["Qd_class"] == "Q4" and value["RL_class"] == "R0"
    assert py.value["Qd"] == out["Qd"] and py.value["RL"] == out["RL"]


def test_marking_errors_are_the_same(cli):
    result = cli("marking", "lambert", "--illumination-angle", "0", check=False)
    with pytest.raises(roadbrdf.InputError) as error:
        roadbrdf.marking("lambert", illumination_angle=0)
    from conftest import assert_same_error
    assert_same_error(result, error.value, "--illumination-angle", "illumination_angle")
    with pytest.raises(TypeError, match="illumination_angle"):
        roadbrdf.marking("lambert", ilumination_angle=1.0)


def test_data_far_from_the_geometry_names_the_fit(cli, tmp_path):
    data = tmp_path / "diffuse.csv"
    data.write_text("theta_i,phi_i,theta_r,phi_r,550\n45,0,0,0,0.1\n30,0,30,180,0.1\n")
    result = cli("marking", data, check=False)
    assert result.returncode == 2
    assert "SOURCE" in result.stderr and "retro-phong" in result.stderr and "--tolerance" in result.stderr
    with pytest.raises(roadbrdf.InputError, match="`tolerance`|tolerance"):
        roadbrdf.marking(data)


@pytest.fixture(scope="module")
def tape(tmp_path_factory):
    """The 3M yellow tape as a dataset and its retro-phong fit (as in docs/data.md)."""
    folder = tmp_path_factory.mktemp("tape")
    exe = ROOT / "build" / "roadbrdf"
    import os
    exe = os.environ.get("ROADBRDF_CLI", str(exe))
    subprocess.run([exe, "convert", str(ROOT / "data/third-party/retroreflective/retro-3M-yellow.dat"), "--from",
                    "alta", "--wavelength", "550", "--exclude-grazing", "--average-duplicates", "-o",
                    str(folder / "tape.csv")], check=True, capture_output=True)
    subprocess.run([exe, "fit", str(folder / "tape.csv"), "-m", "retro-phong", "--multistart", "8", "--bounds",
                    "n=0:1e5", "--quiet", "-o", str(folder / "tape.fit.json")], check=True, capture_output=True)
    return folder


def test_tape_rl_from_data_and_fit_agree(tape):
    # Where the data reach (illumination 30 deg, observation 1.05 deg above it), the measured and the
    # fitted R_L agree within the fit's RMSE at that geometry: |dR_L| <= 1000 rmse sin(epsilon).
    fit_file = json.loads((tape / "tape.fit.json").read_text())
    rmse = fit_file["fits"][0]["rmse"][0]
    data = roadbrdf.marking(tape / "tape.csv", illumination_angle=30, observation_angle=31.05)
    model = roadbrdf.marking(tape / "tape.fit.json", illumination_angle=30, observation_angle=31.05)
    assert data["RL_nearest_measured_deg"] <= 1
    assert abs(data["RL"] - model["RL"]) <= 1000 * rmse * math.sin(math.radians(30))
    # A retroreflective sheet returns hundreds of mcd m^-2 lx^-1 and more (a white paint without beads
    # some tens): both the data and the fit are of that order.
    assert data["RL"] >= 100 and model["RL"] >= 100
    with pytest.warns(roadbrdf.RoadbrdfWarning, match="extrapolation"):
        standard = roadbrdf.marking(tape / "tape.fit.json")
    assert standard["RL"] > 0 and standard["RL_class"] is not None and standard["Qd_class"] is not None


def test_export_openmaterial3d_validates_and_reads_back(cli, tmp_path, real_data):
    jsonschema = pytest.importorskip("jsonschema")
    schema = json.loads((real_data / "openmaterial3d" / "material_brdf_schema.json").read_text())
    out = tmp_path / "lambert_brdf.xompt"
    result = roadbrdf.export("lambert", parameters=["albedo=0.25"], preset="lidar", theta_i="0:80:20",
                             theta_r="0:80:20", phi="0:180:90", output=out, license="CC0-1.0")
    document = json.loads(out.read_text())
    jsonschema.validate(document, schema)
    assert document["metadata"]["sources"] == "simulation" and result["metadata"]["uuid"]
    data = roadbrdf.read_dataset(out)
    assert list(data.wavelengths) == [905.0, 1550.0]
    assert all(v == pytest.approx(0.25 / math.pi, rel=1e-15) for v in data.brdf.ravel())
    # The command line writes the same table (a new uuid and creation date apart).
    out_cli = tmp_path / "lambert_cli_brdf.xompt"
    cli("export", "lambert", "-p", "albedo=0.25", "--preset", "lidar", "--theta-i", "0:80:20", "--theta-r",
        "0:80:20", "--phi", "0:180:90", "--license", "CC0-1.0", "-o", out_cli)
    assert json.loads(out_cli.read_text())["brdf"] == document["brdf"]


def test_asphalt_lidar_file_reads_and_fits(real_data, tmp_path):
    path = real_data / "openmaterial3d" / "example_material_lidar_brdf.xompt"
    data = roadbrdf.read_dataset(path)
    assert list(data.wavelengths) == [905.0]
    fit = roadbrdf.fit(path, ["lambert", "oren-nayar"], where="theta_i<89.9", output=tmp_path / "asphalt.fit.json")
    assert fit is not None


def shell_blocks(document):
    text = (ROOT / document).read_text(encoding="utf-8")
    return [m.group(1) for m in re.finditer(r"^```sh\n(.*?)^```", text, flags=re.S | re.M)]


def test_markings_walkthrough_runs_as_written(tmp_path, real_data):
    import os
    cli_path = pathlib.Path(os.environ.get("ROADBRDF_CLI", ROOT / "build" / "roadbrdf")).resolve()
    tree = tmp_path / "tree"
    tree.mkdir()
    (tree / "data").symlink_to(ROOT / "data")
    (tree / "build").mkdir()
    (tree / "build" / "roadbrdf").symlink_to(cli_path)
    (tmp_path / "shared").symlink_to(real_data.parent)  # ../shared as next to the source tree
    blocks = shell_blocks("docs/markings.md")
    assert len(blocks) == 4
    for body in blocks:
        result = subprocess.run(["bash", "-e", "-o", "pipefail", "-c", body], cwd=tree, capture_output=True,
                                text=True, timeout=600)
        assert result.returncode == 0, f"{body}\n{result.stderr[-3000:]}"
    marking = json.loads((tree / "tape.marking.json").read_text())
    assert marking["RL"] is not None and marking["Qd"] is not None
    # The contrast walkthrough: a retroreflective tape is much brighter than R3 under road lighting.
    contrast = json.loads((tree / "tape.contrast.json").read_text())["contrast"]["installation"]
    assert contrast["contrast_of_averages"] > 0 and len(contrast["observers"]) == 2


def test_check_reports_the_receiver_solid_angles(cli, root):
    corpus = root / "tests" / "fuzz" / "corpus" / "openmaterial3d" / "small_brdf.xompt"
    assert "receiver solid angle at 905 nm: 0.001 sr" in cli("check", corpus).stdout
    assert json.loads(cli("check", corpus, "--json").stdout)["receiver_solid_angles_sr"] == {"905": "0.001"}
