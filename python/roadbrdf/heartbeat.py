"""Progress of the commands the Python package runs (``roadbrdf report``, ``roadbrdf plot``) on standard error,
in the styles and words of the library's progress lines (src/roadbrdf/core/progress.h), so that every command
reads the same in a log:

- standard error not a terminal (a log, a pipe): one plain line at each multiple of ``interval`` seconds (10 s)
  of unfinished work, ``LABEL: DONE/TOTAL PCT%  ELAPSED, ~LEFT left``, and the same line once more at the end
  when one was written; work shorter than the interval writes nothing, so a script never waits in silence and
  a short command stays quiet;
- on a terminal: ``LABEL [####....] DONE/TOTAL PCT%  ELAPSED, ~LEFT left`` redrawn in place from ``delay``
  seconds on (2 s: a command that ends sooner shows nothing), ended by a newline.

A thread writes the lines while the work runs: the library's long calls (fits, albedo, r-tables) release the
interpreter, so the thread keeps its clock during them too. Only the command-line entry points use it; the
functions of the package print nothing."""

from __future__ import annotations

import math
import sys
import threading
import time

__all__ = ["Heartbeat", "heartbeat_line", "bar_line", "seconds_text", "say"]

_active = []  # the Heartbeat of the with block running, if any


def say(text: str, stream=None) -> None:
    """``text`` as a line on ``stream`` (standard error), through the running :class:`Heartbeat` when there is
    one, so that a warning printed while a bar is drawn does not land on the bar's line."""
    if _active and (stream is None or stream is _active[-1].stream):
        _active[-1].say(text)
        return
    stream = sys.stderr if stream is None else stream
    stream.write(text + "\n")
    stream.flush()


def seconds_text(s: float) -> str:
    """Elapsed time as the library writes it: ``12.3 s``, ``4 min 05 s``, ``2 h 03 min``."""
    if s < 60.0:
        return f"{s:.1f} s"
    if s < 3600.0:
        return f"{int(s / 60.0)} min {int(math.fmod(s, 60.0)):02d} s"
    return f"{int(s / 3600.0)} h {int(math.fmod(s, 3600.0) / 60.0):02d} min"


def _count_and_time(done: int, total: int, elapsed: float) -> str:
    done = min(done, total)
    share = done / total if total > 0 else 1.0
    text = f"{done}/{total} {int(math.floor(100.0 * share))}%  {seconds_text(elapsed)}"
    if 0 < done < total:
        text += f", ~{seconds_text(elapsed * (total - done) / done)} left"
    return text


def heartbeat_line(label: str, done: int, total: int, elapsed: float) -> str:
    """A log's line (ProgressBar::heartbeat_line)."""
    return f"{label}: {_count_and_time(done, total, elapsed)}"


def bar_line(label: str, done: int, total: int, elapsed: float, width: int = 24) -> str:
    """A terminal's line (ProgressBar::line)."""
    share = min(done, total) / total if total > 0 else 1.0
    filled = int(share * width)
    return f"{label} [{'#' * filled}{'.' * (width - filled)}] {_count_and_time(done, total, elapsed)}"


class Heartbeat:
    """Progress of ``total`` units of work on ``stream`` (standard error) while the ``with`` block runs.

    ``advance()`` counts a unit done; ``say(text)`` prints a line of the command's own (a step starting)
    without breaking a bar drawn on a terminal. ``enabled`` False (``--quiet``) writes nothing. ``terminal``
    overrides the stream's own answer (tests); ``clock`` is a monotonic clock in seconds."""

    def __init__(self, label: str, total: int = 1, *, stream=None, enabled: bool = True, terminal: bool | None = None,
                 interval: float = 10.0, delay: float = 2.0, redraw: float = 0.5, clock=time.monotonic):
        self.label, self.total, self.done = label, max(int(total), 1), 0
        self.stream = sys.stderr if stream is None else stream
        self.enabled = bool(enabled)
        if terminal is None:
            isatty = getattr(self.stream, "isatty", None)
            terminal = bool(isatty and isatty())
        self.terminal = terminal
        self.interval, self.delay, self.redraw, self.clock = interval, delay, redraw, clock
        self.start = clock()
        self.shown = False  # a line was written (a heartbeat, or the bar drawn)
        self.closed = False  # the with block ended: the bar, if any, was ended by a newline
        self._lock = threading.Lock()
        self._stop = threading.Event()
        self._thread = None

    def __enter__(self) -> Heartbeat:
        self.start = self.clock()
        _active.append(self)
        if self.enabled:
            self._thread = threading.Thread(target=self._run, name="roadbrdf-heartbeat", daemon=True)
            self._thread.start()
        return self

    def __exit__(self, kind, value, traceback) -> None:
        if self in _active:
            _active.remove(self)
        self._stop.set()
        if self._thread is not None:
            self._thread.join()
        with self._lock:
            self.closed = True
            if not self.shown:
                return
            if kind is None:
                self.done = self.total
            elapsed = self.clock() - self.start
            if self.terminal:
                self._write("\r" + bar_line(self.label, self.done, self.total, elapsed) + "\x1b[K\n")
            else:
                self._write(heartbeat_line(self.label, self.done, self.total, elapsed) + "\n")

    def advance(self, units: int = 1) -> None:
        with self._lock:
            self.done = min(self.done + int(units), self.total)

    def say(self, text: str) -> None:
        """``text`` on its own line; on a terminal the bar, when drawn, is erased first and redrawn below."""
        with self._lock:
            if self.terminal and self.shown and not self.closed:
                self._write("\r\x1b[K" + text + "\n")
                self._draw_bar()
            else:
                self._write(text + "\n")

    def _write(self, text: str) -> None:
        try:
            self.stream.write(text)
            self.stream.flush()
        except (OSError, ValueError):  # a closed pipe or stream: progress is never worth an error
            pass

    def _draw_bar(self) -> None:
        self._write("\r" + bar_line(self.label, self.done, self.total, self.clock() - self.start) + "\x1b[K")

    def _run(self) -> None:
        if self.terminal:
            if self._stop.wait(self.delay):
                return
            while True:
                with self._lock:
                    self.shown = True
                    self._draw_bar()
                if self._stop.wait(self.redraw):
                    return
        beats = 1
        while not self._stop.wait(max(0.0, self.start + beats * self.interval - self.clock())):
            with self._lock:
                elapsed = self.clock() - self.start
                # The next line at the next multiple of the interval, however late this one came.
                beats = int(math.floor(elapsed / self.interval)) + 1
                self.shown = True
                self._write(heartbeat_line(self.label, self.done, self.total, elapsed) + "\n")
