"""The contrast of a road marking against a pavement (roadbrdf.marking / roadbrdf marking with
`pavement`, `headlamp`, `installation`): the same numbers and errors from both front ends, and the
closed form of a Lambertian marking on a Lambertian pavement, C = rho_m / rho_r - 1 under any light."""
import json
import math
import pathlib

import pytest

import roadbrdf

ROOT = pathlib.Path(__file__).resolve().parents[2]
LIGHTING = ROOT / "tests" / "data" / "lighting"


def test_cli_and_python_agree_on_the_contrast(cli):
    rho_m, rho_r = 0.6, 0.1
    lamp, installation = LIGHTING / "headlamp.ies", LIGHTING / "installation.json"
    py = roadbrdf.marking("lambert", parameters=[f"albedo={rho_m}"], pavement="lambert",
                          pavement_parameters=[f"albedo={rho_r}"], headlamp=lamp, installation=installation)
    out = json.loads(cli("marking", "lambert", "-p", f"albedo={rho_m}", "--pavement", "lambert",
                         "--pavement-parameter", f"albedo={rho_r}", "--headlamp", lamp, "--installation",
                         installation, "--json").stdout)
    assert py.value["contrast"] == out["contrast"]
    contrast = out["contrast"]
    assert contrast["headlamp"]["contrast"] == pytest.approx(rho_m / rho_r - 1, rel=1e-12)
    # headlamp.ies, plane C270 (down): 12000 cd at gamma 1 deg, 9000 cd at 2 deg; at epsilon = 1.24 deg
    # E = I sin(epsilon) / d^2 on the road, d = 30 m / cos(epsilon); L = (rho / pi) E (Lambert).
    eps = math.radians(1.24)
    intensity = 12000 - 0.24 * 3000
    e_road = intensity * math.sin(eps) * math.cos(eps) ** 2 / 30 ** 2
    light = contrast["headlamp"]["light"]
    assert light["intensity_cd"] == pytest.approx(intensity, rel=1e-12)
    assert light["illuminance_lx"] == pytest.approx(e_road, rel=1e-12)
    assert light["L_marking_cd_m2"] == pytest.approx(rho_m / math.pi * e_road, rel=1e-12)
    b = contrast["installation"]
    for observer in b["observers"]:
        for key in ("contrast_of_averages", "contrast_min", "contrast_max", "contrast_mean",
                    "contrast_of_averages_true_alpha"):
            assert observer[key] == pytest.approx(rho_m / rho_r - 1, rel=1e-9), key


def test_without_a_pavement_there_is_no_contrast():
    assert roadbrdf.marking("lambert", parameters=["albedo=0.6"])["contrast"] is None


def test_missing_pavement_file_is_the_same_error(cli, tmp_path):
    missing = tmp_path / "no-such-pavement.fit.json"
    result = cli("marking", "lambert", "--pavement", missing, check=False)
    with pytest.raises(roadbrdf.InputError) as error:
        roadbrdf.marking("lambert", pavement=missing)
    from conftest import assert_same_error
    assert_same_error(result, error.value, "--pavement", "pavement")
    assert str(missing) in str(error.value)


def test_headlamp_needs_a_pavement_in_both_front_ends(cli):
    lamp = LIGHTING / "headlamp.ies"
    result = cli("marking", "lambert", "--headlamp", lamp, check=False)
    with pytest.raises(roadbrdf.InputError, match=r"^headlamp: .*`pavement`"):
        roadbrdf.marking("lambert", headlamp=lamp)
    # The same message, each front end spelling the field it names its own way.
    assert result.returncode == 2 and result.stderr.startswith("roadbrdf: error: --headlamp: ")
    assert "give a --pavement" in result.stderr
