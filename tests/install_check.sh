#!/usr/bin/env bash
# `cmake --install` gives a self-contained shpb: installed into a temporary prefix, the executable
# holds no path of the source tree and `PREFIX/bin/shpb report` finds its script under PREFIX.
set -euo pipefail
build=$1 source=$2
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
cmake --install "$build" --prefix "$tmp/prefix" >/dev/null
if grep -q -a -F "$source" "$tmp/prefix/bin/shpb"; then
  echo "FAIL: the installed shpb names the source tree $source" >&2; exit 1
fi
cp "$source/experiments/striker-on-bar/scene.json" "$tmp/scene.json"
(cd "$tmp" && prefix/bin/shpb simulate scene.json -o out --quiet)
if ! /usr/bin/python3 -c "import matplotlib, numpy" 2>/dev/null; then
  echo "SKIPPED: python3 with matplotlib and numpy not installed: installed report not checked"; exit 0
fi
(cd "$tmp" && prefix/bin/shpb report out >/dev/null)
test -s "$tmp/out/report.html" || { echo "FAIL: no report.html" >&2; exit 1; }
echo "installed shpb simulated and reported from $tmp/prefix"
