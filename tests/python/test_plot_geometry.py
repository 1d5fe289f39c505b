"""The geometry a spectral figure shows (roadbrdf.plot_geometry): nearest up to a turn about the normal,
road angles accepted, and a geometry far from the one asked for reported. Distances are checked against
the spherical law of cosines, computed here independently of the vector form the module uses."""
import math

import matplotlib.pyplot as plt
import numpy as np
import pytest

import roadbrdf
from roadbrdf import plot as rplot
from roadbrdf.plot_geometry import nearest_geometry, parse_geometry

DATA = "data/examples/single/lazard.csv"


def _relative(row):
    return (row[3] - row[1]) % 360.0


def test_a_retro_request_finds_the_turned_retro_geometry(root):
    d = roadbrdf.read_dataset(root / DATA)
    k, distance = nearest_geometry(d.angles, (40, 0, 40, 0))
    row = d.angles[k]
    assert row[0] == 40 and row[2] == 40 and _relative(row) == 0  # (40, 180, 40, 180) in the file
    assert distance < 1e-5
    # Road angles: gamma = theta_i, alpha = 90 - theta_r, beta = 180 - dphi, delta = phi_r - 180.
    assert parse_geometry("gamma=40,alpha=50,beta=180,delta=0") == (40.0, 180.0, 40.0, 180.0)
    assert nearest_geometry(d.angles, parse_geometry("gamma=40, alpha=50, beta=180, delta=0"))[0] == k


def test_the_distance_is_the_larger_angle_between_directions(root):
    d = roadbrdf.read_dataset(root / DATA)
    want = (33.0, 10.0, 52.0, 100.0)
    k, distance = nearest_geometry(d.angles, want)
    ti, pi, tr, pr = d.angles[k]
    incidence = abs(ti - want[0])
    cos_view = (math.cos(math.radians(tr)) * math.cos(math.radians(want[2])) + math.sin(math.radians(tr)) *
                math.sin(math.radians(want[2])) * math.cos(math.radians((pr - pi) - (want[3] - want[1]))))
    viewing = math.degrees(math.acos(min(1.0, cos_view)))
    assert distance == pytest.approx(max(incidence, viewing), abs=1e-9)
    # No row is nearer by the same measure.
    for row in d.angles:
        c = (math.cos(math.radians(row[2])) * math.cos(math.radians(want[2])) + math.sin(math.radians(row[2])) *
             math.sin(math.radians(want[2])) * math.cos(math.radians((row[3] - row[1]) - (want[3] - want[1]))))
        assert max(abs(row[0] - want[0]), math.degrees(math.acos(min(1.0, c)))) >= distance - 1e-9


def test_a_far_geometry_is_said_on_the_figure_and_on_stderr(root, cli, tmp_path, capsys):
    fig = rplot.spectral([root / DATA], geometry="10,0,85,0")
    (label, (angles, distance)), = fig.roadbrdf_geometries.items()
    assert distance > 1.0
    assert "from the geometry asked for" in fig.axes[0].get_legend().get_texts()[0].get_text()
    assert "roadbrdf: warning:" in capsys.readouterr().err
    plt.close(fig)
    r = cli("plot", "spectral", root / DATA, "--geometry", "10,0,85,0", "-o", tmp_path / "s.png")
    assert "roadbrdf: warning:" in r.stderr and "deg from the one asked for" in r.stderr
    r = cli("plot", "spectral", root / DATA, "--geometry", "gamma=40,alpha=50", "-o", tmp_path / "s.png",
            check=False)
    assert r.returncode == 2 and "missing beta, delta" in r.stderr, r.stderr
