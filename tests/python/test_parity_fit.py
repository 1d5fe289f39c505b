"""roadbrdf fit and roadbrdf.fit: the same numbers with options (distribution, loss, fixed, bounded and
shared parameters) and the same errors for the same bad input (the CLI names its flag, Python the
argument)."""
import json

import numpy as np
import pytest

import roadbrdf

DATA = "data/examples/single/lazard.csv"
MODEL = "lambert+torrance-sparrow"


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


def _cli_error(cli, *args):
    r = cli(*args, check=False)
    assert r.returncode == 2, r.stderr
    assert r.stderr.startswith("roadbrdf: error: "), r.stderr
    return r.stderr[len("roadbrdf: error: "):].strip()


CASES = {
    "distribution-loss-fixed": (
        ["--option", "distribution=beckmann", "--loss", "relative", "--fix", "lambert.weight=1",
         "--fix", "torrance-sparrow.weight=1", "--wavelengths", "510:710:100"],
        dict(options={"distribution": "beckmann"}, loss="relative",
             fixed={"lambert.weight": 1, "torrance-sparrow.weight": 1}, wavelengths="510:710:100")),
    "bounded-multistart-robust": (
        ["--bound", "torrance-sparrow.roughness=0.05:0.1", "--fix", "torrance-sparrow.weight=1",
         "--multistart", "3", "--seed", "7", "--robust", "huber:0.01", "--wavelengths", "550,650"],
        dict(bounds={"torrance-sparrow.roughness": (0.05, 0.1)}, fixed={"torrance-sparrow.weight": 1},
             multistart=3, seed=7, robust="huber:0.01", wavelengths=[550, 650])),
    "shared": (
        ["--shared", "torrance-sparrow.roughness", "--fix", "lambert.weight=1", "--fix", "torrance-sparrow.weight=1",
         "--wavelengths", "510:710:100"],
        dict(shared=["torrance-sparrow.roughness"], fixed={"lambert.weight": 1, "torrance-sparrow.weight": 1},
             wavelengths="510:710:100")),
    "shared-auto": (
        ["--shared", "auto", "--fix", "lambert.weight=1", "--fix", "torrance-sparrow.weight=1",
         "--wavelengths", "550,650"],
        dict(shared="auto", fixed={"lambert.weight": 1, "torrance-sparrow.weight": 1}, wavelengths=[550, 650])),
}


@pytest.mark.parametrize("case", sorted(CASES))
def test_fit_numbers_are_identical(cli, root, tmp_path, case):
    flags, kwargs = CASES[case]
    out = tmp_path / "cli.fit.json"
    cli("fit", root / DATA, "--model", MODEL, *flags, "-o", out)
    from_cli = _without_timing(json.loads(out.read_text()))
    result = roadbrdf.fit(root / DATA, MODEL, **kwargs)
    assert _without_timing(result.to_dict()) == from_cli
    # The same writer: the files differ at most in the timing lines.
    py_out = tmp_path / "py.fit.json"
    result.write(py_out)
    assert _without_timing(json.loads(py_out.read_text())) == from_cli
    f = result.best
    cli_fit = from_cli["fits"][0]
    for k, name in enumerate(f.parameter_names):
        assert list(f.parameters[k]) == cli_fit["parameters"][name]
    if case == "distribution-loss-fixed":
        # The drift this test guards against: Python used to fit GGX here.
        assert f.options["torrance-sparrow.distribution"] == "beckmann"
        assert cli_fit["options"]["torrance-sparrow.distribution"] == "beckmann"
    if case == "bounded-multistart-robust":
        roughness = f.parameter("torrance-sparrow.roughness")
        assert np.all((roughness >= 0.05) & (roughness <= 0.1))
        assert cli_fit["bounds"] == {"torrance-sparrow.roughness": [0.05, 0.1]}
    if case.startswith("shared"):
        roughness = f.parameter("torrance-sparrow.roughness")
        assert np.all(roughness == roughness[0])  # one value for all wavelengths


ERRORS = [
    # (CLI flags, Python keywords, CLI field, Python field)
    (["--option", "distributon=beckmann"], dict(options={"distributon": "beckmann"}),
     "--option distributon", "options.distributon"),
    (["--option", "distribution=cauchy"], dict(options={"distribution": "cauchy"}),
     "--option distribution", "options.distribution"),
    (["--fix", "torrance-sparrow.roughnes=0.2"], dict(fixed={"torrance-sparrow.roughnes": 0.2}),
     "--fix torrance-sparrow.roughnes", "fixed.torrance-sparrow.roughnes"),
    (["--start", "nope=1"], dict(start={"nope": 1}), "--start nope", "start.nope"),
    (["--shared", "lambert.albedoo"], dict(shared=["lambert.albedoo"]), "--shared lambert.albedoo",
     "shared.lambert.albedoo"),
    (["--bound", "torrance-sparrow.roughness=0.1:5"], dict(bounds={"torrance-sparrow.roughness": (0.1, 5)}),
     "--bound torrance-sparrow.roughness", "bounds.torrance-sparrow.roughness"),
    (["--multistart", "0"], dict(multistart=0), "--multistart", "multistart"),
    (["--multistart", "1000000000"], dict(multistart=1000000000), "--multistart", "multistart"),
    (["--loss", "l1"], dict(loss="l1"), "--loss", "loss"),
    (["--robust", "tukey:1"], dict(robust="tukey:1"), "--robust", "robust"),
    (["--joint-solver", "dense-shur", "--shared", "auto"], dict(joint_solver="dense-shur", shared="auto"),
     "--joint-solver", "joint_solver"),
    (["--wavelengths", "510:700:40"], dict(wavelengths="510:700:40"), "--wavelengths", "wavelengths"),
    (["--wavelengths", "3000"], dict(wavelengths=[3000]), "--wavelengths", "wavelengths"),
]


def test_an_unmeasured_wavelength_is_answered_by_the_nearest_band_in_both(cli, root, tmp_path):
    out = tmp_path / "f.json"
    r = cli("fit", root / DATA, "--model", "lambert", "--wavelengths", "515,600", "-o", out)
    # 600 is halfway between 590 and 610: the shorter band answers.
    assert "roadbrdf: note: 515 nm: nearest band 510 nm\nroadbrdf: note: 600 nm: nearest band 590 nm" in r.stderr
    result = roadbrdf.fit(root / DATA, "lambert", wavelengths=[515, 600])
    assert result.notes == ["515 nm: nearest band 510 nm", "600 nm: nearest band 590 nm"]
    assert list(result.wavelengths) == [510, 590]
    assert _without_timing(result.to_dict()) == _without_timing(json.loads(out.read_text()))


@pytest.mark.parametrize("flags,kwargs,cli_field,py_field", ERRORS, ids=[e[3] for e in ERRORS])
def test_fit_errors_are_the_same(cli, root, tmp_path, flags, kwargs, cli_field, py_field):
    message = _cli_error(cli, "fit", root / DATA, "--model", MODEL, *flags, "-o", tmp_path / "f.json")
    with pytest.raises(roadbrdf.InputError) as e:
        roadbrdf.fit(root / DATA, MODEL, **kwargs)
    assert message.startswith(cli_field + ": "), message
    assert str(e.value).startswith(py_field + ": "), str(e.value)
    assert message[len(cli_field) + 2:] == str(e.value)[len(py_field) + 2:]
    assert not (tmp_path / "f.json").exists()


def test_misspelt_names_suggest_the_nearest(root):
    with pytest.raises(roadbrdf.InputError, match=r"did you mean 'distribution'\?"):
        roadbrdf.fit(root / DATA, MODEL, options={"distributon": "beckmann"})
    with pytest.raises(roadbrdf.InputError, match=r"did you mean 'torrance-sparrow.roughness'\?"):
        roadbrdf.fit(root / DATA, MODEL, fixed={"torrance-sparrow.roughnes": 0.2})


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
