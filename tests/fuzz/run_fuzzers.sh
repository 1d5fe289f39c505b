#!/usr/bin/env bash
# Runs every libFuzzer program of BUILD/tests/fuzz for SECONDS each, one at a time, on a scratch
# copy of its seed corpus (the corpus in the repository only grows by hand: seeds and regressions).
# Usage: tests/fuzz/run_fuzzers.sh BUILD [SECONDS]
set -euo pipefail
build=$1
seconds=${2:-20}
source_dir=$(cd "$(dirname "$0")" && pwd)
status=0
for program in "$build"/tests/fuzz/*_fuzz; do
  name=$(basename "$program" _fuzz)
  work="$build/fuzz-corpus/$name"
  crashes="$build/crashes/$name"
  mkdir -p "$work" "$crashes"
  # Seeds: the repository's corpus, or the generated one of the instrument-file parsers.
  cp -n "$source_dir/corpus/$name"/* "$build/tests/fuzz/corpus/$name"/* "$work"/ 2>/dev/null || true
  if "$program" -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 -artifact_prefix="$crashes/" \
       -print_final_stats=1 "$work" > "$build/crashes/$name.log" 2>&1; then
    echo "$name: $(grep -m1 -o 'stat::number_of_executed_units: *[0-9]*' "$build/crashes/$name.log" | grep -o '[0-9]*$') runs, no crash"
  else
    echo "$name: CRASH, see $build/crashes/$name.log and $crashes/"
    status=1
  fi
done
exit $status
