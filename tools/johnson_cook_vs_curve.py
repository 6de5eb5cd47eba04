#!/usr/bin/python3
"""Compare a processed stress-strain curve (curve.csv of `shpb process`) with a Johnson-Cook
specimen file along the measured path, in the law's own terms (docs/methods.md §8): true stress s
against true plastic strain p = e_true - s/E, true strain rate e_rate/(1 - e), temperature from adiabatic heating dT = beta s dp / (rho c_p) (Johnson & Cook 1983).

  /usr/bin/python3 tools/johnson_cook_vs_curve.py specimens/ofhc-copper.json DIR/curve.csv \
      [--temperature "0 degC"] [--min-strain 0.1] [--equilibrium 0.05]

Prints the ratio measured/law over the samples in equilibrium (R <= --equilibrium), loading, past
--min-strain: count, minimum, median, maximum.
"""
import argparse
import csv
import json
import math
import re

SCALE = {"": 1.0, "Pa": 1.0, "kPa": 1e3, "MPa": 1e6, "GPa": 1e9, "K": 1.0, "kg/m3": 1.0,
         "g/cm3": 1e3, "J/(kg K)": 1.0, "J/kgK": 1.0, "1/s": 1.0, "1 1/s": 1.0, "s": 1.0,
         "ms": 1e-3, "us": 1e-6}


def quantity(value):
    """A number, or "<number> <unit>" with the few units specimen files use ("20 degC" → K)."""
    if isinstance(value, (int, float)):
        return float(value)
    m = re.fullmatch(r"\s*([-+0-9.eE]+)\s*(.*?)\s*", value)
    number, unit = float(m.group(1)), m.group(2)
    if unit in ("degC", "°C"):
        return number + 273.15
    if unit not in SCALE:
        raise SystemExit(f"error: unit \"{unit}\" not understood by this script")
    return number * SCALE[unit]


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("specimen", help="a Johnson-Cook material file (specimens/*.json)")
    ap.add_argument("curve", help="curve.csv written by shpb process")
    ap.add_argument("--temperature", help="test temperature (default: the file's, else room)")
    ap.add_argument("--min-strain", type=float, default=0.1)
    ap.add_argument("--equilibrium", type=float, default=0.05)
    a = ap.parse_args()
    jc = json.load(open(a.specimen))
    if jc.get("model") != "johnson-cook":
        raise SystemExit(f"error: {a.specimen}: model: expected \"johnson-cook\"")
    A, B, n, C, m = (quantity(jc[k]) for k in ("A", "B", "n", "C", "m"))
    E, rho = quantity(jc["youngs_modulus"]), quantity(jc["density"])
    rate0 = quantity(jc.get("reference_strain_rate", 1.0))
    t_room = quantity(jc.get("room_temperature", 293.15))
    t_melt = quantity(jc["melting_temperature"])
    cp, beta = quantity(jc["specific_heat"]), quantity(jc.get("taylor_quinney", 0.9))
    T = quantity(a.temperature or jc.get("temperature", t_room))
    p_prev, ratios = 0.0, []
    for row in csv.DictReader(open(a.curve)):
        strain, stress = float(row["true_strain"]), float(row["true_stress_Pa"])
        rate = float(row["strain_rate_1_s"]) / (1 - float(row["strain"]))
        r = float(row["equilibrium_ratio"]) if row["equilibrium_ratio"] not in ("", "nan") else math.inf
        p = max(0.0, strain - stress / E)
        if p > p_prev:  # adiabatic heating along the measured path
            T += beta * stress * (p - p_prev) / (rho * cp)
            p_prev = p
        thermal = 1.0 if T <= t_room else max(0.0, 1 - ((T - t_room) / (t_melt - t_room)) ** m)
        law = (A + B * p ** n) * (1 + C * math.log(max(rate / rate0, 1.0))) * thermal
        if r <= a.equilibrium and rate > 0 and strain >= a.min_strain and law > 0:
            ratios.append(stress / law)
    if not ratios:
        raise SystemExit("error: no sample in equilibrium past --min-strain")
    ratios.sort()
    print(f"samples {len(ratios)}  measured/law: min {ratios[0]:.3f}  "
          f"median {ratios[len(ratios) // 2]:.3f}  max {ratios[-1]:.3f}  final T {T:.1f} K")


if __name__ == "__main__":
    main()
