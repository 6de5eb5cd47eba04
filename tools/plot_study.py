#!/usr/bin/python3
"""Figures of a `shpb study` output folder.

  /usr/bin/python3 tools/plot_study.py DIR [--out OUTDIR]

pareto.csv    -> pareto.png: gauge error against wall time, one marker per method and stepping,
                 resolution next to each point, the Pareto front as a line.
stability.csv -> stability_<method>.png: stable/unstable map over penalty stiffness and Courant
                 number (one panel per mass ratio R/R_crit for the bipenalty methods), with the
                 measured boundary and the closed form from stability_boundary.csv.
"""
import argparse
import csv
import math
import os

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def read_csv(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def num(text):
    return float(text) if text not in ("", None) else math.nan


def plot_pareto(folder, out):
    rows = read_csv(os.path.join(folder, "pareto.csv"))
    fig, ax = plt.subplots(figsize=(7, 4.5))
    markers = {"penalty": "x", "bipenalty": "s", "localized-bipenalty": "o",
               "localized-bipenalty-finite": "D"}
    colors = {"asynchronous": "tab:blue", "global": "tab:orange"}
    points = []
    for method in markers:
        for stepping in colors:
            sel = [r for r in rows if r["method"] == method and r["stepping"] == stepping
                   and r["stable"] == "1" and not math.isnan(num(r["error"]))]
            if not sel:
                continue
            x = [num(r["wall_time_s"]) for r in sel]
            y = [num(r["error"]) for r in sel]
            ax.plot(x, y, marker=markers[method], color=colors[stepping], linestyle=":",
                    fillstyle="none" if stepping == "global" else "full",
                    label=f"{method}, {stepping}")
            for r, xi, yi in zip(sel, x, y):
                res = num(r["resolution"])
                text = f"1/{1 / res:g}" if res < 1 else f"{res:g}"
                ax.annotate(text, (xi, yi), textcoords="offset points", xytext=(4, 3), fontsize=7)
            points += list(zip(x, y))
    front = [p for p in points
             if not any(q != p and q[0] <= p[0] and q[1] <= p[1] for q in points)]
    front.sort()
    if front:
        ax.step([p[0] for p in front], [p[1] for p in front], where="post", color="k", lw=1,
                label="Pareto front")
    unstable = [r for r in rows if r["stable"] != "1"]
    if unstable:
        names = sorted({f'{r["method"]}/{r["stepping"]}' for r in unstable})
        ax.text(0.01, 0.99, "unstable (not shown): " + ", ".join(names), transform=ax.transAxes,
                fontsize=7, va="top")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("wall time of the solve [s]")
    ax.set_ylabel("relative L2 gauge error")
    ax.set_title("Accuracy against cost (labels: mesh resolution factor)", fontsize=10)
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=7, loc="lower left")
    fig.tight_layout()
    path = os.path.join(out, "pareto.png")
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return path


def plot_stability(folder, out):
    rows = read_csv(os.path.join(folder, "stability.csv"))
    bpath = os.path.join(folder, "stability_boundary.csv")
    bounds = read_csv(bpath) if os.path.exists(bpath) else []
    paths = []
    # Localized bipenalty is mapped at several step ratios (asynchronous): one chart per ratio.
    def key(r):
        q = r.get("step_ratio", "") or "1"
        return r["method"] if num(q) == 1 else f"{r['method']}_step-ratio-{num(q):.3g}"
    for r in rows:
        r["method"] = key(r)
    for b in bounds:
        b["method"] = key(b)
    for method in sorted({r["method"] for r in rows}):
        mine = [r for r in rows if r["method"] == method]
        ratios = sorted({num(r["mass_ratio"]) for r in mine}, key=lambda v: (math.isnan(v), v))
        if method != "penalty":
            keep = [v for v in ratios if v in (0.25, 1.0, 2.0, 4.0)]
            ratios = keep or ratios
        fig, axes = plt.subplots(1, len(ratios), figsize=(3.2 * len(ratios) + 0.6, 3.4),
                                 squeeze=False, sharey=True)
        for ax, ratio in zip(axes[0], ratios):
            sel = [r for r in mine if (math.isnan(ratio) and r["mass_ratio"] == "")
                   or num(r["mass_ratio"]) == ratio]
            for stable, style in (("1", dict(marker="o", color="tab:green", s=10)),
                                  ("0", dict(marker="x", color="tab:red", s=14))):
                pts = [r for r in sel if r["stable"] == stable]
                ax.scatter([num(r["stiffness_factor"]) for r in pts],
                           [num(r["courant"]) for r in pts],
                           label="stable" if stable == "1" else "unstable", **style)
            lines = [b for b in bounds if b["method"] == method and
                     ((math.isnan(ratio) and b["mass_ratio"] == "") or num(b["mass_ratio"]) == ratio)]
            for link, style in (("unilateral", "k-"), ("tied", "b--")):
                bl = sorted((num(b["stiffness_factor"]), num(b["critical_courant"]),
                             num(b["closed_form_courant"])) for b in lines if b["link"] == link)
                if not bl:
                    continue
                ax.plot([b[0] for b in bl], [b[1] for b in bl], style, lw=1,
                        label=f"measured boundary ({link})")
            cf = sorted((num(b["stiffness_factor"]), num(b["closed_form_courant"])) for b in lines)
            if cf:
                ax.plot([b[0] for b in cf], [b[1] for b in cf], color="tab:purple", lw=1,
                        linestyle=":", label="closed form")
            ax.set_xscale("log")
            ax.set_ylim(0, 1.1)
            ax.set_xlabel("penalty stiffness / (EA/h)")
            ax.set_title(method if math.isnan(ratio) else f"{method}, R/R_crit = {ratio:g}",
                         fontsize=9)
            ax.grid(True, alpha=0.3)
        axes[0][0].set_ylabel("Courant number c dt/h")
        axes[0][-1].legend(fontsize=6, loc="lower left")
        fig.tight_layout()
        path = os.path.join(out, f"stability_{method}.png")
        fig.savefig(path, dpi=100)
        plt.close(fig)
        paths.append(path)
    return paths


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("folder")
    p.add_argument("--out", help="where to write the PNGs (default: the folder)")
    a = p.parse_args()
    out = a.out or a.folder
    os.makedirs(out, exist_ok=True)
    made = []
    if os.path.exists(os.path.join(a.folder, "pareto.csv")):
        made.append(plot_pareto(a.folder, out))
    if os.path.exists(os.path.join(a.folder, "stability.csv")):
        made += plot_stability(a.folder, out)
    if not made:
        raise SystemExit(f"error: {a.folder}: no pareto.csv or stability.csv: not a study folder")
    for m in made:
        print(m)


if __name__ == "__main__":
    main()
