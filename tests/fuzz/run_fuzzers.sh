#!/usr/bin/env bash
# Runs each libFuzzer target for SECONDS: `make fuzz` calls this after building.
# Usage: run_fuzzers.sh BUILD_DIR SECONDS [target ...]   (default: every fuzz_* in BUILD_DIR)
# The seeds of tests/fuzz/corpus/<target> are copied into BUILD_DIR/corpus/<target>, which grows;
# crashes, leaks and timeouts land in BUILD_DIR/artifacts/<target>/ and fail the run.
set -uo pipefail
build=$1; seconds=$2; shift 2
here=$(cd "$(dirname "$0")" && pwd)
targets=("$@")
if [ ${#targets[@]} -eq 0 ]; then
  for t in "$build"/fuzz_*; do [ -x "$t" ] && targets+=("$(basename "$t")"); done
fi
failed=0
for t in "${targets[@]}"; do
  corpus="$build/corpus/$t"; artifacts="$build/artifacts/$t"
  mkdir -p "$corpus" "$artifacts"
  cp -n "$here/corpus/$t/"* "$corpus/" 2>/dev/null || true
  log="$build/$t.log"
  # Inputs up to 8 kB, or as long as the longest seed (a whole .xls workbook is tens of kB).
  max_len=8192
  for f in "$here/corpus/$t/"*; do
    [ -f "$f" ] && size=$(stat -c %s "$f") && [ "$size" -gt "$max_len" ] && max_len=$size
  done
  "$build/$t" "$corpus" -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 -max_len="$max_len" \
    -print_final_stats=1 -artifact_prefix="$artifacts/" >"$log" 2>&1
  rc=$?
  runs=$(grep -o 'stat::number_of_executed_units: *[0-9]*' "$log" | grep -o '[0-9]*$')
  if [ $rc -eq 0 ]; then
    echo "fuzz: $t: ${runs:-?} executions in ${seconds} s, no crash, leak or hang"
  else
    echo "fuzz: $t: FAILED (exit $rc) after ${runs:-?} executions; see $log and $artifacts/"
    grep -m3 -E 'ERROR|SUMMARY|runtime error' "$log" | sed 's/^/  /'
    failed=1
  fi
done
# report is Python (tools/shpb_report): a mutation fuzzer of its own, run when no target list was
# given and python3 can import matplotlib and numpy; SECONDS of its readers alone (many rounds),
# then SECONDS of --whole (the whole report each round: every figure and the page).
if [ $# -eq 0 ] && /usr/bin/python3 -c 'import matplotlib, numpy' 2>/dev/null; then
  (cd "$build" && /usr/bin/python3 "$here/fuzz_report.py" "$seconds") || failed=1
  (cd "$build" && /usr/bin/python3 "$here/fuzz_report.py" --whole "$seconds") || failed=1
fi
exit $failed
