"""Figure of `shpb dispersion -o FILE` (docs/outputs.md, dispersion): the first-mode
Pochhammer–Chree phase and group velocities against a/Λ, and against frequency when the table
has it (--radius and --c0)."""
import os

from .drawing import new_figure, outside_legend
from .schema import columns

DISPERSION = columns("dispersion")


def fig_dispersion(src, figs):
    for name in src.dispersion:
        t = src.table(name)
        frequency = DISPERSION.frequency_Hz in t
        fig, axes = new_figure(1, 2 if frequency else 1, height=4.2,
                               width=11.0 if frequency else 7.0, sharey=True)
        abscissae = [(t.numeric(DISPERSION.a_over_lambda), "radius over wavelength a/Λ")]
        if frequency:
            abscissae.append((t.numeric(DISPERSION.frequency_Hz) * 1e-3, "frequency (kHz)"))
        for ax, (x, label) in zip(axes[0], abscissae):
            ax.plot(x, t.numeric(DISPERSION.c_over_c0), color="k", linewidth=1.2,
                    label="phase velocity c/c0")
            ax.plot(x, t.numeric(DISPERSION.cg_over_c0), color="C0", linewidth=1.0,
                    linestyle="--", label="group velocity cg/c0")
            ax.set_xlabel(label)
            outside_legend(ax)
        axes[0, 0].set_ylabel("velocity over the bar wave speed c0")
        stem = os.path.splitext(name)[0]
        figs.save(fig, src.png(f"dispersion_{stem}"), src.title(f"Dispersion: {name}"),
                  f"First-mode Pochhammer–Chree phase and group velocities of a solid round bar "
                  f"over its bar wave speed ({name}, docs/methods.md)"
                  + (", against a/Λ and against frequency." if frequency else ", against a/Λ."))
