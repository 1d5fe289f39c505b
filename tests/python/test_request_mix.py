"""The request table of `roadbrdf mix` and roadbrdf.mix (MixRequest::fields, core/request_fields.h): every
row is an option of the command and a keyword of the function, and a bad value is refused with the same
text by both. The notes of skipped methods reach both front ends (the command's warnings, Python's
UserWarning), and the result in memory is the MIX.json the command writes."""
import json
import math

import pytest
from request_table import check_every_row_is_shown, check_refused_alike, fields

import roadbrdf

FIELDS = fields("mix")

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


def test_every_row_is_an_option_and_a_keyword(cli):
    check_every_row_is_shown(cli, "mix", roadbrdf.mix)


def _bad_values(formulation, data, tmp):
    """For every field that takes a value: (command line arguments, Python keywords) of a bad one."""
    absent = str(tmp / "absent.json")
    return {
        "formulation": (["FORMULATION", absent], dict(formulation=absent)),
        "data": (["--data", str(tmp / "absent.csv")], dict(data=str(tmp / "absent.csv"))),
        "delimiter": (["--data", data, "--delimiter", "|"], dict(data=data, delimiter="|")),
        "decimal": (["--data", data, "--decimal", "x"], dict(data=data, decimal="x")),
        "quantity": (["--data", data, "--quantity", "brdff"], dict(data=data, quantity="brdff")),
        "columns": (["--data", data, "--column", "theta_r=No_Such_Column"],
                    dict(data=data, columns=["theta_r=No_Such_Column"])),
        "set": (["--data", data, "--set", "theta_q=30"], dict(data=data, set=["theta_q=30"])),
        "method": (["--method", "fited"], dict(method="fited")),
        "folds": (["--folds", "1"], dict(folds=1)),
        "seed": (["--seed", "-1"], dict(seed=-1)),
        "binder_coverage": (["--binder-coverage", "2"], dict(binder_coverage=2.0)),
        "mastic_fraction": (["--mastic-fraction", "-0.5"], dict(mastic_fraction=-0.5)),
        "residuals": (["--residuals", str(tmp / "r.csv")], dict(residuals=str(tmp / "r.csv"))),
        "reference": (["--reference", str(tmp / "ref.json")], dict(reference=str(tmp / "ref.json"))),
        "cross_sections": (["--method", "areal", "--cross-sections", absent], dict(method="areal", cross_sections=absent)),
        "output": (["OUTPUT", formulation], dict(output=formulation)),
    }


@pytest.mark.parametrize("row", [r for r in FIELDS if r["kind"] != "switch"], ids=lambda r: r["name"])
def test_a_bad_value_is_refused_alike(cli, case, row):
    formulation, data, tmp = case
    bad = _bad_values(formulation, data, tmp)
    assert row["name"] in bad, f"the table's field {row['name']} needs a bad value in this test"
    flags, keywords = bad[row["name"]]
    out = str(tmp / "x.json")
    if flags[0] == "FORMULATION":
        flags = [flags[1], "-o", out]
    elif flags[0] == "OUTPUT":
        flags = [formulation, "-o", flags[1]]
    else:
        flags = [formulation, "-o", out, *flags]
    result = cli("mix", *flags, check=False)
    keywords.setdefault("formulation", formulation)
    with pytest.raises(roadbrdf.InputError) as error:
        roadbrdf.mix(**keywords)
    check_refused_alike("mix", row, result, error.value)
    assert not (tmp / "x.json").exists()


def test_formulation_and_fits_as_values(case):
    """A formulation given as a dict and its fit files as values (a design study's fast path) mix as the
    files do; a fit given as a value is read once by an end-member cache, and a reference that is neither
    a value nor a file is an error naming it."""
    formulation, _, tmp = case
    from_files = roadbrdf.mix(formulation, method="areal")
    content = json.loads(open(formulation, encoding="utf-8").read())
    fits = {}

    def as_value(entry):  # a name no file has: only the value can answer it
        name = "in-memory-" + entry["fit"].split("/")[-1]
        fits[name] = (tmp / entry["fit"]).read_text()
        entry["fit"] = name

    for component in content["components"]:
        as_value(component)
    as_value(content["mastic"])
    cache = roadbrdf._roadbrdf.EndMemberCache()
    in_memory = roadbrdf.mix(content, fits=fits, method="areal", cache=cache)
    roadbrdf.mix(content, fits=fits, method="areal", cache=cache)
    assert cache.fits_read == len(fits) == 3
    assert [list(m.weights.values()) for m in in_memory.methods] == \
        [list(m.weights.values()) for m in from_files.methods]
    for geometry in [(30, 0, 30, 180, 500.0), (0, 0, 60, 90, 700.0)]:
        assert in_memory.spectral_model().evaluate(*geometry) == from_files.spectral_model().evaluate(*geometry)
    del fits["in-memory-gravel.fit.json"]
    with pytest.raises(roadbrdf.InputError, match="in-memory-gravel.fit.json"):
        roadbrdf.mix(content, fits=fits, method="areal")


def test_python_writes_the_outputs(case):
    formulation, data, tmp = case
    result = roadbrdf.mix(formulation, data=data, method="areal", folds=3, output=tmp / "m.json",
                          residuals=tmp / "r.csv")
    assert json.loads((tmp / "m.json").read_text()) == result.to_dict()
    assert (tmp / "r.csv").read_text().count("\n") > 1


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


def test_misspelt_method_suggests(case):
    formulation, data, _ = case
    with pytest.raises(roadbrdf.InputError, match=r"did you mean 'fitted'\?"):
        roadbrdf.mix(formulation, data=data, method="fited")


def test_mixture_reports_take_the_requests_keywords(case):
    """The fast path's reports of a mixture (mixture_albedo, mixture_rtable_report) take their request's
    fields as keywords, as roadbrdf.albedo and roadbrdf.rtable do: the same albedo as the MIX.json read back
    (within the quadrature tolerance), a misspelt keyword refused with the nearest name, and no positional
    request field."""
    formulation, _, tmp = case
    _roadbrdf = roadbrdf._roadbrdf
    cache = _roadbrdf.EndMemberCache()
    run = _roadbrdf.mix(formulation, method="areal", cache=cache)
    run.write(str(tmp / "areal.mix.json"))
    fast = _roadbrdf.mixture_albedo(run, 0, cache, sun_zenith=[20, 50], tolerance=1e-7, uncertainty=False)
    direct = _roadbrdf.albedo(model=str(tmp / "areal.mix.json"), sun_zenith=[20, 50], tolerance=1e-7,
                              uncertainty=False).content()
    assert fast["sun_zenith_deg"] == [20, 50]
    # Lambertian end-members: every black-sky value is the white-sky one (a Lambertian's albedo).
    for row in fast["black_sky"]:
        assert row == pytest.approx(fast["white_sky"], abs=1e-6)
    assert fast["white_sky"] == pytest.approx(direct["white_sky"], abs=1e-6)
    with pytest.raises(TypeError, match="did you mean 'sun_zenith'"):
        _roadbrdf.mixture_albedo(run, 0, cache, sun_zenit=[20])
    with pytest.raises(roadbrdf.InputError, match="model"):
        _roadbrdf.mixture_albedo(run, 0, cache, model="lambert")
    with pytest.raises(roadbrdf.InputError, match="tolerance"):
        _roadbrdf.mixture_albedo(run, 0, cache, tolerance=-1.0)
    with pytest.raises(TypeError):
        _roadbrdf.mixture_albedo(run, 0, cache, [20])
    with pytest.raises(TypeError):
        _roadbrdf.mixture_rtable_report(run, 0, cache, 1.0)
    assert _roadbrdf.mixture_rtable_report(run, 0, cache, illuminant="D65")["weighting"] is not None
