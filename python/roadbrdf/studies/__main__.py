"""``python3 -m roadbrdf.studies`` = ``roadbrdf study``."""
import sys

from . import main

try:
    sys.exit(main())
except ValueError as e:  # InputError is a ValueError: the message names the file and key
    print(f"roadbrdf: error: {e}", file=sys.stderr)
    sys.exit(2)
except KeyboardInterrupt:
    print("roadbrdf: interrupted; the results store keeps every finished candidate: run again to resume",
          file=sys.stderr)
    sys.exit(130)
