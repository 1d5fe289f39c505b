"""The export request's field table (ExportRequest::fields, io/model_export.cpp) seen from both front ends,
row by row: `roadbrdf export --help` shows each row's flag, `roadbrdf.export`'s docstring its keyword and
help, and a bad value is refused with the same text by both (the command line naming the flag, Python the
keyword). The rows come from the table itself, so a new field without a bad value here fails."""
import pytest
from request_table import check_every_row_is_shown, check_refused_alike, fields

import roadbrdf

FIELDS = fields("export")

# A quick valid request: a Lambertian surface on a 3 x 3 x 3 grid at one wavelength.
BASE = {"parameters": "albedo=0.3", "format": "csv", "wavelengths": "550", "theta_i": "0:60:30",
        "theta_r": "0:60:30", "phi": "0:180:90"}
# A bad value per field (the same text from both front ends); None for the free texts, which take any
# text (only Python's type check is compared with the table then).
BAD = {"source": "no-such-model", "parameters": "albedo=2", "options": "bogus=1", "fit": "x", "format": "xlsx",
       "preset": "radar", "wavelengths": "-5", "theta_i": "95", "theta_r": "95", "phi": "400",
       "output": "/nonexistent/folder/x.csv", "name": None, "description": None, "uuid": None,
       "material_version": None, "authors": None, "copyrights": None, "license": None, "sensor": None}


def test_every_row_has_a_bad_value():
    assert sorted(row["name"] for row in FIELDS) == sorted(BAD)


def test_every_row_is_an_option_and_a_keyword(cli):
    check_every_row_is_shown(cli, "export", roadbrdf.export)


@pytest.mark.parametrize("row", FIELDS, ids=[row["name"] for row in FIELDS])
def test_a_bad_value_is_refused_alike(cli, tmp_path, row):
    name = row["name"]
    output = str(tmp_path / "grid.csv")
    values = dict(BASE, output=output)
    if BAD[name] is None:
        with pytest.raises(roadbrdf.InputError, match=f"^{name}: expected a string"):
            roadbrdf.export("lambert", **{key: [value] if key == "parameters" else value
                                          for key, value in values.items()}, **{name: 5})
        return
    values[name] = BAD[name]
    source = values.pop("source", "lambert")
    cli_args = [source]
    for key, value in values.items():
        cli_args += [next(r for r in FIELDS if r["name"] == key)["long_flag"], value]
    result = cli("export", *cli_args, check=False)
    with pytest.raises(roadbrdf.InputError) as error:
        roadbrdf.export(source, **{key: [value] if key in ("parameters", "options") else value
                                   for key, value in values.items()})
    check_refused_alike("export", row, result, error.value)
    assert not (tmp_path / "grid.csv").exists()
