#!/usr/bin/python3
"""Coverage of `process`'s Monte Carlo intervals against the simulated specimen itself
(docs/validation.md, "Coverage against the specimen's own curve"; docs/methods.md §10).

Usage: tools/check_uncertainty_specimen_coverage.py SHPB SETUP [TESTS=60] [DRAWS=200] [SEED=1] [OPTIONS]

SETUP: classic (experiments/classic-al6061), cu (experiments/lanl-cu-ofe-273k, its uncertainty
block's magnitudes), pmma (experiments/lanl-pmma13-mini-kolsky), cu-al (the classic bars in Al
7075-T6, an OFHC copper specimen). Each of TESTS true tests draws its bars' modulus and density,
bar and specimen sizes, gauge positions, bridge factors and a trigger delay from the declared
standard uncertainties, is SIMULATED with them, its gauges turned into half-bridge volts with the
true bridge and delayed by the true delay, and processed with the NOMINAL scene and the declared
`measurement.uncertainty` (`--draws DRAWS`, no dispersion correction: a 1D record). The truth is the
simulation's specimen.csv (engineering stress and strain rate where its strain first reaches e;
its maximum strain). OPTIONS, comma separated: `ws` (bars' wave speed and density uncertain, the
modulus ρc0²), `shared` (bridge errors common to both channels, declared shared), `onsets`,
`onewave` (measurement.align / primary), `key=value` (a standard uncertainty: gauge_factor,
excitation, gain, E, rho relative; bar_d, spec_l, spec_d, pos in m, delay in s; None drops it),
`keep` (keep each test's scenes, record and outputs), `tolerance=1%` (simulate's gauge error: at
its default 3.5 % the coarse bars ring, an error of the record no input declares).
Prints per quantity: tests, coverage of the 95 % interval with its Wilson 95 % interval, the median
half-width, the s.d. and mean of (nominal − truth), relative, and half-width / (1.96 s.d.).
"""
import copy, json, os, shutil, subprocess, sys, tempfile
import numpy as np

SHPB, SETUP = sys.argv[1], sys.argv[2]
N = int(sys.argv[3]) if len(sys.argv) > 3 else 60
DRAWS = int(sys.argv[4]) if len(sys.argv) > 4 else 200
SEED = int(sys.argv[5]) if len(sys.argv) > 5 else 1
OPTS = sys.argv[6].split(',') if len(sys.argv) > 6 else []
REPO = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
GF, VEX, GAIN, ARMS = 2.06, 8.0, 200.0, 2
UNIT = {'mm': 1e-3, 'm': 1, 'GPa': 1e9, 'kg/m3': 1, 'm/s': 1}


def scene_of(path, specimen=None, bar=None):
    s = json.load(open(os.path.join(REPO, path)))
    s.pop('measurement', None)
    for b in s['bars']:
        if b['name'] == 'specimen' and not b['material'] in s.get('materials', {}):
            b['material'] = os.path.join(REPO, 'specimens', specimen or os.path.basename(b['material']))
    if bar:
        s['materials']['steel-c350'].update(bar)
    return s


# Standard uncertainties (relative: gauge_factor, excitation, gain, E, rho; else SI).
U0 = dict(gauge_factor=0.01, excitation=0.005, gain=0.005, E=0.01, rho=0.005, bar_d=0.01e-3,
          spec_l=0.02e-3, spec_d=0.02e-3, pos=1e-3, delay=0.2e-6)
SETUPS = {
    'classic': (lambda: scene_of('experiments/classic-al6061/scene.json'), U0, [0.02, 0.05, 0.1, 0.15]),
    'cu': (lambda: scene_of('experiments/lanl-cu-ofe-273k/scene.json'),
           dict(U0, gauge_factor=0.0029, excitation=0.001, spec_l=0.01e-3, spec_d=0.01e-3, delay=0.1e-6),
           [0.02, 0.05, 0.1]),
    'pmma': (lambda: scene_of('experiments/lanl-pmma13-mini-kolsky/scene.json'),  # bars by area
             dict(U0, bar_d=None, spec_d=None, pos=0.5e-3, spec_l=0.01e-3, delay=0.1e-6),
             [0.005, 0.01, 0.02, 0.03]),
    'cu-al': (lambda: scene_of('experiments/classic-al6061/scene.json', 'ofhc-copper.json',
                               dict(density='2810 kg/m3', youngs_modulus='71.7 GPa', poisson_ratio=0.33)),
              U0, [0.02, 0.05, 0.1, 0.15]),
}
make, U, STRAINS = SETUPS[SETUP]
U = dict(U)
TOLERANCE = None  # simulate's --tolerance (its default: the scene's, else 3.5 %)
for o in OPTS:
    if o.startswith('tolerance='):
        TOLERANCE = o.split('=')[1]
    elif '=' in o:
        k, v = o.split('=')
        U[k] = None if v == 'None' else float(v)
NOM = make()


def qty(v):
    x, u = v.split()
    return float(x) * UNIT[u]


def bar(s, name):
    return next(b for b in s['bars'] if b['name'] == name)


def true_test(rng):
    """A true scene and bridge/delay drawn from the declared uncertainties."""
    s = copy.deepcopy(NOM)
    z = rng.standard_normal
    for name in ('incident', 'transmitter'):
        b = bar(s, name)
        m = dict(s['materials'][b['material']])
        E0, rho0 = qty(m['youngs_modulus']), qty(m['density'])
        rho = rho0 * (1 + U['rho'] * z())
        E = E0 * (1 + U['E'] * z())
        if 'ws' in OPTS:
            E = rho * ((E0 / rho0) ** 0.5 * (1 + U['E'] * z())) ** 2
        m['youngs_modulus'], m['density'] = '%.12g GPa' % (E / 1e9), '%.12g kg/m3' % rho
        b['material'] += '-' + name
        s['materials'][b['material']] = m
        if U['bar_d'] and 'diameter' in b:
            b['diameter'] = '%.12g m' % (qty(b['diameter']) + U['bar_d'] * z())
        g = b['gauges'][0]
        g['position'] = '%.12g m' % (qty(g['position']) + U['pos'] * z())
    b = bar(s, 'specimen')
    b['length'] = '%.12g m' % (qty(b['length']) + U['spec_l'] * z())
    if U['spec_d'] and 'diameter' in b:
        b['diameter'] = '%.12g m' % (qty(b['diameter']) + U['spec_d'] * z())
    common = z(3)
    p = {}
    for c in ('incident', 'transmitted'):
        e = common if 'shared' in OPTS else z(3)
        p[c] = GF * (1 + U['gauge_factor'] * e[0]) * VEX * (1 + U['excitation'] * e[1]) * \
            GAIN * (1 + U['gain'] * e[2]) / (4 / ARMS)  # volts per strain
    p['delay'] = U['delay'] * z() if U['delay'] else 0.0
    return s, p


def lab_scene(csv):
    """The nominal scene reading the record, with its declared uncertainties."""
    s = copy.deepcopy(NOM)
    ch = [dict(gauge=g, column=g, unit='V', bridge=dict(arms=ARMS, gauge_factor=GF, excitation='%g V' % VEX, gain=GAIN))
          for g in ('incident', 'transmitted')]
    pc = lambda k: '%g %%' % (100 * U[k])
    u = dict(gauge_factor=pc('gauge_factor'), excitation=pc('excitation'), gain=pc('gain'),
             gauge_position='%g mm' % (U['pos'] * 1e3))
    if U['delay']:
        u['trigger_delay'] = '%g us' % (U['delay'] * 1e6)
    bu = dict(wave_speed=pc('E'), density=pc('rho')) if 'ws' in OPTS else dict(youngs_modulus=pc('E'), density=pc('rho'))
    if U['bar_d']:
        bu['diameter'] = '%g mm' % (U['bar_d'] * 1e3)
    su = dict(length='%g mm' % (U['spec_l'] * 1e3))
    if U['spec_d']:
        su['diameter'] = '%g mm' % (U['spec_d'] * 1e3)
    u['bars'] = dict(incident=bu, transmitter=dict(bu), specimen=su)
    if 'shared' in OPTS:
        u['shared'] = ['gauge_factor', 'excitation', 'gain']
    s['measurement'] = dict(file=csv, channels=ch, dispersion=dict(correction='none'), uncertainty=u)
    if 'onsets' in OPTS:
        s['measurement']['align'] = 'onsets'
    if 'onewave' in OPTS:
        s['measurement']['primary'] = '1-wave'
    return s


def first_reach(x, y, e):
    """y where x first reaches e (linear between samples), None if never."""
    i = int(np.argmax(x >= e))
    if x[i] < e:
        return None
    if i == 0:
        return y[0]
    f = (e - x[i - 1]) / (x[i] - x[i - 1])
    return y[i - 1] + f * (y[i] - y[i - 1])


def run(k, s, p, work):
    d = os.path.join(work, str(k))
    os.makedirs(d, exist_ok=True)
    json.dump(s, open(d + '/true.json', 'w'))
    subprocess.run([SHPB, 'simulate', d + '/true.json', '-o', d + '/sim', '-q'] + (['--tolerance', TOLERANCE] if TOLERANCE else []),
                   check=True, capture_output=True)
    g = np.genfromtxt(d + '/sim/gauges.csv', delimiter=',', names=True)
    t = g['time_s']
    vin, vtr = g['incident'] * p['incident'], np.interp(t - p['delay'], t, g['transmitted'] * p['transmitted'])
    csv = d + '/rec.csv'
    np.savetxt(csv, np.column_stack([t, vin, vtr]), delimiter=',', header='time_s,incident,transmitted', comments='', fmt='%.10g')
    json.dump(lab_scene(csv), open(d + '/lab.json', 'w'))
    r = subprocess.run([SHPB, 'process', d + '/lab.json', '-o', d + '/out', '-q', '--draws', str(DRAWS), '--seed', str(k + 1)],
                       capture_output=True, text=True)
    if r.returncode:
        raise SystemExit(r.stderr)
    names = dict(delimiter=',', names=True)  # numpy drops the '.' of p2.5 / p97.5
    return (np.genfromtxt(d + '/sim/specimen.csv', **names), np.genfromtxt(d + '/out/curve.csv', **names),
            json.load(open(d + '/out/summary.json'))['uncertainty']['figures'])


def compare(sp, cv, figures):
    """(truth, nominal, low, high) of each quantity with an interval."""
    top = int(np.argmax(sp['strain']))  # the specimen's loading
    e_t, s_t, r_t = sp['strain'][:top + 1], sp['stress_Pa'][:top + 1], sp['strain_rate_1_s'][:top + 1]
    one = 'onewave' in OPTS
    x = cv['strain_1wave'] if one else cv['strain']
    rate = cv['strain_rate_1wave_1_s'] if one else cv['strain_rate_1_s']
    row = {}
    for e in STRAINS:
        for q, truth, nominal, band in (('stress_3wave', s_t, cv['stress_3wave_Pa'], 'stress_3wave_p%s_Pa'),
                                        ('stress_1wave', s_t, cv['stress_1wave_Pa'], 'stress_1wave_p%s_Pa'),
                                        ('strain_rate', r_t, rate, 'strain_rate_p%s_1_s')):
            v = [first_reach(e_t, truth, e), first_reach(x, nominal, e),
                 first_reach(x, cv[band % '25'], e), first_reach(x, cv[band % '975'], e)]
            if None not in v and np.all(np.isfinite(v)):
                row['%s at %g' % (q, e)] = v
    for name, f in figures.items():
        truth = None
        if name.startswith('flow_stress_Pa_at_strain_'):
            truth = first_reach(e_t, s_t, float(name.rsplit('_', 1)[1]))
        elif name == 'max_strain':
            truth = e_t[-1]
        elif name == 'striker_velocity_m_s':
            truth = qty(bar(NOM, 'striker')['velocity'])
        if truth is not None:
            row[name] = [truth, f['nominal']] + f['interval_95']
    return row


work = tempfile.mkdtemp(prefix='shpb-specimen-coverage-')
rng = np.random.default_rng(1000 + SEED)
rows = [compare(*run(k, *true_test(rng), work)) for k in range(N)]
if 'keep' in OPTS:
    print('tests kept in', work)
else:
    shutil.rmtree(work)
print('%s: %d tests x %d draws, options %s' % (SETUP, N, DRAWS, ','.join(OPTS) or 'none'))
print('%-34s %4s %6s %14s %8s %8s %8s %6s' % ('quantity', 'n', 'cov95', 'Wilson 95 %', 'half-w%', 'sd%', 'bias%', 'w/sd'))
for q in sorted({q for r in rows for q in r}):
    tv, nom, lo, hi = np.array([r[q] for r in rows if q in r], dtype=float).T
    n = len(tv)
    c = np.mean((lo <= tv) & (tv <= hi))
    z = 1.96
    mid, hw = (c + z * z / (2 * n)) / (1 + z * z / n), z * np.sqrt(c * (1 - c) / n + z * z / (4 * n * n)) / (1 + z * z / n)
    err = (nom - tv) / np.abs(tv)
    half = np.median((hi - lo) / 2 / np.abs(tv))
    sd = np.std(err)
    print('%-34s %4d %6.3f   [%.2f, %.2f] %8.2f %8.2f %8.2f %6.2f' % (q, n, c, mid - hw, mid + hw, 100 * half, 100 * sd,
                                                                   100 * np.mean(err), half / (z * sd) if sd > 0 else np.inf))
