#!/usr/bin/env bash
# Install the Debian packages of packages.txt that are missing, one line of output per package set;
# apt's own output goes to build/install-deps.log and is shown only when it fails.
# Usage: install-deps.sh [SET ...]   (default: every set). Uses sudo only when not running as root.
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
log="$here/build/install-deps.log"
mkdir -p "$here/build"

# Sets in file order, or those asked for.
mapfile -t all_sets < <(sed -n 's/^\[\([a-z-]*\)\].*/\1/p' "$here/packages.txt")
sets=("$@")
[ ${#sets[@]} -gt 0 ] || sets=("${all_sets[@]}")

packages_of() {  # the packages of set $1
  awk -v want="$1" '
    /^\[/ { match($0, /^\[[a-z-]*\]/); current = substr($0, 2, RLENGTH - 2); next }
    { sub(/#.*/, ""); gsub(/[[:space:]]/, "") }
    $0 != "" && current == want { print }' "$here/packages.txt"
}

sudo=""
if [ "$(id -u)" -ne 0 ]; then sudo="sudo"; fi
updated=0
for set in "${sets[@]}"; do
  if ! printf '%s\n' "${all_sets[@]}" | grep -qx "$set"; then
    echo "roadbrdf: unknown package set '$set' (packages.txt has: ${all_sets[*]})" >&2
    exit 2
  fi
  mapfile -t wanted < <(packages_of "$set")
  missing=()
  for p in "${wanted[@]}"; do
    if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q 'install ok installed'; then missing+=("$p"); fi
  done
  if [ ${#missing[@]} -eq 0 ]; then
    echo "roadbrdf: Debian packages [$set]: all ${#wanted[@]} present"
    continue
  fi
  echo "roadbrdf: Debian packages [$set]: installing ${missing[*]} (log: $log)"
  export DEBIAN_FRONTEND=noninteractive
  if ! { if [ $updated -eq 0 ]; then $sudo apt-get update; fi &&
         $sudo apt-get install -y --no-install-recommends "${missing[@]}"; } >> "$log" 2>&1; then
    tail -n 40 "$log" >&2
    echo "roadbrdf: installing the [$set] packages failed; full log in $log" >&2
    exit 1
  fi
  updated=1
done
