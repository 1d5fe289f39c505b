#!/usr/bin/env bash
# ctest style.sources_carry_no_history: sources carry physics and design; history (issue numbers,
# the draft report's reference README "known errors") belongs to commit messages, and a correction
# of the report is cited from docs/report-corrections.md. Fails naming every line that has one.
# Usage: no_history_in_sources.sh SOURCE_DIR
set -euo pipefail
cd "$1"
if grep -rnIiE '\(issue [0-9]+|\bissue [0-9]+[,:;)]|issue #[0-9]+|known errors|reference README' src python/src; then
  echo "no_history_in_sources: the lines above carry history; move it to the commit message" >&2
  exit 1
fi
echo "no_history_in_sources: clean"
