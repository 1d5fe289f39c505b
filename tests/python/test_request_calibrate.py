"""The calibrate request's field table (CalibrateRequest::fields, io/calibrate_request.cpp; its dataset-reading
rows shared through io/dataset_read_fields.h, its instrument row through io/instrument_options.h) seen from both
front ends, row by row: `roadbrdf calibrate --help` shows each row's flag, `roadbrdf.calibrate`'s docstring its
keyword and help, and a bad value is refused with the same text by both (the command line naming the flag,
Python the keyword). The rows come from the table itself, so a new field without a bad value here fails. The
values are checked against the closed form f = (S - dark)/(white - dark) x rho/pi."""
import math

import numpy as np
import pytest
from request_table import check_bad_value_refused_alike, check_every_row_is_shown, check_refused_alike, fields

import roadbrdf
from roadbrdf import _roadbrdf

FIELDS = fields("calibrate")
WAVELENGTHS = (500.0, 600.0, 700.0)
# Sample radiances at two geometries, a white reference of one row used for both, a dark row, and a
# panel reflectance rho(lambda) (arbitrary units: only the ratios count).
SAMPLE = ((0, 0, 30, 180, (12.0, 14.0, 16.0)), (30, 0, 30, 180, (7.0, 8.0, 9.0)))
WHITE = (52.0, 62.0, 72.0)
DARK = (2.0, 2.0, 2.0)
RHO = (0.90, 0.95, 0.98)


def _write_radiances(path, rows):
    header = "theta_i,phi_i,theta_r,phi_r," + ",".join(f"{w:g}" for w in WAVELENGTHS)
    lines = [header] + [",".join(f"{v:g}" for v in (*angles, *values)) for (*angles, values) in rows]
    path.write_text("# units: arbitrary radiance units\n" + "\n".join(lines) + "\n")
    return path


def _setup(tmp_path):
    sample = _write_radiances(tmp_path / "sample.csv", SAMPLE)
    white = _write_radiances(tmp_path / "white.csv", [(0, 0, 0, 0, WHITE)])
    dark = _write_radiances(tmp_path / "dark.csv", [(0, 0, 0, 0, DARK)])
    rho = tmp_path / "rho.txt"
    rho.write_text("".join(f"{w:g} {r:g}\n" for w, r in zip(WAVELENGTHS, RHO)))
    return sample, white, dark, rho


def _bad_values(tmp_path, instruments):
    """For every field that takes a value: (command line arguments, Python positional arguments, Python
    keywords) of a bad one."""
    sample, white, dark, rho = (str(p) for p in _setup(tmp_path))
    absent = str(tmp_path / "absent.csv")
    run, run_rho = str(instruments / "run.csv"), str(instruments / "rho.txt")

    def radiances(*flags, **keywords):
        return ([sample, "--reference", white, "--panel-reflectance", rho, *flags], [sample],
                dict(reference=white, panel_reflectance=rho, **keywords))

    def manifest(*flags, **keywords):
        return (["--manifest", run, "--panel-reflectance", run_rho, *flags], [],
                dict(manifest=run, panel_reflectance=run_rho, **keywords))

    return {
        "sample": ([absent, "--reference", white, "--panel-reflectance", rho], [absent],
                   dict(reference=white, panel_reflectance=rho)),
        "reference": ([sample, "--reference", absent, "--panel-reflectance", rho], [sample],
                      dict(reference=absent, panel_reflectance=rho)),
        "manifest": (["--manifest", absent, "--panel-reflectance", rho], [], dict(manifest=absent,
                                                                                 panel_reflectance=rho)),
        "overlap": manifest("--overlap", "uper", overlap="uper"),
        "delimiter": radiances("--delimiter", "|", delimiter="|"),
        "decimal": radiances("--decimal", "x", decimal="x"),
        "quantity": radiances("--quantity", "brdff", quantity="brdff"),
        "columns": radiances("--column", "theta_r=No_Such_Column", columns=["theta_r=No_Such_Column"]),
        "set": radiances("--set", "theta_q=30", set=["theta_q=30"]),
        "dark": radiances("--dark", absent, dark=absent),
        "panel_reflectance": ([sample, "--reference", white, "--panel-reflectance", absent], [sample],
                              dict(reference=white, panel_reflectance=absent)),
        "panel_brf": radiances("--panel-brf", absent, panel_brf=absent),
        "panel_brf_start": manifest("--panel-brf-start", "350", panel_brf_start=350.0),
        "panel_brf_step": manifest("--panel-brf-step", "1", panel_brf_step=1.0),
        "format": radiances("--format", "xlsx", format="xlsx"),
        "output": radiances("-o", sample, output=sample),
    }


def test_every_row_is_an_option_and_a_keyword(cli):
    check_every_row_is_shown(cli, "calibrate", roadbrdf.calibrate)


@pytest.mark.parametrize("row", [r for r in FIELDS if r["kind"] != "switch"], ids=lambda r: r["name"])
def test_a_bad_value_is_refused_alike(cli, tmp_path, instruments, row):
    bad = _bad_values(tmp_path, instruments)
    assert row["name"] in bad, f"the table's field {row['name']} needs a bad value in this test"
    flags, positional, keywords = bad[row["name"]]
    out = tmp_path / "out.csv"
    if "-o" not in flags:
        flags = [*flags, "-o", out]
    check_bad_value_refused_alike(cli, "calibrate", roadbrdf.calibrate, row, flags, positional, keywords)
    assert not out.exists()


def test_the_radiances_calibrate_to_the_closed_form_and_both_write_the_same_file(cli, tmp_path):
    sample, white, dark, rho = _setup(tmp_path)
    d = roadbrdf.calibrate(sample, reference=white, dark=dark, panel_reflectance=rho, output=tmp_path / "py.csv")
    assert list(d.wavelengths) == list(WAVELENGTHS)
    for k, (*_, values) in enumerate(SAMPLE):
        expected = [(s - b) / (w - b) * r / math.pi for s, w, b, r in zip(values, WHITE, DARK, RHO)]
        np.testing.assert_allclose(d.brdf[k], expected, rtol=1e-12)
    assert d.metadata["sample_radiance"] == str(sample) and d.metadata["dark"] == str(dark)
    cli("calibrate", sample, "--reference", white, "--dark", dark, "--panel-reflectance", rho, "-o",
        tmp_path / "cli.csv")
    assert (tmp_path / "py.csv").read_bytes() == (tmp_path / "cli.csv").read_bytes()


def test_the_dataset_reading_fields_read_the_radiances(cli, tmp_path):
    """The same radiances written with ';' between fields and ',' as the decimal mark calibrate to the same
    values, given the reading fields by both front ends."""
    sample, white, dark, rho = _setup(tmp_path)
    plain = roadbrdf.calibrate(sample, reference=white, panel_reflectance=rho)
    converted = []
    for path in (sample, white):
        other = path.with_name(path.stem + "-semicolon.csv")
        other.write_text(path.read_text().replace(",", ";").replace(".", ","))
        converted.append(other)
    py = roadbrdf.calibrate(converted[0], reference=converted[1], panel_reflectance=rho, delimiter=";",
                            decimal=",", output=tmp_path / "py.csv")
    np.testing.assert_allclose(py.brdf, plain.brdf, rtol=1e-15)
    cli("calibrate", converted[0], "--reference", converted[1], "--panel-reflectance", rho, "--delimiter", ";",
        "--decimal", ",", "-o", tmp_path / "cli.csv")
    assert (tmp_path / "cli.csv").read_text() == (tmp_path / "py.csv").read_text()


def test_a_manifest_with_radiance_files_or_no_input_is_refused_alike(cli, tmp_path, instruments):
    sample, white, dark, rho = _setup(tmp_path)
    run = instruments / "run.csv"
    row = next(r for r in FIELDS if r["name"] == "manifest")
    result = cli("calibrate", sample, "--manifest", run, "--panel-reflectance", rho, check=False)
    with pytest.raises(roadbrdf.InputError) as error:
        roadbrdf.calibrate(sample, manifest=run, panel_reflectance=rho)
    check_refused_alike("calibrate", row, result, error.value)
    assert "gives the sample, white reference and dark files" in str(error.value)
    result = cli("calibrate", "--reference", white, "--panel-reflectance", rho, check=False)
    with pytest.raises(roadbrdf.InputError) as error:
        roadbrdf.calibrate(reference=white, panel_reflectance=rho)
    check_refused_alike("calibrate", row, result, error.value)
    assert result.stderr.strip() == "roadbrdf: error: give SAMPLE and --reference, or --manifest (a run CSV)"


@pytest.mark.parametrize("flag,keyword", [("--panel-brf-start", "panel_brf_start"),
                                          ("--panel-brf-step", "panel_brf_step")])
def test_the_panel_brf_options_are_checked_before_the_run_is_read(cli, tmp_path, flag, keyword):
    # Neither the manifest nor the panel file exists: the option without its file is the error reported.
    out = tmp_path / "out.csv"
    r = cli("calibrate", "--manifest", tmp_path / "run.csv", "--panel-reflectance", tmp_path / "rho.txt", flag, "350",
            "-o", out, check=False)
    assert r.returncode == 2 and r.stderr.startswith(f"roadbrdf: error: {flag}: needs the panel BRF file"), r.stderr
    with pytest.raises(roadbrdf.InputError, match=f"^{keyword}: needs the panel BRF file"):
        roadbrdf.calibrate_manifest(tmp_path / "run.csv", tmp_path / "rho.txt", **{keyword: 350.0})
    assert not out.exists()


def test_calibrate_manifest_is_the_request_with_its_manifest(instruments, tmp_path):
    d = roadbrdf.calibrate_manifest(instruments / "run.csv", instruments / "rho.txt", overlap="lower",
                                    output=tmp_path / "run.brdf.csv")
    e = roadbrdf.calibrate(manifest=instruments / "run.csv", panel_reflectance=instruments / "rho.txt")
    np.testing.assert_array_equal(d.brdf, e.brdf)
    np.testing.assert_array_equal(roadbrdf.read_dataset(tmp_path / "run.brdf.csv").brdf, d.brdf)
    with pytest.raises(TypeError, match="did you mean 'panel_brf'"):
        roadbrdf.calibrate_manifest(instruments / "run.csv", instruments / "rho.txt", panel_bfr="x")
    with pytest.raises(TypeError, match="missing required argument 'panel_reflectance'"):
        _roadbrdf.calibrate(manifest=str(instruments / "run.csv"))
