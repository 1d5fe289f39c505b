"""Design studies (roadbrdf.study / roadbrdf study): the fast path against closed forms, designs, errors."""

import csv
import json
import math

import pytest

import roadbrdf
from study_support import two_rock_study


def d_eff(lo, hi):
    return (hi - lo) / math.log(hi / lo)


def expected_albedo(grey_percent, rock):
    rho, density = {"dark": (0.1, 2.7), "light": (0.6, 2.5)}[rock]
    w1 = grey_percent / (2.65 * d_eff(2, 6))
    w2 = (100 - grey_percent) / (density * d_eff(6, 10))
    return (w1 * 0.3 + w2 * rho) / (w1 + w2)


def read_csv(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def test_fast_path_matches_closed_form(cli, tmp_path):
    study = two_rock_study(tmp_path)
    out = tmp_path / "results.csv"
    cli("study", study, "-o", out, "--workers", "2", "--quiet")
    rows = read_csv(out)
    assert len(rows) == 6
    assert "Q0 [sr^-1]" in rows[0] and "grey [%]" in rows[0] and "white_sky [1]" in rows[0]
    seen = set()
    for r in rows:
        assert r["status"] == "ok", r["error"]
        grey, rock = float(r["grey [%]"]), r["rock [library]"]
        seen.add((grey, rock))
        a = expected_albedo(grey, rock)
        # A Lambertian surface: every albedo is its albedo, q = rho / pi everywhere, so Q0 = Qd = rho / pi and
        # S1 = r(0, tan 2) / r(0, 0) = cos^3(atan 2) = 5^-1.5.
        for column in ("black_sky_0deg [1]", "black_sky_60deg [1]", "white_sky [1]", "blue_sky_60deg [1]"):
            assert float(r[column]) == pytest.approx(a, abs=2e-5), column
        assert float(r["Q0 [sr^-1]"]) == pytest.approx(a / math.pi, rel=1e-9)
        assert float(r["Qd [sr^-1]"]) == pytest.approx(a / math.pi, rel=1e-9)
        assert float(r["S1 [1]"]) == pytest.approx(5 ** -1.5, rel=1e-9)
        assert r["class [R]"] == "R1"
    assert seen == {(g, k) for g in (20.0, 50.0, 80.0) for k in ("dark", "light")}
    # The same study from Python: the same table, number for number; and it comes from the store.
    py = roadbrdf.study(study, output=tmp_path / "py.csv", progress=False)
    assert (tmp_path / "py.csv").read_text() == out.read_text()
    assert [r["key"] for r in py] == [r["key"] for r in rows]


def test_rerun_costs_nothing_and_workers_do_not_matter(tmp_path, capfd):
    study = two_rock_study(tmp_path)
    roadbrdf.study(study, output=tmp_path / "a.csv", workers=1)
    first = capfd.readouterr().err
    assert "0 already in the store, 6 to compute" in first
    roadbrdf.study(study, output=tmp_path / "a.csv", workers=2)
    assert "6 already in the store, 0 to compute" in capfd.readouterr().err
    roadbrdf.study(study, output=tmp_path / "b.csv", workers=2, progress=False)
    assert (tmp_path / "a.csv").read_text() == (tmp_path / "b.csv").read_text()
    lines = (tmp_path / "a.csv.store.jsonl").read_text().splitlines()
    assert len(lines) == 1 + 6  # header and one line per candidate, nothing twice


def test_share_and_envelope_failure(tmp_path):
    # A share moves part of a component's mass to a library material (same size class); the balance envelope
    # makes some candidates infeasible: they are recorded as failed, the others still run.
    variables = [{"name": "light_share", "kind": "share", "component": ["Other 6/10"], "material": "light",
                  "values": [0.0, 0.5]},
                 {"name": "grey", "kind": "mass_percent", "component": "Grey 2/6", "values": [40, 70],
                  "balance": "Other 6/10", "balance_range": [35, 100]}]
    study = two_rock_study(tmp_path, variables=variables)
    rows = roadbrdf.study(study, progress=False)
    assert len(rows) == 4
    failed = [r for r in rows if r["status"] == "failed"]
    assert len(failed) == 2 and all(r["grey [%]"] == 70 for r in failed)
    assert "outside its envelope [35, 100]" in failed[0]["error"]
    for r in rows:
        if r["status"] != "ok":
            continue
        s = r["light_share [1]"]
        m = 60.0
        w = [40 / (2.65 * d_eff(2, 6)), m * (1 - s) / (2.7 * d_eff(6, 10)), m * s / (2.5 * d_eff(6, 10))]
        a = (w[0] * 0.3 + w[1] * 0.1 + w[2] * 0.6) / sum(w)
        assert r["white_sky [1]"] == pytest.approx(a, abs=2e-5)


def test_designs_are_seeded_and_latin(tmp_path):
    variables = [{"name": "grey", "kind": "mass_percent", "component": "Grey 2/6", "range": [10, 90],
                  "balance": "Other 6/10"},
                 {"name": "rock", "kind": "component", "component": "Other 6/10", "choices": ["dark", "light"]}]
    study = two_rock_study(tmp_path, design={"type": "lhs", "count": 8, "seed": 3}, variables=variables)
    from roadbrdf.studies import design, read_study
    s = read_study(study)
    points = list(design.design_points(s))
    again = list(design.design_points(read_study(study)))
    assert points == again
    # One point in each eighth of the range, and each choice in half of the points.
    strata = sorted(int((p["grey"] - 10) / 80 * 8) for p in points)
    assert strata == list(range(8))
    assert sorted(p["rock"] for p in points) == ["dark"] * 4 + ["light"] * 4
    s.design["seed"] = 4
    assert list(design.design_points(s)) != points


@pytest.mark.parametrize("change, message", [
    ({"format": "x"}, "format: expected \"roadbrdf-study\""),
    ({"variables": [{"name": "g", "kind": "mass_percent", "component": "Nope", "values": [1],
                     "balance": "Grey 2/6"}]}, "variables[0].component: the base formulation has no component 'Nope'"),
    ({"variables": [{"name": "g", "kind": "mass_percent", "component": "Grey 2/6", "range": [5, 1],
                     "balance": "Other 6/10"}]}, "variables[0].range: low 5 must be below high 1"),
    ({"variables": [{"name": "r", "kind": "component", "component": "Grey 2/6", "choices": ["dark", "pink"]}]},
     "variables[0].choices[1]: 'pink' is not in the library"),
    ({"design": {"type": "grid", "count": 3}}, "design.count: a grid has"),
    ({"predictions": {"path": "fast", "methods": ["fitted"]}}, "predictions.methods[0]: 'fitted' is not one of"),
    ({"predictions": {"path": "physical", "physical": {"samples": 0}}}, "predictions.physical.samples: 0 is outside"),
    ({"colour": 1}, "colour: unknown key"),
])
def test_errors_name_the_key_path_same_in_cli_and_python(cli, tmp_path, change, message):
    study = two_rock_study(tmp_path)
    data = json.loads(study.read_text())
    data.update(change)
    study.write_text(json.dumps(data))
    with pytest.raises(roadbrdf.InputError) as e:
        roadbrdf.study(study, progress=False)
    assert f"{study}: {message}" in str(e.value)
    result = cli("study", study, "-o", tmp_path / "r.csv", check=False)
    assert result.returncode != 0
    assert f"roadbrdf: error: {e.value}" in result.stderr
    assert not (tmp_path / "r.csv").exists()


def test_plot_study_plane_and_sensitivity(cli, tmp_path):
    study = two_rock_study(tmp_path)
    out = tmp_path / "results.csv"
    roadbrdf.study(study, output=out, progress=False)
    figure = tmp_path / "plane.png"
    cli("plot", "study", out, "-o", figure, "--axis", "S1", "--method", "areal")
    assert figure.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    from roadbrdf import plot_study
    plot_study.draw(str(out), "plane", output=tmp_path / "q0.png")
    plot_study.draw(str(out), "sensitivity", output=tmp_path / "sensitivity.png")
    assert (tmp_path / "q0.png").stat().st_size > 0 and (tmp_path / "sensitivity.png").stat().st_size > 0
    result = cli("plot", "study", out, "-o", out, check=False)  # never over its own input
    assert result.returncode != 0 and out.read_text().startswith("candidate,")


def test_pareto_front():
    from roadbrdf.plot_study import pareto
    x = [0.1, 0.2, 0.3, 0.2, 0.15]
    y = [0.09, 0.08, 0.05, 0.06, 0.07]
    # (0.2, 0.06) is beaten by (0.2, 0.08), (0.15, 0.07) by (0.2, 0.08); the others trade albedo for Q0.
    assert pareto(x, y) == [0, 1, 2]
    assert pareto(x, y, maximise_y=False) == [2]  # the lightest rock is also the least specular here


def test_physical_path_passes_the_candidate_as_values(tmp_path, monkeypatch):
    """The physical path generates and renders a candidate given as values (its formulation as a dict, its fit
    files' texts by reference): the same sample and the same render, bit for bit, as from the files, and no
    temporary file is written for it."""
    import tempfile

    from roadbrdf import _roadbrdf
    from roadbrdf.surfaces import Surface
    from study_support import physical_study
    physical_study(tmp_path)
    base = json.loads((tmp_path / "base.json").read_text())
    fits = {}
    for entry in [base["mastic"], *base["components"]]:
        name = "value-" + entry["fit"].split("/")[-1]  # a name no file has: only the value can answer it
        fits[name] = (tmp_path / entry["fit"]).read_text()
        entry["fit"] = name

    def no_temporary_files(*args, **kwargs):
        raise AssertionError("a temporary file was made")

    monkeypatch.setattr(tempfile, "mkdtemp", no_temporary_files)
    monkeypatch.setattr(tempfile, "mkstemp", no_temporary_files)
    from_value = Surface(*_roadbrdf.surface(base, size_mm=12.0, cell_mm=0.4, seed=3, mastic_fraction=0.3, fits=fits))
    from_files = roadbrdf.surface(tmp_path / "base.json", size_mm=12, cell_mm=0.4, seed=3, mastic_fraction=0.3)
    assert from_value.mpd_mm == from_files.mpd_mm
    a = roadbrdf.render(from_value, 30.0, 0.0, 30.0, 180.0, wavelengths=[550], samples=64, seed=5, threads=1)
    b = roadbrdf.render(from_files, 30.0, 0.0, 30.0, 180.0, wavelengths=[550], samples=64, seed=5, threads=1)
    assert a.brdf.tolist() == b.brdf.tolist()
    del fits["value-grey.fit.json"]
    lacking = Surface(*_roadbrdf.surface(base, size_mm=12.0, cell_mm=0.4, seed=3, mastic_fraction=0.3, fits=fits))
    with pytest.raises(roadbrdf.InputError, match="value-grey.fit.json"):
        roadbrdf.render(lacking, 30.0, 0.0, 30.0, 180.0, wavelengths=[550], samples=64, seed=5, threads=1)
