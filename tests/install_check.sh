#!/usr/bin/env bash
# `cmake --install` gives a self-contained shpb: installed into a temporary prefix, no installed
# file names the source or build tree, and the prefix still works once moved elsewhere:
# `PREFIX/bin/shpb report` finds its script and package under PREFIX, and writes nothing there.
set -euo pipefail
build=$1 source=$2
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
cmake --install "$build" --prefix "$tmp/prefix" >/dev/null
for tree in "$source" "$build"; do
  if grep -r -q -a -F "$tree" "$tmp/prefix"; then
    echo "FAIL: an installed file names $tree: $(grep -r -l -a -F "$tree" "$tmp/prefix")" >&2; exit 1
  fi
done
test -f "$tmp/prefix/share/shpb/shpb_report/main.py" || { echo "FAIL: no report package" >&2; exit 1; }
mv "$tmp/prefix" "$tmp/moved"  # relocated: nothing may depend on where it was installed
cp "$source/experiments/striker-on-bar/scene.json" "$tmp/scene.json"
(cd "$tmp" && moved/bin/shpb simulate scene.json -o out --quiet)
# The Python package, when built (docs/python.md), beside the executable: imports and runs.
for pkg in "$tmp"/moved/lib/python3*/dist-packages; do
  [ -d "$pkg/shpb" ] || continue
  (cd "$tmp" && PYTHONDONTWRITEBYTECODE=1 PYTHONPATH="$pkg" /usr/bin/python3 -c \
    "import shpb; assert shpb.simulate(shpb.Scene.load('scene.json')).stable") ||
    { echo "FAIL: the installed Python package does not run" >&2; exit 1; }
done
if ! /usr/bin/python3 -c "import matplotlib, numpy" 2>/dev/null; then
  echo "SKIPPED: python3 with matplotlib and numpy not installed: installed report not checked"; exit 0
fi
report="cd '$tmp' && moved/bin/shpb report out >/dev/null"
hidden=""
if unshare --mount true 2>/dev/null; then
  # The source tree (and a build tree inside it) hidden under an empty tmpfs, in a private mount
  # namespace (root only); elsewhere the grep above is the proof that nothing points into it.
  unshare --mount sh -c "mount -t tmpfs none '$source' && $report"
  hidden=" with the source tree hidden"
else
  sh -c "$report"
fi
test -s "$tmp/out/report.html" || { echo "FAIL: no report.html" >&2; exit 1; }
if [ -n "$(find "$tmp/moved" -name __pycache__)" ]; then
  echo "FAIL: the report wrote into the installed prefix" >&2; exit 1
fi
echo "installed shpb, moved to $tmp/moved, simulated and reported$hidden"
