#!/usr/bin/env bash
# ctest style.one_random_family: random numbers come from core/random.h alone (xoshiro256** and its
# own uniform, bounded-integer, normal and shuffle draws). The engines and distributions of <random>
# are refused everywhere, tests and benchmarks included: the distributions' outputs differ between
# standard libraries, so a seed would not give the same draws everywhere. std::random_device is
# allowed as a seed source. Fails naming every line that uses them.
# Usage: one_random_family.sh SOURCE_DIR
set -euo pipefail
cd "$1"
pattern='std::(mt19937|mt19937_64|minstd_rand0?|ranlux[0-9]+|default_random_engine|knuth_b|[a-z_]+_distribution)\b|std::shuffle\b|\brand\(\)'
if grep -rnIE --exclude=one_random_family.sh "$pattern" src python/src tests bench; then
  echo "one_random_family: the lines above draw random numbers outside core/random.h" >&2
  exit 1
fi
echo "one_random_family: clean"
