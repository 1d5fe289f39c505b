#!/usr/bin/env bash
# pip test (ctest: install.pip): `pip install .` into a fresh virtual environment (with Debian's
# numpy/matplotlib visible, no package index), reusing the test build tree through
# $ROADBRDF_PIP_BUILD_DIR so that nothing is compiled twice; then the program, the data and the
# Python package are used from the environment only.
# Usage: check_pip.sh BUILD_DIR SOURCE_DIR PYTHON
set -euo pipefail
build="$(cd "$1" && pwd)"; source_dir="$(cd "$2" && pwd)"; python="$3"
scratch="$(mktemp -d "${TMPDIR:-/tmp}/roadbrdf-pip.XXXXXX")"
trap 'rm -rf "$scratch"' EXIT
fail() { echo "pip check: $*" >&2; exit 1; }

"$python" -m venv --system-site-packages "$scratch/venv"
ROADBRDF_PIP_BUILD_DIR="$build" "$scratch/venv/bin/python" -m pip install --no-index --disable-pip-version-check \
  "$source_dir" > "$scratch/pip.log" 2>&1 || { cat "$scratch/pip.log"; fail "pip install failed"; }
[ -x "$scratch/venv/bin/roadbrdf" ] || fail "no roadbrdf program in the environment's bin/"
[ -f "$scratch/venv/share/roadbrdf/data/ATTRIBUTION.md" ] || fail "no data in the environment's share/"
cd "$scratch"
env -u ROADBRDF_DATA -u PYTHONPATH "$scratch/venv/bin/roadbrdf" albedo lambert -p albedo=0.25 --sun-zenith 30 \
  > /dev/null || fail "the installed program"
env -u ROADBRDF_DATA -u PYTHONPATH -u ROADBRDF_PYTHON "$scratch/venv/bin/roadbrdf" plot hemisphere lambert \
  -p albedo=0.3 --theta-i 30 -o "$scratch/lobe.png" > plot.log 2>&1 || { cat plot.log; fail "plot"; }
env -u ROADBRDF_DATA -u PYTHONPATH "$scratch/venv/bin/python" - "$scratch/venv" <<'PY' || fail "import from the environment"
import os, sys, roadbrdf
venv = os.path.realpath(sys.argv[1])
assert os.path.realpath(roadbrdf.__file__).startswith(venv), roadbrdf.__file__
assert os.path.realpath(roadbrdf.data_directory()) == os.path.join(venv, "share/roadbrdf/data"), roadbrdf.data_directory()
PY
"$scratch/venv/bin/python" -m pip uninstall -y roadbrdf > /dev/null || fail "pip uninstall"
[ ! -e "$scratch/venv/bin/roadbrdf" ] || fail "uninstall left the program"
echo "pip check passed"
