"""`roadbrdf report`: the sample report (python/roadbrdf/report*.py, docs/report.md).

The page's numbers are read back from their ``data-key``/``data-value`` attributes and compared with the
same quantities computed here directly with the Python API (check, fit, params, albedo, rtable, mix) or
from the file itself (size, SHA-256); the rounded text shown must agree with them too. The page is then
loaded by headless Chromium (when /usr/bin/chromium exists): every image must decode, the page must
print to PDF, and a screenshot is taken (kept in $ROADBRDF_SCREENSHOT_DIR when set, for docs/figures).
"""

import base64
import hashlib
import html.parser
import os
import pathlib
import shutil
import struct
import subprocess
import time
import warnings

import numpy as np
import pytest

import roadbrdf
from roadbrdf import report_html

ROOT = pathlib.Path(__file__).resolve().parents[2]
DATA = ROOT / "data" / "examples" / "mixed" / "F1.csv"
MODELS = ["oren-nayar", "lambert+torrance-sparrow"]  # the report's defaults
FIXED = {"lambert.weight": 1.0, "torrance-sparrow.weight": 1.0}  # the composite's weights, held at 1
CHROMIUM = "/usr/bin/chromium"
FIGURES = ["spectral-mirror", "spectral-retro", "spectral-nadir", "hemisphere", "plane", "params-by-incidence",
           "params-by-wavelength", "fit-quality", "albedo", "rtable"]  # in the page's order
SECTIONS = ["provenance", "quality", "coverage", "spectra", "per-incidence", "ranking", "albedo", "rtable", "mixing"]


def _exe():
    return os.environ.get("ROADBRDF_CLI", str(ROOT / "build" / "roadbrdf"))


class _Page(html.parser.HTMLParser):
    """The keyed values (key -> (data-value or None, text)), section ids, figure keys and image sources."""

    def __init__(self, text):
        super().__init__()
        self.values, self.sections, self.figures, self.images, self.tags = {}, [], [], [], set()
        self._open = []  # [key, value, text parts, depth]
        self.feed(text)

    _VOID = {"area", "base", "br", "col", "embed", "hr", "img", "input", "link", "meta", "source", "wbr"}

    def handle_starttag(self, tag, attrs):
        a = dict(attrs)
        self.tags.add(tag)
        if tag == "img":
            self.images.append(a.get("src", ""))
        if tag in self._VOID:  # no end tag
            return
        for item in self._open:
            item[3] += 1
        if "data-key" in a:
            self._open.append([a["data-key"], a.get("data-value"), [], 1])
        if tag == "section":
            self.sections.append(a.get("id"))
        if tag == "figure":
            self.figures.append(a.get("data-figure"))

    def handle_endtag(self, tag):
        for item in list(self._open):
            item[3] -= 1
            if item[3] == 0:
                self._open.remove(item)
                self.values[item[0]] = (None if item[1] is None else float(item[1]), "".join(item[2]).strip())

    def handle_data(self, data):
        for item in self._open:
            item[2].append(data)


def _run(*args, umask=None):
    def preexec():
        if umask is not None:
            os.umask(umask)
    return subprocess.run([_exe(), "report", *map(str, args)], capture_output=True, text=True, preexec_fn=preexec)


@pytest.fixture(scope="module")
def report(tmp_path_factory):
    """The report of the bundled F1 with the default options, made by the command line."""
    folder = tmp_path_factory.mktemp("report")
    out = folder / "F1.html"
    start = time.monotonic()
    result = _run(DATA, "-o", out)
    seconds = time.monotonic() - start
    assert result.returncode == 0, result.stderr
    text = out.read_text(encoding="utf-8")
    page = _Page(text)
    return {"path": out, "text": text, "page": page, "stderr": result.stderr, "seconds": seconds}


def _value(page, key):
    assert key in page.values, f"no '{key}' in the page (keys: {sorted(page.values)[:20]}...)"
    return page.values[key]


def _same(page, key, expected, rel=1e-9, digits=4):
    """The exact value (data-value) equals ``expected`` and the text shown rounds it to ``digits`` digits."""
    value, text = _value(page, key)
    assert value == pytest.approx(expected, rel=rel, abs=1e-15), key
    shown = float(text.split("±")[0].split("(")[0].replace("−", "-"))
    assert shown == pytest.approx(expected, rel=0.6 * 10.0 ** (1 - digits), abs=1e-12), (key, text, expected)


# ---- the page ----------------------------------------------------------------------------------------
def test_sections_and_figures_are_embedded(report):
    page, text = report["page"], report["text"]
    assert page.sections == SECTIONS
    assert page.figures == FIGURES
    assert len(page.images) == len(FIGURES)
    for src in page.images:
        assert src.startswith("data:image/png;base64,")
        assert base64.b64decode(src.split(",", 1)[1])[:8] == b"\x89PNG\r\n\x1a\n"
    # Self-contained: nothing to fetch, no script.
    assert not page.tags & {"script", "link", "iframe", "object", "embed"}
    assert "http://" not in text and "https://" not in text
    assert "figure not drawn" not in text
    assert "Not requested" in text  # no --formulation: the mixing section says what it needs
    for step in ("reading and checking", "fitting", "albedo", "r-table", "drawing the figures", "wrote"):
        assert step in report["stderr"]
    print(f"roadbrdf report on {DATA.name}: {report['seconds']:.1f} s, {len(text) / 1024:.0f} KiB")


def test_provenance_from_the_file(report):
    page = report["page"]
    content = DATA.read_bytes()
    d = roadbrdf.read_dataset(DATA)
    assert _value(page, "file.sha256")[1] == hashlib.sha256(content).hexdigest()
    assert _value(page, "file.size")[0] == len(content)
    assert _value(page, "file.rows")[0] == len(d)  # a wide file: one row per geometry
    assert _value(page, "data.geometries")[0] == len(d)
    assert _value(page, "data.wavelengths")[0] == d.wavelengths.size
    assert d.metadata["sample"] in report["text"]


def test_python_check_is_the_command_lines(tmp_path):
    """roadbrdf.check (new for the report) gives what `roadbrdf check --json` prints, plus its text."""
    import json
    printed = subprocess.run([_exe(), "check", str(DATA), "--json"], capture_output=True, text=True, check=True)
    cli_json = json.loads(printed.stdout)
    text = subprocess.run([_exe(), "check", str(DATA)], capture_output=True, text=True, check=True).stdout
    python = roadbrdf.check(DATA)
    assert python.pop("text") == text.split("\n", 1)[1]  # the command line prints the file name first
    assert json.loads(json.dumps(python)) == cli_json


def test_quality_check_numbers(report):
    page, c = report["page"], roadbrdf.check(DATA)
    assert _value(page, "check.negative_values")[0] == c["negative_values"]
    assert _value(page, "check.missing_values")[0] == c["missing_values"]
    assert _value(page, "check.reciprocity.pairs")[0] == c["reciprocity"]["pairs"]
    assert _value(page, "check.reciprocity.max")[0] == pytest.approx(c["reciprocity"]["max_disagreement"])
    assert _value(page, "check.outliers")[0] == len(c["outliers"])
    assert _value(page, "check.noisy_bands")[0] == len(c["noise"]["noisy_bands"])
    for t in c["coverage"]["incidence_zenith_deg"]:
        geometries = int(np.sum(np.abs(roadbrdf.read_dataset(DATA).theta_i - t) < 1e-6))
        assert _value(page, f"coverage.group.{t:g}.geometries")[0] == geometries


# ---- fits ----------------------------------------------------------------------------------------------
def test_per_incidence_parameters_equal_the_fit(report):
    """Every parameter, standard error and statistic of the per-incidence tables equals roadbrdf.fit's,
    fitted here per theta_i at the band nearest 600 nm (F1: 590 nm; every incidence has enough points)."""
    page = report["page"]
    result = roadbrdf.fit(DATA, MODELS, fixed=FIXED, multistart=8, wavelengths=[600], group_by="theta_i")
    assert result.notes == ["600 nm: nearest band 590 nm"]
    assert "5. Fits per incidence at 590 nm" in report["text"]
    seen = 0
    for f in result.fits:
        key = f"group.{f.model}.theta_i={f.group['theta_i']:g}"
        for k, name in enumerate(f.parameter_names):
            if name in FIXED:
                assert f"{key}.{name}" not in page.values  # held parameters are not table columns
                continue
            _same(page, f"{key}.{name}", f.parameters[k, 0])
            value, text = _value(page, f"{key}.{name}")
            se = f.standard_errors[k, 0]
            on_bound = any(b.split("=")[0] == name for b in f.statistics["at_bounds"][0])
            if on_bound:  # a linearised standard error at a bound means nothing: none is shown
                assert "±" not in text, (key, name, text)
            elif np.isfinite(se):
                assert float(text.split("±")[1]) == pytest.approx(se, rel=0.06)
            seen += 1
        _same(page, f"{key}.rmse_per_sr", f.statistics["rmse"][0])
        _same(page, f"{key}.bic", f.statistics["bic"][0], digits=6)
        _same(page, f"{key}.aic", f.statistics["aic"][0], digits=6)
        _same(page, f"{key}.relative_rmse_percent", 100 * f.statistics["relative_rmse"][0], digits=3)
    assert seen == 5 * (2 + 4)  # 5 incidences x (oren-nayar: albedo, sigma; lambert+torrance-sparrow: 4 free)
    # The ranking within each incidence: BIC order, and the BIC summed over the groups.
    for t in {f.group["theta_i"] for f in result.fits}:
        fits = sorted((f for f in result.fits if f.group["theta_i"] == t), key=lambda f: f.statistics["bic"][0])
        for rank, f in enumerate(fits, start=1):
            assert _value(page, f"group-rank.theta_i={t:g}.{f.model}.rank")[0] == rank
    for m in MODELS:
        total = sum(f.statistics["bic"][0] for f in result.fits if f.model == m)
        _same(page, f"group-total.{m}.bic", total, digits=6)


def test_ranking_over_all_configurations(tmp_path, report):
    page = report["page"]
    result = roadbrdf.fit(DATA, MODELS, fixed=FIXED, multistart=8)
    for rank, index in enumerate(result.ranking, start=1):
        f = result.fits[index]
        assert _value(page, f"rank.{f.model}.rank")[0] == rank
        _same(page, f"rank.{f.model}.bic", f.totals["bic"], digits=7)
        _same(page, f"rank.{f.model}.aic", f.totals["aic"], digits=7)
        _same(page, f"rank.{f.model}.rmse", f.totals["rmse"])
        k = int(np.argmin(np.abs(f.wavelengths - 590.0)))
        for j, name in enumerate(f.parameter_names):
            if name not in FIXED:
                _same(page, f"all.{f.model}.{name}", f.parameters[j, k])
    bics = [result.fits[i].totals["bic"] for i in result.ranking]
    assert _value(page, f"rank.{result.fits[result.ranking[1]].model}.delta_bic")[0] == pytest.approx(bics[1] - bics[0])
    assert f"best model (BIC, all configurations)</span><span class=\"value\">{result.best.model}" in report["text"]


def test_albedo_and_rtable_equal_the_api(tmp_path, report):
    """Albedo and r-table of the best fit, computed here from the fit file as `roadbrdf albedo FIT.json` does."""
    page = report["page"]
    fit_file = tmp_path / "F1.fit.json"
    roadbrdf.fit(DATA, MODELS, fixed=FIXED, multistart=8, output=fit_file)
    with pytest.warns(UserWarning, match="mostly extrapolation"):
        a = roadbrdf.albedo(fit_file, sun_zenith="0:60:30", atmosphere="spectrl2")
    bb = a["broadband"]
    for k, z in enumerate(a["sun_zenith_deg"]):
        _same(page, f"albedo.broadband.black_sky.{z:g}", bb["black_sky"][k])
        _same(page, f"albedo.broadband.blue_sky.{z:g}", bb["blue_sky"][k])
        _same(page, f"coverage.black_sky.{z:g}", 100 * a["coverage"]["black_sky_outside_fraction"][k], digits=3)
    _same(page, "albedo.broadband.white_sky", bb["white_sky"])
    # The solar-weighted values are shown ± the bound for errors correlated across wavelengths, with the
    # (smaller) uncertainty for independent wavelengths beside it, and what both leave out.
    ub = a["uncertainty"]["broadband"]
    for k, z in enumerate(a["sun_zenith_deg"]):
        text = _value(page, f"albedo.broadband.black_sky.{z:g}")[1]
        shown_u = float(text.split("±")[1].split("(")[0])
        assert shown_u == pytest.approx(ub["black_sky"][k]["correlated"], rel=0.06)
        shown_independent = float(text.split("(independent")[1].rstrip(")"))
        assert shown_independent == pytest.approx(ub["black_sky"][k]["independent"], rel=0.06)
        assert ub["black_sky"][k]["correlated"] > ub["black_sky"][k]["independent"]
    assert f"±\u00a0{report_html.number(ub['white_sky']['correlated'], 2)}" in report["text"]
    assert "repeatability between scans" in report["text"]
    _same(page, "summary.white_sky", bb["white_sky"], digits=3)
    band = a["wavelengths"].index(590.0)
    _same(page, "albedo.band.white_sky", a["white_sky"][band])
    _same(page, "albedo.band.black_sky.30", a["black_sky"][1][band])
    _same(page, "coverage.white_sky", 100 * a["coverage"]["white_sky_outside_fraction"], digits=3)
    with pytest.warns(UserWarning, match="mostly extrapolation"):
        t = roadbrdf.rtable(fit_file, illuminant="A")
    _same(page, "rtable.Q0", t["Q0"])
    _same(page, "rtable.S1", t["S1"])
    _same(page, "rtable.S2", t["S2"])
    assert _value(page, "rtable.class")[1] == t["class"]
    # F1 is measured to theta_r = 80 deg and the r-table's alpha = 1 deg is theta_r = 89 deg: every standard
    # cell is extrapolated, so the figures carry "(extrapolated)" instead of an uncertainty from the fit's
    # covariance, and there is no class probability.
    assert t["extrapolated"] and not t["uncertainty"]["class_probabilities"]
    for name in ("Q0", "S1"):
        assert "±" not in _value(page, f"rtable.{name}")[1] and "(extrapolated)" in _value(page, f"rtable.{name}")[1]
    assert "P(class)" not in report["text"] and "none: extrapolated" in report["text"]
    c = t["coverage"]
    _same(page, "coverage.rtable_standard", 100 * c["standard_cells_outside"] / c["standard_cells"], digits=3)
    # The coverage caveats are on the page (here: F1 is measured to theta_r = 80 deg, the r-table's alpha = 1 deg
    # is theta_r = 89 deg: every standard cell is extrapolated).
    assert t["warnings"][0] in report["text"]


def test_single_band_and_an_incidence_too_small_to_fit(tmp_path):
    """One band (no broadband albedo, no parameter-against-wavelength figure) and a model with more free
    parameters (6: lambert+torrance-sparrow with free weights) than theta_i = 0 has geometries (5): that
    incidence is left out of the per-incidence fits, named on the page, and the others equal the fit here."""
    d = roadbrdf.read_dataset(DATA)
    k = int(np.flatnonzero(d.wavelengths == 550.0)[0])
    one = roadbrdf.Dataset(d.angles, d.wavelengths[k:k + 1], d.brdf[:, k:k + 1], d.sigma[:, k:k + 1], d.metadata)
    data = tmp_path / "F1-550.csv"
    one.write(data)
    out = tmp_path / "r.html"
    result = _run(data, "--model", "lambert+torrance-sparrow", "--free-weights", "--quiet", "-o", out)
    assert result.returncode == 0, result.stderr
    text = out.read_text(encoding="utf-8")
    page = _Page(text)
    assert "figure not drawn" not in text
    assert "params-by-wavelength" not in page.figures and "albedo.broadband.white_sky" not in page.values
    assert "θ_i = 0° not fitted per incidence: 5 values for up to 6 free parameters" in text
    fits = roadbrdf.fit(data, ["lambert+torrance-sparrow"], multistart=8, group_by="theta_i", where="theta_i!=0")
    assert sorted(f.group["theta_i"] for f in fits.fits) == [20, 40, 60, 80]
    assert not any(key.startswith("group.lambert+torrance-sparrow.theta_i=0.") for key in page.values)
    for f in fits.fits:
        for j, name in enumerate(f.parameter_names):
            _same(page, f"group.{f.model}.theta_i={f.group['theta_i']:g}.{name}", f.parameters[j, 0])
    fit_file = tmp_path / "one.fit.json"
    roadbrdf.fit(data, ["lambert+torrance-sparrow"], multistart=8, output=fit_file)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        a = roadbrdf.albedo(fit_file, sun_zenith="0:60:30", atmosphere="spectrl2")
    assert a["broadband"] is None
    _same(page, "albedo.band.white_sky", a["white_sky"][0])


# ---- mixing --------------------------------------------------------------------------------------------
COMPONENT_FIT = {"models": ["oren-nayar+torrance-sparrow"], "multistart": 8,  # the demo's best model of each
                 "fixed": {"oren-nayar.weight": 1.0, "torrance-sparrow.weight": 1.0}}


def _formulation(folder, **fit_options):
    """F1's formulation with its components' fits (made here; default oren-nayar+torrance-sparrow, which has
    a covariance at every wavelength) where it looks for them."""
    options = dict(COMPONENT_FIT, **fit_options)
    (folder / "fits").mkdir()
    (folder / "formulations").mkdir()
    for name, path in [("bitumen", "single/bitumen.csv"), ("garonne", "single/garonne.csv"),
                       ("mastic-garonne-bitumen", "mastics/mastic-garonne-bitumen.csv")]:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")  # parameters on a bound: the covariance is still computed
            roadbrdf.fit(ROOT / "data" / "examples" / path, output=folder / "fits" / f"{name}.fit.json", **options)
    shutil.copy(ROOT / "data" / "examples" / "formulations" / "F1.json", folder / "formulations" / "F1.json")
    return folder / "formulations" / "F1.json"


def _rtable_quietly(model, illuminant="A"):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        return roadbrdf.rtable(model, illuminant=illuminant)


def test_mixing_section_and_output_file(tmp_path):
    formulation = _formulation(tmp_path)
    out = tmp_path / "F1-mix.html"
    result = _run(DATA, "--model", "oren-nayar", "--formulation", formulation, "--quiet", "-o", out, umask=0o027)
    assert result.returncode == 0, result.stderr
    assert "roadbrdf report:" not in result.stderr  # --quiet
    text = out.read_text(encoding="utf-8")
    page = _Page(text)
    assert "mixing" in page.figures
    # The same comparison made here: the report's reference is its fit of the sample (oren-nayar).
    reference = tmp_path / "F1.fit.json"
    roadbrdf.fit(DATA, ["oren-nayar"], multistart=8, output=reference)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # skipped methods, as the report lists them
        m = roadbrdf.mix(formulation, data=DATA, method="all", folds=5, reference=reference, uncertainty=True)
    assert _value(page, "mix.best")[1] == m.best.method
    assert len(m.methods) >= 3
    for method in m.methods:
        _same(page, f"mix.{method.method}.rmse", method.comparison["rmse"])
        _same(page, f"mix.{method.method}.albedo_difference", method.comparison["albedo_difference"], digits=3)
    # The uncertainty of the prediction: the r-table of the method with the lowest held-out RMSE among those
    # whose mixture carries the end-members' covariance, computed here from the MixResult; fitted and
    # shadowed carry none, as the page says.
    for name in ("fitted", "shadowed"):
        assert _rtable_quietly(m.method(name).spectral_model())["uncertainty"] is None
    carrying = []
    for method in sorted(m.methods, key=lambda x: x.comparison["rmse"]):
        t = _rtable_quietly(method.spectral_model())
        if t["uncertainty"] is not None and t["uncertainty"]["Q0"] is not None:
            carrying.append((method.method, t))
    assert carrying, "no method carries an uncertainty with these component fits"
    name, t = carrying[0]
    assert name in ("areal", "mastic", "hapke")
    assert _value(page, "mix.uncertainty.method")[1] == name
    u = t["uncertainty"]
    for figure in ("Q0", "S1", "S2", "Qd"):
        _same(page, f"mix.rtable.{figure}", t[figure])
        shown = _value(page, f"mix.rtable.{figure}")[1]
        assert float(shown.split("±")[1]) == pytest.approx(u[figure], rel=0.06), (figure, shown, u[figure])
    assert _value(page, "mix.rtable.class")[1] == t["class"]
    assert _value(page, "mix.rtable.class_probabilities")[1] == ", ".join(
        f"{c['class']} {c['probability']:.2f}" for c in u["class_probabilities"])
    assert "fitted</code> and <code>shadowed</code> carry none" in text
    assert f"roadbrdf albedo F.mix.json --fit {name}" in text  # where the mixture's albedo ± u comes from
    # Written atomically with the permissions of a new file (0666 & ~umask), no temporary file left.
    assert (out.stat().st_mode & 0o777) == 0o640
    assert sorted(p.name for p in tmp_path.iterdir()) == ["F1-mix.html", "F1.fit.json", "fits", "formulations"]


def test_mixing_section_says_when_no_prediction_carries_an_uncertainty(tmp_path):
    """With single-start oren-nayar component fits, no areal, mastic or hapke r-table has a defined
    uncertainty (the bitumen fit has no covariance at all, the mastic's none at 350 and 370 nm, which the
    photometric weighting uses): the section says so instead of showing numbers."""
    from types import SimpleNamespace
    from roadbrdf import report, report_sections
    formulation = _formulation(tmp_path, models=["oren-nayar"], multistart=1, fixed={})
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        m = roadbrdf.mix(formulation, data=DATA, method="all", uncertainty=True)
    for name in ("areal", "mastic", "hapke"):
        u = _rtable_quietly(m.method(name).spectral_model())["uncertainty"]
        assert u is None or u["Q0"] is None, name
    r = SimpleNamespace(mix=m, illuminant="A")
    report._mixture_uncertainty(r, _rtable_quietly)
    assert r.mix_u_method is None and set(r.mix_u_skipped) == {"areal", "mastic", "hapke"}
    text = report_sections._mixture_uncertainty(r)
    assert "No mixing prediction here carries a standard uncertainty" in text
    assert "mix.rtable" not in text


def test_formulation_without_its_component_fits_is_an_error(tmp_path):
    formulation = tmp_path / "F1.json"
    shutil.copy(ROOT / "data" / "examples" / "formulations" / "F1.json", formulation)
    result = _run(DATA, "--model", "oren-nayar", "--formulation", formulation, "-o", tmp_path / "r.html")
    assert result.returncode == 2
    assert result.stderr.splitlines()[-1].startswith("roadbrdf report: error: ")
    assert "fits" in result.stderr and "Traceback" not in result.stderr
    assert not (tmp_path / "r.html").exists()


# ---- errors and writing --------------------------------------------------------------------------------
@pytest.mark.parametrize("args, message", [
    (["MISSING.csv", "-o", "{tmp}/r.html"], "MISSING.csv': no such file"),
    ([str(DATA), "--model", "oren-nayr", "-o", "{tmp}/r.html"], "did you mean 'oren-nayar'?"),
    ([str(DATA), "--model", "lambert+torrance-sparow", "-o", "{tmp}/r.html"], "did you mean 'torrance-sparrow'?"),
    ([str(DATA), "-o", "{tmp}/no-such-folder/r.html"], "no-such-folder' does not exist"),
    ([str(DATA), "-o", str(DATA)], "refusing to overwrite an input"),
    ([str(DATA), "--formulation", "{tmp}/F.json", "-o", "{tmp}/r.html"], "F.json': no such file"),
    ([str(DATA), "--sun-zenith", "0:50:30", "-o", "{tmp}/r.html"], "--sun-zenith"),
    ([str(DATA), "--modle", "x", "-o", "{tmp}/r.html"], "did you mean '--model'?"),
    ([str(DATA)], "required: -o/--output"),
])
def test_errors(tmp_path, args, message):
    result = _run(*[a.replace("{tmp}", str(tmp_path)) for a in args])
    assert result.returncode == 2, result.stderr
    assert result.stderr.startswith("roadbrdf report: error: "), result.stderr
    assert message in result.stderr
    assert "Traceback" not in result.stderr
    assert list(tmp_path.iterdir()) == []


def test_atomic_write_keeps_mode_and_follows_links(tmp_path):
    from roadbrdf.core import write_text_atomic
    target = tmp_path / "kept.html"
    target.write_text("old")
    target.chmod(0o600)
    link = tmp_path / "link.html"
    link.symlink_to(target)
    write_text_atomic(str(link), "new")
    assert link.is_symlink() and target.read_text() == "new"
    assert (target.stat().st_mode & 0o777) == 0o600
    assert sorted(p.name for p in tmp_path.iterdir()) == ["kept.html", "link.html"]


# ---- in a real browser ---------------------------------------------------------------------------------
_CHECKER = """<script>
window.addEventListener('load', function () {
  var images = Array.prototype.slice.call(document.images);
  var decoded = images.filter(function (i) { return i.complete && i.naturalWidth > 0 && i.naturalHeight > 0; });
  document.documentElement.setAttribute('data-images-decoded', decoded.length + '/' + images.length);
});
</script></body>"""


def _chromium(tmp_path, *args):
    if not os.path.exists(CHROMIUM):
        pytest.skip(f"{CHROMIUM} is absent (Debian package chromium, test-only: packages.txt [test])")
    command = [CHROMIUM, "--headless=new", "--disable-gpu", "--no-sandbox", "--hide-scrollbars",
               f"--user-data-dir={tmp_path / 'chromium-profile'}", "--no-first-run", *args]
    result = subprocess.run(command, capture_output=True, text=True, timeout=180)
    assert result.returncode == 0, result.stderr[-2000:]
    return result.stdout


def _decoded(tmp_path, text, name):
    page = tmp_path / name
    page.write_text(text.replace("</body>", _CHECKER, 1), encoding="utf-8")
    dom = _chromium(tmp_path, "--virtual-time-budget=10000", "--dump-dom", page.as_uri())
    marker = 'data-images-decoded="'
    assert marker in dom, dom[:500]
    return dom.split(marker, 1)[1].split('"', 1)[0]


def test_browser_decodes_every_figure_prints_and_screenshots(tmp_path, report):
    # The checker itself: a broken image is seen as broken.
    good = report["page"].images[0]
    control = f'<!DOCTYPE html><html><body><img src="{good}"><img src="data:image/png;base64,AAAA"></body></html>'
    assert _decoded(tmp_path, control, "control.html") == "1/2"
    # The report: every figure decoded.
    assert _decoded(tmp_path, report["text"], "checked.html") == f"{len(FIGURES)}/{len(FIGURES)}"
    # It prints to PDF.
    pdf = tmp_path / "report.pdf"
    _chromium(tmp_path, f"--print-to-pdf={pdf}", "--no-pdf-header-footer", report["path"].as_uri())
    content = pdf.read_bytes()
    assert content.startswith(b"%PDF-") and b"%%EOF" in content[-1024:]
    assert len(content) > 200_000  # the figures are in it
    # A screenshot of its top, for the documentation (docs/figures/report.png).
    shot = pathlib.Path(os.environ.get("ROADBRDF_SCREENSHOT_DIR", tmp_path)) / "report.png"
    _chromium(tmp_path, f"--screenshot={shot}", "--window-size=1200,1600", report["path"].as_uri())
    header = shot.read_bytes()[:24]
    assert header[:8] == b"\x89PNG\r\n\x1a\n"
    assert struct.unpack(">II", header[16:24]) == (1200, 1600)


_WIDTHS = """<script>
window.addEventListener('load', function () {
  Array.prototype.slice.call(document.querySelectorAll('details')).forEach(function (d) { d.open = true; });
  var boxes = Array.prototype.slice.call(document.querySelectorAll('div.table'));
  var clipped = boxes.filter(function (b) { return b.scrollWidth > b.clientWidth + 1; });
  var page = document.documentElement.scrollWidth > window.innerWidth + 1;
  document.documentElement.setAttribute('data-clipped', clipped.length + '/' + boxes.length + (page ? ' page' : ''));
});
</script></body>"""


def test_no_table_is_clipped_in_a_1280_px_window(tmp_path, report):
    """Every table of the report (the ON+TS parameter tables and the r-table's 20 columns, the widest,
    included, with every <details> opened) fits the page in a 1280-px-wide window: none needs its scroll bar,
    and the page itself does not scroll sideways. The check is the browser's own layout (scrollWidth against
    clientWidth of each table box)."""
    page = tmp_path / "widths.html"
    page.write_text(report["text"].replace("</body>", _WIDTHS, 1), encoding="utf-8")
    dom = _chromium(tmp_path, "--virtual-time-budget=10000", "--window-size=1280,1600", "--dump-dom", page.as_uri())
    marker = 'data-clipped="'
    assert marker in dom, dom[:500]
    clipped, boxes = dom.split(marker, 1)[1].split('"', 1)[0].split("/")
    assert int(boxes.split()[0]) >= 5 and clipped == "0" and "page" not in boxes, (clipped, boxes)
    # The checker itself: a table wider than the page is seen as clipped.
    wide = "<table><tr>" + "".join(f"<td>{'x' * 30}</td>" for _ in range(60)) + "</tr></table>"
    control = tmp_path / "control-widths.html"
    control.write_text(f'<!DOCTYPE html><html><body><div class="table" style="overflow-x:auto">{wide}</div>'
                       '</body></html>'.replace("</body>", _WIDTHS, 1), encoding="utf-8")
    dom = _chromium(tmp_path, "--virtual-time-budget=10000", "--window-size=1280,1600", "--dump-dom",
                    control.as_uri())
    assert dom.split(marker, 1)[1].split('"', 1)[0] == "1/1"


def test_a_message_repeated_per_incidence_is_listed_once_with_its_count():
    from roadbrdf import report_sections
    repeated = [f"the per-incidence fits: oren-nayar, theta_i={t}: parameters on a bound at {n} of 108 wavelengths"
                for t, n in [(0, 3), (20, 5), (40, 7)] * 20]  # 60 messages of one kind
    items = repeated[:59] + ["lambert: did not converge at 590 nm"]
    grouped = report_sections.grouped_messages(items)
    assert grouped == [(repeated[0], 59), ("lambert: did not converge at 590 nm", 1)]
    html = report_sections._warnings_details(items)
    assert html.count("<li>") == 2 and "and 58 more like it" in html and "60 messages of the fit (2 kinds)" in html


def test_summary_counts_the_plausibility_warnings(tmp_path):
    """The summary card and the quality table count the check's plausibility warnings: a reflectance in
    percent written where a BRDF in sr^-1 belongs (every value x 100, so pi x the median BRDF, the
    Lambertian-equivalent albedo, is far above 1, which no surface reaches) is warned about; the file as
    measured is not."""
    from types import SimpleNamespace
    from roadbrdf import report_sections
    lines = DATA.read_text(encoding="utf-8").splitlines()
    rows = [i for i, line in enumerate(lines) if line and not line.startswith("#")][1:]  # after the header
    for i in rows:
        fields = lines[i].split(",")
        lines[i] = ",".join(fields[:4] + [repr(100.0 * float(v)) for v in fields[4:]])
    percent = tmp_path / "F1-percent.csv"
    percent.write_text("\n".join(lines) + "\n", encoding="utf-8")
    for path, warned in ((DATA, False), (percent, True)):
        c = roadbrdf.check(path)
        r = SimpleNamespace(sample="F1", best=SimpleNamespace(model="oren-nayar"), albedo=None, rtable=None, check=c,
                            all_caveats=[])
        text = report_sections.summary(r) + report_sections.quality(r).html
        page = _Page(text)
        count = len(c["plausibility"]["warnings"])
        assert (count > 0) == warned, c["plausibility"]["warnings"]
        assert _value(page, "summary.plausibility_warnings")[0] == count
        assert _value(page, "check.plausibility.warnings")[0] == count
        for w in c["plausibility"]["warnings"]:
            assert report_html.esc(w) in text
