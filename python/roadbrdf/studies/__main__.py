"""``python3 -m roadbrdf.studies`` = ``roadbrdf study``."""
import logging
import signal
import sys

from . import main


class Terminated(KeyboardInterrupt):
    """SIGTERM: the study stops as on Ctrl-C (workers ended, the store closed), with the status of SIGTERM."""


def _terminate(signum, frame):
    raise Terminated()


signal.signal(signal.SIGTERM, _terminate)
# The command reports on standard error itself; the Dask client's own log (a traceback for each failed
# reconnection to a scheduler that went away) would bury its one-line error.
logging.disable(logging.CRITICAL)
try:
    sys.exit(main())
except ValueError as e:  # InputError is a ValueError: the message names the file and key
    print(f"roadbrdf: error: {e}", file=sys.stderr)
    sys.exit(2)
except OSError as e:  # a file the study writes (a full or read-only disk): named by the error
    where = f"{e.filename}: " if e.filename else ""
    print(f"roadbrdf: error: {where}{e.strerror or e}; the results store keeps every finished candidate",
          file=sys.stderr)
    sys.exit(2)
except KeyboardInterrupt as e:
    print("roadbrdf: interrupted; the results store keeps every finished candidate: run again to resume",
          file=sys.stderr)
    sys.exit(143 if isinstance(e, Terminated) else 130)
