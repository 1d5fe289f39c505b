"""The resample request's field table (ResampleRequest::fields, io/resample_request.cpp) seen from both front
ends, row by row: `roadbrdf resample --help` shows each row's flag, `roadbrdf.resample`'s docstring its
keyword and help, and a bad value is refused with the same text by both (the command line naming the flag,
Python the keyword). The rows come from the table itself, so a new field without a bad value here fails.
The reference values are closed forms: the band average of a spectrum linear in wavelength is its value
at the band's centre."""
import pytest
from request_table import check_every_row_is_shown, check_refused_alike, fields

import roadbrdf

FIELDS = fields("resample")
A, B = 0.02, 1e-4  # f(lambda) = A + B (lambda - 400 nm) [sr^-1]
WAVELENGTHS = range(400, 801, 10)


def _linear(path, zigzag=()):
    """Spectra A + B (lambda - 400) at 400-800 nm on a few geometries; at the wavelengths `zigzag` the
    values alternate by +-40 % (noise the quality check flags)."""
    rows = ["theta_i,phi_i,theta_r,phi_r," + ",".join(str(w) for w in WAVELENGTHS)]
    for ti in (10, 30, 50):
        for tr in (10, 20, 40, 60):
            values = []
            for k, w in enumerate(WAVELENGTHS):
                f = A + B * (w - 400)
                if w in zigzag:
                    f *= 1.4 if k % 2 else 0.6
                values.append(repr(f))
            rows.append(f"{ti},0,{tr},180," + ",".join(values))
    path.write_text("\n".join(rows) + "\n")
    return path


def _bad_values(tmp_path, data):
    """For every field that takes a value: (command line arguments after DATA, Python keywords)."""
    return {
        "data": (None, None),
        "delimiter": (["--delimiter", "|"], dict(delimiter="|")),
        "decimal": (["--decimal", "x"], dict(decimal="x")),
        "quantity": (["--quantity", "brdff"], dict(quantity="brdff")),
        "columns": (["--column", "theta_r=No_Such_Column"], dict(columns=["theta_r=No_Such_Column"])),
        "set": (["--set", "theta_q=30"], dict(set=["theta_q=30"])),
        "wavelengths": (["--wavelengths", "700,500"], dict(wavelengths="700,500")),
        "drop": (["--drop", "0:5"], dict(drop="0:5")),
        "snr_threshold": (["--snr-threshold", "-1"], dict(snr_threshold=-1)),
        "format": (["--format", "wid"], dict(format="wid")),
        "output": (["-o", data], dict(output=data)),
    }


def test_every_row_is_an_option_and_a_keyword(cli):
    check_every_row_is_shown(cli, "resample", roadbrdf.resample)


@pytest.mark.parametrize("row", [r for r in FIELDS if r["kind"] != "switch"], ids=lambda r: r["name"])
def test_a_bad_value_is_refused_alike(cli, tmp_path, row):
    data = str(_linear(tmp_path / "linear.csv"))
    bad = _bad_values(tmp_path, data)
    assert row["name"] in bad, f"the table's field {row['name']} needs a bad value in this test"
    flags, keywords = bad[row["name"]]
    if flags is None:  # the dataset file itself
        data, flags, keywords = str(tmp_path / "absent.csv"), [], {}
    if "wavelengths" not in keywords:
        flags, keywords = ["--wavelengths", "500:700:100", *flags], dict(wavelengths="500:700:100", **keywords)
    result = cli("resample", data, *flags, check=False)
    with pytest.raises(roadbrdf.InputError) as error:
        roadbrdf.resample(data, **keywords)
    check_refused_alike("resample", row, result, error.value)


def test_the_dataset_and_the_band_edges_are_required_by_both(cli, tmp_path):
    data = _linear(tmp_path / "linear.csv")
    assert cli("resample", "--wavelengths", "500:700:100", check=False).returncode != 0
    assert cli("resample", data, check=False).returncode != 0
    with pytest.raises(TypeError, match="data"):
        roadbrdf.resample(wavelengths="500:700:100")
    with pytest.raises(TypeError, match="wavelengths"):
        roadbrdf.resample(data)


def test_band_averages_of_a_linear_spectrum_are_its_values_at_the_centres_in_both(cli, tmp_path):
    data = _linear(tmp_path / "linear.csv")
    cli("resample", data, "--wavelengths", "450:750:50", "--drop", "600:610", "--format", "long", "-o",
        tmp_path / "cli.csv")
    d = roadbrdf.resample(data, wavelengths=[450, 500, 550, 600, 650, 700, 750], drop=[(600, 610)], format="long",
                          output=tmp_path / "py.csv")
    assert (tmp_path / "py.csv").read_text() == (tmp_path / "cli.csv").read_text()
    # The band 600-650 overlaps the dropped interval 600-610 and is left out; 550-600 only touches it.
    assert list(d.wavelengths) == [475.0, 525.0, 575.0, 675.0, 725.0]
    for w, column in zip(d.wavelengths, d.brdf.T):
        assert column == pytest.approx([A + B * (w - 400)] * len(column), rel=1e-12)


def test_the_noisy_bands_left_out_are_those_check_finds(cli, tmp_path):
    data = _linear(tmp_path / "noisy.csv", zigzag=range(600, 661, 10))
    noisy = [(b["from_nm"], b["to_nm"]) for b in roadbrdf.check(data, snr_threshold=20)["noise"]["noisy_bands"]]
    assert noisy and all(lower <= 660 and upper >= 600 for lower, upper in noisy)
    cli("resample", data, "--wavelengths", "400:800:20", "--drop-noisy", "-o", tmp_path / "cli.csv")
    d = roadbrdf.resample(data, wavelengths="400:800:20", drop_noisy=True, output=tmp_path / "py.csv")
    assert (tmp_path / "py.csv").read_text() == (tmp_path / "cli.csv").read_text()
    explicit = roadbrdf.resample(data, wavelengths="400:800:20", drop=noisy)
    assert list(d.wavelengths) == list(explicit.wavelengths)
    assert (d.brdf == explicit.brdf).all()
    assert "noisy_bands_nm" in d.metadata
