"""Laboratory tables without a script, and the front ends agreeing: column mapping, fixed angles, the
quantity stored, runs combined, one duplicate policy (CLI, Python, plot, report), check of an in-memory
dataset, warnings at the caller's line. The tables in tests/data/io/lab are synthetic."""
import json
import math
import subprocess
import sys
import warnings

import numpy as np
import pytest

import roadbrdf

MAPPING = {"theta_r": "True_Average_View_Zenith", "phi_r": "True_Average_View_Azimuth"}
FIXED = {"theta_i": 30, "phi_i": 0}
CLI_MAPPING = ["--column", "theta_r=True_Average_View_Zenith", "--column", "phi_r=True_Average_View_Azimuth",
               "--set", "theta_i=30", "--set", "phi_i=0"]


@pytest.fixture
def lab(root):
    return root / "tests" / "data" / "io" / "lab"


def _read(path, **kw):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # the note on the columns not read
        return roadbrdf.read_dataset(path, columns=MAPPING, set=FIXED, **kw)


def test_every_quantity_reads_back_the_same_brdf_from_python_and_the_cli(lab, cli, tmp_path):
    reference = _read(lab / "sand_brdf.csv")
    # The formula the synthetic table was written from, at the measured view zeniths.
    wl = reference.wavelengths
    expected = (0.05 + 1e-4 * (wl - 450))[None, :] * (1 + 0.2 * np.cos(np.radians(reference.theta_r)))[:, None]
    np.testing.assert_allclose(reference.brdf, expected, rtol=1e-14)
    np.testing.assert_allclose(reference.theta_r, [0.4, 20.3, 39.8, 60.1, 20.25, 39.65, 60.15], atol=1e-12)
    for name, quantity in (("sand_brf.csv", "brf"), ("sand_brdf_cos.csv", "brdf-cos"),
                           ("sand_percent_brf.csv", "percent-brf")):
        d = _read(lab / name, quantity=quantity)
        np.testing.assert_allclose(d.brdf, reference.brdf, rtol=4e-15)
        assert d.metadata["quantity_read"] == quantity
        out = tmp_path / f"{quantity}.csv"
        cli("convert", lab / name, "--quantity", quantity, *CLI_MAPPING, "-o", out)
        np.testing.assert_array_equal(roadbrdf.read_dataset(out).brdf, d.brdf)


def test_the_columns_not_read_are_named_in_a_warning_at_the_callers_line(lab):
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        line = sys._getframe().f_lineno + 1
        roadbrdf.read_dataset(lab / "sand_brdf.csv", columns=MAPPING, set=FIXED)
    assert len(caught) == 1
    assert "'Commanded_View_Zenith'" in str(caught[0].message) and "'Temperature_C'" in str(caught[0].message)
    assert caught[0].filename == __file__
    assert caught[0].lineno == line


def test_a_misspelt_mapped_column_names_the_nearest_header_name_in_both_front_ends(lab, cli):
    with pytest.raises(roadbrdf.InputError, match=r"sand_brdf.csv:4: `columns` theta_r=True_Average_View_Zenit: .*"
                                                  r"did you mean 'True_Average_View_Zenith'"):
        roadbrdf.read_dataset(lab / "sand_brdf.csv", columns={"theta_r": "True_Average_View_Zenit"}, set=FIXED)
    printed = cli("check", lab / "sand_brdf.csv", "--column", "theta_r=True_Average_View_Zenit", "--set", "theta_i=30",
                  check=False)
    assert printed.returncode == 2
    assert "sand_brdf.csv:4: --column theta_r=True_Average_View_Zenit" in printed.stderr
    assert "did you mean 'True_Average_View_Zenith'" in printed.stderr


def test_combining_runs_equals_reading_the_concatenated_file(lab, cli, tmp_path):
    runs = [lab / "run_theta30.csv", lab / "run_theta45.csv"]
    mapping = {"theta_r": "View_Zenith", "phi_r": "View_Azimuth"}
    fixed = {"run_theta30.csv:theta_i": 30, "run_theta45.csv:theta_i": 45, "phi_i": 0}
    combined = roadbrdf.read_dataset(runs, columns=mapping, set=fixed)
    concatenated = roadbrdf.read_dataset(lab / "runs_concatenated.csv")
    np.testing.assert_allclose(combined.angles, concatenated.angles, atol=1e-12)
    np.testing.assert_array_equal(combined.brdf, concatenated.brdf)
    out = tmp_path / "combined.csv"
    cli("convert", *runs, "--column", "theta_r=View_Zenith", "--column", "phi_r=View_Azimuth", "--set",
        "run_theta30.csv:theta_i=30", "--set", "run_theta45.csv:theta_i=45", "--set", "phi_i=0", "-o", out)
    np.testing.assert_array_equal(roadbrdf.read_dataset(out).brdf, concatenated.brdf)


def _with_duplicate(path):
    path.write_text("theta_i,phi_i,theta_r,phi_r,500,600\n0,0,10,0,0.1,0.2\n0,0,30,180,0.1,0.2\n"
                    "0,0,10,0,0.3,0.4\n")
    return path


def test_one_duplicate_policy_in_the_cli_python_plot_and_report(cli, tmp_path):
    data = _with_duplicate(tmp_path / "dup.csv")
    for command in (["check", data], ["convert", data, "-o", tmp_path / "c.csv"],
                    ["plot", "spectral", data, "-o", tmp_path / "s.png"]):
        refused = cli(*command, check=False)
        assert refused.returncode == 2, command
        assert "--average-duplicates" in refused.stderr, (command, refused.stderr)
        cli(*command, "--average-duplicates")
    report = subprocess.run([sys.executable, "-m", "roadbrdf.report", str(data), "-o", str(tmp_path / "r.html"),
                             "--quiet"], capture_output=True, text=True)
    assert report.returncode == 2 and "--average-duplicates" in report.stderr, report.stderr
    assert "--average-duplicates" in subprocess.run([sys.executable, "-m", "roadbrdf.report", "--help"],
                                                    capture_output=True, text=True).stdout
    with pytest.raises(roadbrdf.InputError, match="`average_duplicates`"):
        roadbrdf.read_dataset(data)
    # A Dataset made in memory follows the same policy, with the same averages.
    with pytest.raises(roadbrdf.InputError, match="`average_duplicates`"):
        roadbrdf.Dataset([[0, 0, 10, 0], [0, 0, 30, 180], [0, 0, 10, 0]], [500, 600],
                         [[0.1, 0.2], [0.1, 0.2], [0.3, 0.4]])
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        averaged = roadbrdf.read_dataset(data, average_duplicates=True)
        made = roadbrdf.Dataset([[0, 0, 10, 0], [0, 0, 30, 180], [0, 0, 10, 0]], [500, 600],
                                [[0.1, 0.2], [0.1, 0.2], [0.3, 0.4]], average_duplicates=True)
    np.testing.assert_array_equal(made.brdf, averaged.brdf)
    np.testing.assert_allclose(averaged.brdf[0], [0.2, 0.3], rtol=1e-15)  # (0.1 + 0.3) / 2, (0.2 + 0.4) / 2
    from roadbrdf import plot
    with pytest.raises(roadbrdf.InputError, match="`average_duplicates`"):
        plot.spectral([str(data)], (0, 0, 10, 0))
    fig = plot.spectral([str(data)], (0, 0, 10, 0), average_duplicates=True)
    np.testing.assert_allclose(list(fig.roadbrdf_data.values())[0][1], [0.2, 0.3], rtol=1e-15)


def test_plot_units_brf_draws_pi_times_the_brdf_with_its_label(lab, cli, tmp_path):
    from roadbrdf import plot
    d = _read(lab / "sand_brdf.csv")
    geometry = tuple(d.angles[1])
    brdf = plot.spectral([d], geometry)
    brf = plot.spectral([d], geometry, units="brf")
    (_, y_brdf), = brdf.roadbrdf_data.values()
    (_, y_brf), = brf.roadbrdf_data.values()
    np.testing.assert_allclose(y_brf, math.pi * np.asarray(y_brdf), rtol=1e-15)
    assert brf.axes[0].get_ylabel() == "BRF (π·BRDF)"
    assert brdf.axes[0].get_ylabel().startswith("BRDF")
    with pytest.raises(ValueError, match="units"):
        plot.spectral([d], geometry, units="percent")
    cli("plot", "spectral", lab / "runs_concatenated.csv", "--units", "brf", "-o", tmp_path / "brf.png")


def test_check_of_a_dataset_in_memory_equals_check_of_its_file(lab):
    path = lab / "runs_concatenated.csv"
    from_file = roadbrdf.check(path)
    from_memory = roadbrdf.check(roadbrdf.read_dataset(path))
    assert from_file.pop("file") == str(path)
    assert from_memory.pop("file") is None
    assert from_memory == from_file


def test_a_brdf_cos_hint_names_the_quantity_field(tmp_path):
    # BRDF cos(theta_i) of a Lambertian surface: reciprocity pairs disagree until divided by cos theta_i.
    rows = ["theta_i,phi_i,theta_r,phi_r,500"]
    for ti in (10, 30, 50, 70):
        for tr in (10, 30, 50, 70):
            rows.append(f"{ti},0,{tr},180,{0.1 / math.pi * math.cos(math.radians(ti))!r}")
    path = tmp_path / "cos.csv"
    path.write_text("\n".join(rows) + "\n")
    text = roadbrdf.check(path)["text"]
    assert "`quantity` brdf-cos" in text
    fixed = roadbrdf.check(path, quantity="brdf-cos")
    assert not fixed["plausibility"]["brdf_times_cos_theta_i"]["likely"]


def test_the_openmaterial_lidar_table_read_as_brdf_cos(real_data):
    path = real_data / "openmaterial3d" / "example_material_lidar_brdf.xompt"
    if not path.is_file():
        pytest.skip(f"{path} is absent")
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        raw = roadbrdf.read_dataset(path)
        divided = roadbrdf.read_dataset(path, quantity="brdf-cos")
    assert divided.metadata["quantity_read"] == "brdf-cos"
    # Its "90 deg" rows (1.570796 rad, read as exactly 90 deg) have no BRDF: BRDF cos theta_i / 0 is missing.
    grazing = raw.theta_i == 90.0
    assert grazing.any()
    expected = raw.brdf / np.cos(np.radians(raw.theta_i))[:, None]
    expected[grazing, :] = np.nan
    np.testing.assert_allclose(divided.brdf, expected, rtol=1e-12)


def test_the_report_mixes_a_formulation_on_averaged_duplicates(root, tmp_path):
    """The duplicate policy reaches the report's mixing step: repeated scans of F1 (exact copies of three rows)
    averaged are F1 itself, so the mixing comparison equals the one on the original file."""
    f1 = root / "data" / "examples" / "mixed" / "F1.csv"
    # F1's formulation with Lambert fits of its components where it looks for them (../fits/NAME.fit.json).
    (tmp_path / "fits").mkdir()
    (tmp_path / "formulations").mkdir()
    for name, path in [("bitumen", "single/bitumen.csv"), ("garonne", "single/garonne.csv"),
                       ("mastic-garonne-bitumen", "mastics/mastic-garonne-bitumen.csv")]:
        roadbrdf.fit(root / "data" / "examples" / path, ["lambert"], output=tmp_path / "fits" / f"{name}.fit.json")
    formulation = tmp_path / "formulations" / "F1.json"
    formulation.write_bytes((root / "data" / "examples" / "formulations" / "F1.json").read_bytes())
    lines = f1.read_text(encoding="utf-8").splitlines(keepends=True)
    rows = [line for line in lines if not line.startswith("#")]
    data = tmp_path / "F1-repeated.csv"
    data.write_text("".join(lines + rows[1:4]), encoding="utf-8")
    with pytest.raises(roadbrdf.InputError, match="`average_duplicates`"):
        roadbrdf.mix(formulation, data=data, method="areal")
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        repeated = roadbrdf.mix(formulation, data=data, method="areal", average_duplicates=True)
        original = roadbrdf.mix(formulation, data=f1, method="areal")
    assert repeated.best.comparison["rmse"] == original.best.comparison["rmse"]
    out = tmp_path / "r.html"
    report = subprocess.run([sys.executable, "-m", "roadbrdf.report", str(data), "--model", "lambert",
                             "--formulation", str(formulation), "--average-duplicates", "--quiet", "-o", str(out)],
                            capture_output=True, text=True)
    assert report.returncode == 0, report.stderr
    assert 'data-key="mix.best"' in out.read_text(encoding="utf-8")


def test_sigma_from_duplicates_in_both_front_ends_equals_the_pooled_formula(lab, cli, tmp_path):
    path = lab / "repeat_concatenated.csv"
    raw = np.loadtxt(path, delimiter=",", skiprows=2)
    scans = raw[:, 4:].reshape(2, -1, 3)  # the second scan repeats the first's geometries
    mean = scans.mean(axis=0)
    # Pooled relative repeatability (ISO 5725-2 on relative deviations), then the sigma of each mean.
    s_rel = np.sqrt((((scans - mean) / mean) ** 2).sum(axis=(0, 1)) / mean.shape[0])
    sigma = s_rel * np.abs(mean) / np.sqrt(2)
    weights = 1 / sigma**2
    albedo = np.pi * (weights * mean).sum(axis=0) / (weights * mean**0).sum(axis=0)  # weighted Lambert fit
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # the averaged duplicates
        result = roadbrdf.fit(path, "lambert", sigma_from_duplicates=True, output=tmp_path / "py.json")
    np.testing.assert_allclose(result.best.parameters[0], albedo, rtol=1e-9)
    assert any("repeatability of duplicate rows" in n for n in result.notes)
    cli("fit", path, "-m", "lambert", "--sigma-from-duplicates", "-o", tmp_path / "cli.json")
    py, cl = (json.loads((tmp_path / f"{n}.json").read_text())["fits"][0] for n in ("py", "cli"))
    assert py["parameters"] == cl["parameters"] and py["stderr"] == cl["stderr"]
    with pytest.raises(roadbrdf.InputError, match="sigma_from_duplicates.*needs the dataset's file"):
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            roadbrdf.fit(roadbrdf.read_dataset(path, average_duplicates=True), "lambert", sigma_from_duplicates=True)
    refused = cli("fit", lab / "sand_brdf.csv", *CLI_MAPPING, "-m", "lambert", "--sigma-from-duplicates", "-o",
                  tmp_path / "x.json", check=False)
    assert refused.returncode == 2 and "--sigma-from-duplicates" in refused.stderr, refused.stderr
    assert "no repeated geometry" in refused.stderr, refused.stderr


def test_tables_in_different_quantities_combine_as_docs_data_md_says(lab, cli, tmp_path):
    # docs/data.md "Lab tables and the run manifest": convert the BRF table first, then combine it with
    # a BRDF run using per-file items.
    sand = tmp_path / "sand_30.csv"
    cli("convert", lab / "sand_brf.csv", "--quantity", "brf", *CLI_MAPPING, "-o", sand)
    both = tmp_path / "sand.csv"
    cli("convert", sand, lab / "run_theta45.csv", "--column", "run_theta45.csv:theta_r=View_Zenith", "--column",
        "run_theta45.csv:phi_r=View_Azimuth", "--set", "run_theta45.csv:theta_i=45", "--set",
        "run_theta45.csv:phi_i=0", "-o", both)
    combined = roadbrdf.read_dataset(both)
    first = _read(lab / "sand_brf.csv", quantity="brf")
    second = roadbrdf.read_dataset(lab / "run_theta45.csv", columns={"theta_r": "View_Zenith", "phi_r": "View_Azimuth"},
                                   set={"theta_i": 45, "phi_i": 0})
    np.testing.assert_array_equal(combined.brdf, np.vstack([first.brdf, second.brdf]))
    np.testing.assert_allclose(combined.theta_i, [30] * len(first.theta_i) + [45] * len(second.theta_i), rtol=1e-15)
