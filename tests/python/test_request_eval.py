"""The eval request's field table (EvalRequest::fields, io/eval_request.cpp; its model source rows shared with
simulate, modelfile/model_source_fields.h) seen from both front ends, row by row: `roadbrdf eval --help` shows
each row's flag, `roadbrdf.evaluate`'s docstring its keyword and help, and a bad value is refused with the
same text by both (the command line naming the flag, Python the keyword). The rows come from the table itself,
so a new field without a bad value here fails. The values are checked against closed forms."""
import json
import math

import pytest
from request_table import check_bad_value_refused_alike, check_every_row_is_shown, fields

import roadbrdf

FIELDS = fields("eval")
ANGLES = dict(theta_i=30, phi_i=0, theta_r=20, phi_r=180)
ANGLE_ARGS = ["--theta-i", "30", "--phi-i", "0", "--theta-r", "20", "--phi-r", "180"]


def _lambert_fit(path, wavelengths, albedos):
    """A fit file of a Lambertian surface, its albedo given per wavelength."""
    fit = {"model": "lambert", "options": {}, "wavelengths": list(wavelengths),
           "parameters": {"albedo": list(albedos)}, "parameter_order": ["albedo"], "fixed": []}
    path.write_text(json.dumps({"format": "roadbrdf-fit", "version": 1, "best": "lambert", "fits": [fit]}))
    return str(path)


def _geometry(path, rows):
    path.write_text("theta_i,phi_i,theta_r,phi_r\n" + "".join(",".join(map(str, r)) + "\n" for r in rows))
    return str(path)


def _bad_values(tmp_path):
    """For every field: (command line arguments, Python model, Python keywords) of a bad value."""
    fit = _lambert_fit(tmp_path / "l3.fit.json", [450, 550, 650], [0.2, 0.3, 0.4])
    geometry = _geometry(tmp_path / "g.csv", [(30, 0, 20, 180)])
    absent = str(tmp_path / "absent.csv")
    three = {k: v for k, v in ANGLES.items() if k != "theta_i"}
    return {
        "model": (["no-such-model", *ANGLE_ARGS], "no-such-model", ANGLES),
        "parameters": (["lambert", "-p", "albedo=2", *ANGLE_ARGS], "lambert", dict(ANGLES, parameters=["albedo=2"])),
        "options": (["lambert", "--option", "bogus=1", *ANGLE_ARGS], "lambert", dict(ANGLES, options=["bogus=1"])),
        "fit": (["lambert", "--fit", "lambert", *ANGLE_ARGS], "lambert", dict(ANGLES, fit="lambert")),
        "wavelength": (["lambert", "--wavelength", "500", *ANGLE_ARGS], "lambert", dict(ANGLES, wavelength=500)),
        "theta_i": (["lambert", *ANGLE_ARGS[2:]], "lambert", three),
        "phi_i": ([fit, *ANGLE_ARGS], fit, ANGLES),  # three bands: choose one with the wavelength
        "theta_r": (["lambert", "--geometry", geometry, *ANGLE_ARGS], "lambert", dict(ANGLES, geometry=geometry)),
        "phi_r": (["lambert", *ANGLE_ARGS[:6]], "lambert", {k: v for k, v in ANGLES.items() if k != "phi_r"}),
        "geometry": (["lambert", "--geometry", absent], "lambert", dict(geometry=absent)),
        "output": (["lambert", "--geometry", geometry, "-o", geometry], "lambert",
                   dict(geometry=geometry, output=geometry)),
    }


def test_every_row_is_an_option_and_a_keyword(cli):
    check_every_row_is_shown(cli, "eval", roadbrdf.evaluate)


@pytest.mark.parametrize("row", FIELDS, ids=[row["name"] for row in FIELDS])
def test_a_bad_value_is_refused_alike(cli, tmp_path, row):
    bad = _bad_values(tmp_path)
    assert row["name"] in bad, f"the table's field {row['name']} needs a bad value in this test"
    cli_args, model, kwargs = bad[row["name"]]
    check_bad_value_refused_alike(cli, "eval", roadbrdf.evaluate, row, cli_args, [model], kwargs)


def test_an_error_naming_parameters_prints_the_parameter_flag(cli):
    # The field `parameters` is spelt by eval's table (its row -p,--parameter), not by a rule of names.
    result = cli("eval", "lambert", "-p", "albedo=x", *ANGLE_ARGS, check=False)
    assert result.stderr.startswith("roadbrdf: error: --parameter: "), result.stderr
    with pytest.raises(roadbrdf.InputError, match="^parameters: "):
        roadbrdf.evaluate("lambert", parameters=["albedo=x"], **ANGLES)


def test_lambert_is_its_albedo_over_pi_in_both(cli, tmp_path):
    # Lambertian BRDF: rho / pi at every geometry (closed form).
    value = float(cli("eval", "lambert", "-p", "albedo=0.3", *ANGLE_ARGS).stdout)
    assert value == pytest.approx(0.3 / math.pi, rel=1e-9)
    assert roadbrdf.evaluate("lambert", parameters=["albedo=0.3"], **ANGLES) == pytest.approx(0.3 / math.pi, rel=1e-12)
    fit = _lambert_fit(tmp_path / "l3.fit.json", [450, 550, 650], [0.2, 0.3, 0.4])
    assert roadbrdf.evaluate(fit, wavelength=650, **ANGLES) == pytest.approx(0.4 / math.pi, rel=1e-12)
    # A geometry file: one value per row, the same table written by both front ends.
    geometry = _geometry(tmp_path / "g.csv", [(0, 0, 0, 0), (60, 10, 45, 200)])
    values = roadbrdf.evaluate(fit, wavelength=450, geometry=geometry, output=tmp_path / "py.csv")
    assert values == pytest.approx([0.2 / math.pi] * 2, rel=1e-12)
    cli("eval", fit, "--wavelength", "450", "--geometry", geometry, "-o", tmp_path / "cli.csv")
    assert (tmp_path / "py.csv").read_bytes() == (tmp_path / "cli.csv").read_bytes()
    assert cli("eval", fit, "--wavelength", "450", "--geometry", geometry).stdout == (tmp_path / "cli.csv").read_text()
