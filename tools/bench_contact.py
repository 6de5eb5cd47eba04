#!/usr/bin/python3
"""Energy balance near C = 1 and the specimen faces' closings after unloading (figures, not
assertions; docs/methods.md §3.7;
docs/validation.md, "The specimen's faces after unloading").

Usage: tools/bench_contact.py [build/shpb] [K ...]

1. Energy error (summary.json energy_error) of every experiments/*/scene.json and the elastic
   classic scene at the default, --tolerance 0.5 / 1 / 3.5 / 10 % and --courant 0.995 / 0.9995 /
   0.9999 / 1 (asynchronous); '*' marks a run beyond 0.5 %, 'exit N' a refused or unstable one.
   Left out when refinements K are given.
2. For every experiment with a specimen, each specimen (and pulse shaper) face after its unloading,
   as summary.json interfaces[] reports it (docs/outputs.md, methods.md §3.7): the unloading's
   instant, the closings after it, the meetings among them and the largest contact force after it
   over the loading peak, for rigid links and finite links (contact.stiffness_factor 1e4),
   asynchronous and global, at the default meshes (those of the default tolerance, 3.5 %) and at
   every bar's elements K x the default run's for each K given; then the share of the record's
   samples after the unloading in which the face is closed and its mean gap: a face pinned to its
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
ARGS = [a for a in sys.argv[1:] if not a.isdigit()]
EXE = ARGS[0] if ARGS else os.path.join(ROOT, 'build', 'shpb')
REFINE = [int(a) for a in sys.argv[1:] if a.isdigit()]  # mesh refinements of the closings table
EXPERIMENTS = sorted(d for d in os.listdir(os.path.join(ROOT, 'experiments'))
                     if os.path.isfile(os.path.join(ROOT, 'experiments', d, 'scene.json')))
ENERGY_LIMIT = 5e-3  # the half per cent a gauge can bear


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


def after_unloading(interfaces_csv, name, unloading_s):
    """The share of the record's samples from the face's unloading (summary.json
    interfaces[].unloading_s) on in which the face is closed, and its mean gap there [m]."""
    rows = list(csv.reader(open(interfaces_csv)))
    col = rows[0].index(name + '_force_N')
    gap_col = rows[0].index(name + '_gap_m')
    after = [r for r in rows[1:] if float(r[0]) >= unloading_s]
    if not after:
        return 0.0, 0.0
    closed = sum(1 for r in after if float(r[col]) > 0) / len(after)
    return closed, sum(float(r[gap_col]) for r in after) / len(after)


def refined_scene(experiment, work, k, finite, stepping):
    """The experiment's scene with every bar's elements k x those of its default run at `stepping`
    (explicit elements withhold the tolerance) and, if `finite`, finite links."""
    out = os.path.join(work, 'm')
    if simulate(os.path.join(ROOT, 'experiments', experiment, 'scene.json'), out,
                '--stepping', stepping):
        return None
    elements = {b['name']: b['elements'] for b in
                json.load(open(os.path.join(out, 'summary.json')))['bars']}

    def edit(scene):
        for b in scene['bars']:
            b['elements'] = k * elements[b['name']]
        if finite:
            finite_links(scene, 1e4)
    return linked_scene(experiment, work, edit)[0]


def closings_table(work, refinements):
    print('\n== specimen faces after their unloading (summary.json interfaces[]): closings / '
          'meetings / largest force over the peak / closed share of the samples / mean gap; '
          'default meshes, then elements k x the default run\'s at the same stepping')
    for e in EXPERIMENTS:
        scene = json.load(open(os.path.join(ROOT, 'experiments', e, 'scene.json')))
        if 'specimen' not in scene:
            continue
        for links in ('rigid', 'finite'):
            for k in refinements:
                mesh = 'default' if k is None else f'k {k:<5d}'
                for stepping in ('asynchronous', 'global'):
                    if k is None:  # the experiment's default meshes
                        path = os.path.join(ROOT, 'experiments', e, 'scene.json') \
                            if links == 'rigid' else finite_links_scene(e, work)
                    else:
                        path = refined_scene(e, work, k, links == 'finite', stepping)
                    out = os.path.join(work, 'c')
                    rc = simulate(path, out, '--stepping', stepping) if path else -1
                    if rc:
                        print(f'{e:26s} {links:6s} {mesh} {stepping:12s} exit {rc}')
                        continue
                    summary = json.load(open(os.path.join(out, 'summary.json')))
                    cells = []
                    for i in summary['interfaces']:
                        sides = i['name'].split('-')
                        if (scene['specimen'] not in sides and 'shaper' not in sides) or \
                                i['method'] == 'bonded':
                            continue
                        if i['unloading_s'] is None:
                            cells.append(f"{i['name']} never unloaded")
                            continue
                        closed, gap = after_unloading(os.path.join(out, 'interfaces.csv'),
                                                      i['name'], i['unloading_s'])
                        cells.append(f"{i['name']} {1e6 * i['unloading_s']:.1f} us: "
                                     f"{i['closings_after_unloading']} / "
                                     f"{i['meetings_after_unloading']} / "
                                     f"{100 * i['force_after_unloading_share']:.3f} % / "
                                     f"{100 * closed:.0f} % / {1e9 * gap:.1f} nm")
                    if not cells:  # bonded faces never open
                        break
                    print(f"{e:26s} {links:6s} {mesh} {stepping:12s} "
                          f"energy {summary['energy_error']:.1e}  " + ';  '.join(cells), flush=True)


with tempfile.TemporaryDirectory() as work:
    if not REFINE:
        energy_table(work)
    closings_table(work, [None] + REFINE)
