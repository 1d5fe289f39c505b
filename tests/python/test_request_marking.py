"""The marking request's field table (MarkingRequest::fields, photometry/marking_request.cpp) seen from both
front ends, row by row: `roadbrdf marking --help` shows each row's flag, `roadbrdf.marking`'s docstring its
keyword and help, and a bad value is refused with the same text by both (the command line naming the flag,
Python the keyword). The rows come from the table itself, so a new field without a bad value here fails."""
import pathlib

import pytest
from request_table import check_every_row_is_shown, check_refused_alike, fields

import roadbrdf

FIELDS = fields("marking")
HEADLAMP = str(pathlib.Path(__file__).resolve().parents[1] / "data" / "lighting" / "headlamp.ies")


def _bad_values(tmp_path):
    """For every field: the fields of a request with one bad value (a white Lambertian marking otherwise)."""
    absent = str(tmp_path / "absent")
    lit = dict(pavement="lambert", headlamp=HEADLAMP)
    return {
        "source": dict(source="no-such-model"),
        "parameters": dict(parameters=["albedo=2"]),
        "options": dict(options=["bogus=1"]),
        "fit": dict(fit="x"),
        "illuminant": dict(illuminant=absent + ".csv"),
        "wavelength": dict(wavelength=-1),
        "illumination_angle": dict(illumination_angle=95),
        "observation_angle": dict(observation_angle=95),
        "tolerance": dict(tolerance=-1),
        "pavement": dict(pavement="no-such-model"),
        "pavement_parameters": dict(pavement="lambert", pavement_parameters=["albedo=2"]),
        "pavement_fit": dict(pavement="lambert", pavement_fit="x"),
        "headlamp": dict(pavement="lambert", headlamp=absent + ".ies"),
        "headlamp_down_plane": dict(lit, headlamp_down_plane=400),
        "installation": dict(installation=absent + ".json"),
    }


def test_every_row_is_an_option_and_a_keyword(cli):
    check_every_row_is_shown(cli, "marking", roadbrdf.marking)


@pytest.mark.parametrize("row", FIELDS, ids=[row["name"] for row in FIELDS])
def test_a_bad_value_is_refused_alike(cli, tmp_path, row):
    bad = _bad_values(tmp_path)
    assert row["name"] in bad, f"the table's field {row['name']} needs a bad value in this test"
    request = dict(source="lambert", parameters=["albedo=0.6"])
    request.update(bad[row["name"]])
    source = request.pop("source")
    cli_args = [source]
    for key, value in request.items():
        flag = next(r for r in FIELDS if r["name"] == key)["long_flag"]
        for item in value if isinstance(value, list) else [value]:
            cli_args += [flag, item]
    result = cli("marking", *cli_args, check=False)
    with pytest.raises(roadbrdf.InputError) as error:
        roadbrdf.marking(source, **request)
    check_refused_alike("marking", row, result, error.value)
