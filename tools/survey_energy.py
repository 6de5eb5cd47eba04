#!/usr/bin/python3
"""Energy balance of ordinary set-ups the experiments do not hold (docs/methods.md §3.7,
docs/validation.md "A law specimen that stays elastic").

Usage: tools/survey_energy.py SHPB [--shapers | --tension | --friction | --inertia | --coarse |
       --polymer] [other simulate options, e.g. --stepping global]

The classic experiment's layout (300 mm striker, 2 m bars of Ø19.05 mm, gauges at mid-length) with
its bars made of steel, aluminium or titanium (or a magnesium transmitter on steel, or an aluminium
striker on steel), a specimen of Al 6061-T6, OFHC copper, Ti-6Al-4V or PMMA (specimens/*.json) of
10 × 5, 16 × 2 or 6 × 6 mm (diameter × length), struck at 8 or 25 m/s: 144 scenes, each run by
`shpb simulate` at its defaults. Prints one line per run whose energy balance is off by more than
0.5 % or that did not exit 0 (exit code, energy error, closings per interface, stepping kept, first
warning), then the counts (and of the runs kept at global steps, repeated so: docs/methods.md
§3.7).

--shapers: instead, experiments/pulse-shaper (steel striker and bars, a copper disc) with discs of
3 × 16, 1 × 10 and 0.5 × 6 mm (length × diameter), the four specimens of 10 × 5 and 16 × 2 mm, at 10
and 25 m/s: 48 scenes (docs/methods.md §8.1, the strain a bar's steps are planned for).
--friction, --inertia: the 144 with face friction 0.1 (contact.friction), or with the specimen's
radial inertia on (docs/methods.md §8.2–8.3; the specimen then keeps the fixed step plan).
--tension: instead, experiments/tension-bonded (bonded specimen, striker pulled at 5 or 15 m/s, the
scene's Courant number left to the default) with steel, aluminium or titanium bars and the four
specimens or the scene's bilinear metal, of 10 × 5, 4 × 8 and 16 × 2 mm: 90 scenes.
--coarse: instead, bars meshed by hand with few elements, ties no end segment covers:
experiments/striker-on-bar with a steel, aluminium or titanium striker of 100 or 300 mm meshed by
1, 2, 3, 5, 10 or 20 elements on its steel bar (36 scenes), and tools/bench_scenes/elastic-classic
with an aluminium, titanium, steel or polycarbonate specimen of 1, 2 or 4 elements (12 scenes).
--polymer: instead, the polymer bars of tests/app/polymer_bars.hpp (viscoelastic PMMA, Ø20 mm, 2 m
incident and 1 m transmitter, gauges 1 m and 0.1 m from the specimen) struck by a 150 mm steel,
aluminium or PMMA striker at 2 or 10 m/s, a 5 × 15 mm specimen (length × diameter) soft elastic
(50 MPa), PMMA, viscoelastic or Al 6061-T6, 1.5 ms: 24 scenes (docs/methods.md §3.6, a metal
striker on polymer bars).
"""
import itertools
import json
import pathlib
import subprocess
import sys
import tempfile

ROOT = pathlib.Path(__file__).resolve().parent.parent
SHPB = sys.argv[1]
MODE = next((a for a in sys.argv[2:]
             if a in ("--shapers", "--tension", "--friction", "--inertia", "--coarse",
                      "--polymer")), "")
EXTRA = [a for a in sys.argv[2:] if a != MODE]
BARS = {"steel": ("8080 kg/m3", "200 GPa", 0.29), "al": ("2700 kg/m3", "70 GPa", 0.33),
        "ti": ("4430 kg/m3", "113.8 GPa", 0.342), "mg": ("1800 kg/m3", "45 GPa", 0.35),
        "pc": ("1200 kg/m3", "2.4 GPa", 0.37)}
LAYOUTS = [("steel", "steel", "steel"), ("steel", "steel", "al"), ("al", "al", "al"),
           ("ti", "ti", "ti"), ("steel", "steel", "mg"), ("al", "steel", "steel")]
SPECIMENS = {"al6061": "al6061-t6.json", "cu": "ofhc-copper.json", "ti": "ti6al4v.json",
             "pmma": "pmma.json"}
SHAPES = [("10 mm", "5 mm"), ("16 mm", "2 mm"), ("6 mm", "6 mm")]
VELOCITIES = [8, 25]
BOUND = 0.005  # the experiments' own bound on the energy balance

DISCS = [("3 mm", "16 mm"), ("1 mm", "10 mm"), ("0.5 mm", "6 mm")]


def elastic_materials(names=BARS):
    """The scene materials of the bar metals `names` (keys of BARS)."""
    return {name: {"model": "elastic", "density": BARS[name][0], "youngs_modulus": BARS[name][1],
                   "poisson_ratio": BARS[name][2]} for name in names}


def bars_scenes():
    base = json.loads((ROOT / "experiments/classic-al6061/scene.json").read_text())
    for layout, specimen, shape, velocity in itertools.product(LAYOUTS, SPECIMENS, SHAPES,
                                                               VELOCITIES):
        scene = json.loads(json.dumps(base))
        scene["materials"] = elastic_materials()
        for bar, material in zip([0, 1, 3], layout):
            scene["bars"][bar]["material"] = material
        scene["bars"][0]["velocity"] = f"{velocity} m/s"
        scene["bars"][2].update(material=str(ROOT / "specimens" / SPECIMENS[specimen]),
                                diameter=shape[0], length=shape[1])
        if MODE == "--friction":
            scene["contact"]["friction"] = 0.1
        if MODE == "--inertia":
            scene["bars"][2]["inertia"] = True
        yield (f"{'-'.join(layout)}_{specimen}_{shape[0].split()[0]}x{shape[1].split()[0]}_"
               f"{velocity}", scene)


def shaper_scenes():
    base = json.loads((ROOT / "experiments/pulse-shaper/scene.json").read_text())
    base["bars"][1]["material"] = str(ROOT / "specimens/pulse-shaper-copper.json")
    for disc, specimen, shape, velocity in itertools.product(DISCS, SPECIMENS, SHAPES[:2],
                                                             [10, 25]):
        scene = json.loads(json.dumps(base))
        scene["bars"][0]["velocity"] = f"{velocity} m/s"
        scene["bars"][1].update(length=disc[0], diameter=disc[1])
        scene["bars"][3].update(material=str(ROOT / "specimens" / SPECIMENS[specimen]),
                                diameter=shape[0], length=shape[1])
        yield (f"disc{disc[0].split()[0]}x{disc[1].split()[0]}_{specimen}_"
               f"{shape[0].split()[0]}x{shape[1].split()[0]}_{velocity}", scene)


def tension_scenes():
    base = json.loads((ROOT / "experiments/tension-bonded/scene.json").read_text())
    base.pop("measurement", None)
    base["simulation"].pop("courant", None)
    base["materials"].update(elastic_materials([name for name in BARS if name != "mg"]))
    specimens = dict(SPECIMENS, metal=None)
    for bars, specimen, shape, velocity in itertools.product(["steel", "al", "ti"], specimens,
                                                             [SHAPES[0], ("4 mm", "8 mm"),
                                                              SHAPES[1]], [5, 15]):
        scene = json.loads(json.dumps(base))
        for bar in (0, 1, 3):
            scene["bars"][bar]["material"] = bars
        scene["bars"][0]["velocity"] = f"{-velocity} m/s"
        if specimens[specimen]:
            scene["bars"][2]["material"] = str(ROOT / "specimens" / specimens[specimen])
        scene["bars"][2].update(diameter=shape[0], length=shape[1])
        yield (f"tension-{bars}_{specimen}_{shape[0].split()[0]}x{shape[1].split()[0]}_"
               f"{velocity}", scene)


def coarse_scenes():
    base = json.loads((ROOT / "experiments/striker-on-bar/scene.json").read_text())
    base["materials"] = elastic_materials()
    base["bars"][1]["material"] = "steel"
    for striker, length, elements in itertools.product(["steel", "al", "ti"], ["100 mm", "300 mm"],
                                                       [1, 2, 3, 5, 10, 20]):
        scene = json.loads(json.dumps(base))
        scene["bars"][0].update(material=striker, length=length, elements=elements)
        yield f"striker-{striker}-{length.split()[0]}mm-{elements}el", scene
    base = json.loads((ROOT / "tools/bench_scenes/elastic-classic.json").read_text())
    for material, elements in itertools.product(["al", "ti", "steel", "pc"], [1, 2, 4]):
        scene = json.loads(json.dumps(base))
        scene["materials"].update(elastic_materials())
        specimen = next(b for b in scene["bars"] if b["name"] == scene["specimen"])
        specimen.update(material=material, elements=elements)
        yield f"elastic-classic-{material}-{elements}el", scene


def polymer_scenes():
    pmma = {"model": "viscoelastic", "density": "1190 kg/m3", "poisson_ratio": 0.35,
            "long_term_modulus": "3 GPa",
            "arms": [{"modulus": "1.5 GPa", "relaxation_time": "1 ms"},
                     {"modulus": "1.2 GPa", "relaxation_time": "20 us"}]}
    specimens = {"soft": {"model": "elastic", "density": "1100 kg/m3", "youngs_modulus": "50 MPa",
                          "poisson_ratio": 0.45},
                 "pmma": str(ROOT / "specimens/pmma.json"),
                 "visco": {"model": "viscoelastic", "density": "1190 kg/m3", "poisson_ratio": 0.35,
                           "long_term_modulus": "1 GPa",
                           "arms": [{"modulus": "2 GPa", "relaxation_time": "30 us"}]},
                 "al6061": str(ROOT / "specimens/al6061-t6.json")}
    for striker, specimen, velocity in itertools.product(["steel", "al", "pmma"], specimens,
                                                         [2, 10]):
        bar = {"material": "pmma", "diameter": "20 mm"}
        scene = {"bars": [dict(bar, name="striker", material=striker, length="0.15 m",
                               velocity=f"{velocity} m/s"),
                          dict(bar, name="incident", length="2 m",
                               gauges=[{"name": "incident", "distance_to_specimen": "1 m"}]),
                          {"name": "specimen", "material": specimens[specimen], "length": "5 mm",
                           "diameter": "15 mm"},
                          dict(bar, name="transmitter", length="1 m",
                               gauges=[{"name": "transmitted", "distance_to_specimen": "0.1 m"}])],
                 "specimen": "specimen",
                 "materials": dict(elastic_materials(["steel", "al"]), pmma=pmma),
                 "simulation": {"duration": "1.5 ms"}}
        yield f"polymer-{striker}_{specimen}_{velocity}", scene


SCENES = {"--shapers": shaper_scenes, "--tension": tension_scenes,
          "--coarse": coarse_scenes, "--polymer": polymer_scenes}.get(MODE, bars_scenes)
off = failed = runs = repeated = 0
with tempfile.TemporaryDirectory() as tmp:
    for name, scene in SCENES():
        runs += 1
        path = pathlib.Path(tmp) / f"{name}.json"
        path.write_text(json.dumps(scene))
        out = pathlib.Path(tmp) / name
        run = subprocess.run([SHPB, "simulate", str(path), "-o", str(out), "-q", *EXTRA],
                             capture_output=True, text=True)
        summary = out / "summary.json"
        if not summary.exists():
            failed += 1
            print(f"{name}: exit {run.returncode}: {run.stderr.strip()[:160]}")
            continue
        s = json.loads(summary.read_text())
        bad = run.returncode != 0 or abs(s["energy_error"]) > BOUND
        off += abs(s["energy_error"]) > BOUND
        failed += run.returncode != 0
        repeated += s["stepping"] != "asynchronous"
        if bad:
            closings = "/".join(str(i["activations"]) for i in s["interfaces"])
            warning = s["warnings"][0][:120] if s["warnings"] else ""
            print(f"{name}: exit {run.returncode}, energy error {s['energy_error']:.2e}, "
                  f"closings {closings}, {s['stepping']}; {warning}")
print(f"{off} runs off by more than {100 * BOUND:g} %, {failed} not exit 0, of {runs} "
      f"({repeated} kept at global steps)")
