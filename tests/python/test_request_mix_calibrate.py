"""The mix-calibrate request's field table (CrossSectionRequest::fields, mixing/cross_section_file.cpp) seen
from both front ends, row by row: `roadbrdf mix-calibrate --help` shows each row's flag,
`roadbrdf.mix_calibrate`'s docstring its keyword and help, and a bad value is refused with the same text by
both (the command line naming the flag, Python the keyword). The rows come from the table itself, so a new
field without a bad value here fails."""
import pytest
from request_table import check_every_row_is_shown, check_refused_alike, fields
from test_mix_calibrate import _setup

import roadbrdf
from roadbrdf import _roadbrdf

FIELDS = fields("mix-calibrate")


def _bad_values(pairs, tmp_path):
    """For every field that takes a value: (command line arguments after the pairs, Python pairs, Python
    keywords) of a bad one."""
    absent = str(tmp_path / "absent.json")
    data = str(pairs[0][1])
    return {
        "mixtures": ([], [(absent, data)], {}),
        "delimiter": (["--delimiter", "|"], pairs, dict(delimiter="|")),
        "decimal": (["--decimal", "x"], pairs, dict(decimal="x")),
        "quantity": (["--quantity", "brdff"], pairs, dict(quantity="brdff")),
        "columns": (["--column", "theta_r=No_Such_Column"], pairs, dict(columns=["theta_r=No_Such_Column"])),
        "set": (["--set", "theta_q=30"], pairs, dict(set=["theta_q=30"])),
        "reference": (["--reference", "granite"], pairs, dict(reference="granite")),
        "output": (["-o", str(pairs[0][0])], pairs, dict(output=pairs[0][0])),
    }


def test_every_row_is_an_option_and_a_keyword(cli):
    check_every_row_is_shown(cli, "mix-calibrate", roadbrdf.mix_calibrate)


@pytest.mark.parametrize("row", [r for r in FIELDS if r["kind"] != "switch"], ids=lambda r: r["name"])
def test_a_bad_value_is_refused_alike(cli, tmp_path, row):
    pairs = _setup(tmp_path)
    bad = _bad_values(pairs, tmp_path)
    assert row["name"] in bad, f"the table's field {row['name']} needs a bad value in this test"
    flags, python_pairs, keywords = bad[row["name"]]
    out = tmp_path / "x.json"
    if "-o" not in flags:
        flags = [*flags, "-o", out]
    result = cli("mix-calibrate", *[p for pair in python_pairs for p in pair], *flags, check=False)
    with pytest.raises(roadbrdf.InputError) as error:
        roadbrdf.mix_calibrate(python_pairs, **keywords)
    check_refused_alike("mix-calibrate", row, result, error.value)
    assert not out.exists()


def test_a_formulation_without_its_data_is_refused_alike(cli, tmp_path):
    pairs = _setup(tmp_path)
    files = [str(pairs[0][0]), str(pairs[0][1]), str(pairs[1][0])]
    result = cli("mix-calibrate", *files, "-o", tmp_path / "x.json", check=False)
    with pytest.raises(roadbrdf.InputError) as error:
        _roadbrdf.mix_calibrate(files)
    row = next(r for r in FIELDS if r["name"] == "mixtures")
    check_refused_alike("mix-calibrate", row, result, error.value)
    assert "3 files given: the last one has no partner" in str(error.value)


def test_the_output_file_is_required_by_the_command_only(cli, tmp_path):
    pairs = _setup(tmp_path)
    result = cli("mix-calibrate", *[p for pair in pairs for p in pair], check=False)
    assert result.returncode != 0 and "--output" in result.stderr
    assert roadbrdf.mix_calibrate(pairs, reference="calcite")["reference"] == "calcite"


def test_the_dataset_reading_fields_read_the_measured_mixtures(cli, tmp_path):
    """The same measurements written with ';' between fields and ',' as the decimal mark calibrate to the
    same factors as the plain files, given the reading fields by both front ends."""
    pairs = _setup(tmp_path)
    plain = roadbrdf.mix_calibrate(pairs, reference="calcite")
    converted = []
    for formulation, data in pairs:
        other = data.with_name(data.stem + "-semicolon.csv")
        other.write_text(data.read_text().replace(",", ";").replace(".", ","))
        converted.append((formulation, other))
    py = roadbrdf.mix_calibrate(converted, reference="calcite", delimiter=";", decimal=",",
                                output=tmp_path / "py.json")
    assert py["factors"] == pytest.approx(plain["factors"], rel=1e-12)
    cli("mix-calibrate", *[p for pair in converted for p in pair], "--reference", "calcite", "--delimiter", ";",
        "--decimal", ",", "-o", tmp_path / "cli.json")
    assert (tmp_path / "cli.json").read_text() == (tmp_path / "py.json").read_text()
