"""Scratch folders left by a process killed with SIGKILL are removed by the next one (roadbrdf/scratch.py)."""
import os
import signal
import subprocess
import sys

from roadbrdf import scratch


def _dead_pid():
    child = subprocess.Popen([sys.executable, "-c", "import time; time.sleep(60)"])
    child.send_signal(signal.SIGKILL)
    child.wait()
    return child.pid


def _folder(tmp_path, name, owner):
    path = tmp_path / name
    path.mkdir()
    (path / "work.tmp").write_text("partial")
    if owner is not None:
        (path / ".roadbrdf-owner").write_text(f"{owner}\n")
    return path


def test_a_dead_owners_folder_is_removed_and_the_others_are_kept(tmp_path):
    dead = _folder(tmp_path, "roadbrdf-study-dead", _dead_pid())
    live = _folder(tmp_path, "roadbrdf-study-live", os.getpid())
    unowned = _folder(tmp_path, "roadbrdf-study-unowned", None)
    garbled = _folder(tmp_path, "roadbrdf-study-garbled", "not a pid")
    other = _folder(tmp_path, "someone-else", _dead_pid())
    removed = scratch.remove_stale("roadbrdf-study-", str(tmp_path))
    assert removed == [str(dead)]
    assert not dead.exists()
    for kept in (live, unowned, garbled, other):
        assert kept.exists()


def test_a_new_scratch_folder_names_its_owner(monkeypatch, tmp_path):
    monkeypatch.setattr("tempfile.tempdir", str(tmp_path))
    stale = _folder(tmp_path, "roadbrdf-study-old", _dead_pid())
    path = scratch.make_scratch("roadbrdf-study-")
    assert not stale.exists()
    assert os.path.dirname(path) == str(tmp_path)
    with open(os.path.join(path, ".roadbrdf-owner"), encoding="ascii") as f:
        assert int(f.read()) == os.getpid()


def test_a_study_killed_with_sigkill_leaves_a_folder_the_next_study_removes(tmp_path):
    # The kill -9 case itself: a process makes its scratch folder and is killed before it can clean up.
    env = dict(os.environ, TMPDIR=str(tmp_path))
    child = subprocess.Popen([sys.executable, "-c",
                              "import sys, time; from roadbrdf.scratch import make_scratch; "
                              "print(make_scratch('roadbrdf-study-'), flush=True); time.sleep(60)"],
                             stdout=subprocess.PIPE, text=True, env=env)
    left = child.stdout.readline().strip()
    child.send_signal(signal.SIGKILL)
    child.wait()
    assert os.path.isdir(left)
    assert scratch.remove_stale("roadbrdf-study-", str(tmp_path)) == [left]
