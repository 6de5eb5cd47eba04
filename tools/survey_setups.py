#!/usr/bin/python3
"""`shpb simulate` then `shpb process` on 50 set-ups the suite does not hold, as an outside laboratory
would build them, against the simulation's own specimen (specimen.csv; docs/validation.md
"Set-ups of an outside laboratory").

Usage: tools/survey_setups.py SHPB OUTDIR [ID-FILTER]

Set-ups (cases() below): compression and tension (bonded, striker pulled) tests on bars of steel,
aluminium, titanium, magnesium or PMMA (specimens/pmma.json: polymer bars) of 10 to 25 mm, elastic,
bilinear, Johnson-Cook (Al 6061, Ti-6Al-4V, copper) and viscoelastic (PMMA) specimens of L/D 0.3 to
2, strain rates of about 300 to 8000 /s, with and without a copper pulse shaper, gauges from 0.05 to
1.5 m from the specimen (incident and reflected pulses overlapping at three of them), recorded at
0.5 to 100 MHz. Each run's gauges are processed twice:
- `process --signals gauges.csv` (the default settings);
- as a coarse scope records them, written as the scene's `measurement` (a CSV of volts, scale 1e-3
  strain/V, no dispersion correction: the 1D model does not disperse): point-sampled at 1 MS/s, a
  pre-trigger of 5 to 100 us at rest, white noise of 1 % of each channel's peak, an offset of +3 %
  (incident) and -2 % (transmitted) of it, 8 bits over the scope range (0.2, 0.5 or 1 × a decade)
  above 1.2 × the peak, each value printed to 6 significant digits as scope exports write them;
- that scope record cut to start 12, 20 or 40 us before the incident pulse's half height, as a
  scope triggered on the pulse with a short pre-trigger keeps it.
Errors, over the loading where the specimen's own stress is at least half its peak, as fractions of
that peak: the median |difference| of the 3-wave stress against its mean stress, the 1-wave against
its back-face and the 2-wave against its front-face stress at the same time; the strain rate as the
mean rate over that window against the specimen's; the strain at its end against the specimen's.
Prints one JSON row a run (exit codes, energy error, warnings, errors), writes OUTDIR/rows.json, and
ends with, per record kind, the runs that exit non-zero and those beyond 5 % (a stress) or 10 % (the
rate) with no warning at all, or whose curve misses the specimen's loading.
"""
import csv, json, math, pathlib, random, subprocess, sys
import numpy as np

SHPB, OUT = sys.argv[1], pathlib.Path(sys.argv[2])
FILT = sys.argv[3] if len(sys.argv) > 3 else ""
SPEC = pathlib.Path(__file__).resolve().parent.parent / "specimens"
OUT.mkdir(parents=True, exist_ok=True)

BARS = {  # density, E, nu
    "steel": {"model": "elastic", "density": 7850, "youngs_modulus": "200 GPa", "poisson_ratio": 0.29},
    "al": {"model": "elastic", "density": 2700, "youngs_modulus": "70 GPa", "poisson_ratio": 0.33},
    "ti": {"model": "elastic", "density": 4430, "youngs_modulus": "114 GPa", "poisson_ratio": 0.34},
    "mg": {"model": "elastic", "density": 1770, "youngs_modulus": "45 GPa", "poisson_ratio": 0.35},
    "pmma": json.load(open(SPEC / "pmma.json")),
}
for k in ("name", "source", "notes"):
    BARS["pmma"].pop(k, None)
LAWS = {
    "elastic": {"model": "elastic", "density": 1200, "youngs_modulus": "5 GPa", "poisson_ratio": 0.4},
    "bilinear": {"model": "bilinear", "density": 2700, "youngs_modulus": "70 GPa", "poisson_ratio": 0.33,
                 "yield_stress": "300 MPa", "tangent_modulus": "2 GPa"},
    "al6061": str(SPEC / "al6061-t6.json"),
    "ti": str(SPEC / "ti6al4v.json"),
    "cu": str(SPEC / "ofhc-copper.json"),
    "pmma": str(SPEC / "pmma.json"),
}
SHAPER = str(SPEC / "pulse-shaper-copper.json")


def scene(c):
    bar = c["bar"]
    Db, Lb = c["Db"], c["Lb"]
    t = c["test"]
    bars = [{"name": "striker", "material": "bar", "length": f"{c['Ls']} mm", "diameter": f"{Db} mm",
             "velocity": f"{-c['V'] if t == 'tension' else c['V']} m/s"}]
    if c.get("shaper"):
        bars.append({"name": "shaper", "material": SHAPER, "length": "1 mm", "diameter": f"{0.6*Db:.1f} mm"})
    bars += [
        {"name": "incident", "material": "bar", "length": f"{Lb} m", "diameter": f"{Db} mm",
         "gauges": [{"name": "incident", "distance_to_specimen": f"{c['di']} m"}]},
        {"name": "specimen", "material": "spec", "length": f"{c['Lsp']} mm", "diameter": f"{c['Dsp']} mm"},
        {"name": "transmitter", "material": "bar", "length": f"{Lb} m", "diameter": f"{Db} mm",
         "gauges": [{"name": "transmitted", "distance_to_specimen": f"{c['dt']} m"}]}]
    s = {"name": c["id"], "bars": bars, "specimen": "specimen",
         "materials": {"bar": BARS[bar], "spec": LAWS[c["law"]] if isinstance(LAWS[c["law"]], dict)
                       else json.load(open(LAWS[c["law"]]))},
         "simulation": {"sample_rate": f"{c['rate']} MHz"}}
    for k in ("name", "source", "notes"):
        s["materials"]["spec"].pop(k, None)
    if t == "tension":
        s["contact"] = {"method": "bonded"}
        s["measurement"] = {"test": "tension"}
    return s


def cases():
    R = random.Random(7)
    out = []
    base = [
        # bar, Db, law, Lsp, Dsp, V, Ls(mm), di, dt, rate MHz, test, shaper
        ("steel", 19, "al6061", 5, 10, 15, 300, 1.0, 1.0, 10, "compression", False),
        ("steel", 19, "al6061", 3, 10, 25, 300, 1.0, 1.0, 10, "compression", False),
        ("steel", 19, "al6061", 2, 8, 24, 200, 1.0, 0.5, 10, "compression", False),
        ("steel", 19, "ti", 4, 8, 30, 300, 1.0, 1.0, 10, "compression", False),
        ("steel", 12, "cu", 6, 6, 12, 250, 0.8, 0.6, 5, "compression", False),
        ("steel", 25, "cu", 4, 20, 10, 400, 1.2, 1.0, 2, "compression", False),
        ("steel", 10, "bilinear", 10, 5, 8, 300, 1.0, 0.4, 20, "compression", False),
        ("steel", 19, "elastic", 5, 10, 8, 300, 1.0, 1.0, 10, "compression", False),
        ("steel", 19, "al6061", 5, 10, 15, 300, 0.4, 1.0, 10, "compression", False),  # overlap at gauge
        ("steel", 19, "al6061", 5, 10, 15, 300, 0.25, 0.2, 10, "compression", False),
        ("steel", 19, "al6061", 5, 10, 15, 300, 1.0, 0.05, 10, "compression", False),  # close tx gauge
        ("steel", 19, "al6061", 5, 10, 15, 300, 1.0, 1.0, 0.5, "compression", False),
        ("steel", 19, "al6061", 5, 10, 15, 300, 1.0, 1.0, 1, "compression", False),
        ("steel", 19, "al6061", 5, 10, 15, 300, 1.0, 1.0, 100, "compression", False),
        ("steel", 19, "al6061", 5, 10, 10, 300, 1.0, 1.0, 10, "compression", True),
        ("steel", 19, "cu", 5, 10, 15, 300, 1.0, 1.0, 10, "compression", True),
        ("steel", 19, "ti", 6, 6, 25, 300, 1.0, 1.0, 5, "compression", True),
        ("al", 20, "al6061", 4, 12, 25, 300, 1.0, 1.0, 10, "compression", False),
        ("al", 16, "cu", 8, 10, 15, 250, 0.8, 0.8, 2, "compression", False),
        ("al", 20, "pmma", 5, 12, 10, 300, 1.0, 1.0, 10, "compression", False),
        ("al", 12, "bilinear", 3, 8, 20, 200, 0.6, 0.3, 1, "compression", False),
        ("ti", 16, "ti", 4, 8, 30, 300, 1.0, 1.0, 10, "compression", False),
        ("ti", 16, "al6061", 6, 10, 20, 250, 1.0, 1.0, 20, "compression", False),
        ("ti", 20, "elastic", 10, 15, 10, 300, 1.0, 0.5, 5, "compression", False),
        ("mg", 20, "pmma", 5, 12, 12, 300, 1.0, 1.0, 10, "compression", False),
        ("mg", 20, "al6061", 5, 10, 25, 300, 1.0, 1.0, 10, "compression", False),
        ("mg", 25, "cu", 8, 20, 10, 400, 1.2, 1.0, 2, "compression", False),
        ("mg", 16, "elastic", 4, 10, 8, 200, 1.0, 0.3, 10, "compression", False),
        ("pmma", 20, "pmma", 5, 12, 5, 200, 0.5, 0.5, 10, "compression", False),
        ("pmma", 20, "elastic", 6, 15, 8, 200, 0.6, 0.4, 5, "compression", False),
        ("pmma", 25, "pmma", 3, 10, 12, 150, 0.5, 0.3, 2, "compression", False),
        ("pmma", 16, "pmma", 10, 12, 6, 200, 0.6, 0.6, 1, "compression", False),
        ("steel", 20, "bilinear", 5, 10, 10, 200, 1.0, 0.5, 10, "tension", False),
        ("steel", 20, "bilinear", 5, 10, 20, 200, 1.0, 0.5, 5, "tension", False),
        ("steel", 20, "al6061", 8, 6, 10, 200, 1.0, 1.0, 10, "tension", False),
        ("steel", 16, "ti", 5, 5, 30, 250, 0.8, 0.5, 20, "tension", False),
        ("steel", 20, "cu", 3, 6, 20, 200, 0.15, 0.5, 10, "tension", False),  # overlap
        ("al", 20, "bilinear", 5, 10, 20, 200, 1.0, 0.5, 10, "tension", False),
        ("al", 16, "al6061", 4, 8, 25, 200, 1.0, 1.0, 2, "tension", False),
        ("ti", 20, "bilinear", 4, 6, 15, 250, 1.0, 0.5, 1, "tension", False),
        ("mg", 20, "bilinear", 5, 10, 20, 200, 1.0, 0.5, 10, "tension", False),
        ("mg", 20, "al6061", 6, 12, 25, 300, 1.0, 0.05, 10, "tension", False),
        ("pmma", 20, "pmma", 5, 10, 6, 200, 0.6, 0.4, 10, "tension", False),
        ("pmma", 20, "elastic", 4, 12, 8, 200, 0.5, 0.3, 5, "tension", False),
        ("steel", 19, "al6061", 2, 6, 30, 150, 1.0, 1.0, 50, "compression", False),  # ~8000/s
        ("steel", 19, "cu", 20, 12, 10, 400, 1.5, 1.0, 10, "compression", False),  # L/D 1.7, ~ 400/s
        ("steel", 19, "al6061", 24, 12, 8, 300, 1.0, 1.0, 10, "compression", False),  # L/D 2
        ("al", 20, "pmma", 2, 10, 10, 200, 1.0, 1.0, 50, "compression", False),
        ("steel", 19, "ti", 3, 10, 20, 300, 1.0, 1.0, 0.5, "compression", False),
        ("steel", 19, "al6061", 5, 10, 15, 600, 0.7, 1.0, 10, "compression", False),  # long striker overlaps
    ]
    for i, b in enumerate(base):
        bar, Db, law, Lsp, Dsp, V, Ls, di, dt, rate, test, shaper = b
        Lb = 2.0 if bar != "pmma" else 1.2
        c = dict(id=f"c{i:02d}-{test[0]}-{bar}-{law}", bar=bar, Db=Db, Lb=Lb, law=law, Lsp=Lsp, Dsp=Dsp,
                 V=V, Ls=Ls, di=di, dt=dt, rate=rate, test=test, shaper=shaper)
        out.append(c)
    return out


def read_csv(p):
    with open(p) as f:
        r = csv.reader(f)
        h = next(r)
        a = np.array([[float(x) if x != "" else np.nan for x in row] for row in r])
    return h, a


def col(h, a, name):
    return a[:, h.index(name)]


def degrade(gauges, dst, rate_hz, seed, pretrig_s):
    h, a = read_csv(gauges)
    t = a[:, 0]
    dt = 1.0 / rate_hz
    if t[1] - t[0] > dt * 1.0001:
        dt = t[1] - t[0]
    tn = np.arange(0, t[-1] + 1e-12, dt)
    rng = np.random.default_rng(seed)
    npre = int(round(pretrig_s / dt))
    tp = np.concatenate([-dt * np.arange(npre, 0, -1), tn])
    cols = {}
    for j, name in enumerate(h[1:], 1):
        y = np.interp(tn, t, a[:, j])
        y = np.concatenate([np.zeros(npre), y])
        peak = np.max(np.abs(y))
        y = y + rng.normal(0, 0.01 * peak, y.size) + (0.03 if j == 1 else -0.02) * peak
        scale = 1e-3  # strain per volt
        v = y / scale
        vr = 10 ** math.ceil(math.log10(1.2 * np.max(np.abs(v))))
        for m in (0.2, 0.5, 1.0):
            if 1.2 * np.max(np.abs(v)) <= m * vr:
                vr = m * vr
                break
        q = 2 * vr / 256
        v = np.clip(np.round(v / q) * q, -vr, vr - q)
        cols[name] = v
    with open(dst, "w") as f:
        f.write("time_s," + ",".join(cols) + "\n")
        for i in range(tp.size):
            f.write(f"{tp[i]:.9e}," + ",".join(f"{cols[k][i]:.6g}" for k in cols) + "\n")
    return list(cols)


def triggered(record, dst, lead_s):
    """The scope record cut to start `lead_s` before the incident pulse's half height, as a scope
    triggered on that pulse with a short pre-trigger keeps it."""
    h, a = read_csv(record)
    x = a[:, 1]
    rest = np.median(x[:20])
    half = np.argmax(np.abs(x - rest) > 0.5 * np.max(np.abs(x - rest)))
    keep = a[:, 0] >= a[half, 0] - lead_s
    np.savetxt(dst, a[keep], delimiter=",", header=",".join(h), comments="", fmt="%.6g")


def compare(curve, spec, test):
    h, a = read_csv(curve)
    hs, s = read_csv(spec)
    sign = -1.0 if test == "tension" else 1.0
    ts = col(hs, s, "time_s")
    t = col(h, a, "time_s")
    tr = {k: sign * np.interp(t, ts, col(hs, s, k)) for k in
          ("stress_Pa", "front_stress_Pa", "back_stress_Pa", "strain")}
    peak = np.max(np.abs(tr["stress_Pa"]))
    win = np.abs(tr["stress_Pa"]) >= 0.5 * peak
    if win.sum() < 3:
        return None
    idx = np.where(win)[0]
    i0, i1 = idx[0], idx[-1]
    sl = slice(i0, i1 + 1)
    def err(p, q):
        return float(np.median(np.abs(p[sl] - q[sl])) / peak)
    e3 = err(col(h, a, "stress_3wave_Pa"), tr["stress_Pa"])
    e1 = err(col(h, a, "stress_1wave_Pa"), tr["back_stress_Pa"])
    e2 = err(col(h, a, "stress_2wave_Pa"), tr["front_stress_Pa"])
    ep = col(h, a, "strain")
    dtw = t[i1] - t[i0]
    if dtw <= 0:
        return None
    rate_p = (ep[i1] - ep[i0]) / dtw
    rate_t = (tr["strain"][i1] - tr["strain"][i0]) / dtw
    er = abs(rate_p - rate_t) / max(abs(rate_t), 1e-9)
    es = float(abs(ep[i1] - tr["strain"][i1]) / max(abs(tr["strain"][i1]), 1e-9))
    return dict(e3=e3, e1=e1, e2=e2, erate=er, estrain=es, rate_true=rate_t, npts=int(i1 - i0 + 1),
                peak_MPa=peak / 1e6, strain_true=float(tr["strain"][i1]))


def run(cmd):
    p = subprocess.run(cmd, capture_output=True, text=True, timeout=900)
    return p.returncode, p.stdout, p.stderr


def main():
    rows = []
    for c in cases():
        if FILT and FILT not in c["id"]:
            continue
        d = OUT / c["id"]
        d.mkdir(exist_ok=True)
        sc = scene(c)
        (d / "scene.json").write_text(json.dumps(sc, indent=1))
        row = dict(id=c["id"])
        rc, so, se = run([SHPB, "simulate", str(d / "scene.json"), "-o", str(d / "sim"), "--quiet"])
        row["sim_rc"] = rc
        if rc != 0 and not (d / "sim" / "gauges.csv").exists():
            row["sim_err"] = se.strip()[-300:]
            rows.append(row); print(json.dumps(row)); continue
        sm = json.load(open(d / "sim" / "summary.json"))
        row["energy_error"] = sm.get("energy_error")
        row["sim_warn"] = sm.get("warnings", [])
        # default process of simulated gauges
        rc, so, se = run([SHPB, "process", str(d / "scene.json"), "--signals", str(d / "sim" / "gauges.csv"),
                          "-o", str(d / "proc"), "--quiet"])
        row["proc_rc"] = rc
        row["proc_stderr"] = se.strip()[-600:]
        if rc == 0:
            ps = json.load(open(d / "proc" / "summary.json"))
            row["proc_warn"] = ps.get("warnings", [])
            row["plateau_rate"] = ps.get("plateau_strain_rate_1_s")
            row["t_eq"] = ps.get("time_to_equilibrium_s")
            row["cmp"] = compare(d / "proc" / "curve.csv", d / "sim" / "specimen.csv", c["test"])
        # degraded measured record
        names = degrade(d / "sim" / "gauges.csv", d / "record.csv", 1e6, sum(map(ord, c["id"])),
                        [20e-6, 50e-6, 100e-6, 5e-6][len(rows) % 4])
        msc = dict(sc)
        meas = {"file": "record.csv", "time": {"column": "time_s", "unit": "s"},
                "channels": [{"gauge": n, "column": n, "unit": "V", "scale": 1e-3} for n in names],
                "dispersion": {"correction": "none"}}
        if c["test"] == "tension":
            meas["test"] = "tension"
        msc["measurement"] = meas
        (d / "scene_meas.json").write_text(json.dumps(msc, indent=1))
        rc, so, se = run([SHPB, "process", str(d / "scene_meas.json"), "-o", str(d / "meas"), "--quiet"])
        row["meas_rc"] = rc
        row["meas_stderr"] = se.strip()[-600:]
        if rc == 0:
            ps = json.load(open(d / "meas" / "summary.json"))
            row["meas_warn"] = ps.get("warnings", [])
            row["meas_cmp"] = compare(d / "meas" / "curve.csv", d / "sim" / "specimen.csv", c["test"])
        # The same record from a scope triggered on the incident pulse, 12 to 40 us before it.
        triggered(d / "record.csv", d / "record_triggered.csv", [12e-6, 20e-6, 40e-6][len(rows) % 3])
        meas["file"] = "record_triggered.csv"
        (d / "scene_triggered.json").write_text(json.dumps(msc, indent=1))
        rc, so, se = run([SHPB, "process", str(d / "scene_triggered.json"), "-o", str(d / "trig"),
                          "--quiet"])
        row["trig_rc"] = rc
        row["trig_stderr"] = se.strip()[-600:]
        if rc == 0:
            ps = json.load(open(d / "trig" / "summary.json"))
            row["trig_warn"] = ps.get("warnings", [])
            row["trig_cmp"] = compare(d / "trig" / "curve.csv", d / "sim" / "specimen.csv", c["test"])
        rows.append(row)
        print(json.dumps(row), flush=True)
    json.dump(rows, open(OUT / "rows.json", "w"), indent=1)
    # Runs beyond 5 % (a stress) or 10 % (the rate) with no warning at all: each one a defect to find.
    for kind, key, warn, rc in (("--signals", "cmp", "proc_warn", "proc_rc"),
                                ("scope", "meas_cmp", "meas_warn", "meas_rc"),
                                ("triggered", "trig_cmp", "trig_warn", "trig_rc")):
        # A curve that misses the specimen's loading altogether (no comparison) counts too.
        bad = [r["id"] for r in rows if r.get(rc) == 0 and not r.get(warn) and
               (not r.get(key) or max(r[key]["e3"], r[key]["e1"], r[key]["e2"]) > 0.05 or
                r[key]["erate"] > 0.10)]
        failed = [f"{r['id']} ({r[rc]})" for r in rows if r.get(rc)]
        print(f"{kind}: {len(rows)} runs, exit != 0: {failed or 'none'}; "
              f"beyond 5 % / 10 % with no warning: {bad or 'none'}")


main()
