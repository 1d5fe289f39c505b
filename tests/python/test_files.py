"""Files from Python follow the command line's rules: an output is never an input,
failed writes raise InputError naming the file, links are written through, nothing is left behind."""
import errno
import os
import pathlib
import subprocess
import sys

import numpy as np
import pytest

import roadbrdf

LAMBERT_FIT = """{"format": "roadbrdf-fit", "version": 1, "best": "lambert",
  "fits": [{"model": "lambert", "options": {}, "wavelengths": [400, 500, 600, 700, 800],
            "parameters": {"albedo": [0.2, 0.25, 0.3, 0.3, 0.3]}}]}"""
FORMULATION = """{"format": "roadbrdf-formulation", "version": 1, "name": "T",
  "components": [{"name": "Grey", "kind": "binder", "mass_percent": 100, "density_g_cm3": 1.0,
                  "fit": "lambert.fit.json"}]}"""


def small_dataset():
    angles = np.array([[0.0, 0.0, 30.0, 180.0], [30.0, 0.0, 0.0, 0.0]])
    return roadbrdf.Dataset(angles, np.array([500.0, 600.0]), np.array([[0.1, 0.2], [0.11, 0.21]]))


def contents(folder: pathlib.Path):
    return {p.name: (p.read_bytes() if p.is_file() else None) for p in folder.iterdir()}


def test_mix_refuses_an_output_that_is_an_input(tmp_path):
    (tmp_path / "lambert.fit.json").write_text(LAMBERT_FIT)
    (tmp_path / "F.json").write_text(FORMULATION)
    before = contents(tmp_path)
    for output in ("F.json", "lambert.fit.json"):
        with pytest.raises(roadbrdf.InputError, match="is the same file as the input .*refusing to overwrite"):
            roadbrdf.mix(tmp_path / "F.json", output=str(tmp_path / output))
    assert contents(tmp_path) == before


def dev_full_refuses_writes():
    """Some containers give a /dev/full that accepts writes: probe it rather than assume."""
    try:
        with open("/dev/full", "wb", buffering=0) as f:
            f.write(b"x")
    except OSError as e:
        return e.errno == errno.ENOSPC
    return False


def test_write_to_a_full_device_names_it():
    if not dev_full_refuses_writes():
        pytest.skip("this machine's /dev/full accepts writes (or is missing); "
                    "test_write_past_the_file_size_limit covers full disks")
    with pytest.raises(roadbrdf.InputError, match="/dev/full: write failed: No space left on device"):
        small_dataset().write("/dev/full")


# A disk that fills up during the write, on any machine: a child interpreter with a 1 KiB file-size
# limit (Python ignores SIGXFSZ, so the write fails with EFBIG) writes a data set larger than that.
WRITE_PAST_LIMIT = """
import resource, sys
import numpy as np
import roadbrdf
angles = np.array([[t, 0.0, 30.0, 180.0] for t in range(0, 80)], dtype=float)
wavelengths = np.arange(400.0, 800.0, 10.0)
values = np.full((len(angles), len(wavelengths)), 0.1)
resource.setrlimit(resource.RLIMIT_FSIZE, (1024, resource.getrlimit(resource.RLIMIT_FSIZE)[1]))
try:
    roadbrdf.Dataset(angles, wavelengths, values).write(sys.argv[1])
except roadbrdf.InputError as e:
    print(e)
"""


def test_write_past_the_file_size_limit_names_the_file_and_leaves_nothing(tmp_path):
    target = tmp_path / "out.csv"
    environment = dict(os.environ, PYTHONPATH=os.pathsep.join(sys.path))
    r = subprocess.run([sys.executable, "-c", WRITE_PAST_LIMIT, str(target)], capture_output=True, text=True,
                       env=environment, check=True)
    assert f"{target}: write failed: File too large" in r.stdout, r.stdout + r.stderr
    assert list(tmp_path.iterdir()) == []


def test_write_through_a_symbolic_link_keeps_it(tmp_path):
    (tmp_path / "target.csv").write_text("old\n")
    (tmp_path / "link.csv").symlink_to("target.csv")
    small_dataset().write(tmp_path / "link.csv")
    assert (tmp_path / "link.csv").is_symlink()
    assert roadbrdf.read_dataset(tmp_path / "target.csv").brdf.shape == (2, 2)
    assert sorted(p.name for p in tmp_path.iterdir()) == ["link.csv", "target.csv"]


def test_directory_is_not_a_file(tmp_path):
    with pytest.raises(roadbrdf.InputError, match="is a directory"):
        roadbrdf.read_dataset(tmp_path)
    with pytest.raises(roadbrdf.InputError, match="is a directory"):
        small_dataset().write(tmp_path)


def test_check_distinct_files_is_the_commands_check(tmp_path):
    data = tmp_path / "d.csv"
    data.write_text("x")
    with pytest.raises(roadbrdf.InputError, match="refusing to overwrite an input"):
        roadbrdf._roadbrdf.check_distinct_files([("DATA", str(data))], [("-o", str(data))])
    roadbrdf._roadbrdf.check_distinct_files([("DATA", str(data))], [("-o", str(tmp_path / "other.csv"))])
