#!/usr/bin/python3
"""`shpb simulate` then `shpb process --signals` on 104 set-ups an outside laboratory would build,
against the simulation's own specimen (specimen.csv), past equilibrium (docs/validation.md,
"Round trips past equilibrium").

Usage: tools/survey_roundtrip.py SHPB OUTDIR [ID-FILTER]

Set-ups (cases() below): the classic layout (19.05 mm steel bars of 2 m, 300 mm striker, gauges at
mid-length) with bilinear copper (E 117 GPa; yield 70, 150 or 300 MPa, tangent modulus 0.5, 1 or
2 GPa), Johnson-Cook OFHC copper and Al 6061-T6 specimens of 5 to 19 mm, L/D 0.25 to 2 (impedance
ratio specimen/bar 0.03 to 0.8) at 5, 15 and 30 m/s; 9 with a 2 mm copper pulse shaper; 12 in
tension (bonded, striker pulled); PMMA (viscoelastic) and bilinear copper on aluminium bars (ratio
0.06 to 2.3). Compared, at the curve's own times, from the time to equilibrium (summary.json) to
the incident pulse's falling edge at the front face less four specimen transits: the 3-wave true
and engineering stress against the specimen's mean, the 1-wave against its back-face and the 2-wave
against its front-face stress (fractions of its peak stress), the 3-wave and 1-wave strain against
its strain (fractions of its largest), the strain rates against the slope of its strain over 2 us
(fractions of its mean rate); and the summary's peak stresses against the specimen's peak over the
curve. Writes OUTDIR/rows.json and prints one row a run, then the medians and the worst.
"""
import csv, json, math, pathlib, shutil, subprocess, sys
import numpy as np
SHPB, OUT = sys.argv[1], pathlib.Path(sys.argv[2])
FILT = sys.argv[3] if len(sys.argv) > 3 else ""
ROOT = pathlib.Path(__file__).resolve().parent.parent
SPEC = ROOT / "specimens"
OUT.mkdir(parents=True, exist_ok=True)
BARS = {"steel": {"model": "elastic", "density": 8080, "youngs_modulus": "200 GPa", "poisson_ratio": 0.29},
        "al": {"model": "elastic", "density": 2700, "youngs_modulus": "70 GPa", "poisson_ratio": 0.33}}
def bl(y, et):
    return {"model": "bilinear", "density": 8960, "youngs_modulus": "117 GPa", "poisson_ratio": 0.34,
            "yield_stress": f"{y} MPa", "tangent_modulus": f"{et} GPa"}
def load(n):
    d = json.load(open(SPEC / n))
    for k in ("name", "source", "notes"):
        d.pop(k, None)
    return d
LAWS = {"bl70": bl(70, 0.5), "bl150": bl(150, 1), "bl300": bl(300, 2), "jccu": load("ofhc-copper.json"),
        "jcal": load("al6061-t6.json"), "pmma": load("pmma.json")}
SHAPER = str(SPEC / "pulse-shaper-copper.json")

def scene(c):
    t = c["test"]; Db = 19.05
    bars = [{"name": "striker", "material": "bar", "length": "300 mm", "diameter": f"{Db} mm",
             "velocity": f"{-c['V'] if t == 'tension' else c['V']} m/s"}]
    if c["shaper"]:
        bars.append({"name": "shaper", "material": SHAPER, "length": "2 mm", "diameter": "10 mm"})
    bars += [{"name": "incident", "material": "bar", "length": "2 m", "diameter": f"{Db} mm",
              "gauges": [{"name": "incident", "position": "1 m"}]},
             {"name": "specimen", "material": "spec", "length": f"{c['L']} mm", "diameter": f"{c['D']} mm"},
             {"name": "transmitter", "material": "bar", "length": "2 m", "diameter": f"{Db} mm",
              "gauges": [{"name": "transmitted", "position": "1 m"}]}]
    s = {"name": c["id"], "bars": bars, "specimen": "specimen",
         "materials": {"bar": BARS[c["bar"]], "spec": LAWS[c["law"]]},
         "contact": {"method": "bonded" if t == "tension" else "localized-bipenalty"},
         "simulation": {"duration": "800 us", "sample_rate": "10 MHz"}}
    if t == "tension":
        s["measurement"] = {"test": "tension"}
    return s

def zratio(c):
    b = BARS[c["bar"]]; E = float(b["youngs_modulus"].split()[0]) * 1e9
    zb = math.sqrt(E * b["density"]) * 19.05**2
    l = LAWS[c["law"]]
    if l["model"] == "viscoelastic":
        Es = 5.7e9
    else:
        Es = float(str(l["youngs_modulus"]).split()[0]) * 1e9
    return math.sqrt(Es * float(l["density"] if not isinstance(l["density"], str) else l["density"].split()[0])) * c["D"]**2 / zb

def cases():
    out = []
    # (law, bar, D, L/D, V, shaper, test)
    grid = []
    for law in ("bl70", "bl150", "bl300", "jccu", "jcal"):
        for D, LD in ((10, 0.5), (5, 1), (16, 0.25), (10, 2), (19, 0.5)):
            for V in (5, 15, 30):
                grid.append((law, "steel", D, LD, V, False, "compression"))
    for law in ("bl150", "jcal", "jccu"):
        for D, LD, V in ((10, 0.5, 15), (10, 1, 25), (5, 2, 10)):
            grid.append((law, "steel", D, LD, V, True, "compression"))
    for law in ("bl70", "bl300", "jcal"):
        for D, LD, V in ((10, 0.5, 10), (6, 1, 20), (16, 0.25, 15), (10, 2, 5)):
            grid.append((law, "steel", D, LD, V, False, "tension"))
    for D, LD, V in ((19, 0.25, 5), (19, 0.5, 10), (12, 1, 15), (12, 0.5, 30)):
        grid.append(("pmma", "al", D, LD, V, False, "compression"))
        grid.append(("bl150", "al", D, LD, V, False, "compression"))
    for g in grid:
        law, bar, D, LD, V, sh, t = g
        c = dict(law=law, bar=bar, D=D, L=round(LD * D, 3), V=V, shaper=sh, test=t)
        c["id"] = f"{t[0]}-{bar}-{law}-D{D}-LD{LD}-V{V}" + ("-sh" if sh else "")
        c["Z"] = zratio(c)
        out.append(c)
    return out

def rd(p):
    with open(p) as f:
        r = csv.reader(f); h = next(r)
        a = np.array([[float(x) if x else np.nan for x in row] for row in r])
    return {k: a[:, i] for i, k in enumerate(h)}

def run(c):
    d = OUT / c["id"]; d.mkdir(exist_ok=True)
    shutil.rmtree(d / "proc", ignore_errors=True)
    json.dump(scene(c), open(d / "scene.json", "w"), indent=1)
    r = subprocess.run([SHPB, "simulate", str(d / "scene.json"), "-o", str(d / "sim"), "-q"], capture_output=True, text=True)
    if r.returncode:
        r = subprocess.run([SHPB, "simulate", str(d / "scene.json"), "-o", str(d / "sim")], capture_output=True, text=True)
    row = dict(id=c["id"], Z=round(c["Z"], 3), sim_rc=r.returncode)
    if r.returncode not in (0,):
        row["err"] = r.stderr[-300:]; return row
    p = subprocess.run([SHPB, "process", str(d / "scene.json"), "--signals", str(d / "sim/gauges.csv"), "-o", str(d / "proc")],
                       capture_output=True, text=True)
    row["proc_rc"] = p.returncode
    if p.returncode:
        row["err"] = p.stderr[-300:]; return row
    s = json.load(open(d / "proc/summary.json"))
    cu = rd(d / "proc/curve.csv"); sp = rd(d / "sim/specimen.csv")
    sg = -1.0 if c["test"] == "tension" else 1.0
    t = cu["time_s"]
    I = lambda k: sg * np.interp(t, sp["time_s"], sp[k])
    st, sf, sb, se, str_ = I("stress_Pa"), I("front_stress_Pa"), I("back_stress_Pa"), I("strain"), I("true_stress_Pa")
    # specimen rate: slope of its strain over 2 us
    tt = sp["time_s"]; e = sg * sp["strain"]
    h = 1e-6
    srate = (np.interp(t + h, tt, e) - np.interp(t - h, tt, e)) / (2 * h)
    peak = np.max(np.abs(st))
    eq = s["equilibrium"].get("holds_until_unloading_from_s")
    # specimen's own equilibrium: last time R_spec > 5 %
    R = 2 * np.abs(sf - sb) / np.maximum(np.abs(sf + sb), 0.02 * 2 * peak)
    bad = np.where(R > 0.05)[0]
    teq_sp = t[bad[-1] + 1] if len(bad) and bad[-1] + 1 < len(t) else (t[0] if not len(bad) else None)
    row.update(teq_proc=None if eq is None else round((eq - t[0]) * 1e6, 2),
               teq_spec=None if teq_sp is None else round((teq_sp - t[0]) * 1e6, 2))
    t0 = eq if eq is not None else teq_sp
    row["maxstrain"] = round(float(s["max_strain"]), 4)
    row["warn"] = s.get("warnings", [])
    row["peak3"] = round(s["peak_stress_Pa"] / peak, 3)
    row["peak1"] = round(s["reductions"]["1-wave"]["peak_stress_Pa"] / peak, 3)
    row["specpeak_MPa"] = round(peak / 1e6, 1)
    if t0 is None:
        return row
    pu = rd(d / "proc/pulses.csv")
    inc = sg * -np.interp(t, pu["time_s"], pu["incident"])
    plat = abs(s["incident_plateau_strain"])
    inb = np.where(np.abs(inc - plat) <= 0.1 * plat)[0]
    tun = t[inb[-1]] if len(inb) else t[-1]
    row["t_unload"] = round((tun - t[0]) * 1e6, 2)
    # specimen ring-down: 4 transits of the elastic wave
    l = LAWS[c["law"]]
    Es = 5.7e9 if l["model"] == "viscoelastic" else float(str(l["youngs_modulus"]).split()[0]) * 1e9
    cs = math.sqrt(Es / float(l["density"] if not isinstance(l["density"], str) else l["density"].split()[0]))
    tend = tun - 4 * c["L"] * 1e-3 / cs
    m = (t >= t0) & (t <= tend)
    row["tail"] = round((t[-1] - tend) * 1e6, 2)
    row["n_past"] = int(m.sum())
    if m.sum() < 3:
        return row
    def err(a, b, den):
        x = np.abs(a[m] - b[m]) / den
        return [round(100 * float(np.median(x)), 2), round(100 * float(np.max(x)), 2)]
    row["e3true"] = err(cu["true_stress_Pa"], str_, peak)
    row["e3"] = err(cu["stress_3wave_Pa"], st, peak)
    row["e1"] = err(cu["stress_1wave_Pa"], sb, peak)
    row["e2"] = err(cu["stress_2wave_Pa"], sf, peak)
    emax = max(np.max(np.abs(se)), 1e-12)
    row["estrain"] = err(cu["strain"], se, emax)
    row["estrain1"] = err(cu["strain_1wave"], se, emax)
    mr = np.mean(np.abs(srate[m])) or 1
    row["erate"] = err(cu["strain_rate_1_s"], srate, mr)
    row["erate1"] = err(cu["strain_rate_1wave_1_s"], srate, mr)
    row["peak3_past"] = round(float(np.max(cu["stress_3wave_Pa"][m])) / float(np.max(st[m])), 3)
    row["peak1_past"] = round(float(np.max(cu["stress_1wave_Pa"][m])) / float(np.max(st[m])), 3)
    return row

rows = []
for c in cases():
    if FILT and FILT not in c["id"]:
        continue
    r = run(c); rows.append(r)
    print(json.dumps({k: v for k, v in r.items() if k != "warn"}), "W%d" % len(r.get("warn", [])), flush=True)
json.dump(rows, open(OUT / "rows.json", "w"), indent=1)
past = [r for r in rows if "e3" in r]
print(f"{len(rows)} runs, {len(past)} reach equilibrium (compared past it)")
for k in ("e3true", "e3", "e1", "e2", "estrain", "estrain1", "erate", "erate1"):
    med = [r[k][0] for r in past]
    mx = [r[k][1] for r in past]
    i = int(np.argmax(mx))
    print(f"{k:9s} median {np.median(med):6.2f} %, worst median {max(med):6.2f} %, "
          f"worst sample {mx[i]:8.2f} % ({past[i]['id']})")
for k in ("peak3", "peak1"):
    v = [r[k] for r in rows if k in r]
    far = [r for r in rows if k in r and abs(r[k] - 1) > 0.05]
    print(f"{k}: summary peak / specimen's, median {np.median(v):.3f}, {min(v):.3f} to {max(v):.3f}; "
          f"{len(far)} beyond 5 %, {sum(1 for r in far if not r.get('warn'))} of them with no warning")
