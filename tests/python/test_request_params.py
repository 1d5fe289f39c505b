"""The params request's field table (ParamsRequest::fields, fitting/params_table.cpp) seen from both front
ends, row by row: `roadbrdf params --help` shows each row's flag, `roadbrdf.params`'s docstring its keyword
and help, and a bad value is refused with the same text by both (the command line naming the flag, Python
the keyword). The rows come from the table itself, so a new field without a bad value here fails. The
numbers are those written into the fit file by the test."""
import json

import pytest
from request_table import check_every_row_is_shown, check_refused_alike, fields

import roadbrdf

FIELDS = fields("params")


def _fit_file(path, albedo=0.3, stderr=0.02, wavelengths=(500, 550)):
    """A fit file of one Lambertian model: albedo +- stderr at every wavelength."""
    n = len(wavelengths)
    fit = {"model": "lambert", "options": {}, "wavelengths": list(wavelengths),
           "parameters": {"albedo": [albedo] * n}, "parameter_order": ["albedo"], "fixed": [],
           "parameter_units": {"albedo": "1"}, "stderr": {"albedo": [stderr] * n}, "correlation": [[[1]]] * n,
           "rmse": [0.001] * n, "relative_rmse": [0.01] * n, "max_relative_error": [0.02] * n, "aic": [-50.0] * n,
           "bic": [-48.0] * n, "converged": [True] * n, "at_bounds": [[]] * n}
    path.write_text(json.dumps({"format": "roadbrdf-fit", "version": 1, "best": "lambert", "fits": [fit]}))
    return path


def _bad_values(tmp_path):
    """For every field: (command line arguments, Python positional fit file, Python keywords) of a bad value."""
    fit = str(_fit_file(tmp_path / "lambert.fit.json"))
    absent = str(tmp_path / "absent.fit.json")
    return {
        "fit_file": ([absent], absent, {}),
        "wavelengths": ([fit, "--wavelengths", "0"], fit, dict(wavelengths=[0])),
        "models": ([fit, "--model", "lambrt"], fit, dict(models="lambrt")),
        "group_by": ([fit, "--group-by", "theta_x"], fit, dict(group_by="theta_x")),
        "format": ([fit, "--format", "latx"], fit, dict(format="latx")),
        "output": ([fit, "-o", fit], fit, dict(output=fit)),
    }


def test_every_row_is_an_option_and_a_keyword(cli):
    check_every_row_is_shown(cli, "params", roadbrdf.params)


@pytest.mark.parametrize("row", FIELDS, ids=[row["name"] for row in FIELDS])
def test_a_bad_value_is_refused_alike(cli, tmp_path, row):
    bad = _bad_values(tmp_path)
    assert row["name"] in bad, f"the table's field {row['name']} needs a bad value in this test"
    cli_args, fit_file, kwargs = bad[row["name"]]
    result = cli("params", *cli_args, check=False)
    with pytest.raises(roadbrdf.InputError) as error:
        roadbrdf.params(fit_file, **kwargs)
    check_refused_alike("params", row, result, error.value)


def test_the_fit_file_is_required_by_both(cli):
    assert cli("params", check=False).returncode != 0
    with pytest.raises(TypeError, match="fit_file"):
        roadbrdf.params()


def test_both_front_ends_give_the_fit_files_numbers_and_write_the_same_file(cli, tmp_path):
    fit = _fit_file(tmp_path / "lambert.fit.json", albedo=0.3, stderr=0.02)
    # A wavelength that was not fitted is answered by the nearest fitted band, with a note.
    r = cli("params", fit, "--wavelength", "540", "--format", "csv", "-o", tmp_path / "cli.csv")
    df = roadbrdf.params(fit, wavelengths=540)
    text = roadbrdf.params(str(fit), wavelengths=[540], format="csv", output=tmp_path / "py.csv")
    assert (tmp_path / "py.csv").read_text() == (tmp_path / "cli.csv").read_text() == text
    assert list(df["wavelength_nm"]) == [550.0]
    assert list(df["albedo"]) == [0.3] and list(df["albedo_stderr"]) == [0.02]
    assert len(df.attrs["notes"]) == 1 and "550" in df.attrs["notes"][0]
    assert f"roadbrdf: note: {df.attrs['notes'][0]}" in r.stderr
    # Without an output file the command prints the text Python returns.
    assert cli("params", fit, "--format", "markdown").stdout == roadbrdf.params(fit, format="markdown")
    # Every fitted wavelength by default: one row each.
    assert list(roadbrdf.params(fit, models=["lambert"])["wavelength_nm"]) == [500.0, 550.0]
