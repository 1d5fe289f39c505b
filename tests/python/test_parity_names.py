"""A name that is not one of an option's names: the program and Python report the same error, listing
the names and suggesting the nearest (the library's tables, core/enum_names.h), the program naming
its flag and Python the argument."""

import pytest

import roadbrdf
from conftest import assert_same_error

DATA = "data/examples/single/lazard.csv"
GEOMETRY = dict(theta_i=0, phi_i=0, theta_r=30, phi_r=180)



def _python_error(call):
    with pytest.raises(roadbrdf.InputError) as error:
        call()
    return error.value


def test_overlap_rule(cli, instruments, tmp_path):
    r = cli("convert", instruments / "sig_overlap.sig", "--geometry", "theta_i=0,phi_i=0,theta_r=30,phi_r=180",
            "--overlap", "uper", "-o", tmp_path / "out.csv", check=False)
    e = _python_error(lambda: roadbrdf.read_instrument(instruments / "sig_overlap.sig", overlap="uper"))
    assert_same_error(r, e, "--overlap", "overlap")
    assert str(e) == "overlap: 'uper' is not one of upper, lower, error (did you mean 'upper'?)"


def test_instrument_quantity(cli, instruments, tmp_path):
    r = cli("convert", instruments / "run_002.asd", "--geometry", "theta_i=0,phi_i=0,theta_r=30,phi_r=180",
            "--quantity", "reflectence", "-o", tmp_path / "out.csv", check=False)
    e = _python_error(lambda: roadbrdf.instrument_dataset(instruments / "run_002.asd", quantity="reflectence",
                                                          **GEOMETRY))
    assert_same_error(r, e, "--quantity", "quantity")
    assert str(e) == "quantity: 'reflectence' is not one of target, reference, reflectance (did you mean 'reflectance'?)"


def test_dataset_layout(cli, root, tmp_path):
    r = cli("convert", root / DATA, "--to", "lng", "-o", tmp_path / "out.csv", check=False)
    d = roadbrdf.read_dataset(root / DATA)
    e = _python_error(lambda: roadbrdf.write_dataset(d, tmp_path / "out.csv", format="lng"))
    assert_same_error(r, e, "--to", "format")
    assert str(e) == "format: 'lng' is not one of wide, long (did you mean 'long'?)"


def test_rtable_format(cli, root, tmp_path):
    table = root / "data/third-party/rtables/r1-table.dat"
    r = cli("rtable", "--import", table, "--import-format", "radiants", check=False)
    e = _python_error(lambda: roadbrdf.read_rtable(table, format="radiants"))
    assert_same_error(r, e, "--import-format", "format")
    assert str(e) == "format: 'radiants' is not one of csv, rtb, radiance (did you mean 'radiance'?)"
