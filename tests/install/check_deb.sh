#!/usr/bin/env bash
# Debian package test (ctest: install.deb): `cpack -G DEB` from the build tree, then check the
# control file (runtime dependencies are Debian packages), the contents, and that the unpacked
# program and Python package work from a scratch root.
# Usage: check_deb.sh BUILD_DIR PYTHON
set -euo pipefail
build="$(cd "$1" && pwd)"; python="$2"
scratch="$(mktemp -d "${TMPDIR:-/tmp}/roadbrdf-deb.XXXXXX")"
trap 'rm -rf "$scratch"' EXIT
fail() { echo "deb check: $*" >&2; exit 1; }

(cd "$scratch" && cpack --config "$build/CPackConfig.cmake" -G DEB -B "$scratch/out" > cpack.log 2>&1) \
  || { cat "$scratch/cpack.log"; fail "cpack failed"; }
deb="$(ls "$scratch"/out/roadbrdf_*.deb)"
dpkg-deb -f "$deb" Package | grep -qx roadbrdf || fail "package name"
depends="$(dpkg-deb -f "$deb" Depends)"
for p in libfmt9 libgoogle-glog python3-numpy python3-matplotlib libc6; do
  grep -q "$p" <<< "$depends" || fail "Depends lacks $p: $depends"
done
dpkg-deb -c "$deb" > "$scratch/contents"
for f in ./usr/bin/roadbrdf ./usr/share/roadbrdf/data/ATTRIBUTION.md ./usr/share/man/man1/roadbrdf.1 \
         ./usr/lib/python3/dist-packages/roadbrdf/__init__.py ./usr/include/roadbrdf/core/geometry.h \
         ./usr/lib/cmake/roadbrdf/roadbrdfConfig.cmake; do
  grep -q " $f\$" "$scratch/contents" || fail "$f not in the package"
done

root="$scratch/root"
dpkg -x "$deb" "$root"
env -u ROADBRDF_DATA "$root/usr/bin/roadbrdf" albedo lambert -p albedo=0.25 --sun-zenith 30 > /dev/null \
  || fail "unpacked program"
env -u ROADBRDF_DATA PYTHONPATH="$root/usr/lib/python3/dist-packages" "$python" -c \
  "import roadbrdf, os; assert os.path.isfile(os.path.join(roadbrdf.data_directory(), 'ATTRIBUTION.md'))" \
  || fail "unpacked Python package"
echo "deb check passed: $(basename "$deb"), Depends: $depends"
