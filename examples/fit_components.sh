#!/usr/bin/env bash
# Fit every bundled single-material sample and mastic (data/examples/single, data/examples/mastics)
# with the three models the demo ranks, writing OUT/<name>.fit.json: the component fits that the
# example formulations (data/examples/formulations/*.json, "fit": "../fits/<name>.fit.json") use.
# Usage: bash examples/fit_components.sh [BUILD] [OUT]   (defaults: build, data/examples/fits)
# Prints each sample's ranking table.
set -euo pipefail
cd "$(dirname "$0")/.."
build="${1:-build}"
out="${2:-data/examples/fits}"
mkdir -p "$out"
for f in data/examples/single/*.csv data/examples/mastics/*.csv; do
  name="$(basename "$f" .csv)"
  echo "-- $name"
  "$build/roadbrdf" fit "$f" --model oren-nayar --model oren-nayar+torrance-sparrow --model hapke \
      --fix oren-nayar.weight=1 --fix torrance-sparrow.weight=1 --multistart 8 -o "$out/$name.fit.json" 2>/dev/null \
      | sed -n '2,99p'
done
