"""Ctrl-C stops long library calls from Python (a long fit, a long render): KeyboardInterrupt within seconds,
not when the work ends; `roadbrdf report` stopped by Ctrl-C or SIGTERM removes its temporary folder. The bounds
are generous (a loaded machine): these are functional tests, not timings."""

import os
import signal
import subprocess
import sys
import time

import pytest

import roadbrdf

SCRIPT_HEAD = """
import sys, time
import roadbrdf
print("started", flush=True)
try:
    {call}
except KeyboardInterrupt:
    print("KeyboardInterrupt", flush=True)
    sys.exit(0)
print("finished", flush=True)
sys.exit(1)
"""


def _env(**more):
    path = os.path.dirname(os.path.dirname(roadbrdf.__file__))
    return dict(os.environ, PYTHONPATH=os.pathsep.join([path, os.environ.get("PYTHONPATH", "")]), **more)


def _interrupt(call, tmp_path, after=1.0):
    p = subprocess.Popen([sys.executable, "-c", SCRIPT_HEAD.format(call=call)], stdout=subprocess.PIPE,
                         stderr=subprocess.PIPE, text=True, env=_env(), cwd=tmp_path)
    assert p.stdout.readline().strip() == "started", p.stderr.read()
    time.sleep(after)  # inside the library call by now
    assert p.poll() is None, p.communicate()
    p.send_signal(signal.SIGINT)
    try:
        out, err = p.communicate(timeout=60)
    except subprocess.TimeoutExpired:
        p.kill()
        p.communicate()
        raise AssertionError("Ctrl-C did not stop the call within 60 s")
    assert "KeyboardInterrupt" in out, (out, err)
    assert p.returncode == 0


def _dataset(tmp_path):
    path = tmp_path / "tile.csv"
    lines = ["theta_i,phi_i,theta_r,phi_r,500,600"]
    for ti in (0, 20, 40, 60):
        for tr in (10, 25, 40, 55, 70, 85):
            for pr in (0, 90, 180):
                lines.append(f"{ti},0,{tr},{pr},{0.1 + 0.001 * tr},{0.12 + 0.001 * ti}")
    path.write_text("\n".join(lines) + "\n")
    return path


def test_ctrl_c_stops_a_long_multistart_fit(tmp_path):
    data = _dataset(tmp_path)
    _interrupt(f"roadbrdf.fit({str(data)!r}, 'oren-nayar+torrance-sparrow', multistart=5000, threads=1)", tmp_path)


def test_ctrl_c_stops_a_long_render(tmp_path):
    call = ("roadbrdf.render(roadbrdf.flat_surface('lambert', {'albedo': 0.3}, cells=8, cell_mm=0.5), 30, 0, "
            "range(0, 80, 5), 180, samples=2**25, threads=1)")
    _interrupt(call, tmp_path)


def test_ctrl_c_stops_a_long_joint_fit(tmp_path):
    data = _dataset(tmp_path)
    _interrupt(f"roadbrdf.fit({str(data)!r}, 'oren-nayar+torrance-sparrow', shared='auto', multistart=5000, "
               "threads=1)", tmp_path)


def test_a_finished_call_leaves_no_pending_interrupt():
    # After an uninterrupted call Python's own Ctrl-C handling is back and the library's request is clear.
    before = signal.getsignal(signal.SIGINT)
    roadbrdf.render(roadbrdf.flat_surface("lambert", {"albedo": 0.3}, cells=8, cell_mm=0.5), 30, 0, 30, 180,
                    samples=64, threads=1)
    assert signal.getsignal(signal.SIGINT) is before


@pytest.mark.parametrize("how", [signal.SIGINT, signal.SIGTERM])
def test_an_interrupted_report_removes_its_temporary_folder(tmp_path, root, how):
    tmp = tmp_path / "tmp"
    tmp.mkdir()
    data = root / "data" / "examples" / "mixed" / "F1.csv"
    p = subprocess.Popen([sys.executable, "-m", "roadbrdf.report", str(data), "-o", str(tmp_path / "r.html"),
                          "--multistart", "2000"], stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                         env=_env(TMPDIR=str(tmp), MPLBACKEND="Agg"))
    deadline = time.monotonic() + 120
    while not any(name.startswith("roadbrdf-report-") for name in os.listdir(tmp)):
        assert p.poll() is None and time.monotonic() < deadline, p.communicate()
        time.sleep(0.05)
    time.sleep(1.0)  # in the fits
    p.send_signal(how)
    _, err = p.communicate(timeout=60)
    assert p.returncode == (130 if how == signal.SIGINT else 143), err
    assert "interrupted" in err and "Traceback" not in err
    assert os.listdir(tmp) == []
    assert not (tmp_path / "r.html").exists()


def _processes_writing(path):
    """Processes whose command line names ``path`` (the report and its figure workers, which are forks)."""
    found = []
    for pid in filter(str.isdigit, os.listdir("/proc")):
        try:
            with open(f"/proc/{pid}/cmdline", "rb") as fh:
                if str(path).encode() in fh.read():
                    found.append(int(pid))
        except OSError:
            continue
    return found


@pytest.mark.parametrize("how", [signal.SIGINT, signal.SIGTERM])
def test_a_report_interrupted_while_drawing_stops_its_figure_workers(tmp_path, root, how):
    tmp = tmp_path / "tmp"
    tmp.mkdir()
    data = root / "data" / "examples" / "mixed" / "F1.csv"
    out, log = tmp_path / "r.html", tmp_path / "stderr.txt"
    with open(log, "w") as err:
        p = subprocess.Popen([sys.executable, "-m", "roadbrdf.report", str(data), "-o", str(out)],
                             stdout=subprocess.DEVNULL, stderr=err, text=True,
                             env=_env(TMPDIR=str(tmp), MPLBACKEND="Agg", ROADBRDF_REPORT_PROCESSES="2"))
        deadline = time.monotonic() + 300
        while "albedo of" not in log.read_text():  # the figure workers are started before the albedo
            assert p.poll() is None and time.monotonic() < deadline, log.read_text()
            time.sleep(0.05)
        time.sleep(0.1)  # the albedo and the r-table take a second or two now: the figures are still drawing
        if p.poll() is not None:
            pytest.skip("the report ended before it could be interrupted while drawing")
        p.send_signal(how)
        p.wait(timeout=60)
    if p.returncode == 0 and "wrote" in log.read_text():
        pytest.skip("the report ended before the signal reached it")
    assert p.returncode == (130 if how == signal.SIGINT else 143), log.read_text()
    text = log.read_text()
    assert "interrupted" in text and "Traceback" not in text
    deadline = time.monotonic() + 30
    while _processes_writing(out) and time.monotonic() < deadline:
        time.sleep(0.1)
    assert _processes_writing(out) == []
    assert os.listdir(tmp) == []
    assert not out.exists()
