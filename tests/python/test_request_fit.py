"""The request table of `roadbrdf fit` and roadbrdf.fit (FitRequest::fields, core/request_fields.h): every
row is an option of the command and a keyword of the function, and a bad value is refused with the same
text by both (the command naming its flag, Python the keyword). The two front ends are made from the
one table, so the numbers need no comparison of copies; the results of the fit in memory and in its
file are compared below."""
import json

import numpy as np
import pytest
from request_table import check_every_row_is_shown, check_refused_alike, fields

import roadbrdf

DATA = "data/examples/single/lazard.csv"
MODEL = "lambert"
FIELDS = fields("fit")


def _ceres_reason(status):
    """Ceres' termination message without its figures ("Function tolerance reached.")."""
    return status.split("|")[0].split(":")[0].strip()


def _without_timing(content):
    # Timings differ run to run. So do the figures inside Ceres' termination messages: the relative
    # cost change it quotes is a difference of two nearly equal costs (1e-12 relative), and its
    # leading digits were seen to vary between repeated identical fits in one process (3.176217e-12,
    # 3.176410e-12) while every parameter and cost stayed bit-identical; the likely cause is the heap
    # alignment of Ceres' dense blocks, which changes where Eigen's vectorised sums start. Every
    # number of the result is compared in full.
    for f in content["fits"]:
        f.pop("seconds", None)
        f.pop("cpu_seconds", None)
        if "status" in f:
            f["status"] = [_ceres_reason(s) for s in f["status"]]
        if "joint_status" in f:
            f["joint_status"] = _ceres_reason(f["joint_status"])
    return content


def _bad_values(root, tmp_path):
    """For every field that takes a value: (command line arguments, Python keywords) of a bad one."""
    data = str(root / DATA)
    return {
        "data": (["--data-is", str(tmp_path / "absent.csv")], dict(data=str(tmp_path / "absent.csv"))),
        "delimiter": (["--delimiter", "|"], dict(delimiter="|")),
        "decimal": (["--decimal", "x"], dict(decimal="x")),
        "quantity": (["--quantity", "brdff"], dict(quantity="brdff")),
        "columns": (["--column", "theta_r=No_Such_Column"], dict(columns=["theta_r=No_Such_Column"])),
        "set": (["--set", "theta_q=30"], dict(set=["theta_q=30"])),
        "models": (["--model", "lambrt"], dict(models=[MODEL, "lambrt"])),
        "options": (["--option", "distribution=beckmann"], dict(options={"distribution": "beckmann"})),
        "shared": (["--shared", "albedoo"], dict(shared="albedoo")),
        "fixed": (["--fix", "albedoo=0.2"], dict(fixed={"albedoo": 0.2})),
        "start": (["--start", "albedoo=0.2"], dict(start={"albedoo": 0.2})),
        "bounds": (["--bound", "albedoo=0.1:0.5"], dict(bounds={"albedoo": (0.1, 0.5)})),
        "loss": (["--loss", "l1"], dict(loss="l1")),
        "robust": (["--robust", "tukey:1"], dict(robust="tukey:1")),
        "multistart": (["--multistart", "0"], dict(multistart=0)),
        "seed": (["--seed", "-1"], dict(seed=-1)),
        "wavelengths": (["--wavelengths", "3000"], dict(wavelengths=[3000])),
        "bands": (["--band", "610:590"], dict(bands="610:590")),
        "where": (["--where", "theta_q<70"], dict(where="theta_q<70")),
        "group_by": (["--group-by", "theta_q"], dict(group_by="theta_q")),
        "threads": (["--threads", "0"], dict(threads=0)),
        "joint_solver": (["--joint-solver", "dense-shur"], dict(joint_solver="dense-shur")),
        "max_iterations": (["--max-iterations", "0"], dict(max_iterations=0)),
        "residuals": (["--residuals", data], dict(residuals=data)),
        "output": (["--output-is", data], dict(output=data)),
    }


def test_every_row_is_an_option_and_a_keyword(cli):
    check_every_row_is_shown(cli, "fit", roadbrdf.fit)


@pytest.mark.parametrize("row", [r for r in FIELDS if r["kind"] != "switch"], ids=lambda r: r["name"])
def test_a_bad_value_is_refused_alike(cli, root, tmp_path, row):
    bad = _bad_values(root, tmp_path)
    assert row["name"] in bad, f"the table's field {row['name']} needs a bad value in this test"
    flags, keywords = bad[row["name"]]
    data = keywords.pop("data", str(root / DATA))
    out = str(tmp_path / "f.json")
    if flags[0] == "--data-is":
        flags = [flags[1], "--model", MODEL, "-o", out]
    elif flags[0] == "--output-is":
        flags = [data, "--model", MODEL, "-o", flags[1]]
    else:
        flags = [data, "--model", MODEL, "-o", out, *flags]
    result = cli("fit", *flags, check=False)
    keywords.setdefault("models", MODEL)
    with pytest.raises(roadbrdf.InputError) as error:
        roadbrdf.fit(data, **keywords)
    check_refused_alike("fit", row, result, error.value)
    assert not (tmp_path / "f.json").exists()


def test_a_list_of_wavelengths_is_the_same_selection_as_its_text(root):
    a = roadbrdf.fit(root / DATA, MODEL, wavelengths=[510, 550])
    b = roadbrdf.fit(root / DATA, MODEL, wavelengths="510,550")
    assert a["fits"][0]["parameters"] == b["fits"][0]["parameters"]


def test_the_switches_turn_their_default_around(cli, root, tmp_path):
    """A switch whose field is on by default turns it off (--no-sigma-weights: use_sigma=False); the fit
    file records the setting either way."""
    out = tmp_path / "f.json"
    cli("fit", root / DATA, "--model", MODEL, "--no-sigma-weights", "--no-covariance", "--wavelengths", "510,610",
        "-o", out)
    from_cli = json.loads(out.read_text())
    result = roadbrdf.fit(root / DATA, MODEL, use_sigma=False, covariance=False, wavelengths=[510, 610])
    assert _without_timing(result.to_dict()) == _without_timing(from_cli)
    defaults = roadbrdf.fit(root / DATA, MODEL, wavelengths=[510, 610])
    assert np.all(np.isfinite(defaults.best.standard_errors))
    assert np.all(np.isnan(result.best.standard_errors))


def test_python_writes_the_outputs_and_checks_them(root, tmp_path):
    out, residuals = tmp_path / "f.json", tmp_path / "r.csv"
    result = roadbrdf.fit(root / DATA, MODEL, wavelengths=[510], output=out, residuals=residuals)
    assert _without_timing(json.loads(out.read_text())) == _without_timing(result.to_dict())
    assert any(line.startswith("theta_i,") for line in residuals.read_text().splitlines())
    with pytest.raises(roadbrdf.InputError, match="same file"):
        roadbrdf.fit(root / DATA, MODEL, output=out, residuals=out)


def test_an_unmeasured_wavelength_is_answered_by_the_nearest_band_in_both(cli, root, tmp_path):
    out = tmp_path / "f.json"
    r = cli("fit", root / DATA, "--model", "lambert", "--wavelengths", "515,600", "-o", out)
    # 600 is halfway between 590 and 610: the shorter band answers.
    assert "roadbrdf: note: 515 nm: nearest band 510 nm\nroadbrdf: note: 600 nm: nearest band 590 nm" in r.stderr
    result = roadbrdf.fit(root / DATA, "lambert", wavelengths=[515, 600])
    assert result.notes == ["515 nm: nearest band 510 nm", "600 nm: nearest band 590 nm"]
    assert list(result.wavelengths) == [510, 590]
    assert _without_timing(result.to_dict()) == _without_timing(json.loads(out.read_text()))


def test_result_objects(root):
    r = roadbrdf.fit(root / DATA, ["lambert", "oren-nayar"], wavelengths="510:710:100")
    assert [f.model for f in r.fits] == ["lambert", "oren-nayar"]
    on = r["oren-nayar"]
    assert on.parameters.shape == (2, 3) and on.standard_errors.shape == (2, 3)
    assert on.covariance.shape == (3, 2, 2)
    # Covariance diagonal = standard error squared.
    np.testing.assert_allclose(np.diagonal(on.covariance, axis1=1, axis2=2), on.standard_errors.T ** 2, rtol=1e-12)
    assert r.best.model in ("lambert", "oren-nayar")
    assert "best (lowest total BIC)" in r.summary and "roadbrdf.FitResult" in repr(r)
    assert "oren-nayar" in repr(on)
    # The spectral model evaluates the fitted parameters (Lambert: albedo / pi).
    lam = r["lambert"]
    sm = lam.spectral_model()
    assert sm.evaluate(30, 0, 40, 180, 610.0) == pytest.approx(lam.parameter("albedo")[1] / np.pi, rel=1e-12)
    assert r["best"] == r.to_dict()["best"]
    pd = pytest.importorskip("pandas")
    df = r.to_dataframe()
    assert isinstance(df, pd.DataFrame)
    assert set(df["model"]) == {"lambert", "oren-nayar"} and len(df) == 3 * (1 + 2)
    wide = on.to_dataframe()
    assert list(wide["wavelength_nm"]) == [510.0, 610.0, 710.0] and "stderr_sigma" in wide


def test_albedo_of_a_fit_result_equals_that_of_its_fit_file(cli, root, tmp_path):
    """A FitResult in memory carries what its fit file carries (parameter covariance, angular
    coverage): its albedo, uncertainties and coverage equal `roadbrdf albedo FIT.json`'s."""
    out = tmp_path / "fit.json"
    cli("fit", root / DATA, "--model", "oren-nayar", "--wavelengths", "400:700:50", "-o", out)
    from_file = json.loads(cli("albedo", out, "--sun-zenith", "20,50", "--json").stdout)
    result = roadbrdf.fit(roadbrdf.read_dataset(root / DATA), "oren-nayar", wavelengths="400:700:50")
    with pytest.warns(UserWarning, match="mostly extrapolation"):  # lazard.csv: one incidence plane
        in_memory = roadbrdf.albedo(result.spectral_model(), sun_zenith=[20, 50])
    assert in_memory["coverage"] == from_file["coverage"] and from_file["coverage"] is not None
    for key in ("black_sky", "white_sky"):
        np.testing.assert_allclose(in_memory[key], from_file[key], rtol=1e-12, atol=0)
        u_file = np.array(from_file["uncertainty"][key], dtype=float)
        assert np.all(u_file > 0), u_file
        np.testing.assert_allclose(np.array(in_memory["uncertainty"][key], dtype=float), u_file, rtol=1e-9, atol=0)
    bb_file, bb_memory = from_file["uncertainty"]["broadband"], in_memory["uncertainty"]["broadband"]
    for kind in ("independent", "correlated"):
        assert bb_file["white_sky"][kind] > 0
        assert bb_memory["white_sky"][kind] == pytest.approx(bb_file["white_sky"][kind], rel=1e-9)
        assert [b[kind] for b in bb_memory["black_sky"]] == pytest.approx([b[kind] for b in bb_file["black_sky"]],
                                                                          rel=1e-9)


def test_uncertainties_of_a_joint_fit_say_what_they_leave_out(cli, root, tmp_path):
    """A joint fit's shared parameter has one error for every wavelength: the per-wavelength covariance
    does not carry that correlation, and the albedo and r-table uncertainties say so (from the file and
    from the result in memory); a per-wavelength fit has no such note."""
    joint, single = tmp_path / "joint.json", tmp_path / "single.json"
    cli("fit", root / DATA, "--model", "oren-nayar", "--wavelengths", "400:700:50", "--shared", "sigma", "-o", joint)
    cli("fit", root / DATA, "--model", "oren-nayar", "--wavelengths", "400:700:50", "-o", single)
    for path, expected in ((joint, True), (single, False)):
        albedo = json.loads(cli("albedo", path, "--json", check=True).stdout)
        rtable = json.loads(cli("rtable", path, "--json").stdout)
        assert albedo["uncertainty"] is not None and rtable["uncertainty"] is not None
        for notes in (albedo["notes"], rtable["notes"]):
            joint_notes = [n for n in notes if n.startswith("joint fit: ")]
            assert len(joint_notes) == (1 if expected else 0), notes
            if expected:
                assert "(oren-nayar.sigma)" in joint_notes[0] or "(sigma)" in joint_notes[0]
    result = roadbrdf.fit(root / DATA, "oren-nayar", wavelengths="400:700:50", shared=["sigma"])
    with pytest.warns(UserWarning):
        in_memory = roadbrdf.albedo(result.spectral_model())
    assert any(n.startswith("joint fit: ") for n in in_memory["notes"])
