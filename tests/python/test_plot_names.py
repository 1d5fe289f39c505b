"""Names are text in figures and pages: a sample name with `$` (matplotlib's mathtext marker) or a macro is shown
as written, a very long one is shortened; the report escapes names once; a report of data outside the visible
range shows every other section and says why it has no r-table."""

import os
import subprocess
import sys

import numpy as np
import pytest

import roadbrdf
import roadbrdf.plot as rplot
from roadbrdf import report_html
from roadbrdf.plot_common import MAX_NAME, plain

MACRO_NAME = r"A $\undefinedmacro$ B"


def _dataset(path, name, wavelengths=(500, 600)):
    lines = [f"# sample: {name}", "theta_i,phi_i,theta_r,phi_r," + ",".join(str(w) for w in wavelengths)]
    for ti in (0, 20, 40, 60):
        for tr in (10, 20, 40, 60):
            for pr in (0, 180):
                lines.append(f"{ti},0,{tr},{pr}," + ",".join(f"{0.1 + 0.0005 * tr + 0.0001 * w / 10:.5f}"
                                                          for w in wavelengths))
    path.write_text("\n".join(lines) + "\n")
    return path


def _texts(fig):
    import matplotlib.text
    return [t.get_text() for t in fig.findobj(matplotlib.text.Text)]


def test_plain_escapes_dollars_and_shortens():
    assert plain("a $x$ b") == r"a \$x\$ b"
    long = plain("n" * 100000)
    assert len(long) == MAX_NAME and long.endswith("…")


@pytest.mark.parametrize("name", [MACRO_NAME, "$$", "cost $5", "x" * 100000])
def test_figures_draw_names_as_text(tmp_path, name):
    data = _dataset(tmp_path / "s.csv", name)
    for kind, draw in [("spectral", lambda out: rplot.spectral([data], geometry=(20, 0, 20, 180), output=out)),
                       ("plane", lambda out: rplot.plane(["lambert"], [data], params={"albedo": 0.3}, theta_i=20,
                                                         output=out)),
                       ("hemisphere", lambda out: rplot.hemisphere(data=data, theta_i=20, output=out))]:
        out = tmp_path / f"{kind}.png"
        fig = draw(out)  # drawing the PNG would fail on a mathtext error
        assert out.stat().st_size > 1000
        shown = " ".join(_texts(fig))
        expected = plain(name)
        assert expected in shown, (kind, shown[:300])
        assert all(len(t) < 2000 for t in _texts(fig))


def test_plot_command_with_a_macro_in_the_name(cli, tmp_path):
    data = _dataset(tmp_path / "s.csv", MACRO_NAME)
    result = cli("plot", "spectral", data, "--geometry", "20,0,20,180", "-o", tmp_path / "s.png", check=False)
    assert result.returncode == 0, result.stderr
    assert (tmp_path / "s.png").stat().st_size > 1000


def test_html_is_escaped_once():
    html = report_html.table(["component"], [[report_html.esc("Sand & filler <0/2>")], ["Grey & co"]])
    assert "Sand &amp; filler &lt;0/2&gt;" in html and "Grey &amp; co" in html
    assert "&amp;amp;" not in html
    assert report_html.esc(report_html.esc("a & b")) == "a &amp; b"


def _report(data, out, *extra):
    path = os.path.dirname(os.path.dirname(roadbrdf.__file__))
    env = dict(os.environ, PYTHONPATH=os.pathsep.join([path, os.environ.get("PYTHONPATH", "")]), MPLBACKEND="Agg")
    return subprocess.run([sys.executable, "-m", "roadbrdf.report", str(data), "-o", str(out), "--model", "lambert",
                           "--multistart", "1", "--quiet", *extra], capture_output=True, text=True, env=env,
                          timeout=900)


@pytest.mark.parametrize("name", [MACRO_NAME, "y" * 100000])
def test_report_keeps_every_figure_of_a_sample_with_an_odd_name(tmp_path, name):
    data = _dataset(tmp_path / "s.csv", name, wavelengths=(450, 550, 650))
    out = tmp_path / "r.html"
    result = _report(data, out)
    assert result.returncode == 0, result.stderr
    text = out.read_text(encoding="utf-8")
    assert "not drawn" not in text and "figure not drawn" not in result.stderr, result.stderr
    assert text.count("<figure") >= 8


@pytest.mark.parametrize("wavelengths", [(800, 850, 900), (590, 610)])
def test_report_outside_the_visible_range_says_why_there_is_no_rtable(tmp_path, wavelengths):
    data = _dataset(tmp_path / "nir.csv", "near infrared", wavelengths=wavelengths)
    out = tmp_path / "r.html"
    result = _report(data, out)
    assert result.returncode == 0, result.stderr
    text = out.read_text(encoding="utf-8")
    assert 'id="rtable"' in text and "No r-table:" in text
    assert 'id="ranking"' in text and 'id="albedo"' in text
    assert "Traceback" not in result.stderr


@pytest.mark.parametrize("args", [
    ["albedo", "{deep}"], ["plane", "--model", "{deep}"], ["hemisphere", "{deep}"], ["study", "{study}"]])
def test_plot_errors_are_roadbrdf_error_lines(cli, tmp_path, args):
    deep = tmp_path / "deep.fit.json"
    deep.write_text("[" * 100000 + "]" * 100000)
    study = tmp_path / "study.csv"
    study.write_text("candidate,status\n1,ok\n")
    args = [a.format(deep=deep, study=study) for a in args]
    result = cli("plot", *args, "-o", tmp_path / "x.png", check=False)
    assert result.returncode == 2 and result.stderr.startswith("roadbrdf: error: "), result.stderr
    assert "Traceback" not in result.stderr
