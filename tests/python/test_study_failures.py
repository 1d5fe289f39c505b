"""The failure policy and the build fingerprint of study tasks: a bug in a candidate is recorded and the study goes
on (--retry-failed runs it again); a task's key includes the build fingerprint, so a store filled by another build
is not reused, and a worker of another build refuses the task; the progress line."""

import csv
import json

import pytest

import roadbrdf
from roadbrdf.core import build_fingerprint
from roadbrdf.studies import campaign, evaluate, read_study, run, worker
from study_support import buggy_run_task, two_rock_study

OTHER = "0" * 64  # the fingerprint of another build


def _rows(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def test_a_bug_in_a_candidate_is_recorded_and_retried(tmp_path, capfd, monkeypatch):
    study = two_rock_study(tmp_path)
    out = tmp_path / "results.csv"
    monkeypatch.setattr(run, "run_task", buggy_run_task)
    roadbrdf.study(study, output=out, workers=2)
    err = capfd.readouterr().err
    assert "6/6 done (0 from the store), 0 running, 2 failed" in err
    # The first internal error's traceback on standard error, once.
    assert err.count("failed with an internal error (a bug in roadbrdf") == 1
    assert "Traceback (most recent call last)" in err and "ZeroDivisionError" in err
    rows = _rows(out)
    failed = [r for r in rows if r["status"] == "failed"]
    assert len(rows) == 6 and [r["grey [%]"] for r in failed] == ["50.0", "50.0"]
    assert all(r["error"] == "internal error: ZeroDivisionError: division by zero" for r in failed)
    records = [json.loads(line) for line in (tmp_path / "results.csv.store.jsonl").read_text().splitlines()[1:]]
    assert sum("ZeroDivisionError" in r.get("traceback", "") for r in records) == 2
    assert {r["build"] for r in records} == {build_fingerprint()}
    # Without --retry-failed a re-run keeps the failures; with it, the failed candidates (only) run again.
    monkeypatch.undo()
    roadbrdf.study(study, output=out)
    assert "6 already in the store, 0 to compute" in capfd.readouterr().err
    roadbrdf.study(study, output=out, retry_failed=True)
    assert "4 already in the store, 2 to compute" in capfd.readouterr().err
    assert all(r["status"] == "ok" for r in _rows(out))


def test_run_task_records_an_unexpected_exception(tmp_path, monkeypatch):
    s = read_study(two_rock_study(tmp_path))
    task = run.make_tasks(s, roadbrdf.__version__)[0][-1]

    def broken(task, path):
        raise KeyError("white_sky")
    monkeypatch.setattr(evaluate, "_fast", broken)
    result = evaluate.run_task(task, s.fits)
    assert result["rows"] == [] and result["error"] == "internal error: KeyError: 'white_sky'"
    assert "in broken" in result["traceback"] and result["build"] == build_fingerprint()


def _campaign(tmp_path):
    data = tmp_path / "sample.csv"
    data.write_text("theta_i,phi_i,theta_r,phi_r,550\n30,0,30,180,0.1\n")
    return campaign.read_campaign({"format": "roadbrdf-campaign", "version": 1, "fit": {"models": "lambert"},
                                   "samples": [str(data)]})


def test_campaign_records_an_unexpected_exception(tmp_path, monkeypatch):
    task = campaign.make_tasks(_campaign(tmp_path), roadbrdf.__version__)[0][-1]

    def broken(*args, **kwargs):
        raise RuntimeError("solver exploded")
    monkeypatch.setattr(roadbrdf.fitting, "fit", broken)
    result = campaign.fit_sample(task, None)
    assert result["error"] == "internal error: RuntimeError: solver exploded" and "seconds" in result


def test_the_key_includes_the_build(tmp_path):
    s = read_study(two_rock_study(tmp_path))
    mine = run.make_tasks(s, roadbrdf.__version__)
    other = run.make_tasks(s, roadbrdf.__version__, build=OTHER)
    assert all(t[-1]["build"] == build_fingerprint() for t in mine)
    assert {t[3] for t in mine}.isdisjoint(t[3] for t in other)
    # The seed does not depend on the build: another build draws the same virtual samples.
    assert [t[-1]["seed"] for t in mine] == [t[-1]["seed"] for t in other]
    c = _campaign(tmp_path)
    assert campaign.make_tasks(c, "0.1.0")[0][2] != campaign.make_tasks(c, "0.1.0", build=OTHER)[0][2]


def test_a_store_of_another_build_is_not_reused(tmp_path, capfd):
    study = two_rock_study(tmp_path)
    s = read_study(study)
    store = tmp_path / "results.csv.store.jsonl"
    # A store filled by another build: the same candidates, other (made-up) numbers.
    lines = [json.dumps({"format": "roadbrdf-study-store", "version": 1})]
    for *_, key, task in run.make_tasks(s, roadbrdf.__version__, build=OTHER):
        lines.append(json.dumps({"key": key, "error": None, "rows": [{"method": "areal", "white_sky": -1.0}],
                                 "cpu_seconds": 0, "build": OTHER}))
    store.write_text("\n".join(lines) + "\n")
    rows = roadbrdf.study(study, output=tmp_path / "results.csv")
    err = capfd.readouterr().err
    assert "0 already in the store, 6 to compute (6 results of other roadbrdf builds in the store are not used)" in err
    assert all(r["status"] == "ok" and r["white_sky [1]"] > 0 for r in rows)


def test_a_worker_of_another_build_refuses_the_task(tmp_path, monkeypatch):
    s = read_study(two_rock_study(tmp_path))
    task = run.make_tasks(s, roadbrdf.__version__, build=OTHER)[0][-1]
    with pytest.raises(worker.BuildMismatch, match=r"its roadbrdf build \(fingerprint [0-9a-f]{16}, .*\) differs "
                                                   r"from the build that submitted the task \(fingerprint 0{16}\)"):
        evaluate.run_task(task, s.fits)
    with pytest.raises(worker.BuildMismatch):
        campaign.fit_sample(campaign.make_tasks(_campaign(tmp_path), roadbrdf.__version__, build=OTHER)[0][-1], None)
    # Through the local processes: the study stops with the error (an input error: the command line's exit 2).
    monkeypatch.setattr(run, "build_fingerprint", lambda: OTHER)
    with pytest.raises(roadbrdf.InputError, match="differs from the build that submitted the task"):
        roadbrdf.study(s.path, output=tmp_path / "r.csv", workers=1, progress=False)
    assert not (tmp_path / "r.csv").exists()


def test_progress_line(monkeypatch, capsys):
    clock = iter([100.0, 130.0, 130.5, 160.0])
    monkeypatch.setattr(run.time, "monotonic", lambda: next(clock))
    bar = run.Progress(total=12, cached=2, enabled=True)  # started at t = 100 s
    bar.done, bar.failed = 3, 1
    bar.update(running=2)  # 3 tasks in 30 s, 7 left: about 70 s
    assert capsys.readouterr().err == ("study: 5/12 done (2 from the store), 2 running, 1 failed, about 0:01:10 "
                                       "left\n")
    bar.update(running=2)  # half a second later: nothing (at most one line a second)
    assert capsys.readouterr().err == ""
    bar.done = 4
    bar.update(running=1)  # 4 tasks in 60 s, 6 left: about 90 s
    assert "6/12 done (2 from the store), 1 running, 1 failed, about 0:01:30 left" in capsys.readouterr().err
