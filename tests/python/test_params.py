"""`roadbrdf fit --group-by/--where`, `roadbrdf params` and their Python twins (roadbrdf.fit(group_by=,
where=), roadbrdf.params): the same numbers and the same errors from both front ends, and tables whose
numbers are the fit file's."""
import json

import numpy as np
import pytest

import roadbrdf

DATA = "data/examples/single/lazard.csv"


@pytest.fixture
def grouped(cli, root, tmp_path):
    out = tmp_path / "grouped.fit.json"
    cli("fit", root / DATA, "--model", "oren-nayar", "--model", "lambert", "--group-by", "theta_i",
        "--where", "theta_r<=70", "--wavelengths", "510:710:100", "-o", out)
    return out


def _number(x):
    return float("nan") if x is None else x


def _without_timing(content):
    for f in content["fits"]:
        f.pop("seconds", None)
        f.pop("cpu_seconds", None)
    return content


def test_grouped_fit_is_the_same_from_python(root, grouped):
    result = roadbrdf.fit(root / DATA, ["oren-nayar", "lambert"], group_by="theta_i", where="theta_r<=70",
                          wavelengths="510:710:100")
    assert _without_timing(result.to_dict()) == _without_timing(json.loads(grouped.read_text()))
    content = json.loads(grouped.read_text())
    assert content["version"] == 2 and content["group_by"] == ["theta_i"]
    incidences = sorted({f["group"]["theta_i"] for f in content["fits"]})
    assert incidences == [0, 20, 40, 60, 80]
    fit40 = result.model_fit("oren-nayar", theta_i=40)
    assert fit40.group == {"theta_i": 40.0}
    with pytest.raises(roadbrdf.InputError, match="one per group"):
        result.model_fit("oren-nayar")
    df = result.to_dataframe()
    assert list(df.columns[:2]) == ["model", "theta_i"]


def test_params_csv_and_dataframe_hold_the_fit_file_numbers(cli, grouped):
    content = json.loads(grouped.read_text())
    df = roadbrdf.params(grouped, wavelengths=[610], models="oren-nayar")
    assert list(df["theta_i_deg"]) == [0, 20, 40, 60, 80]
    for _, row in df.iterrows():
        fit = next(f for f in content["fits"] if f["model"] == "oren-nayar" and f["group"]["theta_i"] == row.theta_i_deg)
        w = fit["wavelengths"].index(610)
        # null in the file (an undefined standard error at normal incidence, where albedo and sigma are
        # degenerate) is NaN in the table.
        np.testing.assert_equal([row.albedo, row.albedo_stderr, row.sigma_stderr, row.rmse_per_sr],
                                [_number(fit["parameters"]["albedo"][w]), _number(fit["stderr"]["albedo"][w]),
                                 _number(fit["stderr"]["sigma"][w]), _number(fit["rmse"][w])])
        assert row.relative_rmse_percent == pytest.approx(100 * fit["relative_rmse"][w], rel=1e-15)
    assert df.attrs["units"] == {"albedo": "1", "sigma": "rad"}
    # The command prints the same text as params(format=...).
    for fmt in ("table", "csv", "markdown", "latex"):
        printed = cli("params", grouped, "--wavelength", "610", "--model", "oren-nayar", "--format", fmt).stdout
        assert printed == roadbrdf.params(grouped, wavelengths=[610], models="oren-nayar", format=fmt)


def test_params_answers_an_unfitted_wavelength_by_the_nearest_with_a_note(cli, grouped):
    r = cli("params", grouped, "--wavelength", "640", "--format", "csv")
    assert "roadbrdf: note: 640 nm: nearest band 610 nm" in r.stderr
    df = roadbrdf.params(grouped, wavelengths=[640])
    assert set(df["wavelength_nm"]) == {610.0}
    assert df.attrs["notes"] == ["640 nm: nearest band 610 nm"]


def test_grouped_file_member_is_chosen_with_fit(cli, grouped):
    r = cli("albedo", grouped, "--sun-zenith", "30", check=False)
    assert r.returncode == 2 and "--fit:" in r.stderr and "one per group" in r.stderr, r.stderr
    ok = cli("albedo", grouped, "--fit", "oren-nayar,theta_i=40", "--sun-zenith", "30")
    assert ok.returncode == 0
    m = roadbrdf.read_fit(grouped, "oren-nayar,theta_i=40")
    content = json.loads(grouped.read_text())
    fit = next(f for f in content["fits"] if f["model"] == "oren-nayar" and f["group"]["theta_i"] == 40)
    assert m.parameters_at(610.0) == {"albedo": fit["parameters"]["albedo"][1], "sigma": fit["parameters"]["sigma"][1]}


@pytest.mark.parametrize("flags, kwargs, message", [
    (["--where", "thta_r<70"], dict(where="thta_r<70"), "unknown column 'thta_r' (did you mean 'theta_r'?)"),
    (["--group-by", "theta_x"], dict(group_by="theta_x"), "unknown column 'theta_x'"),
    (["--where", "theta_r>89"], dict(where="theta_r>89"), "selects none of the"),
])
def test_the_same_errors_from_both_front_ends(cli, root, tmp_path, flags, kwargs, message):
    r = cli("fit", root / DATA, "--model", "lambert", *flags, "-o", tmp_path / "x.json", check=False)
    assert r.returncode == 2 and message in r.stderr, r.stderr
    flag = flags[0]
    assert f"roadbrdf: error: {flag}:" in r.stderr, r.stderr
    with pytest.raises(roadbrdf.InputError) as e:
        roadbrdf.fit(root / DATA, "lambert", **kwargs)
    assert message in str(e.value)
    assert not (tmp_path / "x.json").exists()


def test_params_errors(cli, grouped):
    r = cli("params", grouped, "--format", "latx", check=False)
    assert r.returncode == 2 and "--format: 'latx' is not one of table, csv, markdown, latex" in r.stderr, r.stderr
    r = cli("params", grouped, "--model", "oren-nayr", check=False)
    assert r.returncode == 2 and "(did you mean 'oren-nayar'?)" in r.stderr, r.stderr
    with pytest.raises(roadbrdf.InputError, match="did you mean 'oren-nayar'"):
        roadbrdf.params(grouped, models="oren-nayr")


def test_band_mean_fit_is_the_same_from_both_front_ends_and_recorded(cli, root, tmp_path):
    # lazard.csv is on a 20 nm grid: --band 590:610 fits the mean of the measured spectrum over the band
    # (linear between its two bands: (B590 + B610) / 2) at 600 nm.
    out = tmp_path / "band.fit.json"
    r = cli("fit", root / DATA, "--model", "lambert", "--band", "590:610", "-o", out)
    note = "590-610 nm: the mean over the band of the measured spectrum"
    assert f"roadbrdf: note: {note}" in r.stderr, r.stderr
    content = json.loads(out.read_text())
    assert content["fits"][0]["wavelengths"] == [600.0]
    assert any(note in n for n in content["notes"])
    result = roadbrdf.fit(root / DATA, "lambert", bands="590:610")
    assert _without_timing(result.to_dict()) == _without_timing(content)
    assert any(note in n for n in result.notes)
    # Independently, in closed form: the unweighted Lambertian fit of the band mean is albedo = pi * mean.
    plain = roadbrdf.fit(root / DATA, "lambert", bands="590:610", use_sigma=False)
    data = roadbrdf.read_dataset(root / DATA)
    w = list(data.wavelengths)
    assert 600.0 not in w
    band_mean = (data.brdf[:, w.index(590.0)] + data.brdf[:, w.index(610.0)]) / 2
    assert plain.best.parameter("albedo")[0] == pytest.approx(np.pi * band_mean.mean(), rel=1e-8)

@pytest.mark.parametrize("flags, kwargs, message", [
    (["--band", "590:610", "--wavelengths", "600"], dict(bands="590:610", wavelengths="600"),
     "give wavelengths or bands, not both"),
    (["--band", "610:590"], dict(bands="610:590"), "610:590"),
    (["--band", "590:610", "--band", "600:620"], dict(bands=["590:610", "600:620"]), "overlap"),
])
def test_band_errors_are_the_same_from_both_front_ends(cli, root, tmp_path, flags, kwargs, message):
    r = cli("fit", root / DATA, "--model", "lambert", *flags, "-o", tmp_path / "x.json", check=False)
    assert r.returncode == 2 and message in r.stderr, r.stderr
    with pytest.raises(roadbrdf.InputError) as e:
        roadbrdf.fit(root / DATA, "lambert", **kwargs)
    assert message in str(e.value)
    assert not (tmp_path / "x.json").exists()


def test_params_group_by_makes_one_table_per_value_from_both_front_ends(cli, grouped):
    flat = roadbrdf.params(grouped, wavelengths=[610])
    for fmt, heading in (("table", "## theta_i = {} deg"), ("markdown", "**theta_i = {} deg**"),
                         ("latex", "\\par\\textbf{theta\\_i = {} deg}")):
        text = cli("params", grouped, "--wavelength", "610", "--group-by", "theta_i", "--format", fmt).stdout
        assert text == roadbrdf.params(grouped, wavelengths=[610], group_by="theta_i", format=fmt)
        positions = [text.index(heading.replace("{}", str(t))) for t in (0, 20, 40, 60, 80)]
        assert positions == sorted(positions)
    # In the text table, the section of theta_i = 40 holds the flat table's rows of that group, without
    # the theta_i column, and no other rows.
    text = roadbrdf.params(grouped, wavelengths=[610], group_by="theta_i", format="table")
    section = text.split("## theta_i = 40 deg\n")[1].split("\n\n")[0].splitlines()
    assert "theta_i" not in section[0]
    body = [line.split() for line in section[1:]]
    expected = flat[flat["theta_i_deg"] == 40]
    assert [row[0] for row in body] == list(expected["model"])
    assert [float(row[1]) for row in body] == list(expected["wavelength_nm"])
    # The DataFrame stays one table, its rows in section order (model, then wavelength).
    df = roadbrdf.params(grouped, group_by=["model", "wavelength"])
    assert list(df["model"]) == sorted(df["model"], key=list(dict.fromkeys(df["model"])).index)
    for _, part in df.groupby("model", sort=False):
        assert list(part["wavelength_nm"]) == sorted(part["wavelength_nm"], key=list(dict.fromkeys(
            part["wavelength_nm"])).index)
    assert len(df) == len(roadbrdf.params(grouped))
    message = "unknown column 'thta_i' (did you mean 'theta_i'?)"
    r = cli("params", grouped, "--group-by", "thta_i", check=False)
    assert r.returncode == 2 and f"roadbrdf: error: --group-by: {message}" in r.stderr, r.stderr
    with pytest.raises(roadbrdf.InputError, match=r"did you mean 'theta_i'\?\); the columns of .* are model, "
                                                  r"theta_i, wavelength"):
        roadbrdf.params(grouped, group_by="thta_i")


@pytest.mark.parametrize("selection, group", [
    ("oren-nayar", {}),                       # several groups: name one
    ("oren-nayar,theta_i=50", {"theta_i": 50}),  # no such group
    ("oren-nayr,theta_i=40", {"theta_i": 40}),   # a misspelt model
    ("oren-nayar,theta_r=40", {"theta_r": 40}),  # not a column the file is grouped by
])
def test_one_rule_chooses_the_fit_of_a_file_and_of_a_result(cli, root, grouped, selection, group):
    """Which fit of a grouped result: FitResult.model_fit and the command's `--fit` (read from the FIT.json
    the same fit wrote) apply the readers' one rule, with the same message (the file's name apart)."""
    result = roadbrdf.fit(root / DATA, ["oren-nayar", "lambert"], group_by="theta_i", where="theta_r<=70",
                          wavelengths="510:710:100")
    r = cli("albedo", grouped, "--fit", selection, "--sun-zenith", "30", check=False)
    assert r.returncode == 2
    with pytest.raises(roadbrdf.InputError) as caught:
        result.model_fit(selection.split(",")[0], **group)
    message = str(caught.value)
    for name in (str(grouped), "the fit result"):
        message = message.replace(name, "FILE")
    printed = r.stderr.strip().replace(str(grouped), "FILE").replace("--fit", "fit")
    assert message in printed, (message, printed)
    assert result.model_fit("oren-nayar,theta_i=40") is result.model_fit("oren-nayar", theta_i=40)


def test_params_table_gives_numpy_columns_and_each_fits_fixed_options_and_bounds(root, tmp_path):
    """The binding's columns are NumPy arrays (float, bool, text as objects), and each fit shown comes with what
    the fit file says of it (model, group, options, fixed) and the physical range of its parameters, so that
    no front end reads the file a second time."""
    from roadbrdf import _roadbrdf
    path = tmp_path / "fixed.fit.json"
    roadbrdf.fit(root / DATA, ["oren-nayar", "lambert"], fixed={"sigma": 0.3}, wavelengths="510,610",
                 output=path)
    content = json.loads(path.read_text())
    t = _roadbrdf.params_table(str(path))
    assert "text" not in t  # rendered only when a format is asked for
    assert _roadbrdf.params_table(str(path), format="csv")["text"] == roadbrdf.params(path, format="csv")
    data = t["data"]
    assert all(isinstance(data[c], np.ndarray) for c in t["columns"])
    assert data["wavelength_nm"].dtype == np.float64 and data["converged"].dtype == np.bool_
    assert data["model"].dtype == object and data["at_bounds"].dtype == object
    rows = [(f["model"], w) for f in content["fits"] for w in f["wavelengths"]]
    assert list(zip(data["model"], data["wavelength_nm"])) == rows
    assert [f["model"] for f in t["fits"]] == [f["model"] for f in content["fits"]]
    for shown, written in zip(t["fits"], content["fits"]):
        assert shown["fixed"] == written["fixed"] and shown["options"] == written.get("options", {})
        assert shown["group"] == {}
        # An albedo is a reflectance: [0, 1] (energy conservation); sigma, the facet slope's standard deviation,
        # an angle from 0 to a right angle at most.
        assert shown["bounds"]["albedo"] == (0.0, 1.0)
        if shown["model"] == "oren-nayar":
            assert shown["fixed"] == ["sigma"]
            low, high = shown["bounds"]["sigma"]
            assert low == 0.0 and 0.0 < high <= np.pi / 2
        else:
            assert set(shown["bounds"]) == {"albedo"}
    # The DataFrame of roadbrdf.params is made of the same arrays.
    df = roadbrdf.params(path)
    np.testing.assert_array_equal(df["albedo"].to_numpy(), data["albedo"])
    assert df["converged"].dtype == bool and list(df["model"]) == [r[0] for r in rows]


def test_params_refuses_a_fit_of_a_model_the_library_does_not_have(root, tmp_path):
    path = tmp_path / "unknown.fit.json"
    roadbrdf.fit(root / DATA, ["lambert"], wavelengths="510", output=path)
    content = json.loads(path.read_text())
    content["fits"][0]["model"] = "lambertt"
    content["best"] = "lambertt"
    path.write_text(json.dumps(content))
    with pytest.raises(roadbrdf.InputError, match=r"unknown\.fit\.json: fits\[0\]\.model: unknown model 'lambertt'"):
        roadbrdf.params(path)
