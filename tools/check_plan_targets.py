#!/usr/bin/python3
"""`shpb plan`'s proposals against their targets (docs/validation.md, "Planning a test").

Usage: tools/check_plan_targets.py SHPB [specimen]

Each target (rate, strain) for Al 6061-T6, OFHC copper, Ti-6Al-4V and PMMA is planned on the
unshaped classic bars (experiments/plan-al6061/unshaped.json: striker 100 mm–1 m at 2–40 m/s,
specimen 3–5 mm); the verification run's gauges (simulation/gauges.csv) are processed with
`process --signals`. Prints the chosen set-up, the plan's predicted median rate, the specimen's
median rate over the plan's loading, `process`'s plateau and mean rate over its whole loading, the
strain predicted / simulated / processed, the wall time, band and equilibrium; or plan's exit-3 line.
"""
import json, os, shutil, subprocess, sys, tempfile, time
import numpy as np
SHPB = sys.argv[1]
ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
WORK = tempfile.mkdtemp(prefix='shpb-plan-')
cases = [(m, r, e) for m, r, e in [
    ('al6061-t6', 500, 0.1), ('al6061-t6', 2500, 0.3), ('al6061-t6', 5000, 0.15),
    ('ofhc-copper', 500, 0.2), ('ofhc-copper', 1500, 0.3), ('ofhc-copper', 3000, 0.2), ('ofhc-copper', 5000, 0.2),
    ('ti6al4v', 1000, 0.1), ('ti6al4v', 2500, 0.15), ('ti6al4v', 5000, 0.1),
    ('pmma', 500, 0.1), ('pmma', 1500, 0.1), ('pmma', 3000, 0.2)]]
if len(sys.argv) > 2: cases = [c for c in cases if c[0] == sys.argv[2]]
base = json.load(open(ROOT + '/experiments/plan-al6061/unshaped.json'))
print('%-12s %6s %5s | %-28s | %8s %8s %8s %8s | %6s %6s %6s | %s' % ('specimen', 'target', 'E', 'chosen', 'pred', 'median', 'proc_pl', 'proc_mn', 'E_pred', 'E_sim', 'E_proc', 'note'))
for mat, rate, strain in cases:
    d = os.path.join(WORK, '%s-%d-%g' % (mat, rate, strain))
    s = json.loads(json.dumps(base))
    s['bars'][0]['material'] = s['bars'][1]['material'] = s['bars'][3]['material'] = 'steel-c350'
    s['bars'][2]['material'] = ROOT + '/specimens/%s.json' % mat
    os.makedirs(d, exist_ok=True)
    json.dump(s, open(d + '/scene.json', 'w'))
    t0 = time.time()
    r = subprocess.run(['nice', '-n', '19', SHPB, 'plan', d + '/scene.json', '--rate', str(rate), '--strain', str(strain), '-o', d + '/out', '-q', '--threads', '1'], capture_output=True, text=True)
    wall = time.time() - t0
    if r.returncode:
        print('%-12s %6d %5g | exit %d (%.0f s): %s' % (mat, rate, strain, r.returncode, wall, r.stderr.strip()[-250:])); continue
    j = json.load(open(d + '/out/summary.json')); c = j['chosen']; p = j['predicted']
    sp = np.genfromtxt(d + '/out/simulation/specimen.csv', delimiter=',', names=True)
    rr = sp['strain_rate_1_s']; e = sp['strain']
    k0 = np.argmax(rr >= 0.1 * rate); k1 = k0 + np.argmax(e[k0:])  # the loading: to the strain maximum
    med = np.median(rr[k0:k1 + 1])
    pr = subprocess.run([SHPB, 'process', d + '/out/scene.json', '--signals', d + '/out/simulation/gauges.csv', '-o', d + '/proc', '-q'], capture_output=True, text=True)
    if pr.returncode: print(mat, rate, 'process failed', pr.stderr[-200:]); continue
    q = json.load(open(d + '/proc/summary.json'))
    pl = q['strain_rate']['plateau_1_s']; mn = q['strain_rate']['mean_over_loading_1_s']
    chosen = '%3.0fmm %5.2fm/s L%.1fmm' % (1e3 * c['striker_length_m'], c['striker_velocity_m_s'], 1e3 * c.get('specimen_length_m', 0))
    pred = p['plateau_rate_1_s']
    print('%-12s %6d %5g | %-28s | %8.0f %8.0f %8s %8.0f | %6.3f %6.3f %6.3f | %.0f s, band %.0f %%, eq %.0f %%' % (
        mat, rate, strain, chosen, pred, med, '%.0f' % pl if pl else 'none', mn, p['strain_reached'], e.max(), q['max_strain'], wall,
        100 * p['band_fraction'], 100 * p['equilibrium_fraction']), flush=True)
    for w in j.get('warnings', []): print('    warning:', w[:200])
shutil.rmtree(WORK)
