"""USGS Spectral Library v7 (splib07a) ASCII spectra from Python: roadbrdf.read_usgs / usgs_dataset on
synthetic files written here, the same dataset as `roadbrdf convert --from usgs`, and real files of
../shared/real-data/usgs-splib07a-mixtures (never copied into the repository; skipped when absent).

Real reference values are typed in from the public-domain USGS files (Kokaly et al. 2017, USGS
Spectral Library Version 7 Data, doi:10.5066/F7RR1WDJ; line numbers of the files given with each)."""
import math

import numpy as np
import pytest

import roadbrdf

WAVELENGTHS = (" splib07a Record=23: Wavelengths ASD 0.35-2.5 microns 2151 ch\n"
               " 3.4999999e-001\n 3.5100001e-001\n 3.5200000e-001\n 3.5299999e-001\n")
SPECTRUM = (" splib07a Record=2257: Calcite GDS304 75-150um      ASDFRb AREF\n"
            " 7.9968947e-001\n-1.2300000e+034\n 7.9986185e-001\n 8.0005091e-001\n")


@pytest.fixture
def files(tmp_path):
    w = tmp_path / "w.txt"
    s = tmp_path / "s.txt"
    w.write_text(WAVELENGTHS)
    s.write_text(SPECTRUM)
    return s, w


def test_read_usgs_values_and_missing_channel(files):
    s, w = files
    u = roadbrdf.read_usgs(s, w)
    assert u["record"] == 2257 and u["wavelength_record"] == 23
    assert u["title"] == "Calcite GDS304 75-150um      ASDFRb AREF"
    assert u["channels"] == 4 and u["missing"] == 1
    # The float micrometres become whole nanometres; channel 351 nm (deleted) is left out.
    np.testing.assert_array_equal(u["wavelengths"], [350.0, 352.0, 353.0])
    np.testing.assert_array_equal(u["reflectance"], [0.79968947, 0.79986185, 0.80005091])


def test_read_usgs_errors_name_file_line_and_column(tmp_path, files):
    s, w = files
    bad = tmp_path / "bad.txt"
    bad.write_text(" splib07a Record=1: x\n 0.5\n  0,5\n 0.5\n 0.5\n")
    with pytest.raises(roadbrdf.InputError, match=r"bad\.txt:3:3: '0,5' is not a number"):
        roadbrdf.read_usgs(bad, w)
    short = tmp_path / "short.txt"
    short.write_text(" splib07a Record=1: x\n 0.5\n 0.5\n 0.5\n 0.5\n 0.5\n")
    with pytest.raises(roadbrdf.InputError, match=r"short\.txt:6:1: 5 values but the wavelength file has 4"):
        roadbrdf.read_usgs(short, w)
    plain = tmp_path / "plain.txt"  # a wavelength column without the splib07a title line
    plain.write_text("wavelength\n0.35\n0.351\n0.352\n0.353\n")
    with pytest.raises(roadbrdf.InputError, match=r"plain\.txt:1:1: not a USGS splib07a ASCII file"):
        roadbrdf.read_usgs(s, plain)


def test_usgs_dataset_is_reflectance_over_pi_and_matches_cli(files, cli, tmp_path):
    s, w = files
    d = roadbrdf.usgs_dataset(s, w, theta_i=30, phi_i=0, theta_r=0, phi_r=0)
    assert d.brdf.shape == (1, 3)
    np.testing.assert_allclose(d.brdf[0], np.array([0.79968947, 0.79986185, 0.80005091]) / math.pi, rtol=1e-15)
    assert d.metadata["usgs.quantity"] == "reflectance factor / pi"
    out = tmp_path / "c.csv"
    cli("convert", s, "--from", "usgs", "--usgs-wavelengths", w, "--geometry",
        "theta_i=30,phi_i=0,theta_r=0,phi_r=0", "-o", out)
    c = roadbrdf.read_dataset(out)
    np.testing.assert_array_equal(c.wavelengths, d.wavelengths)
    np.testing.assert_allclose(c.brdf, d.brdf, rtol=1e-15)
    np.testing.assert_allclose(c.angles, d.angles, atol=1e-12)
    with pytest.raises(roadbrdf.InputError, match="give the angles"):
        roadbrdf.usgs_dataset(s, w, theta_i=30)


# --- real files (USGS splib07a, public domain) ---

def _mixtures(real_data):
    folder = real_data / "usgs-splib07a-mixtures"
    if not folder.is_dir():
        pytest.skip(f"USGS splib07a mixtures not available ({folder} is absent)")
    return folder


def test_real_asd_calcite_endmember(real_data):
    folder = _mixtures(real_data)
    u = roadbrdf.read_usgs(folder / "spectra" / "splib07a_Calcite_GDS304_75-150um_ASDFRb_AREF.txt",
                           folder / "splib07a_Wavelengths_ASD_0.35-2.5_microns_2151_ch.txt")
    assert u["record"] == 2257 and u["wavelength_record"] == 23
    assert u["channels"] == 2151 and u["missing"] == 0
    assert u["wavelengths"][0] == 350.0 and u["wavelengths"][-1] == 2500.0
    np.testing.assert_array_equal(np.diff(u["wavelengths"]), 1.0)
    # Values typed in from splib07a_Calcite_GDS304_75-150um_ASDFRb_AREF.txt, lines 202, 652, 1652, 2152
    # (wavelength file lines 5.5000001e-001, 1.0000000e+000, 2.0000000e+000, 2.5000000e+000 um).
    r = dict(zip(u["wavelengths"], u["reflectance"]))
    assert r[550.0] == 8.7086308e-001
    assert r[1000.0] == 8.7320298e-001
    assert r[2000.0] == 7.6623189e-001
    assert r[2500.0] == 4.2205507e-001


def test_real_beckman_mixture_with_deleted_channels(real_data):
    folder = _mixtures(real_data)
    spectrum = folder / "spectra" / "splib07a_Calcite.80+Mont_Swy-1_GDS212_BECKa_AREF.txt"
    wavelengths = folder / "splib07a_Wavelengths_BECK_Beckman_0.2-3.0_microns.txt"
    u = roadbrdf.read_usgs(spectrum, wavelengths)
    # Lines 2-129 of the spectrum file are -1.2300000e+034 (deleted below 0.569 um); 480 channels in all.
    assert u["record"] == 12056 and u["channels"] == 480 and u["missing"] == 128
    assert u["wavelengths"].size == 352
    # Line 130: 5.6930000e-001 um, 7.8990519e-001; line 481: 2.9760001e+000 um, 2.1192528e-001.
    assert u["wavelengths"][0] == 569.3 and u["reflectance"][0] == 7.8990519e-001
    assert u["wavelengths"][-1] == 2976.0 and u["reflectance"][-1] == 2.1192528e-001
    d = roadbrdf.usgs_dataset(spectrum, wavelengths, theta_i=30, phi_i=0, theta_r=0, phi_r=0)
    assert d.brdf[0, 0] == pytest.approx(7.8990519e-001 / math.pi, rel=1e-15)
    # The wrong instrument's wavelength file is refused with both channel counts.
    with pytest.raises(roadbrdf.InputError,
                       match=r"2151_ch\.txt:482:1: 2151 values but the spectrum has 480"):
        roadbrdf.read_usgs(spectrum, folder / "splib07a_Wavelengths_ASD_0.35-2.5_microns_2151_ch.txt")
