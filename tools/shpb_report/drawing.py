"""What every figure module shares: units, the figure collector, axes style and legends.

Conventions (docs/outputs.md): times in µs, bar strains in µε, specimen strains in %, stresses
in MPa; signals tension positive, specimen quantities compression positive.
"""
import logging
import os

# Quiet before matplotlib is imported: with a home it cannot write (another user's, a read-only
# one) it says so on stderr at import, where only the one result or error line goes. A figure of
# an odd but valid file (an all-empty column, nothing to label) is drawn without its chatter too.
logging.getLogger("matplotlib").setLevel(logging.ERROR)
import matplotlib  # noqa: E402

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from .reading import ReportError  # noqa: E402

DPI = 100
# Rows of panels one figure holds: 64 draw in about 7 s; 300 asked for a PNG beyond Agg's 2^16
# pixels (a bug's exit 4), and squeezed into one they took minutes (the constrained layout).
MAX_PANEL_ROWS = 64
US = 1e6  # s -> µs
MICRO = 1e6  # strain -> µε
MPA = 1e-6  # Pa -> MPa


class Figures:
    """Collects figures: saves each PNG in figures/ and remembers its caption."""

    def __init__(self, out_dir):
        self.out_dir = out_dir
        self.items = []  # (file name, title, caption)

    def save(self, fig, name, title, caption):
        entitle(fig, title)
        path = os.path.join(self.out_dir, name)
        fig.savefig(path, dpi=DPI)
        plt.close(fig)
        self.items.append((name, title, caption))


def figure_title(fig):
    """The figure's own title: its suptitle, else its axes' titles joined, else ""."""
    if fig._suptitle is not None and fig._suptitle.get_text():  # get_suptitle: matplotlib 3.8
        return fig._suptitle.get_text()
    return " ".join(t for t in (ax.get_title() for ax in fig.axes) if t)


def entitle(fig, title):
    """Every saved figure carries a title: a figure drawn without one (the bars-together check,
    the plan's figures) gets the page's, so that a PNG opened alone says what it shows."""
    if not figure_title(fig):
        fig.suptitle(title)


def close_all():
    """Closes every figure, also one left open by an error while it was drawn."""
    plt.close("all")


def grid(ax):
    ax.grid(True, color="0.88", linewidth=0.6)
    ax.set_axisbelow(True)


def panel_rows(count, path, what):
    """`count` rows of panels, one per gauge or test of the file `path`: more than a figure
    holds is a bad input (exit 2), named."""
    if count > MAX_PANEL_ROWS:
        raise ReportError(f"{path}: {count} {what}: at most {MAX_PANEL_ROWS} were expected (a "
                          "row of panels each)")
    return count


def new_figure(rows=1, cols=1, height=4.2, width=9.0, **kw):
    fig, axes = plt.subplots(rows, cols, figsize=(width, height), squeeze=False,
                             constrained_layout=True, **kw)
    for ax in axes.flat:
        grid(ax)
    return fig, axes


def outside_legend(ax):
    """A legend above the axes, in one row: it never hides a trace."""
    handles, labels = ax.get_legend_handles_labels()
    if handles:
        ax.legend(loc="lower left", bbox_to_anchor=(0.0, 1.0), ncol=min(len(handles), 4),
                  fontsize=8, frameon=False)


def gauge_columns(table):
    return [n for n in table.names if n != "time_s"]


def ratio_finite(values):
    return np.where(np.isfinite(values), values, np.nan)
