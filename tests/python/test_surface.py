"""Virtual surfaces and the virtual gonioreflectometer from Python (python/src/bind_surface.cpp).

Reference values: closed forms (a flat Lambertian sample reflects albedo/pi at every geometry and has
albedo `albedo`; texture statistics of a hand-made step profile) and the command line's output for the
same input (the binding must make the same library calls with the same settings)."""
import json
import math

import numpy as np
import pytest

import roadbrdf

GEOMETRIES = [(0.0, 0.0, 10.0, 180.0), (30.0, 0.0, 45.0, 180.0), (60.0, 0.0, 50.0, 0.0), (45.0, 20.0, 70.0, 110.0)]


def _angles():
    return [np.array([g[k] for g in GEOMETRIES]) for k in range(4)]


def _write_grid(path):
    path.write_text("theta_i,phi_i,theta_r,phi_r\n" + "".join(",".join(f"{a:g}" for a in g) + "\n"
                                                            for g in GEOMETRIES))
    return path


def _lambert_fit(path, wavelengths, albedo):
    path.write_text(json.dumps({"format": "roadbrdf-fit", "version": 1, "best": "lambert",
                                "fits": [{"model": "lambert", "options": {}, "wavelengths": wavelengths,
                                          "parameters": {"albedo": albedo}}]}))
    return path


# ---- (a) flat Lambertian sample: BRDF albedo/pi exactly, sigma 0 ---------------------------------

@pytest.mark.parametrize("acceptance", [0.0, 5.0])
def test_flat_lambert_renders_albedo_over_pi(acceptance):
    s = roadbrdf.flat_surface(roadbrdf.Model("lambert"), {"albedo": 0.37})
    d = roadbrdf.render(s, *_angles(), wavelengths=[450, 550, 650], samples=256, acceptance_deg=acceptance)
    assert isinstance(d, roadbrdf.Dataset)
    assert d.brdf.shape == (len(GEOMETRIES), 3)
    np.testing.assert_allclose(d.brdf, 0.37 / math.pi, rtol=1e-12)
    assert np.all(np.abs(d.sigma) <= 1e-15)
    np.testing.assert_array_equal(d.angles, np.array(GEOMETRIES))
    np.testing.assert_array_equal(d.wavelengths, [450, 550, 650])
    assert list(d.paths) == [256] * len(GEOMETRIES)


def test_flat_spectral_fit_renders_its_albedo_at_its_wavelengths(tmp_path):
    # A fit file material: default wavelengths are the fit's, and each renders albedo(lambda)/pi.
    fit = _lambert_fit(tmp_path / "white.fit.json", [400, 500, 600, 700], [0.1, 0.3, 0.6, 0.8])
    s = roadbrdf.flat_surface(fit)
    assert s.materials == ["white.fit"]
    d = roadbrdf.render(s, 30, 0, 40, 180, samples=64, acceptance_deg=0)
    np.testing.assert_array_equal(d.wavelengths, [400, 500, 600, 700])
    np.testing.assert_allclose(d.brdf[0], np.array([0.1, 0.3, 0.6, 0.8]) / math.pi, rtol=1e-12)
    # Interpolated between the fit's wavelengths (linear in the parameters).
    d = roadbrdf.render(s, 30, 0, 40, 180, wavelengths=[450], samples=64, acceptance_deg=0)
    assert d.brdf[0, 0] == pytest.approx(0.2 / math.pi, rel=1e-12)


# ---- (c) albedo of a flat Lambertian sample = albedo ---------------------------------------------

def test_flat_lambert_albedo_is_albedo():
    s = roadbrdf.flat_surface("lambert", {"albedo": 0.61})
    a = roadbrdf.render_albedo(s, [0, 30, 75], wavelengths=[500, 600], samples=256)
    assert a["black_sky"].shape == (3, 2)
    np.testing.assert_allclose(a["black_sky"], 0.61, rtol=1e-12)
    np.testing.assert_allclose(a["white_sky"], 0.61, rtol=1e-12)
    assert np.all(np.abs(a["black_sky_error"]) <= 1e-15) and np.all(np.abs(a["white_sky_error"]) <= 1e-15)
    np.testing.assert_array_equal(a["sun_zenith"], [0, 30, 75])
    np.testing.assert_array_equal(a["wavelengths"], [500, 600])
    assert a["white_sky_nodes"] == 8 and a["paths"] == (3 + 8) * 256
    none = roadbrdf.render_albedo(s, 30, wavelengths=[550], samples=16, white_sky_nodes=0)
    assert none["white_sky"] is None and none["black_sky"].shape == (1, 1)


# ---- (b) same results as the command line, bit for bit ------------------------------------------

@pytest.fixture
def rough(cli, tmp_path):
    """A small Gaussian-slope Lambertian surface written by the CLI."""
    path = tmp_path / "rough.surface.json"
    cli("surface", "lambert", "-p", "albedo=0.8", "--gaussian-slopes", "0.4", "--cells", "32", "-o", path)
    return path


def test_gaussian_slope_surface_equals_cli(rough):
    s = roadbrdf.gaussian_slope_surface(roadbrdf.Model("lambert"), 0.4, {"albedo": 0.8}, cells=32)
    written = json.loads(rough.read_text())
    assert s.shape == (written["ny"], written["nx"]) == (32, 32)
    # SURFACE files store heights rounded to 0.1 um (height_field.cpp); the statistics are of the
    # unrounded field, and writing the Python surface gives the CLI's file.
    np.testing.assert_allclose(s.heights.reshape(-1), written["heights_mm"], rtol=0, atol=0.5e-4 + 1e-12)
    assert s.mpd_mm == pytest.approx(written["statistics"]["mpd_mm"], rel=1e-12)
    assert s.mpd_mm > 0
    s.write(rough.with_name("python.json"))
    again = json.loads(rough.with_name("python.json").read_text())
    assert again["heights_mm"] == written["heights_mm"] and again["materials"] == written["materials"]


@pytest.mark.parametrize("python_options, cli_options", [
    (dict(samples=1024, seed=7), ["--samples", "1024", "--seed", "7"]),
    (dict(samples=512, sampling="cosine", acceptance_deg=5, max_bounces=1),
     ["--samples", "512", "--sampling", "cosine", "--acceptance", "5", "--max-bounces", "1"]),
    (dict(target_error=0.03, max_samples=4096, error_floor=1e-4, seed=3),
     ["--target-error", "0.03", "--max-samples", "4096", "--error-floor", "1e-4", "--seed", "3"]),
])
def test_render_equals_cli(cli, rough, tmp_path, python_options, cli_options):
    out = tmp_path / "cli.csv"
    cli("render", rough, "--grid", _write_grid(tmp_path / "grid.csv"), "--wavelengths", "500:600:100",
        "--threads", "2", *cli_options, "-o", out)
    expected = roadbrdf.read_dataset(out)
    d = roadbrdf.render(str(rough), *_angles(), wavelengths=[500, 600], threads=1, **python_options)
    np.testing.assert_allclose(d.angles, expected.angles, rtol=0, atol=1e-12)  # CSV: via radians
    np.testing.assert_array_equal(d.wavelengths, expected.wavelengths)
    np.testing.assert_array_equal(d.brdf, expected.brdf)
    np.testing.assert_array_equal(d.sigma, expected.sigma)
    assert d.metadata == expected.metadata
    assert np.all(d.sigma > 0)  # a real Monte Carlo estimate, not a trivial one


def test_a_missed_target_is_the_same_warning_from_both_front_ends(cli, rough, tmp_path):
    # 8 paths per geometry cannot reach a 0.1 % relative standard error on a rough sample.
    settings = dict(target_error=1e-3, max_samples=8, error_floor=0.0)
    result = cli("render", rough, "--grid", _write_grid(tmp_path / "grid.csv"), "--wavelengths", "550",
                 "--target-error", "1e-3", "--max-samples", "8", "--error-floor", "0", "-o", tmp_path / "cli.csv")
    printed = [line.removeprefix("roadbrdf: warning: ") for line in result.stderr.splitlines()
               if line.startswith("roadbrdf: warning: ")]
    assert printed[-1] == f"{len(GEOMETRIES)} of {len(GEOMETRIES)} geometries did not reach the target"
    assert "reached --max-samples 8" in printed[0]
    with pytest.warns(roadbrdf.RoadbrdfWarning) as caught:
        roadbrdf.render(str(rough), *_angles(), wavelengths=[550], **settings)
    # Python spells the fields by their keywords, the command line by its flags: the same messages.
    issued = [str(w.message) for w in caught]
    assert [m.replace("`max_samples`", "--max-samples").replace("`target_error`", "--target-error")
            for m in issued] == printed


def test_render_depends_on_seed(rough):
    a = roadbrdf.render(rough, 30, 0, 45, 180, wavelengths=[550], samples=512, seed=1)
    b = roadbrdf.render(rough, 30, 0, 45, 180, wavelengths=[550], samples=512, seed=2)
    assert a.brdf[0, 0] != b.brdf[0, 0]
    # Both estimate the same BRDF (within 5 combined standard errors).
    assert abs(a.brdf[0, 0] - b.brdf[0, 0]) < 5 * math.hypot(a.sigma[0, 0], b.sigma[0, 0])


def test_render_albedo_equals_cli(cli, rough, tmp_path):
    out = tmp_path / "albedo.csv"
    cli("render", rough, "--albedo", "20,60", "--white-sky-nodes", "3", "--samples", "1024", "--wavelengths",
        "500:600:100", "-o", out)
    rows = [line.split(",") for line in out.read_text().splitlines() if not line.startswith("#")]
    header, values = rows[0], dict(zip(rows[0], map(float, rows[1])))
    assert header[:3] == ["wavelength_nm", "white_sky", "white_sky_error"]
    written = tmp_path / "python-albedo.csv"
    a = roadbrdf.render_albedo(rough, [20, 60], wavelengths=[500, 600], white_sky_nodes=3, samples=1024,
                               output=written)
    # Both write the table by the library's one writer: the same lines below the comment naming the sample.
    assert written.read_text().splitlines()[1:] == out.read_text().splitlines()[1:]
    assert written.read_text().startswith("# virtual albedo of ")
    # The CLI prints 8 decimals (values) and 3 significant digits (errors).
    assert a["white_sky"][0] == pytest.approx(values["white_sky"], abs=6e-9)
    assert a["black_sky"][0, 0] == pytest.approx(values["black_sky_20deg"], abs=6e-9)
    assert a["black_sky"][1, 0] == pytest.approx(values["black_sky_60deg"], abs=6e-9)
    assert a["black_sky_error"][1, 0] == pytest.approx(values["black_sky_error_60deg"], rel=6e-3)
    assert 0.5 < a["white_sky"][0] < 0.8  # albedo 0.8 minus the interreflection losses


# ---- a sample generated from a formulation: fit files relative to the formulation ---------------

def _formulation(tmp_path):
    (tmp_path / "fits").mkdir()
    (tmp_path / "formulations").mkdir()
    _lambert_fit(tmp_path / "fits" / "mastic.fit.json", [500, 600], [0.1, 0.12])
    _lambert_fit(tmp_path / "fits" / "gravel.fit.json", [500, 600], [0.4, 0.5])
    path = tmp_path / "formulations" / "T.json"
    path.write_text(json.dumps({
        "format": "roadbrdf-formulation", "version": 1, "name": "T", "coarse_min_size_mm": 2.0,
        "mastic": {"name": "mastic", "fit": "../fits/mastic.fit.json"},
        "components": [
            {"name": "Bitumen", "kind": "binder", "mass_percent": 5, "density_g_cm3": 1.03,
             "fit": "../fits/mastic.fit.json"},
            {"name": "Sand 0/2", "kind": "aggregate", "mass_percent": 45, "density_g_cm3": 2.65, "d_min_mm": 0,
             "d_max_mm": 2, "fit": "../fits/mastic.fit.json"},
            {"name": "Gravel 4/6", "kind": "aggregate", "mass_percent": 50, "density_g_cm3": 2.7, "d_min_mm": 4,
             "d_max_mm": 6, "fit": "../fits/gravel.fit.json"}]}))
    return path


def test_formulation_surface_equals_cli_and_renders_from_anywhere(cli, tmp_path, monkeypatch):
    formulation = _formulation(tmp_path)
    cli_file = tmp_path / "cli.surface.json"
    cli("surface", formulation, "--size", "12mm", "--cell", "0.25", "--seed", "3", "--matrix-level", "0.6",
        "-o", cli_file)
    monkeypatch.chdir(tmp_path)  # a relative formulation path: its fits resolve to ./fits/...
    s = roadbrdf.surface("formulations/T.json", size_mm=12, cell_mm=0.25, seed=3, matrix_level=0.6)
    written = json.loads(cli_file.read_text())
    np.testing.assert_allclose(s.heights.reshape(-1), written["heights_mm"], rtol=0, atol=0.5e-4 + 1e-12)
    np.testing.assert_array_equal(s.material_map.reshape(-1), written["material"])
    assert s.materials == [m["name"] for m in written["materials"]] == ["mastic", "Gravel 4/6"]
    assert s.cell_mm == 0.25 and s.size_mm == (12.0, 12.0)
    stats = written["statistics"]
    assert s.mpd_mm == pytest.approx(stats["mpd_mm"], rel=1e-12)
    assert s.area_ratio == pytest.approx(stats["surface_area_ratio"], rel=1e-12)
    np.testing.assert_allclose(s.exposed_area_fraction, stats["exposed_area_fraction"], rtol=1e-12)
    assert s.generation["classes"] == ["Gravel 4/6"] and s.generation["grain_count"][0] > 0
    # The in-memory sample resolves its fits against the formulation's folder, from any directory;
    # written elsewhere, the file's fit paths are relative to it; the CLI renders the same numbers.
    (tmp_path / "elsewhere").mkdir()
    monkeypatch.chdir(tmp_path / "elsewhere")
    d = roadbrdf.render(s, *_angles(), samples=512)
    np.testing.assert_array_equal(d.wavelengths, [500, 600])
    (tmp_path / "out").mkdir()
    mine = tmp_path / "out" / "T.surface.json"
    s.write(mine)
    python_file = json.loads(mine.read_text())
    assert [m["fit"] for m in python_file["materials"]] == ["../fits/mastic.fit.json", "../fits/gravel.fit.json"]
    assert python_file["heights_mm"] == written["heights_mm"]
    out = tmp_path / "cli.csv"
    cli("render", mine, "--grid", _write_grid(tmp_path / "grid.csv"), "--samples", "512", "-o", out)
    expected = roadbrdf.read_dataset(out)
    # The file's heights are rounded to 0.1 um, so the in-memory render follows other paths: same BRDF
    # within 5 combined standard errors; the file rendered from Python is the CLI's bit for bit.
    assert np.all(np.abs(d.brdf - expected.brdf) < 5 * np.hypot(d.sigma, expected.sigma))
    np.testing.assert_array_equal(roadbrdf.render(mine, *_angles(), samples=512).brdf, expected.brdf)
    assert np.all(d.brdf > 0.1 / math.pi * 0.5)


def test_a_missing_fit_file_is_the_same_warning_from_both_front_ends(cli, tmp_path):
    # Fit files are needed only to render: a sample is built without them, and both front ends say so
    # with the library's one message.
    formulation = _formulation(tmp_path)
    (tmp_path / "fits" / "gravel.fit.json").unlink()
    result = cli("surface", formulation, "--size", "12mm", "--cell", "0.25", "-o", tmp_path / "T.surface.json")
    lines = [line for line in result.stderr.splitlines() if "does not exist yet" in line]
    assert len(lines) == 1 and "'Gravel 4/6'" in lines[0], result.stderr
    message = lines[0].removeprefix("roadbrdf: warning: ")
    with pytest.warns(roadbrdf.RoadbrdfWarning) as caught:
        roadbrdf.surface(formulation, size_mm=12, cell_mm=0.25)
    assert [str(w.message) for w in caught if "does not exist yet" in str(w.message)] == [message]
    assert "gravel.fit.json" in message


# ---- (e) texture statistics ---------------------------------------------------------------------

def test_flat_surface_statistics():
    s = roadbrdf.flat_surface("lambert", cells=8, cell_mm=0.5)
    assert s.mpd_mm == 0.0 and s.rms_height_mm == 0.0
    assert s.etd_mm == pytest.approx(0.2, abs=1e-15)  # ETD = 0.2 + 0.8 MPD
    assert s.area_ratio == pytest.approx(1.0, abs=1e-15)
    np.testing.assert_array_equal(s.exposed_area_fraction, [1.0])
    np.testing.assert_array_equal(s.heights, np.zeros((8, 8)))
    np.testing.assert_array_equal(s.material_map, np.zeros((8, 8), dtype=int))


def test_step_profile_statistics_by_hand(tmp_path):
    # Heights depend on x only: 0, 0, H, H, H, H, 0, 0 (symmetric: no linear trend), 4 rows.
    # Rows: mean H/2, both half-baseline peaks H -> MPD H/2; columns are flat -> 0; mean over the
    # 4 + 8 profiles: 4 (H/2) / 12 = H/6. rms height H/2. Cells 1 and 5 rise/fall by H over h:
    # true area sqrt(1 + (H/h)^2) h^2 each -> ratio (6 + 2 sqrt(1 + (H/h)^2)) / 8.
    # Material 1 on the flat top cells 2, 3, 4: projected 3/8, true 3 / (6 + 2 sqrt(1 + (H/h)^2)).
    H, h = 0.25, 0.125
    row = [0, 0, H, H, H, H, 0, 0]
    mats = [0, 0, 1, 1, 1, 0, 0, 0]
    path = tmp_path / "step.json"
    path.write_text(json.dumps({
        "format": "roadbrdf-surface", "version": 1, "name": "step", "cell_size_mm": h, "nx": 8, "ny": 4,
        "periodic": True, "heights_mm": row * 4, "material": mats * 4,
        "materials": [{"name": "low", "model": "lambert", "parameters": {"albedo": 0.2}},
                      {"name": "top", "model": "lambert", "parameters": {"albedo": 0.7}}]}))
    s = roadbrdf.read_surface(path)
    assert s.shape == (4, 8) and s.materials == ["low", "top"]
    np.testing.assert_array_equal(s.heights[2], row)  # heights[j, i]
    np.testing.assert_array_equal(s.material_map[1], mats)
    root = math.sqrt(1 + (H / h) ** 2)
    assert s.mpd_mm == pytest.approx(H / 6, rel=1e-12)
    assert s.etd_mm == pytest.approx(0.2 + 0.8 * H / 6, rel=1e-12)
    assert s.rms_height_mm == pytest.approx(H / 2, rel=1e-12)
    assert s.area_ratio == pytest.approx((6 + 2 * root) / 8, rel=1e-12)
    np.testing.assert_allclose(s.exposed_area_fraction, [5 / 8, 3 / 8], rtol=1e-12)
    np.testing.assert_allclose(s.statistics["exposed_true_area_fraction"],
                               [(3 + 2 * root) / (6 + 2 * root), 3 / (6 + 2 * root)], rtol=1e-12)
    # Round trip through write / read_surface.
    s.write(tmp_path / "again.json")
    again = roadbrdf.read_surface(tmp_path / "again.json")
    np.testing.assert_array_equal(again.heights, s.heights)
    np.testing.assert_array_equal(again.material_map, s.material_map)
    assert again.material_specs == s.material_specs


# ---- (d) errors ---------------------------------------------------------------------------------

def test_errors(tmp_path):
    flat = roadbrdf.flat_surface("lambert")
    with pytest.raises(ValueError, match="samples: excludes target_error"):
        roadbrdf.render(flat, 0, 0, 30, 180, samples=1024, target_error=0.01)
    with pytest.raises(ValueError, match="samples: excludes target_error"):
        roadbrdf.render_albedo(flat, 30, samples=1024, target_error=0.01)
    missing = tmp_path / "no-such.surface.json"
    for call in (lambda: roadbrdf.read_surface(missing), lambda: roadbrdf.render(missing, 0, 0, 30, 180),
                 lambda: roadbrdf.render_albedo(missing, 30)):
        with pytest.raises(ValueError, match="no-such.surface.json"):
            call()
    with pytest.raises(ValueError, match="no-such-formulation.json"):
        roadbrdf.surface(tmp_path / "no-such-formulation.json")
    with pytest.raises(ValueError, match="no-such.fit.json"):
        roadbrdf.flat_surface(tmp_path / "no-such.fit.json")
    with pytest.raises(ValueError, match="sampling"):
        roadbrdf.render(flat, 0, 0, 30, 180, sampling="uniform")
    with pytest.raises(ValueError, match="theta_r"):
        roadbrdf.render(flat, 0, 0, 95, 180)
    with pytest.raises(ValueError, match="samples: 1 is below 2"):
        roadbrdf.render(flat, 0, 0, 30, 180, samples=1)
    with pytest.raises(ValueError, match="acceptance"):
        roadbrdf.render(flat, 0, 0, 30, 180, acceptance_deg=50)
    with pytest.raises(ValueError, match="wavelengths: values must increase"):
        roadbrdf.render(flat, 0, 0, 30, 180, wavelengths=[600, 500])
    with pytest.raises(ValueError, match="outside"):
        roadbrdf.render_albedo(flat, 90)
    with pytest.raises(ValueError, match="albedo"):
        roadbrdf.flat_surface("lambert", {"albedo": 1.5})
    with pytest.raises(ValueError, match=r"sigma_rad: must be in \(0, 1.3\) rad"):
        roadbrdf.gaussian_slope_surface("lambert", 2.0, cells=32)
    formulation = _formulation(tmp_path)
    with pytest.raises(ValueError, match="exclude each other"):
        roadbrdf.surface(formulation, size_mm=12, cell_mm=0.25, matrix_level=0.5, target_mpd=0.5)


def test_surface_mastic_fraction_counted_on_the_map_and_equal_to_the_cli(cli, tmp_path):
    formulation = _formulation(tmp_path)
    s = roadbrdf.surface(formulation, size_mm=12, cell_mm=0.25, seed=3, mastic_fraction=0.4)
    # 48 x 48 cells: tolerance max(0.001, 1/2304); every cell has the same projected area.
    assert np.mean(s.material_map == 0) == pytest.approx(0.4, abs=0.001)
    cli_file = tmp_path / "cli.surface.json"
    cli("surface", formulation, "--size", "12mm", "--cell", "0.25", "--seed", "3", "--mastic-fraction", "0.4",
        "-o", cli_file)
    np.testing.assert_array_equal(s.material_map.reshape(-1), json.loads(cli_file.read_text())["material"])
    with pytest.raises(ValueError, match="exclude each other"):
        roadbrdf.surface(formulation, size_mm=12, cell_mm=0.25, matrix_level=0.5, mastic_fraction=0.4)
    with pytest.raises(ValueError, match="exclude each other"):
        roadbrdf.surface(formulation, size_mm=12, cell_mm=0.25, target_mpd=0.5, mastic_fraction=0.4)
    with pytest.raises(ValueError, match=r"must be in \(0, 1\)"):
        roadbrdf.surface(formulation, size_mm=12, cell_mm=0.25, mastic_fraction=1.0)
