"""The sample report's road-lighting section (`roadbrdf report ... --installation I.json [--lighting-class M]`,
python/roadbrdf/report_lighting.py): its figures are those of `roadbrdf.lighting` on the report's best fit; without
an installation there is no section and no error; bad options are errors before the long steps."""

import pathlib
import subprocess

import pytest

import roadbrdf
from test_report import DATA, FIXED, MODELS, SECTIONS, _exe, _Page, _same, _value

INSTALLATION = pathlib.Path(__file__).resolve().parents[1] / "data" / "lighting" / "installation.json"


def _run(*args):
    return subprocess.run([_exe(), "report", *map(str, args)], capture_output=True, text=True)


def test_lighting_section_equals_the_lighting_of_the_best_fit(tmp_path):
    out = tmp_path / "F1.html"
    result = _run(DATA, "--installation", INSTALLATION, "--lighting-class", "M6", "--multistart", "2", "-o", out)
    assert result.returncode == 0, result.stderr
    assert "road lighting of installation.json" in result.stderr
    page = _Page(out.read_text(encoding="utf-8"))
    assert page.sections == SECTIONS + ["lighting"]
    assert "lighting" in page.figures
    fit_file = tmp_path / "F1.fit.json"
    roadbrdf.fit(DATA, MODELS, fixed=FIXED, multistart=2, output=fit_file)
    with pytest.warns(UserWarning):
        v = roadbrdf.lighting(INSTALLATION, surface=fit_file, target_class="M6").value
    for name in ("L_av", "U_o", "U_l", "f_TI", "R_EI", "E_av", "U_o_E", "D_P", "D_E"):
        _same(page, f"lighting.{name}", v[name], digits=3)
    assert _value(page, "lighting.M_class")[1] == (v["M_class"] or "none")
    _same(page, "lighting.power_per_km_w", v["energy"]["power_per_km_w"])
    _same(page, "lighting.least_power_per_km_w", v["least_flux"]["power_per_km_w"])
    _same(page, "lighting.reflected_upward_lm_per_km", v["upward"]["reflected_upward_lm_per_km"])
    _same(page, "lighting.reflectance", v["upward"]["reflectance"], digits=3)
    # EN 13201-5 from the page's own figures: D_P = P / (E_av A) over one spacing (30 m x 7 m, 90 W), and the
    # installed power per km = 90 W x 1000 / 30 luminaires.
    e_av = _value(page, "lighting.E_av")[0]
    assert _value(page, "lighting.D_P")[0] == pytest.approx(90.0 / (e_av * 30.0 * 7.0), rel=1e-12)
    assert _value(page, "lighting.power_per_km_w")[0] == pytest.approx(90.0 * 1000.0 / 30.0, rel=1e-12)


@pytest.mark.parametrize("args, message", [
    (["--installation", "{tmp}/absent.json"], "--installation: '{tmp}/absent.json': no such file"),
    (["--lighting-class", "M3"], "--lighting-class: needs --installation"),
    (["--installation", str(INSTALLATION), "--lighting-class", "M9"], "'M9' is not an M lighting class"),
])
def test_bad_lighting_options_are_errors_before_any_work(tmp_path, args, message):
    args = [a.replace("{tmp}", str(tmp_path)) for a in args]
    result = _run(DATA, *args, "-o", tmp_path / "r.html")
    assert result.returncode == 2, result.stderr
    assert result.stderr.startswith("roadbrdf report: error: "), result.stderr
    assert message.replace("{tmp}", str(tmp_path)) in result.stderr
    assert "fitting" not in result.stderr and "Traceback" not in result.stderr
    assert list(tmp_path.iterdir()) == []


def test_python_keyword_without_an_installation_has_no_section(tmp_path):
    from roadbrdf.report import gather, render_report
    g = gather(DATA, MODELS, multistart=1, quiet=True)
    page = _Page(render_report(g))
    assert "lighting" not in page.sections and g.lighting is None
