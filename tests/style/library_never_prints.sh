#!/usr/bin/env bash
# ctest style.library_never_prints: the library reports notes and warnings through its results and the
# front end's sink (core/diagnostics.h), never by writing to standard error or standard output itself;
# only the command line (src/roadbrdf/cli) prints. Fails naming every line that prints.
# Usage: library_never_prints.sh SOURCE_DIR
set -euo pipefail
cd "$1"
pattern='(fmt::print|fprintf|fputs)\((stderr|stdout)|std::(cerr|clog)\b|(^|[^a-z_:.>])(printf|puts)\('
if grep -rnIE "$pattern" src/roadbrdf --include='*.cpp' --include='*.h' | grep -v '^src/roadbrdf/cli/'; then
  echo "library_never_prints: the lines above print from the library (route them through core/diagnostics.h)" >&2
  exit 1
fi
echo "library_never_prints: clean"
