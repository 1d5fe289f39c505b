"""roadbrdf mix and roadbrdf.mix: the same MIX.json with options, the same notes for methods that are
skipped (CLI: warnings, Python: UserWarning), and the same errors for the same bad input."""
import json
import math

import pytest

import roadbrdf

WAVELENGTHS = [400, 500, 600, 700]
SPECTRA = {"bitumen": [0.05, 0.06, 0.05, 0.07], "mastic": [0.10, 0.15, 0.12, 0.11],
           "gravel": [0.40, 0.35, 0.50, 0.45]}


@pytest.fixture
def case(tmp_path):
    """Lambertian end-members, a formulation and a measured mixture with sigma."""
    (tmp_path / "fits").mkdir()
    for name, albedo in SPECTRA.items():
        (tmp_path / "fits" / f"{name}.fit.json").write_text(json.dumps({
            "format": "roadbrdf-fit", "version": 1, "best": "lambert",
            "fits": [{"model": "lambert", "options": {}, "wavelengths": WAVELENGTHS, "parameters": {"albedo": albedo}}]}))
    formulation = tmp_path / "F.json"
    formulation.write_text(json.dumps({
        "format": "roadbrdf-formulation", "version": 1, "name": "T", "mastic": {"fit": "fits/mastic.fit.json"},
        "components": [
            {"name": "Bitumen", "kind": "binder", "mass_percent": 5, "density_g_cm3": 1.03, "fit": "fits/bitumen.fit.json"},
            {"name": "Sand 0/2", "kind": "aggregate", "mass_percent": 40, "density_g_cm3": 2.65, "d_min_mm": 0,
             "d_max_mm": 2, "fit": "fits/mastic.fit.json"},
            {"name": "Gravel 6/10", "kind": "aggregate", "mass_percent": 55, "density_g_cm3": 2.7, "d_min_mm": 6,
             "d_max_mm": 10, "fit": "fits/gravel.fit.json"}]}))
    lines = ["theta_i,phi_i,theta_r,phi_r," + ",".join(map(str, WAVELENGTHS)) + ","
             + ",".join(f"sigma_{w}" for w in WAVELENGTHS)]
    i = 0
    for ti in (0, 30, 60):
        for tr in (10, 40, 70):
            for pr in (0, 90, 180):
                values = []
                for m in range(4):
                    i += 1
                    rho = 0.1 * SPECTRA["bitumen"][m] + 0.3 * SPECTRA["mastic"][m] + 0.6 * SPECTRA["gravel"][m]
                    values.append(rho / math.pi * (1 + 0.05 * math.sin(2.3 * i)))
                sigmas = [0.02 * v for v in values]
                lines.append(f"{ti},0,{tr},{pr}," + ",".join(repr(v) for v in values + sigmas))
    data = tmp_path / "mixed.csv"
    data.write_text("\n".join(lines) + "\n")
    return str(formulation), str(data), tmp_path


def _cli_warnings(stderr):
    return [line[len("roadbrdf: warning: "):] for line in stderr.splitlines() if line.startswith("roadbrdf: warning: ")]


def test_mix_without_data_notes_the_skipped_methods(cli, case):
    formulation, _, tmp = case
    r = cli("mix", formulation, "-o", tmp / "cli.mix.json")
    with pytest.warns(UserWarning) as caught:
        result = roadbrdf.mix(formulation)
    notes = [str(w.message) for w in caught]
    assert notes == result.notes == _cli_warnings(r.stderr)
    assert any("'fitted' skipped" in n for n in notes)
    assert result.to_dict() == json.loads((tmp / "cli.mix.json").read_text())


@pytest.mark.parametrize("options", [
    (["--method", "all", "--folds", "3", "--seed", "4"], dict(method="all", folds=3, seed=4)),
    (["--method", "fitted", "--folds", "3", "--sum-to-one", "--per-wavelength"],
     dict(method="fitted", folds=3, sum_to_one=True, per_wavelength=True)),
    (["--method", "areal", "--folds", "3", "--binder-coverage", "0.4"], dict(method="areal", folds=3, binder_coverage=0.4)),
    (["--method", "shadowed", "--folds", "3", "--no-sigma-weights"], dict(method="shadowed", folds=3, use_sigma=False)),
], ids=["all", "fitted", "areal", "shadowed"])
def test_mix_with_data_is_identical(cli, case, options):
    formulation, data, tmp = case
    flags, kwargs = options
    cli("mix", formulation, "--data", data, *flags, "-o", tmp / "cli.mix.json")
    result = roadbrdf.mix(formulation, data=data, **kwargs)
    assert result.to_dict() == json.loads((tmp / "cli.mix.json").read_text())
    result.write(tmp / "py.mix.json")
    assert (tmp / "py.mix.json").read_text() == (tmp / "cli.mix.json").read_text()
    best = result.best
    assert best is not None and best.comparison["rmse"] > 0
    assert result.spectral_model().evaluate(30, 0, 30, 180, 500.0) > 0
    # The written MIX.json is a spectral model for every reader (read_fit, as `--fit METHOD` in the CLI).
    assert roadbrdf.read_fit(tmp / "py.mix.json", best.method).evaluate(30, 0, 30, 180, 500.0) == pytest.approx(
        result.spectral_model().evaluate(30, 0, 30, 180, 500.0), rel=1e-12)
    assert "held-out" in result.summary and "roadbrdf.MixResult" in repr(result)
    pd = pytest.importorskip("pandas")
    df = result.to_dataframe()
    assert isinstance(df, pd.DataFrame)
    assert list(df["method"]) == [m.method for m in result.methods]
    assert list(df["rmse"]) == [m.comparison["rmse"] for m in result.methods]


ERRORS = [
    (["--folds", "1"], dict(folds=1), "--folds", "folds"),
    (["--method", "fited"], dict(method="fited"), "--method", "method"),
    (["--binder-coverage", "2"], dict(binder_coverage=2.0), "--binder-coverage", "binder_coverage"),
    (["--method", "fitted"], dict(method="fitted", data=None), "--method", "method"),
]


@pytest.mark.parametrize("flags,kwargs,cli_field,py_field", ERRORS, ids=[e[3] + str(i) for i, e in enumerate(ERRORS)])
def test_mix_errors_are_the_same(cli, case, flags, kwargs, cli_field, py_field):
    formulation, data, tmp = case
    kwargs = dict(kwargs)
    use_data = kwargs.pop("data", data) is not None
    r = cli("mix", formulation, *(["--data", data] if use_data else []), *flags, "-o", tmp / "x.json", check=False)
    assert r.returncode == 2 and r.stderr.startswith(f"roadbrdf: error: {cli_field}: "), r.stderr
    with pytest.raises(roadbrdf.InputError) as e:
        roadbrdf.mix(formulation, data=data if use_data else None, **kwargs)
    assert str(e.value).startswith(py_field + ": ")
    assert r.stderr.strip()[len(f"roadbrdf: error: {cli_field}: "):] == str(e.value)[len(py_field) + 2:]
    assert not (tmp / "x.json").exists()


def test_misspelt_method_suggests(case):
    formulation, data, _ = case
    with pytest.raises(roadbrdf.InputError, match=r"did you mean 'fitted'\?"):
        roadbrdf.mix(formulation, data=data, method="fited")
