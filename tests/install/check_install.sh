#!/usr/bin/env bash
# Install test (ctest: install.prefix): install the build tree into a scratch prefix and use it the
# ways users do: the program (with its data and figures), the Python package with only the prefix's
# package folder on the path, a downstream CMake project with find_package(roadbrdf), and no source
# or build path left in the installed binaries.
# Usage: check_install.sh BUILD_DIR SOURCE_DIR PYTHON
set -euo pipefail
build="$(cd "$1" && pwd)"; source_dir="$(cd "$2" && pwd)"; python="$3"
scratch="$(mktemp -d "${TMPDIR:-/tmp}/roadbrdf-install.XXXXXX")"
trap 'rm -rf "$scratch"' EXIT
prefix="$scratch/prefix"
fail() { echo "install check: $*" >&2; exit 1; }

cmake --install "$build" --prefix "$prefix" > "$scratch/install.log" || { cat "$scratch/install.log"; fail "cmake --install failed"; }
pydir="$prefix/lib/python3/dist-packages"
for f in bin/roadbrdf lib/libroadbrdf_core.a lib/libroadbrdf_fitting.a include/roadbrdf/models/model.h \
         lib/cmake/roadbrdf/roadbrdfConfig.cmake lib/cmake/roadbrdf/roadbrdfTargets.cmake \
         share/roadbrdf/data/ATTRIBUTION.md share/man/man1/roadbrdf.1 share/doc/roadbrdf/models.md \
         lib/python3/dist-packages/roadbrdf/__init__.py; do
  [ -e "$prefix/$f" ] || fail "missing $f"
done
ls "$pydir"/roadbrdf/_roadbrdf*.so > /dev/null || fail "missing the Python extension"
[ ! -e "$prefix/include/roadbrdf/cli" ] || fail "CLI headers installed"

# No path of the source or build tree compiled into what was installed.
for f in "$prefix/bin/roadbrdf" "$pydir"/roadbrdf/_roadbrdf*.so; do
  if grep -q -a -F -e "$source_dir/" -e "$build/" "$f"; then fail "$f contains a source or build path"; fi
done

# The program from the prefix, with the build tree out of sight: data, models, albedo.
cd "$scratch"
env -u ROADBRDF_DATA "$prefix/bin/roadbrdf" --version | grep -q "roadbrdf " || fail "--version"
env -u ROADBRDF_DATA "$prefix/bin/roadbrdf" albedo lambert -p albedo=0.25 --sun-zenith 30 > albedo.txt \
  || fail "albedo with the installed data"
grep -q "0.25" albedo.txt || fail "albedo output: $(cat albedo.txt)"
# Figures: the program finds its installed Python package.
env -u ROADBRDF_DATA -u PYTHONPATH ROADBRDF_PYTHON="$python" "$prefix/bin/roadbrdf" plot hemisphere lambert \
  -p albedo=0.3 --theta-i 30 -o "$scratch/lobe.png" > plot.log 2>&1 || { cat plot.log; fail "plot from the prefix"; }
[ -s "$scratch/lobe.png" ] || fail "no figure written"

# Python with only the prefix's package folder on the path.
env -u ROADBRDF_DATA PYTHONPATH="$pydir" "$python" - "$prefix" <<'PY' || fail "Python import from the prefix"
import os, sys, roadbrdf
prefix = os.path.realpath(sys.argv[1])
assert os.path.realpath(roadbrdf.__file__).startswith(prefix), roadbrdf.__file__
assert os.path.realpath(roadbrdf.data_directory()) == os.path.join(prefix, "share/roadbrdf/data"), roadbrdf.data_directory()
m = roadbrdf.Model("lambert")
v = m.evaluate(30.0, 0.0, 45.0, 180.0, albedo=0.5)
assert abs(float(v) - 0.5 / 3.141592653589793) < 1e-12, v
PY

# A downstream CMake project.
cmake -S "$source_dir/tests/install/downstream" -B "$scratch/downstream" -DCMAKE_PREFIX_PATH="$prefix" \
  -DCMAKE_BUILD_TYPE=Release > "$scratch/downstream.log" 2>&1 || { cat "$scratch/downstream.log"; fail "downstream configure"; }
cmake --build "$scratch/downstream" -j 2 >> "$scratch/downstream.log" 2>&1 || { cat "$scratch/downstream.log"; fail "downstream build"; }
"$scratch/downstream/downstream" || fail "downstream program"
echo "install check passed ($prefix)"
