"""The r-table request's field table (RTableRequest::fields, photometry/rtable_task.cpp) seen from both front
ends, row by row: `roadbrdf rtable --help` shows each row's flag, `roadbrdf.rtable`'s docstring its keyword
and help, and a bad value is refused with the same text by both (the command line naming the flag, Python
the keyword). The rows come from the table itself, so a new field without a bad value here fails. The
numbers are checked against closed forms and published tables."""
import json
import math

import pytest
from request_table import check_every_row_is_shown, check_refused_alike, fields

import roadbrdf

FIELDS = fields("rtable")
R1 = "data/third-party/rtables/r1-table.dat"


def _fit_file(path, model, parameters, stderr=None, correlation=None, wavelengths=(550,)):
    """A fit file of one model with the given parameters (the same at every wavelength)."""
    fit = {"model": model, "options": {}, "wavelengths": list(wavelengths),
           "parameters": {k: [v] * len(wavelengths) for k, v in parameters.items()},
           "parameter_order": list(parameters), "fixed": []}
    if stderr:
        fit["stderr"] = {k: [v] * len(wavelengths) for k, v in stderr.items()}
        fit["correlation"] = [correlation] * len(wavelengths)
    path.write_text(json.dumps({"format": "roadbrdf-fit", "version": 1, "best": model, "fits": [fit]}))
    return path


def _bad_values(root, tmp_path):
    """For every field: (command line arguments, Python positional model, Python keywords) of a bad value."""
    fit = str(_fit_file(tmp_path / "lambert.fit.json", "lambert", {"albedo": 0.3},
                        wavelengths=range(400, 701, 50)))
    table = str(root / R1)
    absent = str(tmp_path / "absent.csv")
    lambert = ["lambert", "-p", "albedo=0.3"]
    return {
        "model": (["no-such-model"], "no-such-model", {}),
        "parameters": (["lambert", "-p", "albedo=2"], "lambert", dict(parameters=["albedo=2"])),
        "options": (["lambert", "--option", "bogus=1"], "lambert", dict(options=["bogus=1"])),
        "fit": ([*lambert, "--fit", "lambert"], "lambert", dict(parameters=["albedo=0.3"], fit="lambert")),
        "import_file": (["--import", absent], None, dict(import_file=absent)),
        "import_format": (["--import", table, "--import-format", "radiants"], None,
                          dict(import_file=table, import_format="radiants")),
        "scale": ([*lambert, "--scale", "1"], "lambert", dict(parameters=["albedo=0.3"], scale=1)),
        "alpha": ([*lambert, "--alpha", "0"], "lambert", dict(parameters=["albedo=0.3"], alpha=0)),
        "illuminant": ([fit, "--illuminant", "Z"], fit, dict(illuminant="Z")),
        "wavelength": ([fit, "--wavelength", "-1"], fit, dict(wavelength=-1)),
        "band": ([fit, "--band", "600:500"], fit, dict(band=(600, 500))),
        "format": ([*lambert, "-o", str(tmp_path / "t.csv"), "--format", "xlsx"], "lambert",
                   dict(parameters=["albedo=0.3"], output=str(tmp_path / "t.csv"), format="xlsx")),
        "output": ([fit, "-o", fit], fit, dict(output=fit)),
        "compare": ([*lambert, "--compare", absent], "lambert", dict(parameters=["albedo=0.3"], compare=absent)),
        "q0_region": ([*lambert, "--q0-region", "all"], "lambert", dict(parameters=["albedo=0.3"], q0_region="all")),
        "class_system": ([*lambert, "--class-system", "Q"], "lambert",
                         dict(parameters=["albedo=0.3"], class_system="Q")),
    }


def test_every_row_is_an_option_and_a_keyword(cli):
    check_every_row_is_shown(cli, "rtable", roadbrdf.rtable)


@pytest.mark.parametrize("row", FIELDS, ids=[row["name"] for row in FIELDS])
def test_a_bad_value_is_refused_alike(cli, root, tmp_path, row):
    bad = _bad_values(root, tmp_path)
    assert row["name"] in bad, f"the table's field {row['name']} needs a bad value in this test"
    cli_args, model, kwargs = bad[row["name"]]
    result = cli("rtable", *cli_args, check=False)
    with pytest.raises(roadbrdf.InputError) as error:
        roadbrdf.rtable(model, **kwargs)
    check_refused_alike("rtable", row, result, error.value)


def test_a_model_and_an_import_exclude_each_other(cli, root):
    result = cli("rtable", "lambert", "--import", root / R1, check=False)
    with pytest.raises(roadbrdf.InputError) as error:
        roadbrdf.rtable("lambert", import_file=root / R1)
    assert result.stderr.startswith("roadbrdf: error: give either a MODEL")
    assert str(error.value).startswith("give either a `model`")


def test_lambert_figures_follow_the_closed_forms_and_warn_alike(cli):
    # Lambertian: Q0 = rho/pi, S1 = cos^3(atan 2) = 5^-1.5 (class N1 in the N system).
    r = cli("rtable", "lambert", "-p", "albedo=0.3", "--wavelength", "550", "--class-system", "N", "--json")
    j = json.loads(r.stdout)
    with pytest.warns(UserWarning, match="do not depend on wavelength"):
        t = roadbrdf.rtable(roadbrdf.Model("lambert"), {"albedo": 0.3}, wavelength=550.0, class_system="N")
    assert j["Q0"] == t["Q0"] == pytest.approx(0.3 / math.pi, rel=1e-12)
    assert j["S1"] == t["S1"] == pytest.approx(5 ** -1.5, rel=1e-12)
    assert j["class"] == t["class"] == "N1"
    assert j["warnings"] == t["warnings"]
    assert "roadbrdf: warning: " + t["warnings"][0] in r.stderr
    # The model by its name with parameters is the same request as the Model object.
    with pytest.warns(UserWarning, match="do not depend on wavelength"):
        by_name = roadbrdf.rtable("lambert", {"albedo": 0.3}, wavelength=550.0, class_system="N")
    assert by_name["Q0"] == t["Q0"] and by_name["source"] == j["source"] == {"model": "lambert"}


def test_uncertainty_follows_the_lambert_closed_form(cli, tmp_path):
    # Lambertian fit, albedo 0.3 +- 0.02: Q0 = Qd = rho/pi are linear in rho, so u(Q0) = u(Qd) = 0.02/pi;
    # S1 and S2 do not depend on rho (u = 0) and the class is certain.
    fit = _fit_file(tmp_path / "lambert.fit.json", "lambert", {"albedo": 0.3}, {"albedo": 0.02}, [[1]])
    j = json.loads(cli("rtable", str(fit), "--json").stdout)
    t = roadbrdf.rtable(fit)
    assert j["uncertainty"] == t["uncertainty"]
    u = t["uncertainty"]
    assert u["Q0"] == pytest.approx(0.02 / math.pi, rel=1e-9)
    assert u["Qd"] == pytest.approx(0.02 / math.pi, rel=1e-9)
    assert u["S1"] == pytest.approx(0.0, abs=1e-12)
    assert u["S2"] == pytest.approx(0.0, abs=1e-12)
    assert u["class_probabilities"] == [{"class": t["class"], "probability": 1.0}]
    assert u["correlated"]["Q0"] == pytest.approx(u["Q0"], rel=1e-12)  # one wavelength: the same
    # Rough diffuse with a correlated roughness: S1 moves too; the text names the uncertainties.
    fit = _fit_file(tmp_path / "on.fit.json", "oren-nayar", {"albedo": 0.4, "sigma": 0.3},
                    {"albedo": 0.01, "sigma": 0.05}, [[1, 0.6], [0.6, 1]])
    t = roadbrdf.rtable(fit, class_system="N")
    assert t["uncertainty"]["S1"] > 0
    assert sum(c["probability"] for c in t["uncertainty"]["class_probabilities"]) <= 1.0 + 1e-12
    assert t["uncertainty"]["class_probabilities"][0]["class"].startswith("N")
    assert f"u(S1) = {t['uncertainty']['S1']:.3g}" in cli("rtable", str(fit), "-o", str(tmp_path / "t.csv")).stdout
    # A model given by its parameters has no covariance.
    assert roadbrdf.rtable(roadbrdf.Model("lambert"), {"albedo": 0.3})["uncertainty"] is None


def test_an_imported_standard_table_has_its_published_figures(cli, root, tmp_path):
    # CIE 144 (2001) standard table R1: Q0 = 0.10 sr^-1, class R1; its S1 lies in R1's class interval S1 < 0.42.
    t = roadbrdf.rtable(import_file=root / R1, compare=root / R1, output=tmp_path / "py.rtb")
    assert t["Q0"] == pytest.approx(0.10, abs=0.005)
    assert t["class"] == "R1" and t["S1"] < 0.42
    assert t["comparison"]["max_relative_difference"] == 0.0
    assert t["source"]["format"] == "radiance" and t["output"]["format"] == "rtb"
    # One writer: the file Python writes is the command's.
    cli("rtable", "--import", root / R1, "-o", tmp_path / "cli.rtb")
    assert (tmp_path / "py.rtb").read_bytes() == (tmp_path / "cli.rtb").read_bytes()
