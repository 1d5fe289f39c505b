#!/usr/bin/env bash
# Checks (or with --fix, applies) the C++ style of .clang-format on every C++ file of the source
# tree: src/, python/src/, tests/ and bench/. Exit 0 when clean, 1 when a file differs (each one is
# named), 77 when clang-format 14 is not installed (ctest reports the test as skipped).
# Usage: check_format.sh SOURCE_DIR [--fix]
set -euo pipefail
source_dir="$(cd "${1:-.}" && pwd)"
fix="${2:-}"
formatter="${CLANG_FORMAT:-clang-format-14}"
if ! command -v "$formatter" > /dev/null; then
  echo "check_format: $formatter is not installed (packages.txt [test]: clang-format-14); skipped" >&2
  exit 77
fi
cd "$source_dir"
mapfile -d '' files < <(find src python/src tests bench -type f \( -name '*.h' -o -name '*.cpp' \) -print0 | sort -z)
if [ "$fix" = "--fix" ]; then
  "$formatter" -i --style=file "${files[@]}"
  echo "check_format: formatted ${#files[@]} files"
  exit 0
fi
# One clang-format run over every file; it names each file that differs ("FILE:LINE:COL: error: code
# should be clang-formatted").
report="$("$formatter" --style=file --dry-run --Werror "${files[@]}" 2>&1)" && status=0 || status=$?
mapfile -t differing < <(printf '%s\n' "$report" | sed -n 's/^\(.*\):[0-9]*:[0-9]*: error: code should be clang-formatted.*/\1/p' | sort -u)
if [ "$status" -ne 0 ] || [ "${#differing[@]}" -gt 0 ]; then
  if [ "${#differing[@]}" -gt 0 ]; then
    printf 'check_format: %s differs from .clang-format\n' "${differing[@]}" >&2
  else
    printf '%s\n' "$report" >&2
  fi
  echo "check_format: ${#differing[@]} of ${#files[@]} files differ; run \`make format\` to apply the style" >&2
  exit 1
fi
echo "check_format: ${#files[@]} files follow .clang-format"
