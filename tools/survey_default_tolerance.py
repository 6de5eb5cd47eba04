#!/usr/bin/python3
"""The default run's gauge error on set-ups the experiments do not cover (docs/validation.md
"The default run beyond the experiments"): each set-up's default run (3.5 %, docs/methods.md §1.1)
against the study's reference (exact, or 8 x the automatic meshes recorded at 8 x the rate), with
the automatic meshes beside it, by `bench_simulator --defaults` (its columns: CPU of the mesh
choice, solve wall and CPU time, node updates, recorded gauge error, the model's prediction).

Usage: tools/survey_default_tolerance.py BUILD-DIR [WORK-DIR]

The set-ups are edits of experiments/classic-al6061 (unless named otherwise): bars of 0.5 and 1 m,
strikers of 50 mm–1 m, aluminium, titanium, magnesium (0.3–1 m strikers) and PMMA (viscoelastic) bars, a steel
striker on aluminium bars, bars of 8 and 40 mm, a 25 mm striker, specimens of L/D 0.3–2 and of
copper, Ti-6Al-4V and PMMA (specimens/), gauges 0.1–0.3 m from the specimen and 0.05–0.1 m from
the struck end, 5 and 30 m/s, global stepping, records of 1.2 and 2 ms and of 2 and 50 MHz, two
gauges on the incident bar; the tension test without its Courant number (gauges 0.1 and 0.2 m from
the specimen too), the pulse shaper with its disc and a 1 mm one, the striker-on-bar, LANL copper and
the mini-Kolsky bar edited likewise. Each scene is written to WORK-DIR/<set-up>/scene.json
(default /tmp/survey-default-tolerance), its material files named by their full paths.
"""
import copy
import json
import os
import subprocess
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
AL = {"model": "elastic", "density": "2810 kg/m3", "youngs_modulus": "71.7 GPa",
      "poisson_ratio": 0.33}
TI = {"model": "elastic", "density": "4430 kg/m3", "youngs_modulus": "114 GPa",
      "poisson_ratio": 0.34}
MG = {"model": "elastic", "density": "1780 kg/m3", "youngs_modulus": "45 GPa",
      "poisson_ratio": 0.35}
PMMA = {"model": "viscoelastic", "density": "1190 kg/m3", "poisson_ratio": 0.35,
        "long_term_modulus": "3 GPa",
        "arms": [{"modulus": "1.5 GPa", "relaxation_time": "1 ms"},
                 {"modulus": "1.2 GPa", "relaxation_time": "20 us"}]}


def specimen(name):
    return os.path.join(ROOT, 'specimens', name + '.json')


def load(experiment):
    """The experiment's scene, its material files by full path, without its measurement."""
    folder = os.path.join(ROOT, 'experiments', experiment)
    with open(os.path.join(folder, 'scene.json')) as f:
        scene = json.load(f)
    for b in scene['bars']:
        m = b['material']
        if isinstance(m, str) and m.endswith('.json'):
            b['material'] = os.path.normpath(os.path.join(folder, m))
    scene.pop('measurement', None)
    return scene


def bars(s):
    return {b['name']: b for b in s['bars']}


def bar_material(s, material, names=('striker', 'incident', 'transmitter')):
    s['materials']['bar'] = material
    for n in names:
        bars(s)[n]['material'] = 'bar'


def bar_lengths(s, length, gauge):
    for n in ('incident', 'transmitter'):
        bars(s)[n]['length'] = length
        bars(s)[n]['gauges'][0]['position'] = gauge
    s['simulation'].pop('duration', None)  # the automatic duration


def setups():
    classic = load('classic-al6061')
    out = {}

    def v(name, edit, base=classic):
        s = copy.deepcopy(base)
        edit(s)
        out[name] = s

    def striker(length=None, velocity=None):
        def edit(s):
            if length:
                bars(s)['striker']['length'] = length
                s['simulation'].pop('duration', None)
            if velocity:
                bars(s)['striker']['velocity'] = velocity
        return edit

    def spec(material=None, length=None, diameter=None, velocity=None):
        def edit(s):
            b = bars(s)['specimen']
            if material:
                b['material'] = specimen(material)
            if length:
                b['length'] = length
            if diameter:
                b['diameter'] = diameter
            if velocity:
                bars(s)['striker']['velocity'] = velocity
        return edit

    def gauges(incident, transmitted):
        def edit(s):
            bars(s)['incident']['gauges'][0]['position'] = incident
            bars(s)['transmitter']['gauges'][0]['position'] = transmitted
        return edit

    def diameter(bar_mm, spec_l, spec_d):
        def edit(s):
            for n in ('striker', 'incident', 'transmitter'):
                bars(s)[n]['diameter'] = bar_mm
            bars(s)['specimen'].update(length=spec_l, diameter=spec_d)
        return edit

    v('bars-0.5m', lambda s: (bar_lengths(s, '0.5 m', '0.25 m'),
                              bars(s)['striker'].update(length='150 mm')))
    v('bars-0.5m-striker-0.3m', lambda s: bar_lengths(s, '0.5 m', '0.25 m'))
    v('bars-1m', lambda s: bar_lengths(s, '1 m', '0.5 m'))
    v('striker-50mm', striker('50 mm'))
    v('striker-50mm-30m/s', striker('50 mm', '30 m/s'))
    v('striker-0.6m', striker('600 mm'))
    v('striker-1m', striker('1 m'))
    v('striker-25mm-diameter', lambda s: bars(s)['striker'].update(diameter='25 mm'))
    v('al-bars', lambda s: bar_material(s, AL))
    v('ti-bars', lambda s: bar_material(s, TI))
    v('mg-bars', lambda s: bar_material(s, MG))
    v('mg-bars-striker-0.6m', lambda s: (bar_material(s, MG), striker('600 mm')(s)))
    v('mg-bars-striker-1m', lambda s: (bar_material(s, MG), striker('1 m')(s)))
    v('steel-striker-al-bars', lambda s: bar_material(s, AL, ('incident', 'transmitter')))
    v('pmma-bars', lambda s: (bar_material(s, PMMA), striker(velocity='5 m/s')(s),
                              s['simulation'].pop('duration')))
    v('bars-8mm', diameter('8 mm', '2.5 mm', '5 mm'))
    v('bars-40mm', diameter('40 mm', '10 mm', '20 mm'))
    v('specimen-L/D-0.3', spec(length='3 mm'))
    v('specimen-L/D-2', spec(length='20 mm'))
    v('copper-L/D-1', spec('ofhc-copper', '10 mm'))
    v('ti6al4v-L/D-0.5-25m/s', spec('ti6al4v', velocity='25 m/s'))
    v('pmma-L/D-1-8m/s', spec('pmma', '10 mm', velocity='8 m/s'))
    v('gauges-0.1m-from-specimen', gauges('1.9 m', '0.1 m'))
    v('gauges-0.2m-from-specimen', gauges('1.8 m', '0.2 m'))
    v('gauges-0.3m-from-specimen', gauges('1.7 m', '0.3 m'))
    v('gauge-0.1m-from-struck-end', gauges('0.1 m', '1 m'))
    v('gauge-0.05m-from-struck-end-striker-0.6m', lambda s: (gauges('0.05 m', '1 m')(s),
                                                             striker('600 mm')(s)))
    v('striker-1m-gauges-0.2m', lambda s: (gauges('1.8 m', '0.2 m')(s), striker('1 m')(s)))
    v('two-incident-gauges', lambda s: bars(s)['incident']['gauges'].append(
        {'name': 'incident2', 'position': '0.5 m'}))
    v('record-2MHz', lambda s: s['simulation'].update(sample_rate='2 MHz'))
    v('record-50MHz', lambda s: s['simulation'].update(sample_rate='50 MHz'))
    v('5m/s', striker(velocity='5 m/s'))
    v('30m/s', striker(velocity='30 m/s'))
    v('global', lambda s: s['simulation'].update(stepping='global'))
    v('global-al-bars', lambda s: (bar_material(s, AL), s['simulation'].update(stepping='global')))
    v('global-striker-50mm', lambda s: (striker('50 mm')(s),
                                        s['simulation'].update(stepping='global')))
    v('record-1.2ms', lambda s: s['simulation'].update(duration='1.2 ms'))
    v('record-2ms', lambda s: s['simulation'].update(duration='2 ms'))
    v('al-bars-0.8m-striker-50mm-25m/s', lambda s: (
        bar_material(s, AL), bar_lengths(s, '0.8 m', '0.4 m'), gauges('0.6 m', '0.2 m')(s),
        striker('50 mm', '25 m/s')(s)))
    v('ti-bars-20mm-striker-0.6m-copper', lambda s: (
        bar_material(s, TI), diameter('20 mm', '4 mm', '8 mm')(s),
        spec('ofhc-copper')(s), striker('600 mm')(s)))
    tension = load('tension-bonded')
    v('tension', lambda s: s['simulation'].pop('courant'), tension)
    for d in ('0.1', '0.2'):
        v(f'tension-gauges-{d}m', lambda s, d=d: (
            s['simulation'].pop('courant'),
            [g.update(distance_to_specimen=f'{d} m') for b in s['bars']
             for g in b.get('gauges', [])]), tension)
    shaper = load('pulse-shaper')
    v('pulse-shaper', lambda s: None, shaper)
    v('pulse-shaper-1mm', lambda s: bars(s)['shaper'].update(length='1 mm'), shaper)
    bar = load('striker-on-bar')
    v('striker-on-bar-al-0.8m', lambda s: (
        s['materials'].update(steel=AL), bars(s)['bar'].update(length='0.8 m'),
        bars(s)['bar']['gauges'][0].update(position='0.4 m'), s['simulation'].pop('duration')), bar)
    v('striker-on-bar-striker-50mm', lambda s: bars(s)['striker'].update(length='50 mm'), bar)
    v('striker-on-bar-gauge-0.05m', lambda s: bars(s)['bar']['gauges'][0].update(
        position='0.05 m'), bar)
    copper = load('lanl-cu-ofe-273k')
    v('lanl-copper-striker-0.5m', striker('500 mm'), copper)
    v('lanl-copper-no-rise-10m/s', lambda s: (s['contact'].pop('interfaces'),
                                              striker(velocity='10 m/s')(s)), copper)
    mini = load('lanl-pmma13-mini-kolsky')
    v('mini-kolsky-striker-100mm', striker('100 mm'), mini)
    v('mini-kolsky-specimen-L/D-2', spec(length='3 mm'), mini)
    return out


def main():
    if len(sys.argv) < 2:
        sys.exit(__doc__)
    build = sys.argv[1]
    work = sys.argv[2] if len(sys.argv) > 2 else '/tmp/survey-default-tolerance'
    files = []
    for name, scene in setups().items():
        folder = os.path.join(work, name.replace('/', '_'))
        os.makedirs(folder, exist_ok=True)
        path = os.path.join(folder, 'scene.json')
        with open(path, 'w') as f:
            json.dump(scene, f, indent=1)
        files.append(path)
    print(f'{len(files)} set-ups', flush=True)
    subprocess.run([os.path.join(build, 'bench_simulator'), '--repeat', '1', '--defaults'] + files,
                   check=True)


if __name__ == '__main__':
    main()
