#!/usr/bin/env bash
# The instrument files of this folder are roadbrdf's own synthetic files, not copies of real
# instrument data (../shared/real-data is never copied into the repository): each one is exactly
# what make_synthetic.py writes from its closed-form signals.
#   check_generated.sh PYTHON
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
out="$(mktemp -d)"
trap 'rm -rf "$out"' EXIT
"$1" "$here/make_synthetic.py" "$out" > /dev/null
status=0
for f in "$here"/*.asd "$here"/*.sed "$here"/*.sig "$here"/rho.txt; do
  name="$(basename "$f")"
  if ! cmp -s "$f" "$out/$name"; then
    echo "tests/data/instruments/$name is not what make_synthetic.py writes" >&2
    status=1
  fi
done
exit $status
