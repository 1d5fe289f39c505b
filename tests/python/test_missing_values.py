"""Missing cells (nan, empty, NA) are measurements not made: the Python readers keep
them as NaN, the fit masks them out at their wavelength, and the fit of a file with one NaN cell equals
the fit of the same file with that geometry removed at that wavelength (an independent fit of the
reduced file is the reference)."""
import math

import numpy as np
import pytest

import roadbrdf

HEADER = "theta_i,phi_i,theta_r,phi_r,500,600\n"


def rows():
    """A rough, not exactly Oren-Nayar surface on 24 geometries (deterministic 'noise')."""
    out = []
    k = 0
    for ti in (0, 20, 40, 60):
        for tr in (10, 35, 60):
            for pr in (0, 180):
                k += 1
                base = 0.08 * (1 + 0.4 * math.cos(math.radians(tr)) + 0.2 * (pr == 0) * math.sin(math.radians(ti)))
                wiggle = 1 + 0.03 * math.sin(7.3 * k)
                out.append([ti, 0, tr, pr, base * wiggle, 1.5 * base * wiggle * (1 + 0.02 * math.cos(3.1 * k))])
    return out


def write(path, table, missing=None):
    with open(path, "w") as f:
        f.write(HEADER)
        for i, r in enumerate(table):
            cells = [f"{v:.10g}" for v in r]
            if missing is not None and i == missing[0]:
                cells[4 + missing[1]] = missing[2]
            f.write(",".join(cells) + "\n")
    return path


@pytest.mark.parametrize("spelling", ["nan", "", "NA"])
def test_reader_keeps_missing_cells(tmp_path, spelling):
    with pytest.warns(UserWarning, match="1 of 48 BRDF values are missing"):
        d = roadbrdf.read_dataset(write(tmp_path / "d.csv", rows(), (5, 1, spelling)))
    assert np.isnan(d.brdf[5, 1]) and np.isfinite(np.delete(d.brdf.ravel(), 5 * 2 + 1)).all()
    with pytest.raises(roadbrdf.InputError, match=r"d\.csv:7:"):
        roadbrdf.read_dataset(tmp_path / "d.csv", allow_missing=False)


def test_fit_with_a_nan_cell_equals_the_fit_without_that_geometry(tmp_path):
    table = rows()
    with pytest.warns(UserWarning, match="missing"):
        holed = roadbrdf.fit(write(tmp_path / "holed.csv", table, (5, 1, "nan")), "oren-nayar", warm_start=False)
    reduced = roadbrdf.fit(write(tmp_path / "reduced.csv", table[:5] + table[6:]), "oren-nayar",
                           wavelengths=[600])
    complete = roadbrdf.fit(write(tmp_path / "complete.csv", table), "oren-nayar", warm_start=False)
    h, r, c = holed.best, reduced.best, complete.best
    assert holed.missing_values == 1 and "1 of 48 values missing" in holed.summary
    np.testing.assert_allclose(h.parameters[:, 1], r.parameters[:, 0], rtol=1e-9)
    np.testing.assert_allclose(h.standard_errors[:, 1], r.standard_errors[:, 0], rtol=1e-7)
    np.testing.assert_allclose(h.parameters[:, 0], c.parameters[:, 0], rtol=1e-9)  # 500 nm: complete
    assert not np.allclose(h.parameters[:, 1], c.parameters[:, 1], rtol=1e-6, atol=0)  # the cell mattered
    d = holed.to_dict()["fits"][0]
    assert d["points"] == [24, 23] and d["points_total"] == 47 and d["missing_values"] == 1


def test_cli_fit_and_convert_keep_missing_cells(tmp_path, cli):
    data = write(tmp_path / "holed.csv", rows(), (5, 1, "NA"))
    r = cli("fit", data, "-m", "oren-nayar", "-o", tmp_path / "f.json")
    assert "1 of 48 values missing" in r.stdout
    out = tmp_path / "long.csv"
    r = cli("convert", data, "--to", "long", "-o", out)
    assert "1 of 48 BRDF values are missing" in r.stderr
    with pytest.warns(UserWarning):
        d = roadbrdf.read_dataset(out)
    assert np.isnan(d.brdf[5, 1])


def test_long_file_without_a_row_reads_and_fits_as_a_missing_cell(tmp_path):
    table = rows()
    long = tmp_path / "absent.csv"
    with open(long, "w") as f:
        f.write("theta_i,phi_i,theta_r,phi_r,wavelength,brdf\n")
        for i, r in enumerate(table):
            for j, wl in enumerate((500, 600)):
                if (i, j) != (5, 1):  # the row of geometry 5 at 600 nm is never written
                    f.write(",".join(f"{v:.10g}" for v in r[:4]) + f",{wl},{r[4 + j]:.10g}\n")
    with pytest.warns(UserWarning, match=r"1 \(geometry, wavelength\) pairs of 48 have no row"):
        d = roadbrdf.read_dataset(long)
    assert np.isnan(d.brdf[5, 1]) and np.isfinite(np.delete(d.brdf.ravel(), 5 * 2 + 1)).all()
    with pytest.warns(UserWarning):
        absent = roadbrdf.fit(long, "oren-nayar", warm_start=False)
        holed = roadbrdf.fit(write(tmp_path / "holed.csv", table, (5, 1, "nan")), "oren-nayar", warm_start=False)
    assert absent.missing_values == 1
    np.testing.assert_allclose(absent.best.parameters, holed.best.parameters, rtol=1e-12)
    with pytest.raises(roadbrdf.InputError, match=r"absent\.csv:\d+: the geometry first given on this line has no "
                                                  r"value at wavelength 600 nm"):
        roadbrdf.read_dataset(long, allow_missing=False)
