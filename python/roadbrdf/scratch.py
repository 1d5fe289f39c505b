"""Scratch folders that outlive no one: each holds the process id of its owner, and a new one first removes
those whose owner has died without cleaning up (``kill -9``, a power cut), which no handler in the dead process
could do."""
from __future__ import annotations

import os
import shutil
import tempfile

_OWNER = ".roadbrdf-owner"


def _alive(pid: int) -> bool:
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except PermissionError:  # another user's process: alive
        return True
    return True


def remove_stale(prefix: str, folder: str | None = None) -> list[str]:
    """Remove this user's ``prefix*`` folders in ``folder`` (default: the temporary folder) whose owner process
    has ended; folders without an owner file, other users' and live owners' are left alone. Returns the removed
    paths."""
    folder = folder or tempfile.gettempdir()
    removed = []
    try:
        names = os.listdir(folder)
    except OSError:
        return removed
    for name in names:
        path = os.path.join(folder, name)
        if not name.startswith(prefix) or os.path.islink(path) or not os.path.isdir(path):
            continue
        try:
            if os.stat(path).st_uid != os.getuid():
                continue
            with open(os.path.join(path, _OWNER), encoding="ascii") as f:
                pid = int(f.read().strip())
        except (OSError, ValueError):
            continue
        if pid > 0 and not _alive(pid):
            shutil.rmtree(path, ignore_errors=True)
            removed.append(path)
    return removed


def make_scratch(prefix: str) -> str:
    """A new folder ``prefix*`` in the temporary folder, owned by this process (stale ones removed first)."""
    remove_stale(prefix)
    path = tempfile.mkdtemp(prefix=prefix)
    with open(os.path.join(path, _OWNER), "w", encoding="ascii") as f:
        f.write(f"{os.getpid()}\n")
    return path
