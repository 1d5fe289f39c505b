#!/usr/bin/env bash
# ctest style.names_come_from_tables: an enumeration's names are declared once, in its table
# (core/enum_names.h), and parsed by parse_name; a chain of comparisons with literal names, each
# returning a value of an enumeration ('if (text == "wide") return DatasetFormat::kWide;'), is a
# second declaration that drifts from the table. (File extensions, ".csv", are no names.) Fails
# naming every such line.
# Usage: names_come_from_tables.sh DIRECTORY...
set -euo pipefail
pattern='if \(.*== "[A-Za-z][^"]*"\)( \{)? *return [A-Za-z_:]+::[A-Za-z_]+;'
if grep -rnHIE --include='*.cpp' --include='*.h' "$pattern" "$@"; then
  echo "names_come_from_tables: the lines above compare with literal names; give the enumeration a table" >&2
  exit 1
fi
echo "names_come_from_tables: clean"
