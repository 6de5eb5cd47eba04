#!/usr/bin/python3
"""The specimen faces' closings after unloading as the meshes are refined (figures, not assertions;
docs/methods.md §3.7; docs/validation.md, "The specimen's faces after unloading"):
is the rattle the model's physics or its discretization?

Usage: tools/rattle_convergence.py [build/shpb] [experiment ...]
       (default: classic-al6061 lanl-cu-ofe-273k lanl-pmma13-mini-kolsky)

For each experiment, links (rigid, then finite: contact.stiffness_factor 1e4 at every rigid interface),
stepping (global, then asynchronous) and mesh — the default, --tolerance 1 %
and 0.5 %, every bar's elements k x the default run's (k = 1, 2, 4, and 8 when the k = 4 run
predicts it under a minute), and the bars alone refined ("bars k": 4, 6, 8, 20 x, the specimen kept, so
that the bars' cut-off frequency rises above the specimen's element-scale ringing), and the specimen
alone coarsened ("spec N": 3, 6 elements, the bars at the default run's) — prints one line per
specimen face:
  elements per bar (striker/incident/specimen/transmitter), wall time of the full run;
  t_r, the face's unloading (summary.json interfaces[].unloading_s: its first opening after its
  force's peak)
  (each face's windows below are after its own; a face never released says so);
  closings after the first release (summary.json interfaces[].activations - 1), total and per
  window after t_r: before t_r | 0-10 | 10-40 | 40-100 | 100+ us, counted exactly by re-running
  the same scene to t_r + 10, 40, 100 us (the solver is deterministic and causal);
  the face force's RMS over the loading peak in the same windows (%), the specimen's stress
  (specimen.csv stress_Pa) RMS over its peak in the same windows (%: its ringing), the largest gap after t_r;
  the timing of the closings: their count in the record (100 MHz with explicit elements, else the
  scene's rate), the meetings after t_r (summary.json interfaces[].meetings_after_unloading), the
  closings "felt" (the force rising through 0.1 % of the loading peak), the median interval
  between the closings seen; the specimen's fundamental period 2L/c (L deformed, at the end of the
  run; c = Courant x h / step from summary.json), its element transit h/c, and the dominant period
  (below 5 us) of the specimen's stress (its ringing) over 40 us after t_r.
Runs one simulation at a time under nice -n 19; the three experiments take about 9 minutes (the classic 7).
"""
import json
import os
import subprocess
import sys
import tempfile
import time

import numpy as np

from experiment_variant import finite_links, linked_scene

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
EXE = sys.argv[1] if len(sys.argv) > 1 else os.path.join(ROOT, 'build', 'shpb')
EXPERIMENTS = sys.argv[2:] or ['classic-al6061', 'lanl-cu-ofe-273k', 'lanl-pmma13-mini-kolsky']
WINDOWS_US = (10, 40, 100)  # window edges after the unloading
SAMPLE_RATE = '100 MHz'  # finer than the specimens' element transits (>= 20 ns) at k <= 4
K8_BUDGET_S = 60  # the k = 8 refinement only when predicted under a minute
BAND_PERIOD_S = 5e-6  # the ringing's period is sought below 5 us (the specimens' 2L/c < 2 us)
RING_WINDOW_S = 40e-6  # ... over the first 40 us after the unloading, while the specimen rings
FELT = 1e-3  # a closing whose force reaches 0.1 % of the loading peak: what a gauge could see
FINITE = 1e4  # contact.stiffness_factor of the finite links
BARS_ONLY_K = (4, 6, 8, 20)  # the bars alone refined, the specimen at the default run's elements
SPECIMEN_ONLY = (3, 6)  # the specimen alone coarsened to these elements, the bars at the default's


def scene_copy(experiment, work, elements=None, duration_s=None, finite=False):
    """The experiment's scene (tools/experiment_variant.py) with explicit elements per bar (then
    recorded at SAMPLE_RATE), a shorter duration and/or finite links at every rigid interface."""
    def edit(scene):
        if elements:  # a finer record would make a tolerance choose finer meshes
            scene.setdefault('simulation', {})['sample_rate'] = SAMPLE_RATE
        if duration_s is not None:
            scene['simulation']['duration'] = f'{duration_s * 1e6:.6f} us'
        if elements:
            for b in scene['bars']:
                b['elements'] = elements[b['name']]
        if finite:
            finite_links(scene, FINITE)
    path, scene = linked_scene(experiment, work, edit)
    return path, scene['specimen']


def run(scene, out, options):
    t0 = time.time()
    r = subprocess.run(['nice', '-n', '19', EXE, 'simulate', scene, '-o', out, '-q', *options],
                       capture_output=True, text=True)
    if r.returncode:
        raise RuntimeError(f'exit {r.returncode}: {r.stderr.strip()}')
    return json.load(open(os.path.join(out, 'summary.json'))), time.time() - t0


def faces(summary, specimen):
    return [i['name'] for i in summary['interfaces']
            if specimen in i['name'].split('-') and i['method'] != 'bonded']


def closings(summary, name):
    return max(0, next(i for i in summary['interfaces'] if i['name'] == name)['activations'] - 1)


def record(out, name):
    rows = np.loadtxt(os.path.join(out, 'interfaces.csv'), delimiter=',', skiprows=1)
    head = open(os.path.join(out, 'interfaces.csv')).readline().strip().split(',')
    return rows[:, 0], rows[:, head.index(name + '_force_N')], rows[:, head.index(name + '_gap_m')]


def face(summary, name):
    return next(i for i in summary['interfaces'] if i['name'] == name)


def measure(experiment, work, elements, options, finite):
    path, specimen = scene_copy(experiment, work, elements, finite=finite)
    out = os.path.join(work, 'full')
    summary, wall = run(path, out, options)
    names = faces(summary, specimen)
    recs = {n: record(out, n) for n in names}
    releases = [face(summary, n)['unloading_s'] for n in names]
    bars = {b['name']: b for b in summary['bars']}
    spec = bars[specimen]
    value, unit = next(b for b in json.load(open(path))['bars']
                       if b['name'] == specimen)['length'].split()
    assert unit == 'mm', 'the specimens measured here are given in mm'
    h = float(value) * 1e-3 / spec['elements']
    c = spec['courant'] * h / spec['time_step_s']
    spec_rec = np.loadtxt(os.path.join(out, 'specimen.csv'), delimiter=',', skiprows=1)
    ts, strain, stress = spec_rec[:, 0], spec_rec[-1, 1], spec_rec[:, 3]
    L = h * spec['elements'] * (1 - strain)  # the deformed specimen's length at the end
    result = {'elements': '/'.join(str(b['elements']) for b in summary['bars']), 'wall': wall,
              'L_c': L / c, 'h_c': h / c, 'faces': {}}
    if any(r is None for r in releases):
        for n in names:
            result['faces'][n] = {'total': closings(summary, n), 'released': False}
        return result, summary
    release = dict(zip(names, releases))
    result['t_r'] = min(releases)
    edges = {n: [t_r] + [t_r + w * 1e-6 for w in WINDOWS_US] for n, t_r in release.items()}
    cumulative = {}  # (face, instant) -> closings after the first release up to that instant
    for e in sorted({e for v in edges.values() for e in v}):
        if e >= summary['duration_s']:
            for n in names:
                cumulative[(n, e)] = closings(summary, n)
            continue
        s, _ = run(scene_copy(experiment, work, elements, e, finite)[0],
                   os.path.join(work, 'cut'), options)
        if [b['elements'] for b in s['bars']] != [b['elements'] for b in summary['bars']]:
            raise RuntimeError('a shorter run chose other meshes: windows not counted')
        for n in names:
            cumulative[(n, e)] = closings(s, n)
    for n in names:
        t, f, g = recs[n]
        t_r = release[n]
        total = closings(summary, n)
        cum = [cumulative[(n, e)] for e in edges[n]] + [total]
        counts = [cum[0]] + [cum[k + 1] - cum[k] for k in range(len(cum) - 1)]
        peak = f.max()
        rms = []
        bounds = edges[n] + [t[-1] + 1]
        ringing = []  # the specimen's mean stress, RMS over its loading peak, per window
        for a, b in zip(bounds[:-1], bounds[1:]):
            m = (t >= a) & (t < b)
            rms.append(100 * np.sqrt(np.mean(f[m] ** 2)) / peak if m.any() else float('nan'))
            m = (ts >= a) & (ts < b)
            ringing.append(100 * np.sqrt(np.mean(stress[m] ** 2)) / np.abs(stress).max()
                           if m.any() else float('nan'))
        m = t >= t_r
        onsets = t[1:][(f[1:] > 0) & (f[:-1] <= 0) & (t[1:] > t_r)]
        gaps = np.diff(onsets)
        level = FELT * peak
        felt = int(np.sum((f[1:] > level) & (f[:-1] <= level) & (t[1:] > t_r)))
        ring = (ts >= t_r) & (ts < t_r + RING_WINDOW_S)
        x = np.polyval(np.polyfit(ts[ring], stress[ring], 1), ts[ring]) - stress[ring]
        spectrum = np.abs(np.fft.rfft(x * np.hanning(x.size), 8 * x.size))
        freqs = np.fft.rfftfreq(8 * x.size, ts[1] - ts[0])
        band = freqs > 1 / BAND_PERIOD_S
        dominant = 1 / freqs[band][int(np.argmax(spectrum[band]))] if band.any() else float('nan')
        meetings = face(summary, n)['meetings_after_unloading']
        result['faces'][n] = {'released': True, 't_r': t_r, 'total': total, 'counts': counts, 'rms': rms,
                              'ringing': ringing,
                              'max_gap': g[m].max(), 'seen': onsets.size, 'meetings': meetings,
                              'felt': felt,
                              'interval': float(np.median(gaps)) if gaps.size else float('nan'),
                              'dominant': dominant}
    return result, summary


def line(label, stepping, r):
    head = f"{label:10s} {stepping:13s} {r['elements']:>24s} {r['wall']:6.1f}s"
    out = []
    for n, x in r['faces'].items():
        if not x['released']:
            out.append(f"{head}  {n:22s} {x['total']:5d}  never released")
            continue
        counts = ' '.join(f'{c:4d}' for c in x['counts'])
        rms = ' '.join(f'{v:6.3f}' for v in x['rms'])
        ringing = ' '.join(f'{v:6.3f}' for v in x['ringing'])
        out.append(f"{head}  {n:22s} t_r {1e6 * x['t_r']:7.2f} us {x['total']:5d} | {counts} | rms% {rms} | stress% {ringing} | gap "
                   f"{1e9 * x['max_gap']:7.1f} nm | seen {x['seen']:4d}, {x['meetings']:3d} meetings, "
                   f"{x['felt']:3d} felt, median "
                   f"{1e6 * x['interval']:6.3f} us | 2L/c {2e6 * r['L_c']:5.3f} h/c "
                   f"{1e6 * r['h_c']:5.3f} ringing {1e6 * x['dominant']:6.3f} us")
    return '\n'.join(out)


print('mesh       links, step   elements striker/inc/spec/tr   wall  face                   '
      'unloading     total | '
      'pre 0-10 10-40 40-100 100+ | rms% 0-10 10-40 40-100 100+ | stress% (same windows) | '
      'largest gap | timing')
with tempfile.TemporaryDirectory() as work:
    for e in EXPERIMENTS:
        print(f'== {e} (windows in us after each face\'s unloading t_r)', flush=True)
        for finite in (False, True):
            for stepping in ('global', 'async'):
                tag = ('finite ' if finite else 'rigid ') + stepping
                options = ['--stepping', 'global' if stepping == 'global' else 'asynchronous']
                base = None
                for label, extra in (('default', []), ('tol 1 %', ['--tolerance', '1 %']),
                                     ('tol 0.5 %', ['--tolerance', '0.5 %'])):
                    try:
                        r, s = measure(e, work, None, options + extra, finite)
                    except RuntimeError as err:
                        print(f'{label:10s} {tag:13s} {err}', flush=True)
                        continue
                    if label == 'default':
                        base = {b['name']: b['elements'] for b in s['bars']}
                    print(line(label, tag, r), flush=True)
                wall = 0
                for k in (1, 2, 4, 8):
                    if base is None:
                        break
                    if k == 8 and wall * 4 > K8_BUDGET_S:
                        print(f'k 8        {tag:13s} skipped (k 4 took {wall:.0f} s)', flush=True)
                        continue
                    try:
                        r, s = measure(e, work, {n: k * v for n, v in base.items()}, options,
                                       finite)
                    except RuntimeError as err:
                        print(f'k {k:<8d} {tag:13s} {err}', flush=True)
                        continue
                    wall = r['wall']
                    print(line(f'k {k}', tag, r), flush=True)
                specimen = json.load(open(os.path.join(ROOT, 'experiments', e, 'scene.json')))['specimen']
                # The bars' cut-off raised above the specimen's ringing, or that ringing lowered
                # to the bars' cut-off.
                variants = [] if base is None else (
                    [(f'bars k {k}', {n: v * (1 if n == specimen else k) for n, v in base.items()})
                     for k in BARS_ONLY_K] +
                    [(f'spec {n}', {**base, specimen: n}) for n in SPECIMEN_ONLY])
                for label, elements in variants:
                    try:
                        r, s = measure(e, work, elements, options, finite)
                    except RuntimeError as err:
                        print(f'{label:10s} {tag:13s} {err}', flush=True)
                        continue
                    print(line(label, tag, r), flush=True)
