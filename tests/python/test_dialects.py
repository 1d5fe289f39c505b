"""Dataset dialects in Python: the same detection, options and errors as the command line."""
import numpy as np
import pytest

import roadbrdf

CANONICAL = ("theta_i,phi_i,theta_r,phi_r,450,550.5\n"
             "0,0,30,180,0.0125,0.025\n"
             "30,0,45.5,180,0.0375,-0.0005\n")


def spreadsheet(text):
    return "\ufeff" + text.replace(",", ";").replace(".", ",").replace("\n", "\r\n")


def test_spreadsheet_export_reads_like_the_canonical_file(tmp_path):
    (tmp_path / "a.csv").write_text(CANONICAL)
    (tmp_path / "b.csv").write_text(spreadsheet(CANONICAL.replace("theta_i", " Theta_I [deg]")), encoding="utf-8",
                                    newline="")
    with pytest.warns(UserWarning):
        a = roadbrdf.read_dataset(tmp_path / "a.csv")
    with pytest.warns(UserWarning):
        b = roadbrdf.read_dataset(tmp_path / "b.csv", delimiter=";", decimal=",")
    with pytest.warns(UserWarning):
        c = roadbrdf.read_dataset(tmp_path / "b.csv")
    np.testing.assert_array_equal(a.brdf, b.brdf)
    np.testing.assert_array_equal(a.brdf, c.brdf)
    np.testing.assert_array_equal(a.wavelengths, [450.0, 550.5])
    assert b.brdf[1, 1] == -0.0005


def test_same_errors_as_the_command_line(tmp_path, cli):
    path = tmp_path / "b.csv"
    path.write_text(spreadsheet(CANONICAL))
    with pytest.raises(roadbrdf.InputError, match="a decimal comma needs another delimiter"):
        roadbrdf.read_dataset(path, delimiter=",", decimal=",")
    with pytest.raises(roadbrdf.InputError, match="^delimiter: 'pipe' is not one of auto"):
        roadbrdf.read_dataset(path, delimiter="pipe")
    # Python names the keyword argument, the command line its flag.
    with pytest.raises(roadbrdf.InputError, match=r"b\.csv:1:.*see `decimal`"):
        roadbrdf.read_dataset(path, decimal=".")
    r = cli("check", path, "--decimal", ".", check=False)
    assert r.returncode != 0 and "see --decimal" in r.stderr
