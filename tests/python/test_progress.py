"""Progress bars of long commands: drawn on standard error only when it is a terminal, never with
--quiet; a pipe or log gets no bar (at most a plain heartbeat line every 10 s, core/progress.h)."""
import os
import pty
import subprocess

import pytest

EXE = os.environ.get("ROADBRDF_CLI")


def run_on_terminal(args):
    """Runs the program with standard error on a pseudo-terminal; returns (status, what it drew)."""
    leader, follower = pty.openpty()
    with subprocess.Popen([EXE, *map(str, args)], stdout=subprocess.DEVNULL, stderr=follower) as p:
        os.close(follower)
        chunks = []
        while True:
            try:
                chunk = os.read(leader, 4096)
            except OSError:  # the terminal closed with the program
                break
            if not chunk:
                break
            chunks.append(chunk)
        status = p.wait()
    os.close(leader)
    return status, b"".join(chunks).decode(errors="replace")


@pytest.fixture(scope="module")
def render_args(tmp_path_factory):
    if not EXE:
        pytest.skip("ROADBRDF_CLI is not set (run through ctest)")
    d = tmp_path_factory.mktemp("progress")
    subprocess.run([EXE, "surface", "lambert", "--flat", "-p", "albedo=0.5", "-o", d / "flat.json"], check=True,
                   capture_output=True)
    (d / "grid.csv").write_text("theta_i,phi_i,theta_r,phi_r\n" + "".join(
        f"{ti},0,{tr},180\n" for ti in (0, 20, 40, 60) for tr in (10, 30, 50, 70)))
    # Enough paths for well over the bar's 1 s delay on a 2-core machine.
    return ["render", d / "flat.json", "--grid", d / "grid.csv", "--samples", "400000", "--acceptance", "5",
            "-o", d / "out.csv"]


def test_render_draws_a_bar_on_a_terminal_only(render_args, cli):
    status, drawn = run_on_terminal(render_args)
    assert status == 0, drawn
    assert "render: blocks of paths [" in drawn and "\r" in drawn, drawn
    assert "100%" in drawn, drawn  # the last line drawn is the whole work
    status, drawn = run_on_terminal(render_args + ["--quiet"])
    assert status == 0 and "blocks of paths" not in drawn, drawn
    piped = cli(*render_args)
    assert "\r" not in piped.stderr and "[#" not in piped.stderr, piped.stderr


@pytest.mark.parametrize("command", [["albedo", "lambert", "-p", "albedo=0.5"], ["fit", "--help"],
                                     ["mix", "--help"], ["surface", "--help"], ["render", "--help"]])
def test_every_long_command_has_quiet(command, cli):
    if command[-1] == "--help":
        assert "--quiet" in cli(*command).stdout
    else:
        r = cli(*command, "--quiet")
        assert "\r" not in r.stderr
