"""Design studies with lighting predictions (``"predictions": {"lighting": ...}``, docs/studies.md): each candidate's
mixture BRDF through the EN 13201 calculation, against the direct ``roadbrdf.lighting`` call on the same BRDF and
closed forms for a Lambertian road; bad study keys name their JSON key path; bad store lines are located errors;
the albedo - lighting power figure."""

import json
import math
import pathlib
import shutil
import subprocess
import sys

import numpy as np
import pytest

import roadbrdf
from roadbrdf import plot_study
from roadbrdf.studies.run import make_tasks
from roadbrdf.studies.spec import read_study
from study_support import candidate_file, two_rock_study
from test_study import expected_albedo

DATA = pathlib.Path(__file__).resolve().parents[1] / "data" / "lighting"
# The flat luminaire on the right-hand edge of a two-lane road (closed forms); its surface is replaced by each
# candidate's.
INSTALLATION = {"format": "roadbrdf-installation", "version": 1, "road": {"lanes": 2, "lane_width_m": 3.5},
                "luminaires": {"file": "flat.ldt", "arrangement": "single-sided", "side": "right", "spacing_m": 30,
                               "height_m": 10, "overhang_m": 0, "tilt_deg": 0, "maintenance_factor": 1,
                               "power_w": 90},
                "surface": {"rtable": "R3"}}
# The bundled installation (a road luminaire, 12000 lm, 90 W, MF 0.8, spacing 30 m, height 10 m), under which every
# candidate can be dimmed to M6.
BUNDLED = json.loads((DATA / "installation.json").read_text())
I0_CD_PER_KLM = 300.0  # the flat luminaire's constant intensity below the horizontal
LAMP_FLUX = 10000.0


def flat_ldt(watts=90):
    """An EULUMDAT file of rotational symmetry (Isym 1) with the constant intensity I0 cd/klm for gamma 0-90 deg
    (none above: the file stops at 90 deg), 10000 lm of lamps, LORL 100 %, ``watts`` of system power."""
    lines = ["Test Lighting", "1", "1", "1", "0", "3", "45", "R-1", "flat", "N-1", "flat.ldt", "2026-12-06",
             "600", "200", "100", "500", "150", "20", "30", "20", "30", "100", "100", "1", "0", "1", "1", "LED",
             f"{LAMP_FLUX:g}", "4000K", "80", f"{watts:g}"]
    lines += ["0.5"] * 10
    lines += ["0", "0", "45", "90"] + [f"{I0_CD_PER_KLM:g}"] * 3
    return "\r\n".join(lines) + "\r\n"


def lighting_study(tmp_path, lighting=None, installation=None, watts=90):
    """The two-rock study (Lambertian rocks: every candidate is a Lambertian road of a known albedo) with
    lighting predictions over the flat luminaire (or ``installation``)."""
    study = two_rock_study(tmp_path)
    (tmp_path / "flat.ldt").write_text(flat_ldt(watts))
    shutil.copy(DATA / "road.ldt", tmp_path / "road.ldt")
    (tmp_path / "road.json").write_text(json.dumps(installation or INSTALLATION))
    data = json.loads(study.read_text())
    data["predictions"]["lighting"] = lighting or {"installation": "road.json", "class": "M6"}
    study.write_text(json.dumps(data))
    return study


@pytest.fixture(scope="module")
def rows(tmp_path_factory):
    """The study under the bundled installation, least power for M6."""
    folder = tmp_path_factory.mktemp("lighting-study")
    study = lighting_study(folder, installation=BUNDLED)
    return folder, roadbrdf.study(str(study), workers=1, progress=False)


@pytest.fixture(scope="module")
def flat_rows(tmp_path_factory):
    """The study under the flat luminaire, no class."""
    folder = tmp_path_factory.mktemp("lighting-study-flat")
    study = lighting_study(folder, lighting={"installation": "road.json"})
    return folder, roadbrdf.study(str(study), workers=1, progress=False)


def test_each_candidate_equals_the_direct_lighting_call_on_its_brdf(rows):
    folder, table = rows
    assert len(table) == 6
    for row in table:
        rho = expected_albedo(row["grey [%]"], row["rock [library]"])
        installation = dict(BUNDLED, surface={"model": "lambert", "parameters": {"albedo": rho}})
        path = folder / "direct.json"
        path.write_text(json.dumps(installation))
        direct = roadbrdf.lighting(path, target_class="M6")
        for name in ("L_av", "U_o", "U_l", "f_TI", "R_EI", "E_av", "U_o_E", "D_P", "D_E"):
            assert row[f"{name} [{direct['units'][name]}]"] == pytest.approx(direct[name], rel=1e-9), name
        assert row["M_class [class]"] == direct["M_class"]
        assert row["power_per_km_w [W/km]"] == pytest.approx(direct["energy"]["power_per_km_w"], rel=1e-12)
        assert row["least_class [class]"] == "M6"
        assert row["least_power_per_km_w [W/km]"] == pytest.approx(direct["least_flux"]["power_per_km_w"], rel=1e-9)
        assert row["reflected_upward_lm_per_km [lm/km]"] == pytest.approx(
            direct["upward"]["reflected_upward_lm_per_km"], rel=1e-6)
        assert row["ULOR [1]"] == direct["upward"]["ULOR"] == 0.0


def test_lambertian_candidates_follow_the_closed_forms(flat_rows, rows):
    _, table = flat_rows
    h, width, spacing = 10.0, 7.0, 30.0
    intensity = I0_CD_PER_KLM * LAMP_FLUX / 1000.0  # [cd], MF = 1
    per_km = 1000.0 / spacing
    for row in table:
        rho = expected_albedo(row["grey [%]"], row["rock [library]"])
        assert row["lighting_reflectance [1]"] == pytest.approx(rho, rel=1e-6)
        # A point source of constant intensity I at height h over the edge of an infinitely long strip of width W
        # sends 2 I atan(W / h) lm onto it (the solid angle of the strip seen from the source is 2 atan(W / h) for
        # a constant intensity, integrated in x = h tan u); a Lambertian road reflects the fraction rho upward.
        assert row["reflected_upward_lm_per_km [lm/km]"] == pytest.approx(
            rho * 2 * intensity * math.atan(width / h) * per_km, rel=1e-4)
        # The illuminance does not depend on the road; the luminance of a Lambertian road is rho E / pi up to the
        # r-table's interpolation, so L_av / rho is the same for every candidate.
        first = table[0]
        rho0 = expected_albedo(first["grey [%]"], first["rock [library]"])
        assert row["E_av [lx]"] == pytest.approx(first["E_av [lx]"], rel=1e-12)
        assert row["L_av [cd/m^2]"] / rho == pytest.approx(first["L_av [cd/m^2]"] / rho0, rel=1e-9)
        assert row["L_av [cd/m^2]"] == pytest.approx(rho * row["E_av [lx]"] / math.pi, rel=0.02)
        assert row["least_class [class]"] is None and row["least_power_per_km_w [W/km]"] is None
        # EN 13201-5: D_P = P / (E_av A), D_E = P t / A over one spacing of the carriageway.
        assert row["D_P [W lx^-1 m^-2]"] == pytest.approx(90 / (row["E_av [lx]"] * width * spacing), rel=1e-12)
        assert row["D_E [Wh m^-2 per year]"] == pytest.approx(90 * 4000 / (width * spacing), rel=1e-12)
    # Under the road luminaire, the least flux for a class limited by L_av (L_av,M6 = 0.3 cd/m^2) is inversely
    # proportional to rho, and so is the power per km (power proportional to flux).
    _, table = rows
    for row in table:
        rho = expected_albedo(row["grey [%]"], row["rock [library]"])
        assert row["least_class [class]"] == "M6" and row["least_blocking [criteria]"] is None
        assert row["least_dimming_factor [1]"] == pytest.approx(0.3 / row["L_av [cd/m^2]"], rel=1e-12)
        assert row["least_power_per_km_w [W/km]"] == pytest.approx(row["least_dimming_factor [1]"] * 90 * per_km,
                                                                   rel=1e-12)
        assert row["least_power_per_km_w [W/km]"] * rho == pytest.approx(
            table[0]["least_power_per_km_w [W/km]"] * expected_albedo(table[0]["grey [%]"], table[0]["rock [library]"]),
            rel=1e-9)


def test_the_installation_files_are_in_the_task_keys(tmp_path):
    study = lighting_study(tmp_path)
    before = [t[3] for t in make_tasks(read_study(str(study)), "v")]
    (tmp_path / "flat.ldt").write_text(flat_ldt().replace("Test Lighting", "Test Lighting 2"))
    after = [t[3] for t in make_tasks(read_study(str(study)), "v")]
    assert not set(before) & set(after)
    plain = json.loads(study.read_text())
    del plain["predictions"]["lighting"]
    study.write_text(json.dumps(plain))
    without = [t[3] for t in make_tasks(read_study(str(study)), "v")]
    assert not set(without) & set(after)


def _no_power():
    """The flat installation without power_w (and the luminaire file written with 0 W)."""
    luminaires = {k: v for k, v in INSTALLATION["luminaires"].items() if k != "power_w"}
    return dict(INSTALLATION, luminaires=luminaires)


@pytest.mark.parametrize("lighting, installation, key, fragment", [
    ("road.json", None, "predictions.lighting", "expected an object"),
    ({"class": "M3"}, None, "predictions.lighting.installation", "required key is missing"),
    ({"installation": "road.json", "clas": "M3"}, None, "predictions.lighting.clas", "unknown key"),
    ({"installation": "absent.json"}, None, "predictions.lighting.installation", "absent.json"),
    ({"installation": "road.json", "class": "M9"}, None, "predictions.lighting.class", "not an M lighting class"),
    ({"installation": "road.json", "class": 3}, None, "predictions.lighting.class", "not an M lighting class"),
    ({"installation": "road.json", "operating_hours": -1}, None, "predictions.lighting.operating_hours",
     "outside [0, 8784]"),
    ({"installation": "road.json", "operating_hours": "night"}, None, "predictions.lighting.operating_hours",
     "expected a number"),
    ({"installation": "road.json"}, dict(INSTALLATION, road={"lanes": 0, "lane_width_m": 3.5}),
     "predictions.lighting.installation", "road.lanes"),
    ({"installation": "road.json"}, _no_power(), "predictions.lighting.installation", "luminaires.power_w"),
])
def test_bad_lighting_keys_name_their_key_path(tmp_path, lighting, installation, key, fragment):
    study = lighting_study(tmp_path, lighting=lighting, installation=installation,
                           watts=0 if fragment == "luminaires.power_w" else 90)
    with pytest.raises(roadbrdf.InputError) as error:
        read_study(str(study))
    message = str(error.value)
    assert message.startswith(f"{study}: {key}: "), message
    assert fragment in message, message


def test_lighting_needs_the_fast_path(tmp_path):
    study = lighting_study(tmp_path)
    data = json.loads(study.read_text())
    data["predictions"] = {"path": "physical", "sun_zenith_deg": [30], "diffuse_fraction": 0.2,
                           "lighting": {"installation": "road.json"}}
    study.write_text(json.dumps(data))
    with pytest.raises(roadbrdf.InputError, match=r"predictions\.lighting: only with \"path\": \"fast\""):
        read_study(str(study))


@pytest.mark.parametrize("row, fragment", [
    ({"method": "areal", "L_av": "bright"}, "rows[0].L_av: expected a number or null"),
    ({"method": "areal", "least_power_per_km_w": [1]}, "rows[0].least_power_per_km_w: expected a number"),
    ({"method": "areal", "M_class": 4}, "rows[0].M_class: expected text or null"),
    ({"method": "areal", "U_o": True}, "rows[0].U_o: expected a number"),
])
def test_malformed_lighting_fields_in_the_store_are_located_errors(tmp_path, row, fragment):
    study = lighting_study(tmp_path)
    store = tmp_path / "s.jsonl"
    text = (json.dumps({"format": "roadbrdf-study-store", "version": 1}) + "\n"
            + json.dumps({"key": "k", "error": None, "rows": [row]}) + "\n")
    store.write_text(text)
    result = subprocess.run([sys.executable, "-m", "roadbrdf.studies", str(study), "-o", str(tmp_path / "r.csv"),
                             "--store", str(store)], capture_output=True, text=True, timeout=600)
    assert result.returncode == 2 and result.stderr.startswith("roadbrdf: error: "), result.stderr
    assert f"{store}:2:" in result.stderr and fragment in result.stderr, result.stderr
    assert "Traceback" not in result.stderr
    assert store.read_text() == text


def test_the_csv_names_each_lighting_column_with_its_unit(rows, tmp_path):
    _, table = rows
    header = list(table[0])
    for name in ("M_class [class]", "L_av [cd/m^2]", "f_TI [%]", "E_av [lx]", "D_P [W lx^-1 m^-2]",
                 "D_E [Wh m^-2 per year]", "power_per_km_w [W/km]", "least_power_per_km_w [W/km]",
                 "reflected_upward_lm_per_km [lm/km]", "direct_upward_lm_per_km [lm/km]"):
        assert name in header, name


def test_plot_study_draws_albedo_against_lighting_power(rows, tmp_path, cli):
    folder, _ = rows
    results = tmp_path / "results.csv"
    roadbrdf.study(str(folder / "study.json"), output=str(results), workers=1, progress=False)
    fig = plot_study.plane(str(results), "power", output=str(tmp_path / "plane.png"))
    ax = fig.axes[0]
    assert ax.get_xlabel().startswith("solar albedo")
    assert ax.get_ylabel() == "least lighting power for M6 [W/km]"
    data = fig.roadbrdf_data
    assert data["lighting_column"] == "least_power_per_km_w [W/km]"
    assert len(data["albedo"]) == 6
    # Lambertian roads: a higher albedo needs less power (L_av proportional to rho), so the candidate of the highest
    # albedo has the least power and dominates every other: the front is that one candidate.
    best = int(np.argmax(data["albedo"]))
    assert data["lighting"][best] == min(data["lighting"])
    assert data["pareto"] == [best]
    assert (tmp_path / "plane.png").stat().st_size > 0
    # The command line: the same figure.
    out = tmp_path / "cli.png"
    cli("plot", "study", results, "--axis", "power", "-o", out)
    assert out.stat().st_size > 0


def test_plot_study_power_without_lighting_columns_is_an_error(tmp_path):
    results = tmp_path / "results.csv"
    results.write_text("candidate,replicate,key,status,error,method,black_sky_30deg [1],Q0 [sr^-1]\n"
                       "1,1,k,ok,,areal,0.2,0.07\n")
    with pytest.raises(ValueError, match="no lighting power column"):
        plot_study.plane(str(results), "power")


def test_the_bundled_installation_is_usable(tmp_path):
    """The installation of tests/data works as a study's installation too (paths relative to the study)."""
    study = two_rock_study(tmp_path)
    shutil.copy(DATA / "installation.json", tmp_path / "inst.json")
    shutil.copy(DATA / "road.ldt", tmp_path / "road.ldt")
    data = json.loads(study.read_text())
    data["predictions"]["lighting"] = {"installation": "inst.json", "class": "M5", "operating_hours": 3000}
    study.write_text(json.dumps(data))
    s = read_study(str(study))
    assert s.predictions["lighting"]["installation"] == str(tmp_path / "inst.json")
    assert s.predictions["lighting"]["operating_hours"] == 3000


def test_a_rough_candidate_equals_the_lighting_of_its_mix_file(tmp_path):
    """Oren-Nayar rocks (the hemispherical integral has something to refine): each row equals `roadbrdf lighting
    --surface MIX.json` on the candidate's MIX.json; the r-table and luminances bit for bit, the reflectance behind
    the upward flux within the two quadratures' tolerances (1e-4 each) and the two photometric weightings."""
    from roadbrdf.studies import evaluate
    from test_study_fast import oren_nayar_fit
    study = lighting_study(tmp_path, installation=BUNDLED)
    for name, albedo, sigma in (("grey", 0.25, 0.3), ("dark", 0.08, 0.5), ("light", 0.5, 0.2)):
        oren_nayar_fit(tmp_path / "fits" / f"{name}.fit.json", albedo, sigma)
    s = read_study(str(study))
    for _, _, _, _, task in make_tasks(s, "v")[:2]:
        result = evaluate._run(task, s.fits)
        assert result["error"] is None, result["error"]
        formulation = candidate_file(task, s.fits, tmp_path / "candidate")
        for row in result["rows"]:
            mixture = tmp_path / f"{row['method']}.mix.json"
            roadbrdf.mix(formulation, method=row["method"], output=mixture)
            direct = roadbrdf.lighting(tmp_path / "road.json", surface=mixture, target_class="M6")
            for name in ("L_av", "U_o", "U_l", "f_TI", "R_EI", "E_av", "M_class"):
                assert row[name] == direct[name], name
            assert row["least_power_per_km_w"] == direct["least_flux"]["power_per_km_w"]
            assert row["lighting_reflectance"] == pytest.approx(direct["upward"]["reflectance"], abs=3e-4)
            assert row["reflected_upward_lm_per_km"] == pytest.approx(
                direct["upward"]["reflected_upward_lm_per_km"], rel=3e-3)
