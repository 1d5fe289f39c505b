"""The progress lines of the commands the Python package runs (roadbrdf.heartbeat): the library's words
(src/roadbrdf/core/progress.h gives the heartbeat line "LABEL: 12/40 30%  10.0 s, ~23.3 s left"), a line per
interval in a log, nothing for short work, a bar on a terminal."""

import io
import re
import threading

from roadbrdf.heartbeat import Heartbeat, bar_line, heartbeat_line, say, seconds_text


def test_lines_are_the_librarys():
    # The example of core/progress.h: 12 of 40 after 10 s leaves 28 units at 10/12 s each.
    assert heartbeat_line("LABEL", 12, 40, 10.0) == "LABEL: 12/40 30%  10.0 s, ~23.3 s left"
    assert heartbeat_line("x", 0, 3, 4.0) == "x: 0/3 0%  4.0 s"
    assert heartbeat_line("x", 3, 3, 4.0) == "x: 3/3 100%  4.0 s"
    assert bar_line("LABEL", 12, 40, 2.1) == "LABEL [#######.................] 12/40 30%  2.1 s, ~4.9 s left"
    assert seconds_text(125.0) == "2 min 05 s"
    assert seconds_text(7380.0) == "2 h 03 min"


def test_a_log_gets_a_line_per_interval_and_a_last_one():
    out = io.StringIO()
    done = threading.Event()
    with Heartbeat("roadbrdf plot albedo", 2, stream=out, terminal=False, interval=0.05) as beat:
        beat.advance()
        done.wait(0.4)
    lines = out.getvalue().splitlines()
    assert len(lines) >= 2
    for line in lines[:-1]:
        assert re.fullmatch(r"roadbrdf plot albedo: 1/2 50%  \d+\.\d s, ~\d+\.\d s left", line), line
    assert re.fullmatch(r"roadbrdf plot albedo: 2/2 100%  \d+\.\d s", lines[-1]), lines[-1]


def test_short_work_and_quiet_write_nothing():
    out = io.StringIO()
    with Heartbeat("x", stream=out, terminal=False, interval=60.0):
        pass
    with Heartbeat("x", stream=out, terminal=True, delay=60.0):
        pass
    with Heartbeat("x", stream=out, terminal=False, interval=0.01, enabled=False):
        threading.Event().wait(0.1)
    assert out.getvalue() == ""


def test_a_terminal_gets_a_bar_redrawn_in_place_and_lines_above_it():
    out = io.StringIO()
    with Heartbeat("roadbrdf report", 4, stream=out, terminal=True, delay=0.01, redraw=0.01) as beat:
        threading.Event().wait(0.2)
        beat.say("roadbrdf report: fitting ...")
        beat.advance(2)
        threading.Event().wait(0.1)
    text = out.getvalue()
    assert "\rroadbrdf report [......................." in text
    assert "\r\x1b[Kroadbrdf report: fitting ...\n" in text
    assert text.endswith("\rroadbrdf report [########################] 4/4 100%  " + text.rsplit("100%  ", 1)[1])
    assert text.endswith(" s\x1b[K\n")
    # A line after the end (the report's last one) is a plain line: no bar drawn again below it.
    beat.say("roadbrdf report: wrote r.html")
    assert out.getvalue() == text + "roadbrdf report: wrote r.html\n"


def test_a_warning_said_while_a_bar_is_drawn_goes_above_it():
    out = io.StringIO()
    with Heartbeat("roadbrdf plot albedo", stream=out, terminal=True, delay=0.0, redraw=0.01):
        threading.Event().wait(0.1)
        say("roadbrdf: warning: mostly extrapolation", stream=out)
    assert "\r\x1b[Kroadbrdf: warning: mostly extrapolation\n\rroadbrdf plot albedo [" in out.getvalue()
    plain = io.StringIO()
    say("no bar", stream=plain)
    assert plain.getvalue() == "no bar\n"
