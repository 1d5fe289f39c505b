"""A study killed mid-way resumes: nothing lost, nothing duplicated, nothing recomputed."""

import csv
import os
import signal
import subprocess
import time

from study_support import physical_study, store_keys


def _start(cli_exe, study, out, *extra):
    return subprocess.Popen([cli_exe, "study", str(study), "-o", str(out), *extra], stdout=subprocess.PIPE,
                            stderr=subprocess.PIPE, text=True, start_new_session=True)


def _wait_for_records(store, n, process, timeout=120):
    deadline = time.monotonic() + timeout
    while time.monotonic() < deadline:
        if store.exists() and len(store.read_text().splitlines()) >= 1 + n:
            return
        if process.poll() is not None:
            raise AssertionError(f"the study ended before it could be interrupted: {process.stderr.read()}")
        time.sleep(0.02)
    raise AssertionError("no results appeared in the store")


def test_killed_study_resumes_without_loss_or_duplicates(tmp_path, root):
    cli_exe = os.environ.get("ROADBRDF_CLI", str(root / "build" / "roadbrdf"))
    study = physical_study(tmp_path, shares=(0.0, 0.25, 0.5, 0.75, 1.0), rtable=False, samples=8)
    out = tmp_path / "results.csv"
    store = tmp_path / "results.csv.store.jsonl"
    p = _start(cli_exe, study, out, "--workers", "1")
    _wait_for_records(store, 2, p)
    os.killpg(p.pid, signal.SIGKILL)  # the program, its interpreter and the worker process, at once
    p.wait()
    assert not out.exists()  # the table is written only when the study is complete
    before = store_keys(store)
    assert 2 <= len(before) < 10
    # A study killed while writing a line leaves a torn last line: it is reported and its task runs again.
    with open(store, "a") as f:
        f.write('{"key":"0123')
    p = _start(cli_exe, study, out, "--workers", "2")
    _, err = p.communicate(timeout=300)
    assert p.returncode == 0, err
    assert "removed a torn last line" in err
    assert f"10 candidates, {len(before)} already in the store, {10 - len(before)} to compute" in err
    after = store_keys(store)
    assert after[:len(before)] == before  # nothing rewritten
    assert len(after) == len(set(after)) == 10  # nothing lost, nothing twice
    with open(out, newline="") as f:
        rows = list(csv.DictReader(f))
    assert sorted(r["key"] for r in rows) == sorted(after)
    assert all(r["status"] == "ok" for r in rows)
    # Finished: a re-run computes nothing and writes the same table.
    table = out.read_text()
    result = subprocess.run([cli_exe, "study", str(study), "-o", str(out)], capture_output=True, text=True)
    assert result.returncode == 0, result.stderr
    assert "10 already in the store, 0 to compute" in result.stderr
    assert out.read_text() == table
    assert store_keys(store) == after


def test_store_in_use_is_refused(tmp_path):
    import pytest

    import roadbrdf
    from roadbrdf.studies.store import Store
    study = physical_study(tmp_path, shares=(0.0,), mastic=(0.3,), rtable=False, samples=4)
    held = Store(tmp_path / "held.jsonl")
    try:
        with pytest.raises(roadbrdf.InputError, match="in use by another running study"):
            roadbrdf.study(study, output=tmp_path / "r.csv", store=tmp_path / "held.jsonl", progress=False)
    finally:
        held.close()
