#!/usr/bin/python3
"""`shpb simulate` against the exact solution of elastic bar chains it is not tested on
(docs/validation.md "Simulation", "Elastic chains against their exact solution").

Usage: tools/check_exact_chains.py SHPB OUTDIR [--count N] [--seed S] [--only ID,ID...] [--reuse yes]
       tools/check_exact_chains.py --exact SCENE.json     (the exact gauges and forces of one scene)

The exact solution (exact_chain() below, independent of shpb): a chain of linear elastic bars, each
its own E, density, area and length and initial rigid velocity, joined by frictionless unilateral
contacts (compression only, an initial gap allowed) or bonded joints, traced by the method of
characteristics. In each bar the axial force is N = N+ + N-, the right-going part N+ = -Z v and the
left-going N- = Z v (Z = rho c A), each a step function of time that crosses the bar in L/c. Every
end takes its incoming parts and sends its outgoing ones: a free end N = 0; a closed contact
N = 2 (a Z_r + b Z_l)/(Z_l + Z_r) (a, b the parts arriving from left and right), kept while N <= 0
(bonded: always); an open one reflects both, its gap moving at v_r - v_l = 2 b/Z_r + 2 a/Z_l until
it closes. From rigid velocities every part is a step function, so the solution is event driven and
exact (arrivals closer than 1 ps are one event). Time zero is the first contact, as in shpb.

Set-ups (setups() below, drawn with a seed): striker on a bar, bar-to-bar steps of area and
material, striker/incident/elastic specimen/transmitter (specimen of another material, of the bars'
own, wider or narrower than the bars), with an elastic pulse shaper, tension (striker pulled,
bonded chain), initial gaps, gauges 1-5 mm from an end; impedance ratios 0.05-20 at the impact and
at the specimen, strikers shorter than, equal to and longer than half the incident bar, durations
of 3-6 transits of the longest bar. Each runs `shpb simulate` three times: the defaults,
`--stepping global` and `--tolerance 1%`.

Compared (the gauges as recorded: the exact strain smoothed by the record's Gaussian of one sample
interval, docs/outputs.md): the relative L2 error of all gauges over the record (the tolerance
model's norm), each gauge's first plateau, peak, arrival (half height) and first pulse length; each
interface's first plateau force and the times its contact opens and closes again (force above 2 %
of its peak); the energy error of summary.json. Prints one JSON row per run, writes OUTDIR/rows.json,
and ends with the worst of each quantity and the runs beyond the limits (LIMITS). `--reuse yes`
compares the outputs already in OUTDIR again without running shpb.
"""
import bisect, json, math, pathlib, random, subprocess, sys

import numpy as np

EPS_T = 1e-12  # s: arrivals closer than this are one event (round-off of sums of transit times)

# ----------------------------------------------------------------------------------------- exact


class Steps:
    """A right-continuous step function: init before times[0], vals[k] from times[k]."""

    def __init__(self, init):
        self.init, self.times, self.vals = init, [], []

    def last(self):
        return self.vals[-1] if self.vals else self.init

    def set(self, t, v):
        if v == self.last():
            return
        if self.times and abs(self.times[-1] - t) <= EPS_T:
            self.vals[-1] = v
            if (self.vals[-2] if len(self.vals) > 1 else self.init) == v:
                self.times.pop(), self.vals.pop()
            return
        self.times.append(t), self.vals.append(v)

    def at(self, t):
        k = bisect.bisect_right(self.times, t) - 1
        return self.init if k < 0 else self.vals[k]

    def next_after(self, t):
        k = bisect.bisect_right(self.times, t)
        return self.times[k] if k < len(self.times) else math.inf


def exact_chain(bars, joints, t_end):
    """bars: [{E, rho, A, L, V}], joints: [{gap, bonded}] between bars k and k+1 (len(bars)-1).
    Returns (t0, P, M, contact) with P[i] (N+ leaving bar i's left end) and M[i] (N- leaving its
    right end) as Steps on the absolute clock, t0 the first contact, and per joint a list of
    (t, gap, force compression positive) at every event (the gap linear in between)."""
    n = len(bars)
    for b in bars:
        b["c"] = math.sqrt(b["E"] / b["rho"])
        b["Z"] = b["rho"] * b["c"] * b["A"]
        b["T"] = b["L"] / b["c"]
    P = [Steps(-b["Z"] * b["V"] / 2) for b in bars]
    M = [Steps(b["Z"] * b["V"] / 2) for b in bars]
    gap = [j["gap"] for j in joints]
    closed = [False] * len(joints)
    rate = [0.0] * len(joints)
    history = [[] for _ in joints]
    t0 = min([j["gap"] / (bars[k]["V"] - bars[k + 1]["V"]) for k, j in enumerate(joints)
              if bars[k]["V"] > bars[k + 1]["V"]] or [0.0])

    def incoming(k, t):  # parts arriving at junction k (0: left end of bar 0, n: right end)
        a = P[k - 1].at(t - bars[k - 1]["T"] + EPS_T) if k > 0 else 0.0
        b = M[k].at(t - bars[k]["T"] + EPS_T) if k < n else 0.0
        return a, b

    def settle(t):
        for k in range(n + 1):
            a, b = incoming(k, t)
            if k == 0:
                P[0].set(t, -b)
                continue
            if k == n:
                M[n - 1].set(t, -a)
                continue
            j, zl, zr = k - 1, bars[k - 1]["Z"], bars[k]["Z"]
            force = 2 * (a * zr + b * zl) / (zl + zr)
            if gap[j] <= 0 and (joints[j]["bonded"] or force <= 0):
                closed[j], gap[j], rate[j] = True, 0.0, 0.0
                M[k - 1].set(t, force - a), P[k].set(t, force - b)
                history[j].append((t, 0.0, -force))
            else:
                closed[j] = False
                M[k - 1].set(t, -a), P[k].set(t, -b)
                rate[j] = 2 * b / zr + 2 * a / zl
                history[j].append((t, gap[j], 0.0))

    t = 0.0
    settle(t)
    while t < t_end:
        nxt = math.inf
        for k in range(n + 1):
            if k > 0:
                nxt = min(nxt, P[k - 1].next_after(t - bars[k - 1]["T"] + EPS_T) + bars[k - 1]["T"])
            if k < n:
                nxt = min(nxt, M[k].next_after(t - bars[k]["T"] + EPS_T) + bars[k]["T"])
        closing = [t + gap[j] / -rate[j] if not closed[j] and rate[j] < 0 else math.inf
                   for j in range(len(joints))]
        t_next = min(nxt, min(closing, default=math.inf), t_end)
        for j in range(len(joints)):
            if not closed[j]:
                gap[j] = 0.0 if closing[j] <= t_next + EPS_T else gap[j] + rate[j] * (t_next - t)
        t = t_next
        settle(t)
    return t0, P, M, history


def gauge_steps(bars, P, M, i, x, t0):
    """The exact strain at x on bar i: (initial value, jump times on the clock from t0, jumps)."""
    b = bars[i]
    d1, d2 = x / b["c"], (b["L"] - x) / b["c"]
    ea = b["E"] * b["A"]
    times = [tt + d1 for tt in P[i].times] + [tt + d2 for tt in M[i].times]
    jumps = list(np.diff([P[i].init] + P[i].vals)) + list(np.diff([M[i].init] + M[i].vals))
    order = np.argsort(times, kind="stable")
    tj = np.array(times)[order] - t0 if times else np.zeros(0)
    dj = np.array(jumps)[order] / ea if times else np.zeros(0)
    return (P[i].init + M[i].init) / ea, tj, dj


def step_value(init, tj, dj, t):
    c = np.concatenate([[0.0], np.cumsum(dj)])
    return init + c[np.searchsorted(tj, t, side="right")]


def phi(z):
    """The standard normal distribution function (Abramowitz & Stegun 7.1.26: within 1.5e-7)."""
    x = np.abs(z) / math.sqrt(2)
    u = 1 / (1 + 0.3275911 * x)
    erf = 1 - u * (0.254829592 + u * (-0.284496736 + u * (1.421413741 + u * (-1.453152027
                                                                              + u * 1.061405429)))) * np.exp(-x * x)
    return 0.5 * (1 + np.sign(z) * erf)


def smoothed(init, tj, dj, t, sigma):
    """The step function seen through a Gaussian of standard deviation sigma."""
    if sigma <= 0:
        return step_value(init, tj, dj, t)
    out = step_value(init, tj, dj, t - 8 * sigma)
    lo = np.searchsorted(tj, t - 8 * sigma, side="right")
    hi = np.searchsorted(tj, t + 8 * sigma, side="right")
    for k in range(int((hi - lo).max(initial=0))):
        j = lo + k
        m = j < hi
        if not m.any():
            break
        jj = np.where(m, j, 0)
        out = out + np.where(m, dj[jj] * phi((t - tj[jj]) / sigma), 0.0)
    return out


# ------------------------------------------------------------------------------------ set-ups

MATERIALS = {  # E (Pa), density (kg/m3), Poisson ratio
    "steel": (200e9, 7850, 0.29), "aluminium": (70e9, 2700, 0.33), "titanium": (114e9, 4430, 0.34),
    "magnesium": (45e9, 1770, 0.35), "brass": (105e9, 8500, 0.34), "tungsten-carbide": (600e9, 15000, 0.22),
    "pmma": (3.2e9, 1190, 0.35), "nylon": (2.8e9, 1140, 0.39), "copper": (120e9, 8940, 0.34),
}


def scene_from(bars_spec, contact, duration, rate=10e6, name="exact"):
    """bars_spec: [{name, mat, L, D or A, V, gap, gauges:[(name, x)], bonded_right}]."""
    mats = {}
    bars = []
    for b in bars_spec:
        E, rho, nu = MATERIALS[b["mat"]]
        mats[b["mat"]] = {"model": "elastic", "density": rho, "youngs_modulus": E, "poisson_ratio": nu}
        e = {"name": b["name"], "material": b["mat"], "length": b["L"]}
        e["diameter" if "D" in b else "area"] = b.get("D", b.get("A"))
        if b.get("V"):
            e["velocity"] = b["V"]
        if b.get("gap"):
            e["gap"] = b["gap"]
        if b.get("gauges"):
            e["gauges"] = [{"name": g, "position": x} for g, x in b["gauges"]]
        bars.append(e)
    sc = {"name": name, "bars": bars, "materials": mats,
          "simulation": {"duration": duration, "sample_rate": rate}}
    if any(b.get("specimen") for b in bars_spec):
        sc["specimen"] = next(b["name"] for b in bars_spec if b.get("specimen"))
    if contact:
        sc["contact"] = contact
    return sc


def chain_of(scene):
    """The exact solver's chain of a scene written by scene_from (SI numbers)."""
    bonded_all = scene.get("contact", {}).get("method") == "bonded"
    over = {tuple(sorted(o["between"])): o.get("method") == "bonded"
            for o in scene.get("contact", {}).get("interfaces", [])}
    bars, joints = [], []
    for k, b in enumerate(scene["bars"]):
        m = scene["materials"][b["material"]]
        area = b["area"] if "area" in b else math.pi * b["diameter"] ** 2 / 4
        bars.append({"E": m["youngs_modulus"], "rho": m["density"], "A": area, "L": b["length"],
                     "V": b.get("velocity", 0.0)})
        if k + 1 < len(scene["bars"]):
            key = tuple(sorted((b["name"], scene["bars"][k + 1]["name"])))
            joints.append({"gap": b.get("gap", 0.0), "bonded": over.get(key, bonded_all)})
    return bars, joints


def setups(count, seed):
    rng = random.Random(seed)
    out = []
    kinds = ["striker-bar", "step", "kolsky", "kolsky", "shaper", "tension", "gaps", "three-bar"]
    for i in range(count):
        kind = kinds[i % len(kinds)]
        bar_mat = rng.choice(["steel", "aluminium", "titanium", "magnesium", "steel", "pmma"])
        D = rng.choice([0.0127, 0.016, 0.019, 0.02, 0.025])
        L_inc = rng.choice([0.6, 0.8, 1.0, 1.2, 1.5])
        L_s = L_inc / 2 * rng.choice([0.3, 0.6, 1.0, 1.0, 1.4, 1.8])
        V = rng.choice([3.0, 5.0, 10.0, 15.0, 20.0])
        if bar_mat in ("pmma",):
            V = min(V, 5.0)
        near = rng.choice([0.001, 0.003, 0.005])
        s_mat = rng.choice([bar_mat, bar_mat, "steel", "aluminium", "tungsten-carbide", "brass",
                            "magnesium", "pmma"])
        s_D = D * rng.choice([0.5, 0.8, 1.0, 1.0, 1.3, 2.0])
        striker = {"name": "striker", "mat": s_mat, "L": L_s, "D": s_D, "V": V}
        c_bar = math.sqrt(MATERIALS[bar_mat][0] / MATERIALS[bar_mat][1])
        if kind == "striker-bar":
            bars = [striker, {"name": "bar", "mat": bar_mat, "L": L_inc, "D": D,
                              "gauges": [("mid", L_inc / 2), ("near_impact", near),
                                         ("near_far_end", L_inc - near)]}]
            if rng.random() < 0.5:
                striker["gap"] = rng.choice([0.0005, 0.002])
            contact = None
        elif kind == "step":
            m2 = rng.choice(["steel", "aluminium", "titanium", "brass", "magnesium"])
            D2 = D * rng.choice([0.4, 0.6, 1.0, 1.5, 2.5])
            L2 = rng.choice([0.4, 0.8, 1.2])
            bars = [striker, {"name": "bar1", "mat": bar_mat, "L": L_inc, "D": D,
                              "gauges": [("g1", L_inc / 2)]},
                    {"name": "bar2", "mat": m2, "L": L2, "D": D2,
                     "gauges": [("g2", L2 / 2), ("g2_near", near)]}]
            contact = None
        elif kind in ("kolsky", "shaper", "gaps", "tension"):
            sp_mat = rng.choice([bar_mat, "aluminium", "magnesium", "pmma", "tungsten-carbide",
                                 "nylon", "copper", "titanium"])
            sp_D = D * rng.choice([0.3, 0.5, 0.7, 1.0, 1.5])
            sp_L = rng.choice([0.004, 0.006, 0.01, 0.02])
            L_tr = rng.choice([0.6, 1.0, 1.5])
            bars = [striker,
                    {"name": "incident", "mat": bar_mat, "L": L_inc, "D": D,
                     "gauges": [("incident", L_inc / 2), ("inc_near_specimen", L_inc - near)]},
                    {"name": "specimen", "mat": sp_mat, "L": sp_L, "D": sp_D, "specimen": True},
                    {"name": "transmitter", "mat": bar_mat, "L": L_tr, "D": D,
                     "gauges": [("transmitted", rng.choice([0.1, 0.3, L_tr / 2])),
                                ("tr_near_far_end", L_tr - near)]}]
            contact = None
            if kind == "shaper":
                sh = {"name": "shaper", "mat": rng.choice(["copper", "aluminium", "brass", "pmma"]),
                      "L": rng.choice([0.001, 0.002, 0.004]), "D": D * rng.choice([0.3, 0.5, 0.8])}
                bars.insert(1, sh)
            if kind == "gaps":
                striker["gap"] = rng.choice([0.001, 0.005])
                bars[1]["gap"] = rng.choice([1e-5, 5e-5, 2e-4])
                bars[2]["gap"] = rng.choice([0.0, 1e-5, 1e-4])
            if kind == "tension":
                striker["V"] = -V
                contact = {"method": "bonded"}
        else:  # three-bar: striker, two bars, the second with a far gauge, one pair bonded
            m2 = rng.choice([bar_mat, "aluminium", "steel", "pmma"])
            bars = [striker, {"name": "bar1", "mat": bar_mat, "L": L_inc, "D": D,
                              "gauges": [("g1", L_inc / 2)]},
                    {"name": "bar2", "mat": m2, "L": 0.3, "D": D * rng.choice([0.7, 1.0, 1.4]),
                     "gauges": [("g2", 0.15)]},
                    {"name": "bar3", "mat": bar_mat, "L": 0.5, "D": D, "gauges": [("g3", 0.25)]}]
            contact = {"method": "localized-bipenalty",
                       "interfaces": [{"between": ["bar2", "bar3"], "method": "bonded"}]}
        longest = max(b["L"] / math.sqrt(MATERIALS[b["mat"]][0] / MATERIALS[b["mat"]][1])
                      for b in bars)
        duration = round(longest * rng.choice([3.0, 4.5, 6.0]) * 1e6) * 1e-6
        duration = min(duration, 3e-3)
        sc = scene_from(bars, contact, duration, name=f"{i:02d}-{kind}")
        out.append((f"{i:02d}-{kind}", sc))
    return out


# ----------------------------------------------------------------------------------- compare

LIMITS = {"energy": 0.005}
SEPARATION_MIN = 2e-6  # s: an opening that lasts this long is a separation
SEPARATION_GAP = 0.05  # of the exact largest gap of the interface: open, not touching
RUNS = {"default": [], "global": ["--stepping", "global"], "tol1": ["--tolerance", "1%"]}


def read_csv(path):
    with open(path) as f:
        head = f.readline().strip().split(",")
    data = np.loadtxt(path, delimiter=",", skiprows=1, ndmin=2)
    return head, data


def first_pulse(t, y, level):
    """Half-height arrival and the time the signal falls back below half of `level` after it."""
    half = 0.5 * level
    s = np.sign(level)
    above = s * y >= s * half
    if not above.any():
        return math.nan, math.nan
    k = int(np.argmax(above))
    ta = t[k] if k == 0 else t[k - 1] + (t[k] - t[k - 1]) * (s * half - s * y[k - 1]) / (s * y[k] - s * y[k - 1])
    below = ~above[k:]
    if not below.any():
        return ta, math.nan
    m = k + int(np.argmax(below))
    te = t[m - 1] + (t[m] - t[m - 1]) * (s * y[m - 1] - s * half) / (s * y[m - 1] - s * y[m])
    return ta, te - ta


def open_intervals(t, is_open, min_len):
    """(start, end) of each run of `is_open` samples at least min_len long (end NaN: to the end)."""
    out, k, n = [], 0, len(t)
    while k < n:
        if not is_open[k]:
            k += 1
            continue
        m = k
        while m < n and is_open[m]:
            m += 1
        if t[m - 1] - t[k] >= min_len or m == n:
            out.append((t[k], t[m] if m < n else math.nan))
        k = m
    return out


def compare(scene, folder):
    bars, joints = chain_of(scene)
    head, g = read_csv(folder / "gauges.csv")
    t = g[:, 0]
    dt = t[1] - t[0]
    summ = json.loads((folder / "summary.json").read_text())
    filtered = "tolerance" in summ
    t0, P, M, hist = exact_chain(bars, joints, t[-1] + 1e-9 + first_contact(bars, joints))
    res = {"energy_error": summ.get("energy_error"), "stable": summ.get("stable"),
           "warnings": len(summ.get("warnings", [])), "gauges": {}, "interfaces": {}}
    num = den = 0.0
    gauges = {gg["name"]: (i, gg["position"]) for i, b in enumerate(scene["bars"])
              for gg in b.get("gauges", [])}
    for col, name in enumerate(head[1:], start=1):
        i, x = gauges[name]
        init, tj, dj = gauge_steps(bars, P, M, i, x, t0)
        ex = smoothed(init, tj, dj, t, dt if filtered else 0.0)
        sim = g[:, col]
        num += float(np.sum((sim - ex) ** 2))
        den += float(np.sum(ex ** 2))
        r = {}
        if len(dj):
            level = dj[0]
            nxt = tj[1] if len(tj) > 1 else t[-1]
            plateau = (tj[0], min(nxt, t[-1]))
            r["plateau_exact"] = level
            if plateau[1] - plateau[0] > 8 * dt:
                w = (t > plateau[0] + 3 * dt) & (t < plateau[1] - 3 * dt)
                r["plateau_err"] = float(np.median(sim[w]) / level - 1)
            pk = np.argmax(np.abs(ex))
            r["peak_err"] = float(np.max(np.abs(sim)) / abs(ex[pk]) - 1)
            ta_e, len_e = first_pulse(t, ex, level)
            ta_s, len_s = first_pulse(t, sim, level)
            r["arrival_err_s"] = ta_s - ta_e
            r["length_err_s"] = len_s - len_e
        res["gauges"][name] = r
    res["l2"] = math.sqrt(num / den) if den > 0 else math.nan
    fh, fd = read_csv(folder / "interfaces.csv")
    for j, hj in enumerate(hist):
        name = fh[1 + 2 * j][: -len("_force_N")]
        ht = np.array([h[0] for h in hj]) - t0
        hf = np.array([h[2] for h in hj])
        hg = np.array([h[1] for h in hj])
        k = np.searchsorted(ht, t, side="right") - 1
        ex_f = np.where(k >= 0, hf[np.maximum(k, 0)], 0.0)
        sim_f, sim_g = fd[:, 1 + 2 * j], fd[:, 2 + 2 * j]
        fpk = max(np.max(np.abs(ex_f)), 1e-30)
        r = {"peak_force_exact": float(fpk), "peak_force_err": float(np.max(np.abs(sim_f)) / fpk - 1)}
        ex_g = np.interp(t, ht, hg)
        r["gap_max_exact"] = float(np.max(ex_g))
        r["gap_err"] = float(np.max(np.abs(sim_g - ex_g)))
        first = next((kk for kk in range(len(ht)) if hf[kk] != 0), None)
        if first is not None:
            lvl = hf[first]
            nxt = next((ht[kk] for kk in range(first + 1, len(ht)) if hf[kk] != lvl), t[-1])
            if nxt - ht[first] > 8 * dt:
                w = (t > ht[first] + 3 * dt) & (t < nxt - 3 * dt)
                r["plateau_force_err"] = float(np.median(sim_f[w]) / lvl - 1)
        if not joints[j]["bonded"]:
            # Separations as the gap shows them: open wider than SEPARATION_GAP of the exact
            # largest gap (a release at a vanishing force tail, r^n of an elastic specimen's
            # ring-down, leaves both faces touching to within nanometres), for SEPARATION_MIN.
            wide = max(SEPARATION_GAP * float(np.max(ex_g)), 1e-9)
            e_ex = open_intervals(t, ex_g > wide, SEPARATION_MIN)
            e_sim = open_intervals(t, sim_g > wide, SEPARATION_MIN)
            r["separations_exact"] = [list(map(float, e)) for e in e_ex]
            r["separations_sim"] = [list(map(float, e)) for e in e_sim]
            r["separation_count"] = [len(e_ex), len(e_sim)]
            if e_ex and e_sim:
                r["first_release_err_s"] = float(e_sim[0][0] - e_ex[0][0])
                if not math.isnan(e_ex[0][1]) and not math.isnan(e_sim[0][1]):
                    r["first_reclose_err_s"] = float(e_sim[0][1] - e_ex[0][1])
                elif math.isnan(e_ex[0][1]) != math.isnan(e_sim[0][1]):
                    r["first_reclose_err_s"] = math.inf
            elif e_ex or e_sim:
                r["first_release_err_s"] = math.inf
        res["interfaces"][name] = r
    return res


def first_contact(bars, joints):
    return min([j["gap"] / (bars[k]["V"] - bars[k + 1]["V"]) for k, j in enumerate(joints)
                if bars[k]["V"] > bars[k + 1]["V"]] or [0.0])


def main(argv):
    if argv[1:2] == ["--exact"]:
        sc = json.loads(pathlib.Path(argv[2]).read_text())
        bars, joints = chain_of(sc)
        t0, P, M, hist = exact_chain(bars, joints, sc["simulation"]["duration"] + first_contact(bars, joints))
        for j, h in enumerate(hist):
            print("joint", j, [(round((a - t0) * 1e6, 4), g, f) for a, g, f in h][:40])
        return 0
    shpb, out = argv[1], pathlib.Path(argv[2])
    opts = dict(zip(argv[3::2], argv[4::2]))
    count, seed = int(opts.get("--count", 60)), int(opts.get("--seed", 1))
    only = set(opts["--only"].split(",")) if "--only" in opts else None
    reuse = opts.get("--reuse") == "yes"
    out.mkdir(parents=True, exist_ok=True)
    rows = []
    for sid, sc in setups(count, seed):
        if only and sid not in only and sid[:2] not in only:
            continue
        d = out / sid
        d.mkdir(exist_ok=True)
        (d / "scene.json").write_text(json.dumps(sc, indent=1))
        for run, extra in RUNS.items():
            o = d / run
            if reuse and (o / "summary.json").exists():  # compared again, not run again
                p = subprocess.CompletedProcess([], 0, "", "")
            else:
                p = subprocess.run([shpb, "simulate", str(d / "scene.json"), "-o", str(o), "-q"]
                                   + extra, capture_output=True, text=True)
            row = {"id": sid, "run": run, "exit": p.returncode, "stderr": p.stderr.strip()[-300:]}
            if p.returncode == 0 or (o / "gauges.csv").exists():
                try:
                    row.update(compare(sc, o))
                except Exception as e:  # a finding: report, do not stop the survey
                    row["compare_error"] = repr(e)
            rows.append(row)
            print(json.dumps({k: row.get(k) for k in ("id", "run", "exit", "l2", "energy_error")}),
                  flush=True)
    (out / "rows.json").write_text(json.dumps(rows, indent=1))
    summarize(rows)
    return 0


def summarize(rows):
    worst = {}

    def note(q, v, where):
        if v is None or (isinstance(v, float) and math.isnan(v)):
            return
        if q not in worst or abs(v) > abs(worst[q][0]):
            worst[q] = (v, where)

    for r in rows:
        w = f"{r['id']}/{r['run']}"
        note("l2 " + r["run"], r.get("l2"), w)
        note("energy", r.get("energy_error"), w)
        for gname, gr in r.get("gauges", {}).items():
            for q in ("plateau_err", "peak_err", "arrival_err_s", "length_err_s"):
                note(q, gr.get(q), w + ":" + gname)
        for iname, ir in r.get("interfaces", {}).items():
            for q in ("plateau_force_err", "peak_force_err", "first_release_err_s",
                      "first_reclose_err_s"):
                note(q, ir.get(q), w + ":" + iname)
    print(f"{len(rows)} runs of {len({r['id'] for r in rows})} set-ups")
    for q, (v, w) in sorted(worst.items()):
        print(f"worst {q}: {v:.4g} at {w}")
    bad = [r for r in rows if r["exit"] != 0 or "compare_error" in r]
    for r in bad:
        print("FAILED", r["id"], r["run"], r["exit"], r.get("stderr"), r.get("compare_error"))


if __name__ == "__main__":
    sys.exit(main(sys.argv))
