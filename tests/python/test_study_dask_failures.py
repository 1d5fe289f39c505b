"""A Dask scheduler without workers, or one that goes away in the middle of a study: a `roadbrdf: error:` line
with status 2 (no traceback), the store keeping every result that arrived, and a local re-run finishing the
study."""

import os
import signal
import socket
import subprocess
import sys
import time

import pytest

import roadbrdf
from study_support import physical_study, store_keys

distributed = pytest.importorskip(
    "distributed", reason="the Python package 'distributed' is not installed (Debian: python3-distributed); "
                          "the Dask executor of roadbrdf study is not tested")


def _free_port():
    with socket.socket(socket.AF_INET, socket.SOCK_STREAM) as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def _spawn(*args, log):
    return subprocess.Popen([sys.executable, "-m", *args], stdout=log, stderr=subprocess.STDOUT,
                            start_new_session=True)


def _env():
    path = os.path.dirname(os.path.dirname(roadbrdf.__file__))
    return dict(os.environ, PYTHONPATH=os.pathsep.join([path, os.environ.get("PYTHONPATH", "")]))


def _scheduler(tmp_path, workers):
    port = _free_port()
    address = f"tcp://127.0.0.1:{port}"
    log = open(tmp_path / "cluster.log", "w")
    processes = [_spawn("distributed.cli.dask_scheduler", "--host", "127.0.0.1", "--port", str(port),
                        "--no-dashboard", log=log)]
    for _ in range(workers):
        processes.append(_spawn("distributed.cli.dask_worker", address, "--host", "127.0.0.1", "--nthreads", "1",
                                "--no-nanny", "--no-dashboard", "--worker-port", str(_free_port()), log=log))
    deadline = time.monotonic() + 60
    while True:
        try:
            client = distributed.Client(address, timeout=5)
            break
        except OSError:
            assert time.monotonic() < deadline, "the scheduler did not start"
            time.sleep(0.2)
    if workers:
        client.wait_for_workers(workers, timeout=60)
    client.close()
    return address, processes, log


def _stop(processes, log):
    for p in processes:
        if p.poll() is None:
            os.killpg(p.pid, signal.SIGKILL)
        p.wait()
    log.close()


def test_a_scheduler_without_workers_is_an_error(tmp_path):
    study = physical_study(tmp_path, shares=(0.0,), mastic=(0.3,), rtable=False, samples=4)
    address, processes, log = _scheduler(tmp_path, workers=0)
    try:
        result = subprocess.run([sys.executable, "-m", "roadbrdf.studies", str(study), "-o", str(tmp_path / "r.csv"),
                                 "--scheduler", address, "--worker-wait", "3"], capture_output=True, text=True, env=_env(),
                                timeout=300)
    finally:
        _stop(processes, log)
    assert result.returncode == 2, result.stderr
    assert "roadbrdf: error: --scheduler" in result.stderr and "no workers" in result.stderr
    assert "within 3 s" in result.stderr
    assert "Traceback" not in result.stderr


def test_a_scheduler_that_dies_mid_study_is_an_error_and_the_study_resumes(tmp_path):
    study = physical_study(tmp_path, shares=(0.0, 0.25, 0.5, 0.75, 1.0), rtable=False, samples=8)
    out, store = tmp_path / "r.csv", tmp_path / "r.csv.store.jsonl"
    address, processes, log = _scheduler(tmp_path, workers=1)
    try:
        p = subprocess.Popen([sys.executable, "-m", "roadbrdf.studies", str(study), "-o", str(out), "--scheduler",
                              address], stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, env=_env())
        deadline = time.monotonic() + 300
        while not (store.exists() and len(store.read_text().splitlines()) >= 2):
            assert p.poll() is None and time.monotonic() < deadline, p.communicate()
            time.sleep(0.05)
        os.killpg(processes[0].pid, signal.SIGKILL)  # the scheduler
        _, err = p.communicate(timeout=300)
    finally:
        _stop(processes, log)
    assert p.returncode == 2, err
    assert "roadbrdf: error: --scheduler" in err and "Traceback" not in err
    before = store_keys(store)
    assert 1 <= len(before) < 10
    result = subprocess.run([sys.executable, "-m", "roadbrdf.studies", str(study), "-o", str(out), "--workers", "2"],
                            capture_output=True, text=True, env=_env(), timeout=600)
    assert result.returncode == 0, result.stderr
    assert f"{len(before)} already in the store" in result.stderr
    assert len(set(store_keys(store))) == 10
