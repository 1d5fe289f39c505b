"""The luminaire request's field table (LuminaireRequest::fields, lighting/luminaire_request.cpp) seen from
both front ends, row by row: `roadbrdf luminaire --help` shows each row's flag, `roadbrdf.luminaire`'s
docstring its keyword and help, and a bad value is refused with the same text by both. The rows come from
the table itself, so a new field without a bad value here fails."""
import pathlib

import pytest
from request_table import check_bad_value_refused_alike, check_every_row_is_shown, fields

import roadbrdf

FIELDS = fields("luminaire")


def _bad_values(tmp_path):
    """For every field: (command line arguments, Python positional arguments, Python keywords)."""
    absent = str(tmp_path / "absent.ldt")
    return {"file": ([absent], [absent], {})}


def test_every_row_is_an_option_and_a_keyword(cli):
    check_every_row_is_shown(cli, "luminaire", roadbrdf.luminaire)


@pytest.mark.parametrize("row", FIELDS, ids=[row["name"] for row in FIELDS])
def test_a_bad_value_is_refused_alike(cli, tmp_path, row):
    bad = _bad_values(tmp_path)
    assert row["name"] in bad, f"the table's field {row['name']} needs a bad value in this test"
    cli_args, args, kwargs = bad[row["name"]]
    check_bad_value_refused_alike(cli, "luminaire", roadbrdf.luminaire, row, cli_args, args, kwargs)


def test_an_unknown_keyword_names_the_nearest(tmp_path):
    with pytest.raises(TypeError, match="did you mean 'file'"):
        roadbrdf.luminaire(fil=str(pathlib.Path(tmp_path) / "x.ldt"))
