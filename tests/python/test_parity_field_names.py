"""Library messages name request fields (core/error.h): Python shows the keyword argument, the command
line its flag, in the same message. Covers the field as the subject of an error (atmosphere) and a
field mentioned inside a message (a hint naming `average_duplicates`)."""
import pytest

import roadbrdf

ATMOSPHERES = [
    ("spectrl2:fog=1", "spectrl2: unknown setting 'fog'"),
    ("spectrl2:aod", "spectrl2: expected NAME=VALUE, got 'aod'"),
    ("spectrl2:day=0", "spectrl2: day = '0' must be an integer day of year in 1..366"),
    ("cloudy", "expected spectrl2[:aod=...,water=...,ozone=...,pressure=...], got 'cloudy'"),
]


@pytest.mark.parametrize("spec,detail", ATMOSPHERES, ids=[a[0] for a in ATMOSPHERES])
def test_atmosphere_errors_name_the_field(cli, tmp_path, spec, detail):
    r = cli("albedo", "lambert", "-p", "albedo=0.3", "--atmosphere", spec, "-o", tmp_path / "a.csv", check=False)
    assert r.returncode == 2, r.stderr
    assert r.stderr.startswith(f"roadbrdf: error: --atmosphere: {detail}"), r.stderr
    with pytest.raises(roadbrdf.InputError) as e:
        roadbrdf.albedo(roadbrdf.Model("lambert"), {"albedo": 0.3}, atmosphere=spec)
    assert str(e.value).startswith(f"atmosphere: {detail}")
    assert "--" not in str(e.value)
    assert r.stderr.strip()[len("roadbrdf: error: --atmosphere: "):] == str(e.value)[len("atmosphere: "):]


def test_a_hint_names_the_flag_or_the_keyword(cli, tmp_path):
    path = tmp_path / "dup.csv"
    path.write_text("theta_i,phi_i,theta_r,phi_r,550\n30,0,30,180,0.1\n30,0,30,180,0.12\n")
    r = cli("check", path, check=False)
    assert r.returncode == 2, r.stderr
    assert "ask for averaging of duplicates (--average-duplicates) to average them" in r.stderr, r.stderr
    with pytest.raises(roadbrdf.InputError) as e:
        roadbrdf.read_dataset(path)
    message = str(e.value)
    assert "ask for averaging of duplicates (`average_duplicates`) to average them" in message
    # Apart from the field's spelling, the two messages are the same.
    assert r.stderr.strip() == "roadbrdf: error: " + message.replace("`average_duplicates`", "--average-duplicates")


def test_columns_is_spelt_by_the_dataset_table_of_check(cli, tmp_path):
    # `columns` is the row --column of the dataset-reading table that `check` is made from, not a rename.
    path = tmp_path / "d.csv"
    path.write_text("theta_i,phi_i,theta_r,phi_r,550\n30,0,30,180,0.1\n")
    r = cli("check", path, "--column", "bogus=x", check=False)
    assert r.returncode == 2, r.stderr
    assert r.stderr.startswith("roadbrdf: error: --column: 'bogus' is no dataset field"), r.stderr
    with pytest.raises(roadbrdf.InputError, match="^columns: 'bogus' is no dataset field"):
        roadbrdf.read_dataset(path, columns={"bogus": "x"})
    # A reference inside a file's message is spelt by the same table.
    r = cli("check", path, "--column", "theta_r=View", check=False)
    assert "--column theta_r=View" in r.stderr and "`columns`" not in r.stderr, r.stderr
