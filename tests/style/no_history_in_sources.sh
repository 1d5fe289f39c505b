#!/usr/bin/env bash
# ctest style.sources_carry_no_history: sources, tests, scripts and build files carry physics and
# design; history (issue numbers, the draft report's reference README "known errors") belongs to
# commit messages, and a correction of the report is cited from docs/report-corrections.md. Fails
# naming every line that has one. The documents (docs/, README.md) may speak of history.
# Usage: no_history_in_sources.sh SOURCE_DIR
set -euo pipefail
cd "$1"
pattern='\bissues? #?[0-9]+\b|known errors|reference README'
# This script names the pattern it looks for, so it is left out.
if grep -rnIiE --exclude=no_history_in_sources.sh "$pattern" \
     src python tests bench examples scripts cmake CMakeLists.txt Makefile data/examples .ci; then
  echo "no_history_in_sources: the lines above carry history; move it to the commit message" >&2
  exit 1
fi
echo "no_history_in_sources: clean"
