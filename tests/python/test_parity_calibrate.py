"""roadbrdf calibrate and roadbrdf.calibrate_manifest: the panel BRF options are checked once, in the
library (io/calibration.h read_panel_brf), with the same message (the CLI naming its flag)."""
import pytest

import roadbrdf


@pytest.mark.parametrize("flag,keyword", [("--panel-brf-start", "panel_brf_start"),
                                          ("--panel-brf-step", "panel_brf_step")])
def test_panel_brf_options_without_a_file(cli, tmp_path, flag, keyword):
    out = tmp_path / "out.csv"
    r = cli("calibrate", "--manifest", tmp_path / "run.csv", "--panel-reflectance", tmp_path / "rho.txt", flag, "350",
            "-o", out, check=False)
    prefix = f"roadbrdf: error: {flag}: "
    assert r.returncode == 2 and r.stderr.startswith(prefix), r.stderr
    with pytest.raises(roadbrdf.InputError) as e:
        roadbrdf.calibrate_manifest(tmp_path / "run.csv", tmp_path / "rho.txt", **{keyword: 350.0})
    assert str(e.value) == f"{keyword}: " + r.stderr.strip()[len(prefix):]
    assert not out.exists()
