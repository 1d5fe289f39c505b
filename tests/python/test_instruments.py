"""Instrument files and run manifests from Python: the same results and errors as the CLI."""
import math

import numpy as np
import pytest

import roadbrdf



def rho(l):  # make_synthetic.py
    return 0.95 + 0.00001 * (l - 350.0)


def test_calibrate_manifest_closed_form_and_same_as_cli(instruments, cli, tmp_path):
    d = roadbrdf.calibrate_manifest(instruments / "run.csv", instruments / "rho.txt")
    assert d.brdf.shape == (3, 21)
    for k in range(3):
        expected = 0.1 * (k + 1) * (1 + d.wavelengths / 10000.0) * rho(d.wavelengths) / math.pi
        np.testing.assert_allclose(d.brdf[k], expected, rtol=1e-14)
    assert d.metadata["white_reference"] == "run_white.asd"
    out = tmp_path / "run.brdf.csv"
    cli("calibrate", "--manifest", instruments / "run.csv", "--panel-reflectance", instruments / "rho.txt", "-o", out)
    c = roadbrdf.read_dataset(out)
    np.testing.assert_array_equal(c.brdf, d.brdf)
    np.testing.assert_allclose(c.angles, d.angles, atol=1e-12)


def test_read_instrument_and_overlap_rules(instruments):
    with pytest.warns(UserWarning, match="detector overlap"):
        s = roadbrdf.read_instrument(instruments / "sig_overlap.sig")
    assert s.format == "sig" and s.wavelengths.size == 31 and s.quantity == "radiance"
    with pytest.warns(UserWarning, match="upper detector dropped"):
        lower = roadbrdf.read_instrument(instruments / "sig_overlap.sig", overlap="lower")
    assert lower.wavelengths[20] == 380.0
    with pytest.raises(roadbrdf.InputError, match=r"sig_overlap.sig:30:1: detector overlap"):
        roadbrdf.read_instrument(instruments / "sig_overlap.sig", overlap="error")
    a = roadbrdf.read_instrument(instruments / "run_001.asd")
    assert a.metadata["asd.integration_time_ms"] == "68" and a.reference is not None
    n = roadbrdf.read_instrument(instruments / "sed_no_reflectance.sed")
    assert n.reflectance is None


def test_instrument_dataset_matches_cli_convert(instruments, cli, tmp_path):
    d = roadbrdf.instrument_dataset(instruments / "run_002.asd", quantity="reflectance", gamma=30, alpha=45, beta=0,
                                    delta=0)
    out = tmp_path / "one.csv"
    cli("convert", instruments / "run_002.asd", "--geometry", "gamma=30,alpha=45,beta=0,delta=0", "--quantity",
        "reflectance", "-o", out)
    text = out.read_text()
    assert "# units: 1 (reflectance factor relative to the reference panel)" in text
    row = [float(x) for x in text.strip().splitlines()[-1].split(",")]
    np.testing.assert_array_equal(row[4:], d.brdf[0])


def test_errors_are_the_cli_errors(instruments, cli, tmp_path):
    cut = tmp_path / "cut.asd"
    cut.write_bytes((instruments / "run_001.asd").read_bytes()[:600])
    with pytest.raises(roadbrdf.InputError) as e:
        roadbrdf.read_instrument(cut)
    r = cli("convert", cut, "--geometry", "theta_i=0,phi_i=0,theta_r=30,phi_r=180", check=False)
    assert r.returncode != 0
    assert str(e.value) in r.stderr
    assert "byte 484: file ends inside the spectrum" in str(e.value)
    with pytest.raises(roadbrdf.InputError, match="different settings"):
        roadbrdf.calibrate_manifest(instruments / "run_settings_mismatch.csv", instruments / "rho.txt")


def test_real_asd_and_svc_files(real_data):
    folder = real_data / "instrument-files"
    # PROVENANCE.md header table: v7sample00003, reflectance, IT 68 ms, ratio 0.843 / 0.893 / 0.824.
    s = roadbrdf.read_instrument(folder / "asd-pyASD-MIT" / "v7sample" / "v7sample00003.asd")
    assert s.metadata["asd.data_type"] == "reflectance" and s.metadata["asd.integration_time_ms"] == "68"
    for wl, ratio in ((500, 0.843), (1000, 0.893), (2000, 0.824)):
        assert abs(s.reflectance[wl - 350] - ratio) < 5e-4
    # The SVC white-reference scan: the reflectance column read back (percent / 100).
    with pytest.warns(UserWarning, match="detector overlap"):
        w = roadbrdf.read_instrument(folder / "svc-sig-spectrolab-GPL3" / "ACPL_D2_P1_T_1_WR_000.sig")
    assert abs(np.mean(w.reflectance) - 1.0) < 1e-3
