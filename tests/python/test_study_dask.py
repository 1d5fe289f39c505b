"""A study on a Dask cluster (scheduler and two workers on 127.0.0.1, started here) equals the local run bit for
bit, survives the loss of a worker, and re-runs for free."""

import os
import signal
import socket
import subprocess
import sys
import time

import pytest

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


@pytest.fixture
def cluster(tmp_path):
    port = _free_port()
    address = f"tcp://127.0.0.1:{port}"
    log = open(tmp_path / "cluster.log", "w")
    processes = [_spawn("distributed.cli.dask_scheduler", "--host", "127.0.0.1", "--port", str(port),
                        "--no-dashboard", log=log)]
    try:
        for _ in range(2):
            processes.append(_spawn("distributed.cli.dask_worker", address, "--host", "127.0.0.1", "--nthreads", "1",
                                    "--no-nanny", "--no-dashboard", "--worker-port", str(_free_port()), log=log))
        client = None
        deadline = time.monotonic() + 60
        while client is None:
            try:
                client = distributed.Client(address, timeout=5)
            except OSError:
                if time.monotonic() > deadline:
                    raise
                time.sleep(0.2)
        client.wait_for_workers(2, timeout=60)
        client.close()
        yield address, processes
    finally:
        for p in processes:
            if p.poll() is None:
                os.killpg(p.pid, signal.SIGKILL)
            p.wait()
        log.close()


def test_dask_equals_local_and_survives_a_lost_worker(cluster, tmp_path, root):
    address, processes = cluster
    cli_exe = os.environ.get("ROADBRDF_CLI", str(root / "build" / "roadbrdf"))
    study = physical_study(tmp_path, shares=(0.0, 1.0), mastic=(0.2, 0.4), samples=8)
    local = tmp_path / "local.csv"
    result = subprocess.run([cli_exe, "study", str(study), "-o", str(local), "--workers", "2"], capture_output=True,
                            text=True)
    assert result.returncode == 0, result.stderr
    out = tmp_path / "dask.csv"
    store = tmp_path / "dask.csv.store.jsonl"
    env = dict(os.environ, ROADBRDF_SCHEDULER=address)  # the variable and --scheduler are the same
    p = subprocess.Popen([cli_exe, "study", str(study), "-o", str(out)], env=env, stdout=subprocess.PIPE,
                         stderr=subprocess.PIPE, text=True)
    deadline = time.monotonic() + 120
    while not (store.exists() and len(store.read_text().splitlines()) >= 2):
        assert p.poll() is None, p.stderr.read()
        assert time.monotonic() < deadline, "no result from the cluster"
        time.sleep(0.02)
    os.killpg(processes[1].pid, signal.SIGKILL)  # one worker dies mid-study
    _, err = p.communicate(timeout=300)
    assert p.returncode == 0, err
    assert f"on {address}" in err
    keys = store_keys(store)
    assert len(keys) == len(set(keys)) == 4  # nothing lost, nothing twice
    assert out.read_text() == local.read_text()  # bit for bit: same seeds, one thread per task
    result = subprocess.run([cli_exe, "study", str(study), "-o", str(out), "--scheduler", address],
                            capture_output=True, text=True)
    assert result.returncode == 0, result.stderr
    assert "4 already in the store, 0 to compute" in result.stderr
    assert store_keys(store) == keys and out.read_text() == local.read_text()


def test_a_worker_of_another_build_stops_the_study(cluster, tmp_path, monkeypatch):
    """Tasks submitted by another build (here: a fingerprint made up in the submitting process) are refused by
    the workers; the study stops with the error, nothing is stored under the other build's keys."""
    import roadbrdf
    from roadbrdf.studies import run
    address, _ = cluster
    study = physical_study(tmp_path, shares=(0.0,), mastic=(0.3,), rtable=False, samples=4)
    monkeypatch.setattr(run, "build_fingerprint", lambda: "0" * 64)
    with pytest.raises(roadbrdf.InputError, match=r"worker .*: its roadbrdf build \(fingerprint [0-9a-f]{16}, .*\) "
                                                  r"differs from the build that submitted the task"):
        roadbrdf.study(study, output=tmp_path / "r.csv", scheduler=address, progress=False)
    assert store_keys(tmp_path / "r.csv.store.jsonl") == []
