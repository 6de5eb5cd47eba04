#!/usr/bin/python3
"""Does a change of the specimen's numerics move the loading? (figures, not assertions;
docs/methods.md §3.7;
docs/validation.md, "The specimen's faces after unloading")

Usage: tools/compare_loading.py BASE_SHPB NEW_SHPB [--converged] [simulate options...]

Runs every experiments/*/scene.json with a specimen through both executables (rigid links,
asynchronous and global stepping, the options given) and prints, per gauge on the bars next to
the specimen, the largest difference NEW − BASE over the gauge's peak while the specimen is
loaded: up to the instant the BASE run's face force, past its peak, first falls below
LOADED_SHARE of it, carried to the gauge at the bar's wave speed, less MAPPING_MARGIN_S. Then the
energy errors and the closings of the specimen (and pulse shaper) faces after their first release
(interfaces[].activations − 1), BASE -> NEW. The acceptance for a change at the faces is a
loading moved by at most 0.1 % of the peak.

--converged: also the gauges after the unloading against the converged run of the same scene
(NEW with --tolerance 0.5 % --stepping global): from the instant that run's face force, past its
peak, first falls below LOADED_SHARE of it, carried to the gauge, to the end of the record; RMS /
largest |run − converged| over the gauge's peak, BASE -> NEW (docs/validation.md, "End segments
from the faces' unloading").
"""
import csv
import json
import os
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
LOADED_SHARE = 0.9  # the unloading has begun once the face force is 10 % below its peak
MAPPING_MARGIN_S = 1e-6  # the face-to-gauge time is known to a record sample or two; a steep
# unloading front within it would count as a loading difference


def length_m(text):
    value, unit = text.split()
    return float(value) * {'m': 1.0, 'mm': 1e-3}[unit]


def face_force(rows, face):
    col = rows[0].index(face + '_force_N')
    return [float(r[0]) for r in rows[1:]], [float(r[col]) for r in rows[1:]]


def unloading_at_gauges(scene, run):
    """(gauge name, instant the unloading of `run` reaches it) for the gauges on the bars next to
    the specimen: its face force past its peak first below LOADED_SHARE of it, carried to the
    gauge at the bar's wave speed."""
    names = [b['name'] for b in scene['bars']]
    si = names.index(scene['specimen'])
    summary = json.load(open(os.path.join(run, 'summary.json')))
    rows = list(csv.reader(open(os.path.join(run, 'interfaces.csv'))))
    out = []
    for bi in (si - 1, si + 1):
        bar = scene['bars'][bi]
        length = length_m(bar['length'])
        b = summary['bars'][bi]
        c = b['courant'] * length / b['elements'] / b['time_step_s']
        face = f'{names[bi]}-{names[si]}' if bi < si else f'{names[si]}-{names[bi]}'
        t, f = face_force(rows, face)
        peak = max(range(len(f)), key=lambda k: f[k])
        unloading = next((t[k] for k in range(peak, len(f)) if f[k] < LOADED_SHARE * f[peak]), t[-1])
        for g in bar.get('gauges', []):
            x = length_m(g['position'])
            out.append((g['name'], unloading + ((length - x) if bi < si else x) / c))
    return out


def gauge_differences(reference, run, name, keep):
    """|run − reference| of gauge `name` at the record's samples whose time `keep` accepts, and the
    gauge's peak in the reference; None for a gauge no pulse reaches in the record."""
    ga = list(csv.reader(open(os.path.join(reference, 'gauges.csv'))))
    gb = list(csv.reader(open(os.path.join(run, 'gauges.csv'))))
    col = ga[0].index(name)
    top = max(abs(float(r[col])) for r in ga[1:])
    if top == 0:
        return None
    return [abs(float(q[col]) - float(p[col])) for p, q in zip(ga[1:], gb[1:])
            if keep(float(p[0]))], top


def compare(scene, base, new):
    cells = []
    for name, arrival in unloading_at_gauges(scene, base):
        found = gauge_differences(base, new, name, lambda t: t <= arrival - MAPPING_MARGIN_S)
        if found:
            d, top = found
            cells.append(f"{name} {100 * max(d) / top:.3f} %")
    return cells


def after_unloading(scene, converged, runs):
    """Per gauge: RMS / largest difference of each run from the converged one after the unloading
    reaches the gauge, over the gauge's peak (%)."""
    cells = []
    for name, arrival in unloading_at_gauges(scene, converged):
        figures = []
        for run in runs:
            found = gauge_differences(converged, run, name, lambda t: t >= arrival)
            if not found:
                break
            d, top = found
            rms = (sum(x * x for x in d) / len(d)) ** 0.5
            figures.append(f'{100 * rms / top:.3f} / {100 * max(d) / top:.2f}')
        if figures:
            cells.append(f'{name} ' + ' -> '.join(figures) + ' %')
    return cells


def closings(scene, summary):
    out = {}
    for i in summary['interfaces']:
        sides = i['name'].split('-')
        if (scene['specimen'] in sides or 'shaper' in sides) and i['method'] != 'bonded':
            out[i['name']] = max(0, i['activations'] - 1)
    return out


def main():
    if len(sys.argv) < 3:
        sys.exit(__doc__)
    base_exe, new_exe, options = sys.argv[1], sys.argv[2], sys.argv[3:]
    converged = '--converged' in options
    options = [o for o in options if o != '--converged']
    print('loading moved (largest |NEW - BASE| over the peak while loaded) | energy error | '
          'closings after the first release, BASE -> NEW')
    with tempfile.TemporaryDirectory() as work:
        for e in sorted(os.listdir(os.path.join(ROOT, 'experiments'))):
            path = os.path.join(ROOT, 'experiments', e, 'scene.json')
            if not os.path.isfile(path):
                continue
            scene = json.load(open(path))
            if 'specimen' not in scene:
                continue
            for stepping in ('asynchronous', 'global'):
                runs = []
                for k, exe in enumerate((base_exe, new_exe)):
                    out = os.path.join(work, str(k))
                    r = subprocess.run([exe, 'simulate', path, '-o', out, '-q', '--stepping',
                                        stepping, *options], capture_output=True)
                    runs.append(out if r.returncode == 0 else None)
                if None in runs:
                    print(f'{e:26s} {stepping:12s} a run failed')
                    continue
                sb, sn = (json.load(open(os.path.join(r, 'summary.json'))) for r in runs)
                if all(i['method'] == 'bonded' for i in sb['interfaces'] if scene['specimen'] in
                       i['name'].split('-')):
                    break
                cb, cn = closings(scene, sb), closings(scene, sn)
                cells = compare(scene, *runs)
                if not cells:  # a recorded pulse drives the bars (no pulse in the gauges' record)
                    break
                print(f'{e:26s} {stepping:12s} ' + ', '.join(cells) +
                      f" | {sb['energy_error']:.1e} -> {sn['energy_error']:.1e} | " +
                      ', '.join(f'{k} {cb[k]} -> {cn.get(k, "-")}' for k in cb), flush=True)
                if converged and stepping == 'asynchronous':
                    ref = os.path.join(work, 'converged')
                    r = subprocess.run([new_exe, 'simulate', path, '-o', ref, '-q', *options,
                                        '--tolerance', '0.5 %', '--stepping', 'global'],
                                       capture_output=True)
                    print(f'{e:26s} {"":12s} after the unloading against the converged run, RMS / '
                          'largest over the peak, BASE -> NEW: ' +
                          (', '.join(after_unloading(scene, ref, runs)) if r.returncode == 0
                           else 'the converged run failed'), flush=True)


main()
