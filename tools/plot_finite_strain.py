#!/usr/bin/python3
"""Finite against small strain: processed true stress-strain curves of the same simulated test
(curve.csv of `shpb process --signals`) over the law the specimen followed (true columns of the
finite-strain run's specimen.csv), docs/methods.md §8.

  /usr/bin/python3 tools/plot_finite_strain.py FINITE_PROC SMALL_PROC FINITE_SIM OUT.png

FINITE_PROC and SMALL_PROC are `process` output folders, FINITE_SIM the `simulate` folder of the
finite-strain run.
"""
import csv
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def columns(path, *names):
    rows = list(csv.DictReader(open(path)))
    return [[float(r[n]) for r in rows] for n in names]


def main(argv):
    if len(argv) != 5:
        raise SystemExit(__doc__.strip())
    finite, small, sim, out = argv[1:]
    fig, ax = plt.subplots(figsize=(7.5, 4.5))
    law_e, law_s, eng = columns(os.path.join(sim, "specimen.csv"), "true_strain", "true_stress_Pa",
                                "strain_rate_1_s")
    keep = [i for i, r in enumerate(eng) if r > 0]  # loading
    ax.plot([law_e[i] * 100 for i in keep], [law_s[i] / 1e6 for i in keep], color="k",
            linewidth=2.2, label="law as the specimen followed it (model truth)")
    for folder, label, color in ((finite, "processed, finite strain (default)", "C0"),
                                 (small, 'processed, "kinematics": "small"', "C3")):
        e, s, rate = columns(os.path.join(folder, "curve.csv"), "true_strain", "true_stress_Pa",
                             "strain_rate_1_s")
        keep = [i for i, r in enumerate(rate) if r > 0]
        ax.plot([e[i] * 100 for i in keep], [s[i] / 1e6 for i in keep], color=color,
                linewidth=1.2, linestyle="--", label=label)
    ax.set_xlabel("true strain (%, compression +)")
    ax.set_ylabel("true stress (MPa, compression +)")
    ax.set_title("Classic Al 6061-T6 test simulated and processed back")
    ax.grid(alpha=0.3)
    ax.legend(loc="lower right", fontsize=8)
    fig.tight_layout()
    fig.savefig(out, dpi=110)


if __name__ == "__main__":
    main(sys.argv)
