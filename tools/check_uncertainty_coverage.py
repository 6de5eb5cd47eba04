#!/usr/bin/python3
"""Coverage of `process`'s Monte Carlo intervals against a known truth (docs/validation.md,
"Coverage against a known truth, through the command line"; docs/methods.md §10).

Usage: tools/check_uncertainty_coverage.py SHPB [TESTS=200] [DRAWS=200] [NOISE=0] [common] [quiet-record]
                                            [noise-only]

The classic Al 6061-T6 scene is simulated once; its gauges become half-bridge volts. Each of TESTS
labs types the truth off by a draw of the declared uncertainties (per channel, or `common`: one
error shared by both channels, then declared with measurement.uncertainty.shared; `quiet-record`:
measurement.uncertainty.record_noise false, the draws without the record's noise; `noise-only`: the
lab's values exact, no trigger delay and none of them declared uncertain, so the record's noise is
its only error), adds white noise of NOISE x the incident peak and an unknown trigger delay, and
runs `process --draws DRAWS`. The
truth is the same reduction with the true values. Prints, per headline figure: the tests, the
coverage of nominal +- 1 standard uncertainty and of the 95 % interval, the s.d. and mean of
(nominal - truth)/u, and the median relative u in %; then, for the 3-wave stress and the strain
rate of curve.csv, the share of the rows (strain 0.01 to the truth's largest) whose 95 % band holds
the truth's value at that strain (where its strain first reaches it), over all tests, and its
median over the tests.
"""
import json, os, shutil, subprocess, sys, tempfile
import numpy as np

SHPB = sys.argv[1]
N = int(sys.argv[2]) if len(sys.argv) > 2 else 200
DRAWS = int(sys.argv[3]) if len(sys.argv) > 3 else 200
NOISE = float(sys.argv[4]) if len(sys.argv) > 4 else 0.0   # white noise, fraction of incident peak
COMMON = 'common' in sys.argv[5:]
QUIET_RECORD = 'quiet-record' in sys.argv[5:]
NOISE_ONLY = 'noise-only' in sys.argv[5:]

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.dirname(HERE)
WORK = tempfile.mkdtemp(prefix='shpb-coverage-')
SCENE0 = json.load(open(os.path.join(REPO, 'experiments/classic-al6061/scene.json')))
subprocess.run([SHPB, 'simulate', os.path.join(REPO, 'experiments/classic-al6061/scene.json'), '-o', WORK + '/sim', '-q'], check=True)
g = np.genfromtxt(WORK + '/sim/gauges.csv', delimiter=',', names=True)
t = g['time_s']; dt = t[1] - t[0]
GF, VEX, GAIN, ARMS = 2.06, 8.0, 200.0, 2
U = dict(gauge_factor=0.01, excitation=0.005, gain=0.005, E=0.01, rho=0.005, bar_d=0.01e-3,
         spec_l=0.02e-3, spec_d=0.02e-3, pos=1e-3, delay=0.2e-6)

def volts(eps, gf, vex, gain):
    return eps * gf * gain * vex / (4 / ARMS)

def scene(lab, csv, truth=False):
    s = json.loads(json.dumps(SCENE0))
    s['materials']['steel-c350'] = dict(model='elastic', density='8080 kg/m3', youngs_modulus='200 GPa', poisson_ratio=0.29)
    mats = {}
    for b in s['bars']:
        if b['name'] == 'specimen':
            b['material'] = os.path.join(REPO, 'specimens/al6061-t6.json')
            b['length'] = '%.9g m' % lab['spec_l']; b['diameter'] = '%.9g m' % lab['spec_d']
        elif b['name'] in ('incident', 'transmitter'):
            k = b['name']
            name = 'steel-' + k
            mats[name] = dict(model='elastic', density='%.9g kg/m3' % lab['rho_' + k],
                              youngs_modulus='%.9g Pa' % lab['E_' + k], poisson_ratio=0.29)
            b['material'] = name
            b['diameter'] = '%.9g m' % lab['d_' + k]
            b['gauges'][0]['position'] = '%.9g m' % lab['pos_' + k]
    s['materials'].update(mats)
    ch = []
    for gname, k in (('incident', 'inc'), ('transmitted', 'tr')):
        ch.append(dict(gauge=gname, column=gname, unit='V',
                       bridge=dict(arms=ARMS, gauge_factor=lab['gf_' + k], excitation='%.9g V' % lab['vex_' + k], gain=lab['gain_' + k])))
    s['measurement'] = dict(file=csv, channels=ch, dispersion=dict(correction='none'),
        uncertainty=dict(**({'shared': ['gauge_factor','excitation','gain']} if COMMON else {}), gauge_factor='%g %%' % (100 * U['gauge_factor']), excitation='%g %%' % (100 * U['excitation']),
                         gain='%g %%' % (100 * U['gain']), gauge_position='%g mm' % (U['pos'] * 1e3),
                         trigger_delay='%g us' % (U['delay'] * 1e6),
                         bars=dict(incident=dict(youngs_modulus='%g %%' % (100 * U['E']), density='%g %%' % (100 * U['rho']), diameter='%g mm' % (U['bar_d'] * 1e3)),
                                   transmitter=dict(youngs_modulus='%g %%' % (100 * U['E']), density='%g %%' % (100 * U['rho']), diameter='%g mm' % (U['bar_d'] * 1e3)),
                                   specimen=dict(length='%g mm' % (U['spec_l'] * 1e3), diameter='%g mm' % (U['spec_d'] * 1e3)))))
    if NOISE_ONLY and not truth: s['measurement']['uncertainty'] = {}
    if QUIET_RECORD: s['measurement']['uncertainty']['record_noise'] = False
    return s

TRUE = dict(spec_l=5e-3, spec_d=10e-3, E_incident=200e9, E_transmitter=200e9, rho_incident=8080, rho_transmitter=8080,
            d_incident=19.05e-3, d_transmitter=19.05e-3, pos_incident=1.0, pos_transmitter=1.0,
            gf_inc=GF, gf_tr=GF, vex_inc=VEX, vex_tr=VEX, gain_inc=GAIN, gain_tr=GAIN)

def run(lab, vin, vtr, d, draws, truth=False):
    os.makedirs(d, exist_ok=True)
    csv = os.path.join(d, 'rec.csv')
    np.savetxt(csv, np.column_stack([t, vin, vtr]), delimiter=',', header='time_s,incident,transmitted', comments='', fmt='%.9g')
    sc = os.path.join(d, 'scene.json'); json.dump(scene(lab, csv, truth), open(sc, 'w'))
    args = [SHPB, 'process', sc, '-o', os.path.join(d, 'out'), '--quiet', '--threads', '1']
    if draws: args += ['--draws', str(draws), '--seed', '7']
    else:
        s = json.load(open(sc)); del s['measurement']['uncertainty']; json.dump(s, open(sc, 'w'))
    r = subprocess.run(args, capture_output=True, text=True)
    if r.returncode: raise SystemExit(r.stderr)
    s = json.load(open(os.path.join(d, 'out', 'summary.json')))
    s['curve'] = np.genfromtxt(os.path.join(d, 'out', 'curve.csv'), delimiter=',', names=True, deletechars='')
    return s

def first_reach(x, y, v):
    # y where x first reaches v (linear between the samples where x reaches a new maximum)
    keep = x >= np.maximum.accumulate(x)
    keep[1:] &= np.diff(np.maximum.accumulate(x)) > 0
    return np.interp(v, x[keep], y[keep], left=np.nan, right=np.nan)

BANDS = [('stress_3wave_Pa', 'stress_3wave_p2.5_Pa', 'stress_3wave_p97.5_Pa'), ('strain_rate_1_s', 'strain_rate_p2.5_1_s', 'strain_rate_p97.5_1_s')]
def band_hits(curve, truth_curve):
    out = {}
    for col, lo, hi in BANDS:
        x = curve['strain']; tv = first_reach(truth_curve['strain'], truth_curve[col], x)
        ok = np.isfinite(tv) & np.isfinite(curve[lo]) & (x >= 0.01)
        out[col] = ((curve[lo][ok] <= tv[ok]) & (tv[ok] <= curve[hi][ok]))
    return out

vin0 = volts(g['incident'], GF, VEX, GAIN); vtr0 = volts(g['transmitted'], GF, VEX, GAIN)
truth_run = run(TRUE, vin0, vtr0, WORK + '/truth', 2, truth=True)
truth, truth_curve = truth_run['uncertainty']['figures'], truth_run['curve']
bands = []
FIG = ['peak_stress_Pa', 'max_strain', 'flow_stress_Pa_at_strain_0.05', 'flow_stress_Pa_at_strain_0.1', 'mean_strain_rate_1_s', 'plateau_strain_rate_1_s', 'striker_velocity_m_s']
rng = np.random.default_rng(12345)
peak = np.max(np.abs(vin0))
rows = []
for k in range(N):
    z = lambda: rng.standard_normal()
    lab = dict(TRUE)
    for b in ('incident', 'transmitter'):
        lab['E_' + b] = 200e9 * (1 + U['E'] * z()); lab['rho_' + b] = 8080 * (1 + U['rho'] * z())
        lab['d_' + b] = 19.05e-3 + U['bar_d'] * z(); lab['pos_' + b] = 1.0 + U['pos'] * z()
    lab['spec_l'] = 5e-3 + U['spec_l'] * z(); lab['spec_d'] = 10e-3 + U['spec_d'] * z()
    zc = [z(), z(), z()]
    for c in ('inc', 'tr'):
        zz = zc if COMMON else [z(), z(), z()]
        lab['gf_' + c] = GF * (1 + U['gauge_factor'] * zz[0]); lab['vex_' + c] = VEX * (1 + U['excitation'] * zz[1]); lab['gain_' + c] = GAIN * (1 + U['gain'] * zz[2])
    delay = U['delay'] * z()
    if NOISE_ONLY: lab, delay = dict(TRUE), 0.0
    vtr = np.interp(t - delay, t, vtr0)
    vin = vin0 + NOISE * peak * rng.standard_normal(len(t)); vtr = vtr + NOISE * peak * rng.standard_normal(len(t))
    s = run(lab, vin, vtr, WORK + '/k', DRAWS)
    figs = s['uncertainty']['figures']
    bands.append(band_hits(s['curve'], truth_curve))
    row = {}
    for f in FIG:
        if f not in figs: continue
        row[f] = (figs[f]['nominal'], figs[f]['standard_uncertainty'], figs[f]['interval_95'], figs[f]['median'])
    rows.append(row)
shutil.rmtree(WORK)
print('%d tests x %d draws, noise %g of the incident peak, errors %s%s' % (N, DRAWS, NOISE, 'none (noise only)' if NOISE_ONLY else 'common (declared shared)' if COMMON else 'per channel', ', draws without the record noise' if QUIET_RECORD else ''))
print('%-32s %5s %7s %7s %7s %8s %8s' % ('figure', 'n', 'cov68', 'cov95', 'sd(z)', 'mean(z)', 'med u%'))
for f in truth:
    zs, us, c95, c68 = [], [], 0, 0
    for r in rows:
        if f not in r: continue
        nom, sd, (lo, hi), med = r[f]; tv = truth[f]['nominal']
        c95 += lo <= tv <= hi; c68 += abs(nom - tv) <= sd; zs.append((nom - tv) / sd); us.append(sd / abs(tv))
    if zs:
        n = len(zs)
        print('%-32s %5d %7.3f %7.3f %7.2f %8.2f %8.3f' % (f, n, c68 / n, c95 / n, np.std(zs), np.mean(zs), 100 * np.median(us)))
print('%-32s %9s %9s %9s' % ('band (95 %) at each strain', 'rows', 'coverage', 'median'))
for col, lo, hi in BANDS:
    hits = [b[col] for b in bands]
    allh = np.concatenate(hits)
    print('%-32s %9d %9.3f %9.3f' % (col, len(allh), allh.mean() if len(allh) else np.nan, np.median([h.mean() for h in hits if len(h)])))
