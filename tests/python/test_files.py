"""Files from Python follow the command line's rules (issue 15): an output is never an input,
failed writes raise InputError naming the file, links are written through, nothing is left behind."""
import os
import pathlib

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


def test_write_to_a_full_device_names_it():
    if not os.path.exists("/dev/full"):
        pytest.skip("no /dev/full")
    with pytest.raises(roadbrdf.InputError, match="/dev/full: write failed: No space left on device"):
        small_dataset().write("/dev/full")


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
