"""A study ended by kill -9 or SIGTERM resumes at once (its workers end with it, the store's lock is the study's
alone, a stale lock is named); bad stores, outputs and study files are `roadbrdf: error:` lines with status 2 and
the store intact; a design of millions of candidates streams and is checked against the memory it needs."""

import fcntl
import json
import os
import signal
import subprocess
import sys
import time

import pytest

import roadbrdf
from study_support import physical_study, store_keys, two_rock_study


def _env():
    path = os.path.dirname(os.path.dirname(roadbrdf.__file__))
    return dict(os.environ, PYTHONPATH=os.pathsep.join([path, os.environ.get("PYTHONPATH", "")]))


def _start(study, out, *extra):
    return subprocess.Popen([sys.executable, "-m", "roadbrdf.studies", str(study), "-o", str(out), *extra],
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, env=_env(),
                            start_new_session=True)


def _run(*args):
    return subprocess.run([sys.executable, "-m", "roadbrdf.studies", *map(str, args)], capture_output=True, text=True,
                          env=_env(), timeout=600)


def _holders(path):
    """Processes with an open descriptor of ``path`` (from /proc)."""
    st = os.stat(path)
    out = []
    for pid in filter(str.isdigit, os.listdir("/proc")):
        try:
            for fd in os.listdir(f"/proc/{pid}/fd"):
                other = os.stat(f"/proc/{pid}/fd/{fd}")
                if (other.st_dev, other.st_ino) == (st.st_dev, st.st_ino):
                    out.append(int(pid))
                    break
        except OSError:
            continue
    return out


def _children(pid):
    try:
        with open(f"/proc/{pid}/task/{pid}/children") as f:
            return [int(p) for p in f.read().split()]
    except OSError:
        return []


def _wait_until(condition, what, timeout=60):
    deadline = time.monotonic() + timeout
    while time.monotonic() < deadline:
        if condition():
            return
        time.sleep(0.05)
    raise AssertionError(f"not within {timeout} s: {what}")


def _alive(pid):
    try:
        with open(f"/proc/{pid}/stat") as f:
            return f.read().rsplit(")", 1)[1].split()[0] != "Z"
    except OSError:
        return False


@pytest.mark.parametrize("how", [signal.SIGKILL, signal.SIGTERM])
def test_a_killed_study_leaves_no_worker_and_resumes(tmp_path, how):
    study = physical_study(tmp_path, shares=(0.0, 0.25, 0.5, 0.75, 1.0), rtable=False, samples=8)
    out, store = tmp_path / "results.csv", tmp_path / "results.csv.store.jsonl"
    p = _start(study, out, "--workers", "2")
    _wait_until(lambda: store.exists() and len(store.read_text().splitlines()) >= 2 or p.poll() is not None,
                "a first result")
    assert p.poll() is None, p.stderr.read()
    workers = _children(p.pid)
    assert workers, "the study runs worker processes"
    # Only the study process: its workers must end with it (they are not in the signal's reach).
    os.kill(p.pid, how)
    p.wait(timeout=60)
    if how == signal.SIGTERM:
        assert p.returncode == 143 and "interrupted" in p.stderr.read()
    _wait_until(lambda: not any(_alive(w) for w in workers), "the workers end")
    assert _holders(store) == []
    before = store_keys(store)
    result = _run(study, "-o", out, "--workers", "2")
    assert result.returncode == 0, result.stderr
    after = store_keys(store)
    assert after[:len(before)] == before and len(set(after)) == len(after) == 10
    assert not any(name.startswith("roadbrdf-study-") for name in os.listdir(tmp_path))


def test_a_stale_lock_is_named_with_its_processes(tmp_path):
    study = two_rock_study(tmp_path)
    store = tmp_path / "held.jsonl"
    store.write_text(json.dumps({"format": "roadbrdf-study-store", "version": 1}) + "\n")
    # A process that locked the store and forked a child keeping the descriptor, then ended: the child (adopted
    # by init) holds the lock, as the workers of an older roadbrdf did.
    holder = subprocess.Popen([sys.executable, "-c", f"""
import fcntl, os, sys, time
fd = os.open({str(store)!r}, os.O_RDWR)
fcntl.flock(fd, fcntl.LOCK_EX)
if os.fork() == 0:
    os.setsid()
    time.sleep(120)
    os._exit(0)
"""])
    holder.wait()
    _wait_until(lambda: len(_holders(store)) == 1, "the orphan holds the store")
    orphan, = _holders(store)
    try:
        result = _run(study, "-o", tmp_path / "r.csv", "--store", store)
        assert result.returncode == 2
        assert f"stale lock: processes {orphan}" in result.stderr and f"kill {orphan}" in result.stderr
        assert result.stderr.startswith("roadbrdf: error: ")
    finally:
        os.kill(orphan, signal.SIGKILL)


def test_a_store_in_use_names_the_running_study(tmp_path):
    study = two_rock_study(tmp_path)
    store = tmp_path / "held.jsonl"
    store.write_text(json.dumps({"format": "roadbrdf-study-store", "version": 1}) + "\n")
    holder = subprocess.Popen([sys.executable, "-c", f"""
import fcntl, os, sys, time
fd = os.open({str(store)!r}, os.O_RDWR)
fcntl.flock(fd, fcntl.LOCK_EX)
print("locked", flush=True)
time.sleep(120)
"""], stdout=subprocess.PIPE, text=True)
    try:
        assert holder.stdout.readline().strip() == "locked"
        result = _run(study, "-o", tmp_path / "r.csv", "--store", store)
        assert result.returncode == 2
        assert f"in use by another running study (process {holder.pid})" in result.stderr
    finally:
        holder.kill()
        holder.wait()


def test_forked_children_do_not_keep_the_lock(tmp_path):
    from roadbrdf.studies.store import Store
    held = Store(tmp_path / "s.jsonl")
    try:
        pid = os.fork()
        if pid == 0:  # the child: its copy of the locked descriptor is closed at the fork
            try:
                fd = os.open(tmp_path / "s.jsonl", os.O_RDWR)
                fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
                os._exit(1)  # it could take the lock: the parent's lock would be shared with it
            except BlockingIOError:
                os._exit(0)
        _, status = os.waitpid(pid, 0)
        assert os.waitstatus_to_exitcode(status) == 0
        assert held._fd is not None  # the parent keeps its lock
    finally:
        held.close()


def _deep(depth):
    return "[" * depth + "]" * depth


@pytest.mark.parametrize("make, fragment", [
    (lambda d: (d / "s.json").write_text('{"format": "roadbrdf-study", "version": 1, "base": ' + _deep(100000) + "}"),
     "nested deeper than 64 levels"),
    (lambda d: (d / "s.json").write_bytes(b'{"format": "roadbrdf-study", "name": "\xff"}'), "not UTF-8"),
])
def test_bad_study_files_are_errors(tmp_path, make, fragment):
    make(tmp_path)
    result = _run(tmp_path / "s.json", "-o", tmp_path / "r.csv")
    assert result.returncode == 2 and result.stderr.startswith("roadbrdf: error: "), result.stderr
    assert fragment in result.stderr and "Traceback" not in result.stderr


_HEADER = json.dumps({"format": "roadbrdf-study-store", "version": 1})


@pytest.mark.parametrize("line, fragment", [
    ('{"key": "k"}', "error: expected null or a message"),
    ('{"key": "k", "error": null}', "rows: expected an array of objects"),
    ('{"key": "k", "error": null, "rows": [1]}', "rows: expected an array of objects"),
    ('{"key": 5, "error": null, "rows": []}', "key: expected"),
    ('{"key": "k", "error": 5, "rows": []}', "error: expected null or a message"),
    ('{"key": "k", "error": null, "rows": [], "units": 3}', "units: expected an object"),
    ("[1, 2]", "must be a JSON object"),
    ("[" * 5000 + "]" * 5000, "nested"),
])
def test_store_lines_missing_fields_are_located_errors(tmp_path, line, fragment):
    study = two_rock_study(tmp_path)
    store = tmp_path / "s.jsonl"
    text = _HEADER + "\n" + line + "\n"
    store.write_text(text)
    result = _run(study, "-o", tmp_path / "r.csv", "--store", store)
    assert result.returncode == 2 and result.stderr.startswith("roadbrdf: error: "), result.stderr
    assert f"{store}:2:" in result.stderr and fragment in result.stderr, result.stderr
    assert store.read_text() == text  # the store is left as it was
    assert not (tmp_path / "r.csv").exists()


@pytest.mark.parametrize("store", ["/tmp", "/dev/null", "/proc/self/status"])
def test_a_store_that_is_not_a_regular_file_is_an_error(tmp_path, store):
    study = two_rock_study(tmp_path)
    result = _run(study, "-o", tmp_path / "r.csv", "--store", store)
    assert result.returncode == 2 and result.stderr.startswith("roadbrdf: error: "), result.stderr
    assert "Traceback" not in result.stderr


def test_outputs_are_checked_before_any_work(tmp_path):
    study = two_rock_study(tmp_path)
    result = _run(study, "-o", tmp_path / "missing" / "r.csv")
    assert result.returncode == 2 and "the folder" in result.stderr and "does not exist" in result.stderr
    assert "candidates" not in result.stderr  # nothing ran
    readonly = tmp_path / "readonly"
    readonly.mkdir()
    readonly.chmod(0o555)
    try:
        if os.access(readonly, os.W_OK):
            pytest.skip("running as a user that can write to read-only folders (root)")
        result = _run(study, "-o", readonly / "r.csv")
        assert result.returncode == 2 and "not writable" in result.stderr
    finally:
        readonly.chmod(0o755)


def test_a_full_disk_is_an_error_and_the_store_keeps_the_results(tmp_path):
    study = two_rock_study(tmp_path)
    store = tmp_path / "s.jsonl"
    result = _run(study, "-o", "/dev/full", "--store", store, "--workers", "1")
    assert result.returncode == 2 and result.stderr.rstrip().splitlines()[-1].startswith("roadbrdf: error: ")
    assert "/dev/full" in result.stderr and "Traceback" not in result.stderr
    assert len(store_keys(store)) == 6  # every candidate kept for the next run
    assert os.path.exists("/dev/full") and not os.path.isfile("/dev/full")  # written directly, not replaced


def test_a_million_candidates_stream_and_ten_million_are_checked_against_memory(tmp_path):
    from roadbrdf.studies import read_study
    from roadbrdf.studies.run import Tasks, check_size
    variables = [{"name": "grey", "kind": "mass_percent", "component": "Grey 2/6", "range": [20, 80],
                  "balance": "Other 6/10"}]
    study = two_rock_study(tmp_path, design={"type": "random", "count": 10_000_000, "seed": 1}, variables=variables)
    s = read_study(study)
    tasks = Tasks(s, roadbrdf.__version__)
    assert len(tasks) == 10_000_000
    first = next(iter(tasks))  # made one at a time: the first without the others
    assert first[0] == 0 and first[3] == first[4]["key"]
    # Memory: the study needs at least 1 kB per candidate; 10^7 of them do not fit in 4 GB.
    with pytest.raises(roadbrdf.InputError, match="design.count .* need about .* GB of memory"):
        check_size(s, progress=False, available=4e9)
    check_size(s, progress=False, available=1e12)


def test_interrupting_a_study_ends_its_workers_at_once(tmp_path):
    study = physical_study(tmp_path, shares=(0.0, 0.25, 0.5, 0.75, 1.0), rtable=False, samples=8)
    out, store = tmp_path / "results.csv", tmp_path / "results.csv.store.jsonl"
    p = _start(study, out, "--workers", "2")
    _wait_until(lambda: store.exists() or p.poll() is not None, "the store")
    _wait_until(lambda: _children(p.pid) or p.poll() is not None, "the workers")
    workers = _children(p.pid)
    os.killpg(p.pid, signal.SIGINT)  # Ctrl-C: the whole foreground group
    _, err = p.communicate(timeout=60)
    assert p.returncode == 130, err
    assert "interrupted; the results store keeps every finished candidate" in err and "Traceback" not in err
    _wait_until(lambda: not any(_alive(w) for w in workers), "the workers end")
