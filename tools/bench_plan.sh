#!/usr/bin/env bash
# `shpb plan` on the classic Al 6061-T6 bars (experiments/plan-al6061): targets 1000, 2500 and
# 5000 1/s at strain 0.15, with a copper pulse shaper allowed (scene.json) and without one
# (unshaped.json) side by side, then 20 000 1/s (beyond the striker's velocity bound: exit 3).
# Prints each plan's wall time, the chosen set-up and its predicted band fraction and equilibrium,
# then the planned scene re-simulated on its own at --tolerance 0.5 % with the band measured from
# that run's specimen.csv and equilibrium from its interfaces.csv (the bars' forces on the faces,
# what the gauges measure), not the planner's numbers. Ends with the shaper's gain: the chosen
# set-up's rate flatness beside the best unshaped and shaped ones' (summary.json `unshaped`,
# `shaped`).
# Usage: tools/bench_plan.sh [build-dir] [threads]
set -euo pipefail
BUILD=${1:-build}
THREADS=${2:-2}
cd "$(dirname "$0")/.."
WORK=$(mktemp -d)
trap 'rm -rf "$WORK"' EXIT
: > "$WORK/gain.txt"

# Band fraction and equilibrium of a simulation folder, measured as docs/methods.md §12 defines
# them (R of the forces on the specimen's faces, the denominator floored at 2 % of its peak).
measure() {
  /usr/bin/python3 - "$1" "$2" <<'PY'
import csv, sys
def columns(f):
    rows = list(csv.reader(open(f)))
    return {n: [float(r[i]) for r in rows[1:]] for i, n in enumerate(rows[0])}
s, i = columns(sys.argv[1] + "/specimen.csv"), columns(sys.argv[1] + "/interfaces.csv")
R = float(sys.argv[2])
t, e, rate = s["time_s"], s["strain"], s["strain_rate_1_s"]
f, b = i["incident-specimen_force_N"], i["specimen-transmitter_force_N"]
# The loading: the rate first at a tenth of the target to the strain maximum; equilibrium judged
# until unloading, the loading's last rate within the band.
k0 = next(k for k, x in enumerate(rate) if x >= 0.1 * R)
k1 = max(range(k0, len(e)), key=lambda k: (e[k], -k))
band = sum(abs(x - R) <= 0.1 * R for x in rate[k0:k1 + 1]) / (k1 - k0 + 1)
unloading = max([k for k in range(k0, k1 + 1) if abs(rate[k] - R) <= 0.1 * R], default=k0)
peak = max(abs(x + y) for x, y in zip(f, b))
keq = k0
for k in range(k0, unloading + 1):
    if 2 * abs(f[k] - b[k]) > 0.05 * max(abs(f[k] + b[k]), 0.02 * peak):
        keq = k + 1
eq = (t[min(keq, k1)] - t[k0]) / (t[k1] - t[k0])
print("  re-simulated at 0.5 %%: rate in band over %.0f %% of the loading (>= 50 %%), "
      "equilibrium at %.0f %% of it (<= 25 %%), strain %.3f" % (100 * band, 100 * eq, max(e)))
PY
}

for rate in 1000 2500 5000; do
  for scene in scene unshaped; do
    out="$WORK/$scene-$rate"
    echo "== $rate 1/s, experiments/plan-al6061/$scene.json"
    t0=$(date +%s.%N)
    set +e
    nice -n 19 "$BUILD"/shpb plan "experiments/plan-al6061/$scene.json" --rate "$rate" \
      -o "$out" --threads "$THREADS" -q
    rc=$?
    set -e
    printf "  exit %d, wall %.1f s\n" "$rc" "$(echo "$(date +%s.%N) - $t0" | bc)"
    [ "$rc" -eq 0 ] || continue
    /usr/bin/python3 -c "
import json; j = json.load(open('$out/summary.json')); c = j['chosen']; p = j['predicted']
sh = c['shaper']
print('  striker %.0f mm at %.2f m/s, %s; %d change(s); predicted band %.0f %%, equilibrium %.0f %%, spread %.3f'
      % (1e3 * c['striker_length_m'], c['striker_velocity_m_s'],
         'shaper %.2f mm x %.1f mm' % (1e3 * sh['thickness_m'], 1e3 * sh['diameter_m']) if sh else 'no shaper',
         j['changes'], 100 * p['band_fraction'], 100 * p['equilibrium_fraction'], p['rate_spread']))"
    [ "$scene" = scene ] && /usr/bin/python3 -c "
import json; j = json.load(open('$out/summary.json'))
def side(p, u=None):
    text = 'band %.0f %%, spread %.3f, equilibrium %.0f %%' % (
        100 * p['band_fraction'], p['rate_spread'], 100 * p['equilibrium_fraction'])
    return text + ('' if u is None else ', ' + ('meets' if u['meets'] else 'misses'))
print('$rate 1/s: chosen %s | best unshaped %s | best shaped %s' % (side(j['predicted']),
      *(side(j[k]['predicted'], j[k]) if j[k] else 'none searched' for k in ('unshaped', 'shaped'))))
" >> "$WORK/gain.txt"
    nice -n 19 "$BUILD"/shpb simulate "$out/scene.json" -o "$out/check" --tolerance "0.5 %" -q
    measure "$out/check" "$rate"
  done
done
echo "== the shaper's gain (scene.json): the chosen set-up beside the best unshaped and shaped ones"
cat "$WORK/gain.txt"
echo "== 20000 1/s (beyond the bounds)"
set +e
nice -n 19 "$BUILD"/shpb plan experiments/plan-al6061/scene.json --rate 20000 -o "$WORK/x" \
  --threads "$THREADS" -q
echo "  exit $?"
