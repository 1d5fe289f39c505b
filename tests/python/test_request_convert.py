"""The convert request's field table (ConvertRequest::fields, io/convert_request.cpp; its dataset-reading rows
shared through io/dataset_read_fields.h, its instrument row through io/instrument_options.h) seen from both front
ends, row by row: `roadbrdf convert --help` shows each row's flag, `roadbrdf.convert`'s docstring its keyword and
help, and a bad value is refused with the same text by both (the command line naming the flag, Python the
keyword). The rows come from the table itself, so a new field without a bad value here fails."""
import math
import os

import numpy as np
import pytest
from request_table import check_bad_value_refused_alike, check_every_row_is_shown, check_refused_alike, fields

import roadbrdf

FIELDS = fields("convert")
ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
CURET = os.path.join(ROOT, "data", "third-party", "curet", "abrdf.dat")
ALTA = os.path.join(ROOT, "data", "third-party", "retroreflective", "retro-gray-tape.dat")
GEOMETRY = "theta_i=0,phi_i=0,theta_r=30,phi_r=180"
# Reflectance factors (BRF) at two geometries and two wavelengths: BRDF = BRF / pi.
BRF = {(0, 0, 30, 180): (0.20, 0.25), (30, 0, 30, 180): (0.40, 0.50)}


def _data(tmp_path):
    path = tmp_path / "brf.csv"
    rows = ["theta_i,phi_i,theta_r,phi_r,500,600"]
    rows += [",".join(f"{v:g}" for v in (*angles, *values)) for angles, values in BRF.items()]
    path.write_text("\n".join(rows) + "\n")
    return str(path)


def _bad_values(tmp_path, instruments):
    """For every field that takes a value: (command line arguments, Python positional arguments, Python
    keywords) of a bad one."""
    data = _data(tmp_path)
    absent = str(tmp_path / "absent.csv")
    asd, run = str(instruments / "run_001.asd"), str(instruments / "run.csv")

    def on_data(*flags, **keywords):
        return ([data, *flags], [data], keywords)

    def on_curet(*flags, **keywords):
        return ([CURET, "--from", "curet", *flags], [CURET], dict(source="curet", **keywords))

    return {
        "inputs": ([absent], [absent], {}),
        "source": on_data("--from", "curett", source="curett"),
        "to": on_data("--to", "xlsx", to="xlsx"),
        "curet_table": on_curet("--sample", "45", "--curet-table", absent, sample=45, curet_table=absent),
        "sample": on_curet("--sample", "999", sample=999),
        "wavelength": on_curet("--sample", "45", "--wavelength", "-1", sample=45, wavelength=-1.0),
        "alta_output": ([ALTA, "--from", "alta", "--wavelength", "550", "--alta-output", "bogus"], [ALTA],
                        dict(source="alta", wavelength=550.0, alta_output="bogus")),
        "delimiter": on_data("--delimiter", "|", delimiter="|"),
        "decimal": on_data("--decimal", "x", decimal="x"),
        "quantity": on_data("--quantity", "brdff", quantity="brdff"),
        "columns": on_data("--column", "theta_r=No_Such_Column", columns=["theta_r=No_Such_Column"]),
        "set": on_data("--set", "theta_q=30", set=["theta_q=30"]),
        "convention": on_data("--convention", "polar", convention="polar"),
        "geometry": ([asd, "--geometry", "theta_i=0,phi_i=0"], [asd], dict(geometry="theta_i=0,phi_i=0")),
        "usgs_wavelengths": ([asd, "--geometry", GEOMETRY, "--usgs-wavelengths", absent], [asd],
                             dict(geometry=GEOMETRY, usgs_wavelengths=absent)),
        "overlap": ([run, "--from", "manifest", "--overlap", "uper"], [run], dict(source="manifest", overlap="uper")),
        "output": on_data("-o", data, output=data),
    }


def test_every_row_is_an_option_and_a_keyword(cli):
    check_every_row_is_shown(cli, "convert", roadbrdf.convert)


@pytest.mark.parametrize("row", [r for r in FIELDS if r["kind"] != "switch"], ids=lambda r: r["name"])
def test_a_bad_value_is_refused_alike(cli, tmp_path, instruments, row):
    bad = _bad_values(tmp_path, instruments)
    assert row["name"] in bad, f"the table's field {row['name']} needs a bad value in this test"
    flags, positional, keywords = bad[row["name"]]
    out = tmp_path / "out.csv"
    if "-o" not in flags:
        flags = [*flags, "-o", out]
    check_bad_value_refused_alike(cli, "convert", roadbrdf.convert, row, flags, positional, keywords)
    assert not out.exists()


def test_reflectance_factors_become_brdf_and_both_write_the_same_file(cli, tmp_path):
    data = _data(tmp_path)
    d = roadbrdf.convert(data, quantity="brf", to="long", convention="road", output=tmp_path / "py.csv")
    assert list(d.wavelengths) == [500.0, 600.0]
    for k, values in enumerate(BRF.values()):
        np.testing.assert_allclose(d.brdf[k], np.array(values) / math.pi, rtol=1e-15)
    cli("convert", data, "--quantity", "brf", "--to", "long", "--convention", "road", "-o", tmp_path / "cli.csv")
    assert (tmp_path / "py.csv").read_bytes() == (tmp_path / "cli.csv").read_bytes()
    assert (tmp_path / "cli.csv").read_text().count("\ngamma,alpha,beta,delta,wavelength,brdf") == 1


def test_several_runs_combine_and_other_inputs_do_not_alike(cli, tmp_path, instruments):
    data = _data(tmp_path)
    other = tmp_path / "other.csv"
    other.write_text("theta_i,phi_i,theta_r,phi_r,500,600\n60,0,30,180,0.1,0.2\n")
    d = roadbrdf.convert([data, other], quantity="brf")
    np.testing.assert_allclose(d.brdf[2], np.array([0.1, 0.2]) / math.pi, rtol=1e-15)
    asd = instruments / "run_001.asd"
    result = cli("convert", asd, data, "--geometry", GEOMETRY, check=False)
    with pytest.raises(roadbrdf.InputError) as error:
        roadbrdf.convert([asd, data], geometry=GEOMETRY)
    check_refused_alike("convert", next(r for r in FIELDS if r["name"] == "inputs"), result, error.value)
    assert result.stderr.strip() == ("roadbrdf: error: several INPUT files combine only as dataset CSV files "
                                     "(wide or long)")


def test_an_instrument_file_without_geometry_is_refused_alike(cli, instruments):
    asd = instruments / "run_001.asd"
    result = cli("convert", asd, check=False)
    with pytest.raises(roadbrdf.InputError) as error:
        roadbrdf.convert(asd)
    check_refused_alike("convert", next(r for r in FIELDS if r["name"] == "geometry"), result, error.value)
    assert "give --geometry theta_i=D" in result.stderr and "with --from manifest" in result.stderr
    with pytest.raises(TypeError, match="did you mean 'source'"):
        roadbrdf.convert(asd, sourc="asd")
