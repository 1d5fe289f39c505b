"""The check request's field table (CheckRequest::fields, io/check_request.cpp) seen from both front ends,
row by row: `roadbrdf check --help` shows each row's flag, `roadbrdf.check`'s docstring its keyword and
help, and a bad value is refused with the same text by both (the command line naming the flag, Python the
keyword). The rows come from the table itself, so a new field without a bad value here fails. The
reference numbers are those of the synthetic datasets written below (a Lambertian panel: f = rho/pi)."""
import json
import math

import pytest
from request_table import check_every_row_is_shown, check_refused_alike, fields

import roadbrdf

FIELDS = fields("check")
RHO = 0.6  # the panel's reflectance, flat in wavelength


def _lambertian(path, rho=RHO, metadata=()):
    """A Lambertian surface f = rho/pi at 500-600 nm on 4 x 4 incidence/viewing angles (both azimuth
    planes), with `metadata` lines ("# key: value")."""
    rows = [f"# {key}: {value}" for key, value in metadata]
    rows.append("theta_i,phi_i,theta_r,phi_r,500,550,600")
    for ti in (10, 30, 50, 70):
        for tr in (10, 20, 40, 60):
            for pr in (0, 180):
                rows.append(f"{ti},0,{tr},{pr}," + ",".join([repr(rho / math.pi)] * 3))
    path.write_text("\n".join(rows) + "\n")
    return path


def _panel_file(path, rho=RHO):
    path.write_text("".join(f"{w} {rho}\n" for w in range(400, 701, 50)))
    return path


def _bad_values(tmp_path):
    """For every field that takes a value: (command line arguments after DATA, Python keywords)."""
    return {
        "path": (None, None),
        "delimiter": (["--delimiter", "|"], dict(delimiter="|")),
        "decimal": (["--decimal", "x"], dict(decimal="x")),
        "quantity": (["--quantity", "brdff"], dict(quantity="brdff")),
        "columns": (["--column", "theta_r=No_Such_Column"], dict(columns=["theta_r=No_Such_Column"])),
        "set": (["--set", "theta_q=30"], dict(set=["theta_q=30"])),
        "panel_reflectance": (["--panel-reflectance", tmp_path / "absent.txt"],
                              dict(panel_reflectance=str(tmp_path / "absent.txt"))),
        "tolerance": (["--tolerance", "1e-310"], dict(tolerance=1e-310)),
        "reciprocity_threshold": (["--reciprocity-threshold", "-0.1"], dict(reciprocity_threshold=-0.1)),
        "snr_threshold": (["--snr-threshold", "-1"], dict(snr_threshold=-1)),
        "noise_window": (["--noise-window", "-1"], dict(noise_window=-1)),
        "neighbours": (["--neighbours", "1"], dict(neighbours=1)),
        "outlier_threshold": (["--outlier-threshold", "-6"], dict(outlier_threshold=-6)),
        "outlier_min_ratio": (["--outlier-min-ratio", "0"], dict(outlier_min_ratio=0)),
        "specular_window": (["--specular-window", "181"], dict(specular_window=181)),
        "listed_outliers": (["--listed-outliers", "-1"], dict(listed_outliers=-1)),
    }


def test_every_row_is_an_option_and_a_keyword(cli):
    check_every_row_is_shown(cli, "check", roadbrdf.check)


@pytest.mark.parametrize("row", [r for r in FIELDS if r["kind"] != "switch"], ids=lambda r: r["name"])
def test_a_bad_value_is_refused_alike(cli, tmp_path, row):
    bad = _bad_values(tmp_path)
    assert row["name"] in bad, f"the table's field {row['name']} needs a bad value in this test"
    flags, keywords = bad[row["name"]]
    data = str(_lambertian(tmp_path / "panel.csv"))
    if flags is None:  # the dataset file itself
        data, flags, keywords = str(tmp_path / "absent.csv"), [], {}
    result = cli("check", data, *flags, check=False)
    with pytest.raises(roadbrdf.InputError) as error:
        roadbrdf.check(data, **keywords)
    check_refused_alike("check", row, result, error.value)


def test_the_dataset_file_is_required_by_both(cli):
    assert cli("check", check=False).returncode != 0
    with pytest.raises(TypeError, match="path"):
        roadbrdf.check()


def test_a_panel_measured_as_a_sample_agrees_with_rho_over_pi_in_both(cli, tmp_path):
    """f = rho/pi exactly: every relative deviation (f - rho/pi)/(rho/pi) is zero, reported alike by the
    command's JSON and Python; a panel file of another reflectance gives (0.6 - 0.5)/0.5 = 0.2."""
    data = _lambertian(tmp_path / "panel.csv")
    options = ["--panel-reflectance", _panel_file(tmp_path / "rho.txt"), "--exact-reciprocity", "--tolerance", "1",
               "--listed-outliers", "0", "--snr-threshold", "5", "--neighbours", "8"]
    from_cli = json.loads(cli("check", data, "--json", *options).stdout)
    python = roadbrdf.check(data, panel_reflectance=tmp_path / "rho.txt", exact_reciprocity=True, tolerance=1,
                            listed_outliers=0, snr_threshold=5, neighbours=8)
    text = python.pop("text")
    assert python == from_cli
    assert python["panel_validation"]["mean_relative_deviation"] == pytest.approx(0.0, abs=1e-12)
    assert python["panel_validation"]["max_abs_relative_deviation"] == pytest.approx(0.0, abs=1e-12)
    assert cli("check", data, *options).stdout == f"{data}\n{text}"
    other = roadbrdf.check(data, panel_reflectance=_panel_file(tmp_path / "rho-0.5.txt", rho=0.5))
    assert other["panel_validation"]["mean_relative_deviation"] == pytest.approx(0.2, rel=1e-12)


def test_a_dataset_in_memory_takes_the_options_but_not_the_reading_fields(tmp_path):
    data = _lambertian(tmp_path / "panel.csv")
    from_file = roadbrdf.check(data, panel_reflectance=_panel_file(tmp_path / "rho.txt"), neighbours=8)
    from_memory = roadbrdf.check(roadbrdf.read_dataset(data), panel_reflectance=tmp_path / "rho.txt", neighbours=8)
    assert from_file.pop("file") == str(data) and from_memory.pop("file") is None
    assert from_memory == from_file
    with pytest.raises(TypeError, match="quantity"):
        roadbrdf.check(roadbrdf.read_dataset(data), quantity="brdf-cos")


def test_receiver_solid_angles_of_the_metadata_are_reported_by_both(cli, tmp_path):
    """The solid angles an OpenMATERIAL 3D file records (kept in the metadata) appear in the text and
    under receiver_solid_angles_sr, the same from both front ends."""
    data = _lambertian(tmp_path / "omat.csv", metadata=[("receiver_solid_angle_sr.550", "0.0012")])
    python = roadbrdf.check(data)
    assert python["receiver_solid_angles_sr"] == {"550": "0.0012"}
    assert "receiver solid angle at 550 nm: 0.0012 sr\n" in python["text"]
    assert json.loads(cli("check", data, "--json").stdout)["receiver_solid_angles_sr"] == {"550": "0.0012"}
    assert cli("check", data).stdout == f"{data}\n{python['text']}"
