#!/usr/bin/python3
"""Energy balance near C = 1 and the specimen faces' closings after unloading (figures, not
assertions; docs/methods.md §3.7;
docs/validation.md, "The specimen's faces after unloading").

Usage: tools/bench_contact.py [build/shpb]

1. Energy error (summary.json energy_error) of every experiments/*/scene.json and the elastic
   classic scene at the default, --tolerance 0.5 / 1 / 3.5 / 10 % and --courant 0.995 / 0.9995 /
   0.9999 / 1 (asynchronous); '*' marks a run beyond 0.5 %, 'exit N' a refused or unstable one.
2. For every experiment with a specimen: closings of each specimen (and pulse shaper) face after
   its first release
   (interfaces[].activations - 1), "meetings" (closings more than the specimen's L/c = 1 us apart,
   from interfaces.csv at the record's rate) and the largest contact force after the release over
   the loading peak, for rigid links and finite links (contact.stiffness_factor 1e4), asynchronous
   and global, at the default meshes (those of the default tolerance, 3.5 %); then the share of the record's
   samples after the release in which the face is closed and its mean gap: a face pinned to its
   bar (closed most of the time, mean gap within a nm) or a specimen floating between separating
   bars (closed a few % of the time, mean gap of order 100 nm) — the two regimes measured there.
"""
import csv
import json
import os
import subprocess
import sys
import tempfile

from experiment_variant import finite_links, linked_scene

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
EXE = sys.argv[1] if len(sys.argv) > 1 else os.path.join(ROOT, 'build', 'shpb')
EXPERIMENTS = sorted(d for d in os.listdir(os.path.join(ROOT, 'experiments'))
                     if os.path.isfile(os.path.join(ROOT, 'experiments', d, 'scene.json')))
ENERGY_LIMIT = 5e-3  # the half per cent a gauge can bear
MEETING_GAP_S = 1e-6  # closings closer than a specimen transit L/c belong to one meeting


def simulate(scene, out, *options):
    r = subprocess.run([EXE, 'simulate', scene, '-o', out, '-q', *options], capture_output=True)
    return r.returncode


def energy_table(work):
    scenes = [(e, os.path.join(ROOT, 'experiments', e, 'scene.json')) for e in EXPERIMENTS]
    scenes.append(('elastic-classic', os.path.join(ROOT, 'tools/bench_scenes/elastic-classic.json')))
    runs = [('default', [])] + [('tol ' + t, ['--tolerance', t + ' %']) for t in
                                ('0.5', '1', '3.5', '10')] + \
           [('C ' + c, ['--courant', c]) for c in ('0.995', '0.9995', '0.9999', '1')]
    print('== energy error, asynchronous (* beyond 0.5 %)')
    print(f"{'scene':26s}" + ''.join(f'{n:>10s}' for n, _ in runs))
    for name, scene in scenes:
        cells = []
        for _, options in runs:
            out = os.path.join(work, 'e')
            rc = simulate(scene, out, *options)
            if rc:
                cells.append(f'exit {rc}')
                continue
            e = json.load(open(os.path.join(out, 'summary.json')))['energy_error']
            cells.append(f"{e:.1e}{'*' if e > ENERGY_LIMIT else ''}")
        print(f'{name:26s}' + ''.join(f'{c:>10s}' for c in cells), flush=True)


def finite_links_scene(experiment, work):
    """The experiment's scene with finite links (stiffness_factor 1e4) at every interface it
    leaves rigid (tools/experiment_variant.py)."""
    return linked_scene(experiment, work, lambda scene: finite_links(scene, 1e4))[0]


def after_release(interfaces_csv, name):
    """Meetings, the largest force after the face's first release over the loading peak, the share
    of the samples after it in which the face is closed and its mean gap there [m]."""
    rows = list(csv.reader(open(interfaces_csv)))
    col = rows[0].index(name + '_force_N')
    gap_col = rows[0].index(name + '_gap_m')
    t = [float(r[0]) for r in rows[1:]]
    f = [float(r[col]) for r in rows[1:]]
    g = [float(r[gap_col]) for r in rows[1:]]
    peak = max(range(len(f)), key=lambda k: f[k])
    start = next((k for k in range(peak, len(f)) if f[k] <= 0), None)
    if start is None:
        return 0, 0.0, 1.0, 0.0
    meetings, last = 0, None
    for k in range(start, len(f)):
        if f[k] > 0:
            if last is None or t[k] - last > MEETING_GAP_S:
                meetings += 1
            last = t[k]
    n = len(f) - start
    closed = sum(1 for x in f[start:] if x > 0) / n
    return meetings, max(f[start:]) / f[peak] if f[peak] > 0 else 0.0, closed, sum(g[start:]) / n


def closings_table(work, meshes, options):
    print(f'\n== specimen faces after their first release ({meshes}): closings / meetings / '
          'largest force over the peak / closed share of the samples / mean gap')
    for e in EXPERIMENTS:
        scene = json.load(open(os.path.join(ROOT, 'experiments', e, 'scene.json')))
        if 'specimen' not in scene:
            continue
        for links in ('rigid', 'finite'):
            path = os.path.join(ROOT, 'experiments', e, 'scene.json') if links == 'rigid' \
                else finite_links_scene(e, work)
            for stepping in ('asynchronous', 'global'):
                out = os.path.join(work, 'c')
                rc = simulate(path, out, '--stepping', stepping, *options)
                if rc:
                    print(f'{e:26s} {links:6s} {stepping:12s} exit {rc}')
                    continue
                summary = json.load(open(os.path.join(out, 'summary.json')))
                cells = []
                for i in summary['interfaces']:
                    sides = i['name'].split('-')
                    if (scene['specimen'] not in sides and 'shaper' not in sides) or \
                            i['method'] == 'bonded':
                        continue
                    meetings, force, closed, gap = after_release(
                        os.path.join(out, 'interfaces.csv'), i['name'])
                    cells.append(f"{i['name']} {max(0, i['activations'] - 1)} / {meetings} / "
                                 f"{100 * force:.1f} % / {100 * closed:.0f} % / {1e9 * gap:.1f} nm")
                if not cells:  # bonded faces never open
                    break
                print(f"{e:26s} {links:6s} {stepping:12s} energy {summary['energy_error']:.1e}  " +
                      ';  '.join(cells), flush=True)


with tempfile.TemporaryDirectory() as work:
    energy_table(work)
    closings_table(work, 'default meshes', [])
