#!/usr/bin/python3
"""Face friction across specimens and set-ups (docs/validation.md "The specimen as it really
deforms"): each set-up is simulated with contact.friction mu and without, processed by
`shpb process --signals` as is and with measurement.corrections.friction, and compared with the
specimen's law along its own path, in the law's terms (docs/methods.md §8.2).

  /usr/bin/python3 tools/survey_friction.py build/shpb OUT_DIR [--rate-filter] [--jobs 2]

Specimens: specimens/ Al 6061-T6, OFHC copper, Ti-6Al-4V (Johnson-Cook), PMMA (viscoelastic), the
copper pulse-shaper law and a steel-like bilinear law (E 200 GPa, yield 500 MPa, E_t 3 GPa);
10 mm diameter at L/D 0.3, 0.5, 1; steel and aluminium bars of 19.05 mm; four striker speeds
each; mu 0, 0.05, 0.1, 0.2. Then friction with the specimen's radial inertia and with a copper
pulse shaper. Per set-up: median true strain rate, largest strain, and the medians (over all
samples past 2 % flow strain in equilibrium, and over the last third of that flow strain) of
  mu0   processed / law, frictionless twin
  raw   processed uncorrected / (law x phi)
  corr  processed with corrections.friction / law
  spec  specimen.csv true stress / (law x phi) over the processed curve's window
phi = 1 + mu d/(3 sqrt 3 L) of the volume-conserving shape. The law's heating and elastic strain
come from its own stress, the true stress over phi. --rate-filter gives the Johnson-Cook
specimens a 1 us strain_rate_filter (docs/scene-format.md). The summary counts the set-ups at
1000-5000 /s whose raw or corr ratios miss 1 %.
"""
import argparse
import csv
import json
import math
import os
import subprocess
import sys
from concurrent.futures import ThreadPoolExecutor

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from johnson_cook_vs_curve import quantity  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
SPECIMENS = os.path.join(ROOT, "specimens")
BARS = {"steel": {"model": "elastic", "density": 8080, "youngs_modulus": "200 GPa",
                  "poisson_ratio": 0.29},
        "aluminium": {"model": "elastic", "density": 2810, "youngs_modulus": "71.7 GPa",
                      "poisson_ratio": 0.33}}
BILINEAR_STEEL = {"model": "bilinear", "density": 7850, "youngs_modulus": "200 GPa",
                  "poisson_ratio": 0.29, "yield_stress": "500 MPa", "tangent_modulus": "3 GPa"}
# Specimen: its file (or law) and striker speeds (m/s) spanning about 1000-5000 /s.
LAWS = {"Al 6061-T6": ("al6061-t6.json", [6, 10, 16, 24]),
        "OFHC copper": ("ofhc-copper.json", [6, 10, 16, 24]),
        "Ti-6Al-4V": ("ti6al4v.json", [14, 20, 28, 38]),
        "PMMA": ("pmma.json", [6, 10, 16, 24]),
        "copper shaper law": ("pulse-shaper-copper.json", [5, 8, 12, 18]),
        "bilinear steel": (BILINEAR_STEEL, [12, 18, 26, 36])}
FLOW_START = 0.02   # past the elastic-plastic transition (tests/app/test_specimen_response.cpp)
EQUILIBRIUM = 0.05  # R <= 5 %
TOLERANCE = 0.01


def read_csv(path):
    with open(path) as f:
        rows = list(csv.reader(f))
    return {name: [float(r[i]) for r in rows[1:]] for i, name in enumerate(rows[0])}


def law_along(c, m, phi):
    """(flow strain, law stress) per sample: the law's true stress along the curve's path."""
    E = quantity(m.get("youngs_modulus", 0))
    flow, law = [], []
    if m["model"] == "viscoelastic":  # exact per interval for a piecewise-linear strain
        dt = c["time_s"][1] - c["time_s"][0]
        arms = [(quantity(a["modulus"]), quantity(a["relaxation_time"])) for a in m["arms"]]
        state, previous = [0.0] * len(arms), 0.0
        for strain in c["true_strain"]:
            stress = quantity(m["long_term_modulus"]) * strain
            for k, (Ek, tk) in enumerate(arms):
                x = dt / tk
                state[k] = math.exp(-x) * state[k] - Ek * math.expm1(-x) / x * (strain - previous)
                stress += state[k]
            previous = strain
            flow.append(strain)
            law.append(stress)
        return flow, law
    if m["model"] == "johnson-cook":
        A, B, n, C, mm = (quantity(m[k]) for k in ("A", "B", "n", "C", "m"))
        rate0 = quantity(m.get("reference_strain_rate", 1.0))
        t_room, t_melt = quantity(m["room_temperature"]), quantity(m["melting_temperature"])
        heat = quantity(m["taylor_quinney"]) / (
            quantity(m["density"]) * quantity(m["specific_heat"]))
        T, p_prev, tau_prev = t_room, 0.0, 0.0
    for k, e in enumerate(c["strain"]):
        tau = c["true_stress_Pa"][k] / phi(e)  # the law's own stress
        p = max(0.0, c["true_strain"][k] - tau / E)
        if m["model"] == "bilinear":
            Et = quantity(m["tangent_modulus"])
            stress = quantity(m["yield_stress"]) + E * Et / (E - Et) * p
        else:
            if p > p_prev:  # adiabatic heating from the law's plastic work
                T += heat * 0.5 * (tau + tau_prev) * (p - p_prev)
                p_prev = p
            tau_prev = tau
            rate = c["strain_rate_1_s"][k] / (1 - e)
            thermal = 1 - min(max((T - t_room) / (t_melt - t_room), 0.0), 1.0) ** mm
            stress = (A + B * p ** n) * (1 + C * math.log(max(rate / rate0, 1.0))) * thermal
        flow.append(p)
        law.append(stress)
    return flow, law


def median(v):
    v = sorted(v)
    return v[len(v) // 2]


def ratios(c, m, phi, equilibrium):
    """Medians of true stress / (law x phi) in flow and equilibrium, and over the last third."""
    flow, law = law_along(c, m, phi)
    e = c["strain"]
    e_max = max(e)
    rate = [r / (1 - x) for r, x in zip(c["strain_rate_1_s"], e)]
    loading = [k for k in range(len(e))
               if flow[k] > FLOW_START and e[k] < 0.98 * e_max and rate[k] > 0]
    if not loading:
        return None
    test_rate = median([rate[k] for k in loading])
    kept = [k for k in loading if rate[k] > 0.5 * test_rate and equilibrium[k] <= EQUILIBRIUM]
    if len(kept) < 5:
        return None
    third = FLOW_START + 2 / 3 * (max(flow[k] for k in kept) - FLOW_START)
    r = {k: c["true_stress_Pa"][k] / (law[k] * phi(e[k])) for k in kept}
    return {"rate": test_rate, "e_max": e_max, "samples": len(kept), "median": median(r.values()),
            "last_third": median([r[k] for k in kept if flow[k] >= third])}


def scene(law, L_mm, V, mu, bars, shaper=False, inertia=False):
    b = BARS[bars]
    chain = [{"name": "striker", "material": b, "length": "200 mm", "diameter": "19.05 mm",
              "velocity": f"{V} m/s"}]
    if shaper:
        chain.append({"name": "shaper", "length": "3 mm", "diameter": "16 mm",
                      "material": os.path.join(SPECIMENS, "pulse-shaper-copper.json")})
    chain += [{"name": "incident", "material": b, "length": "2 m", "diameter": "19.05 mm",
               "gauges": [{"name": "incident", "position": "1 m"}]},
              {"name": "specimen", "material": law, "length": f"{L_mm} mm", "diameter": "10 mm",
               "inertia": inertia},
              {"name": "transmitter", "material": b, "length": "2 m", "diameter": "19.05 mm",
               "gauges": [{"name": "transmitted", "position": "1 m"}]}]
    return {"name": "friction survey", "bars": chain, "specimen": "specimen",
            "contact": {"method": "localized-bipenalty", "friction": mu},
            "simulation": {"duration": "800 us", "sample_rate": "10 MHz"}}


def run(shpb, folder, s, m, mu, L_mm, corrections):
    """One set-up: simulate, process as is and corrected; the ratios of the docstring."""
    os.makedirs(folder, exist_ok=True)
    files = {}
    for name, measurement in (("raw", None), ("corrected", corrections)):
        t = dict(s, measurement={"corrections": measurement}) if measurement else s
        files[name] = os.path.join(folder, name + ".json")
        with open(files[name], "w") as f:
            json.dump(t, f, indent=1)
    sim = os.path.join(folder, "sim")
    steps = [[shpb, "simulate", files["raw"], "-o", sim, "--quiet"]]
    for name in ("raw", "corrected"):
        steps.append([shpb, "process", files[name], "--signals", os.path.join(sim, "gauges.csv"),
                      "-o", os.path.join(folder, name), "--quiet"])
    for step in steps:
        done = subprocess.run(step, capture_output=True, text=True)
        if done.returncode:
            return {"error": done.stderr.strip()}
    phi = lambda e: 1 + mu / (3 * math.sqrt(3)) * (10 / math.sqrt(1 - e)) / (L_mm * (1 - e))
    one = lambda e: 1.0
    raw = read_csv(os.path.join(folder, "raw", "curve.csv"))
    corrected = read_csv(os.path.join(folder, "corrected", "curve.csv"))
    # specimen.csv over the processed window; its equilibrium from the face stresses as R.
    sp = read_csv(os.path.join(sim, "specimen.csv"))
    window = [k for k, t in enumerate(sp["time_s"]) if raw["time_s"][0] <= t <= raw["time_s"][-1]]
    sp = {name: [v[k] for k in window] for name, v in sp.items()}
    total = [abs(a + b) for a, b in zip(sp["front_stress_Pa"], sp["back_stress_Pa"])]
    floor = 0.02 * max(total)
    sp_r = [2 * abs(a - b) / max(t, floor)
            for a, b, t in zip(sp["front_stress_Pa"], sp["back_stress_Pa"], total)]
    # Cauchy (specimen.csv) to Kirchhoff: x J = exp(-(1 - 2 nu) tau/E) in compression (bar.hpp).
    E = quantity(m.get("youngs_modulus", 0)) or quantity(m["long_term_modulus"]) + sum(
        quantity(a["modulus"]) for a in m["arms"])
    sp["true_stress_Pa"] = [s_ * math.exp(-(1 - 2 * m["poisson_ratio"]) * s_ / phi(e) / E)
                            for s_, e in zip(sp["true_stress_Pa"], sp["strain"])]
    with open(os.path.join(sim, "summary.json")) as f:
        energy = json.load(f)["energy_error"]
    return {"raw": ratios(raw, m, phi, raw["equilibrium_ratio"]),
            "corr": ratios(corrected, m, one, corrected["equilibrium_ratio"]),
            "spec": ratios(sp, m, phi, sp_r), "energy": energy}


def set_ups(rate_filter):
    """(label, scene, law, mu, L_mm, corrections) of the sweep and the combined set-ups."""
    out = []
    for name, (law, speeds) in LAWS.items():
        m = law if isinstance(law, dict) else json.load(open(os.path.join(SPECIMENS, law)))
        if rate_filter and m["model"] == "johnson-cook":
            m = dict(m, strain_rate_filter="1 us")
        for ld in (0.3, 0.5, 1):
            for bars in BARS:
                for V in speeds:
                    for mu in (0, 0.05, 0.1, 0.2):
                        label = f"{name}, L/D {ld}, {bars} bars, {V} m/s, mu {mu}"
                        s = scene(m, 10 * ld, V, mu, bars)
                        out.append((label, s, m, mu, 10 * ld, {"friction": mu}))
    al = json.load(open(os.path.join(SPECIMENS, "al6061-t6.json")))
    pmma = json.load(open(os.path.join(SPECIMENS, "pmma.json")))
    for m, name, L, V, mu, shaper, inertia in (
            (al, "Al 6061-T6", 5, 15, 0.1, False, True),
            (al, "Al 6061-T6", 3, 20, 0.2, False, True),
            (pmma, "PMMA", 10, 16, 0.2, False, True), (al, "Al 6061-T6", 5, 20, 0.2, True, False),
            (al, "Al 6061-T6", 10, 20, 0.05, True, False), (pmma, "PMMA", 5, 12, 0.1, True, False),
            (al, "Al 6061-T6", 5, 15, 0.1, True, True)):
        label = f"{name}, L/D {L / 10}, steel bars, {V} m/s, mu {mu}" + \
            (", copper shaper" if shaper else "") + (", inertia" if inertia else "")
        corrections = {"friction": mu, "inertia": inertia}
        out.append((label, scene(m, L, V, mu, "steel", shaper, inertia), m, mu, L, corrections))
    return out


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("shpb")
    ap.add_argument("out")
    ap.add_argument("--rate-filter", action="store_true")
    ap.add_argument("--jobs", type=int, default=1)
    a = ap.parse_args()
    jobs = set_ups(a.rate_filter)
    work = lambda i: run(a.shpb, os.path.join(a.out, str(i)), *jobs[i][1:])
    cell = lambda r: f"{r['median']:.4f} {r['last_third']:.4f}" if r else "   -      -   "
    counted = missed = 0
    with ThreadPoolExecutor(a.jobs) as pool:
        for (label, _, _, mu, _, _), res in zip(jobs, pool.map(work, range(len(jobs)))):
            if "error" in res:
                print(f"{label}: {res['error']}")
                continue
            raw = res["raw"]
            print(f"{label}: rate {raw['rate'] if raw else 0:.0f} /s, e_max "
                  f"{raw['e_max'] if raw else 0:.3f} | raw {cell(raw)} | corr {cell(res['corr'])} "
                  f"| spec {cell(res['spec'])} | energy {res['energy']:.4f}", flush=True)
            if mu > 0 and raw and 1000 <= raw["rate"] <= 5000:
                counted += 1
                missed += any(abs(r[k] - 1) > TOLERANCE for r in (raw, res["corr"]) if r
                              for k in ("median", "last_third"))
    print(f"with friction at 1000-5000 /s: {counted} set-ups, {missed} miss 1 %")


if __name__ == "__main__":
    main()
