"""The one-page report: a section per output folder (headline figures of a processed test, every
warning, summary.json as tables, comparison.csv) and every figure embedded as base64 PNG, so the
page is self-contained, each linking its file in figures/."""
import base64
import datetime
import html
import json
import math
import os

from .drawing import MPA
from .reading import NUMBER

# The generator line marks a report.html as this package's own (folder.py, ownership).
GENERATOR = "<meta name='generator' content='shpb report'>"


def summary_html(src):
    s = src.summary
    if not isinstance(s, dict) or not s:
        return ""
    scalars = [(k, v) for k, v in s.items() if not isinstance(v, (dict, list))]
    out = []
    if scalars:
        out.append("<table class='kv'>")
        for k, v in scalars:
            out.append(f"<tr><th>{html.escape(str(k))}</th><td>{html.escape(fmt(v))}</td></tr>")
        out.append("</table>")
    for k, v in s.items():
        # A list of records, or records by name (fit's parameters: value, unit, interval_95 …,
        # its result, which was seen only in the folded summary.json), is a table.
        named = (isinstance(v, dict) and v and all(isinstance(r, dict) for r in v.values()))
        if named:
            v = [{"name": name, **r} for name, r in v.items()]
        if isinstance(v, list) and v and all(isinstance(r, dict) for r in v):
            if k == "warnings":
                continue
            keys = list(dict.fromkeys(key for r in v for key in r))
            out.append(f"<p class='cap'>{html.escape(k)}</p><table><tr>"
                       + "".join(f"<th>{html.escape(c)}</th>" for c in keys) + "</tr>")
            for r in v:
                out.append("<tr>" + "".join(f"<td>{html.escape(fmt(r.get(c, '')))}</td>"
                                            for c in keys) + "</tr>")
            out.append("</table>")
    try:
        text = json.dumps(s, indent=2)
    except RecursionError:  # read, but nested too deep to print back
        text = "(nested too deeply to show)"
    out.append("<details><summary>summary.json</summary><pre>" + html.escape(text)
               + "</pre></details>")
    return "\n".join(out)


def headline_html(src):
    """What a reader of a processed test needs first (striker, rate, stress, equilibrium), and
    every warning of any producer: a run can be stable and still not physical."""
    rows = []

    def number(*keys):
        return src.value(*keys, kind=NUMBER)

    if src.value("command") == "process":
        v = number("striker_velocity_m_s", "inferred")
        if src.value("striker_velocity_m_s", "meaningful") is False:
            rows.append(("striker velocity (inferred)",
                         "not meaningful: a pulse shaper sets the incident plateau"))
        elif v is not None:
            scene_v = number("striker_velocity_m_s", "scene")
            rows.append(("striker velocity (inferred)", f"{v:.4g} m/s"
                         + (f" (scene: {scene_v:.4g} m/s)" if scene_v is not None else "")))
        plateau = number("plateau_strain_rate_1_s")
        mean = number("strain_rate", "mean_over_loading_1_s")
        window_mean = number("strain_rate", "mean_over_window_1_s")
        if window_mean is not None:
            lo, hi = (number("strain_rate", "window", "strain", i) for i in (0, 1))
            t0, t1 = (number("strain_rate", "window", "time_s", i) for i in (0, 1))
            span = (f"strain {lo:.4g}–{hi:.4g}" if lo is not None and hi is not None else
                    f"{t0 * 1e6:.6g}–{t1 * 1e6:.6g} µs" if t0 is not None and t1 is not None
                    else "the scene's window")
            rows.append(("strain rate (mean over the rate window)",
                         f"{window_mean:.4g} 1/s over {span}"))
        elif plateau is not None:
            rows.append(("strain rate (plateau)", f"{plateau:.4g} 1/s"))
        elif mean is not None:
            rows.append(("strain rate", f"no plateau; mean over the loading {mean:.4g} 1/s"))
        primary = src.value("primary", "reduction", kind=str) or "3-wave"
        # The reduction the headline peak comes from (summary.json peak_stress_from; the
        # transmitted face's in equilibrium), the primary one in summaries without it.
        source = src.value("peak_stress_from", "reduction", kind=str) or primary
        peak = number("peak_stress_Pa")
        if peak is not None:
            rows.append((f"peak {source} stress"
                         + ("" if source == primary else " (transmitted face, in equilibrium)"),
                         f"{peak * MPA:.4g} MPa"))
        strain = number("max_strain")
        if strain is not None:
            how = src.value("end_of_loading", "how", kind=str) or ""
            record = number("end_of_loading", "record_max_strain")
            if src.value("end_of_loading", "cut_short") is True and record is not None:
                rows.append(("strain at the end of loading",
                             f"{strain:.4g}, short of the record's strain maximum {record:.4g} "
                             f"({how})"))
            else:
                rows.append(("strain at the end of loading", f"{strain:.4g} ({how})"))
        frac = number("equilibrium", "fraction_of_loaded_time")
        if frac is not None:
            t_eq = number("time_to_equilibrium_s")
            t_from = number("equilibrium", "holds_until_unloading_from_s")
            # time_to_equilibrium_s counts from the window start; the figures' axis is the
            # faces' clock, on which the same instant is equilibrium.holds_until_unloading_from_s.
            clock = (f" ({t_from * 1e6:.6g} µs at the faces, the figures' clock)"
                     if t_from is not None else "")
            holds = ("never holds until unloading" if t_eq is None else
                     f"holds from {t_eq * 1e6:.3g} µs after the window start{clock} until "
                     "unloading")
            rows.append(("equilibrium (R ≤ 5 %)", f"{100 * frac:.0f} % of the loaded time; "
                         + holds))
        rms = [f"{100 * v:.3g} % with {how}" for v, how in (
            (number("rms_of_peak", "pochhammer_chree"), "Pochhammer–Chree"),
            (number("rms_of_peak", "time_shift"), "a time shift")) if v is not None]
        if rms:  # the one present, never a "nan %" for the other
            rows.append(("bars together: RMS of peak", ", ".join(rms)))
        if src.value("error"):
            rows.append(("error", str(src.value("error"))))
    warnings = (src.value("warnings", kind=list) or []) + src.missing + src.notes
    out = []
    if rows:
        out.append("<table class='kv headline'>" + "".join(
            f"<tr><th>{html.escape(k)}</th><td>{html.escape(str(v))}</td></tr>" for k, v in rows)
            + "</table>")
    if warnings:
        out.append("<div class='warnings'><p><b>Warnings</b></p><ul>" + "".join(
            f"<li>{html.escape(str(w))}</li>" for w in warnings) + "</ul></div>")
    return "\n".join(out)


def fmt(v):
    if isinstance(v, float):
        # An empty CSV field, read as NaN, is an undefined value (docs/outputs.md, Conventions):
        # shown empty as written, never as "nan".
        return "" if math.isnan(v) else f"{v:.6g}"
    if isinstance(v, (dict, list)):
        return json.dumps(v)
    return str(v)


def csv_html(table, caption):
    out = [f"<p class='cap'>{html.escape(caption)}</p><table><tr>"
           + "".join(f"<th>{html.escape(n)}</th>" for n in table.names) + "</tr>"]
    for row in table.rows:
        out.append("<tr>" + "".join(f"<td>{html.escape(fmt(v))}</td>" for v in row) + "</tr>")
    out.append("</table>")
    return "\n".join(out)


CSS = """
body{font-family:sans-serif;max-width:1100px;margin:1.5em auto;padding:0 1em;color:#222;
background:#fff}
h1{font-size:1.5em;margin-bottom:.2em}h2{font-size:1.2em;border-bottom:1px solid #ccc;
margin-top:1.6em}h3{font-size:1.05em}
figure{margin:1em 0}figure img{max-width:100%;border:1px solid #ddd}
figcaption{font-size:.9em;color:#444;margin-top:.3em}
table{border-collapse:collapse;font-size:.85em;margin:.5em 0}
td,th{border:1px solid #ccc;padding:2px 6px;text-align:left}th{background:#f2f2f2}
.meta{color:#666;font-size:.9em}.cap{font-weight:bold;margin-bottom:0}
.warn{border:2px solid #c60;background:#fff4e5;padding:.3em .8em;margin:.5em 0}
pre{font-size:.8em;background:#f8f8f8;padding:.5em;overflow-x:auto}
.headline th{background:#e8eef8}.warnings{background:#fff4e0;border:1px solid #e0a040;
padding:.2em 1em;font-size:.9em}
"""


def write_html(path, folder, sources, figs, fig_dir_name):
    parts = ["<!DOCTYPE html>", "<html lang='en'><head><meta charset='utf-8'>", GENERATOR,
             f"<title>shpb report — {html.escape(os.path.basename(os.path.abspath(folder)))}"
             "</title>", f"<style>{CSS}</style></head><body>",
             f"<h1>shpb report: {html.escape(os.path.basename(os.path.abspath(folder)))}</h1>",
             f"<p class='meta'>Folder {html.escape(os.path.abspath(folder))}; generated "
             f"{datetime.datetime.now(datetime.timezone.utc):%Y-%m-%d %H:%M} UTC by "
             "shpb report. Signals tension positive; a processed test's stress–strain and "
             "strain rate positive in its own loading (compression, or tension for a tension "
             "test: its summary.json conventions); the simulation's specimen stress and "
             "interface forces compression positive.</p>"]
    for src in sources:
        name = "this folder" if src.label == "." else src.label
        parts.append(f"<h2>Results: {html.escape(name)}</h2>")
        parts.append(f"<p class='meta'>files: {html.escape(', '.join(sorted(src.files)))}</p>")
        parts.append(headline_html(src))
        parts.append(summary_html(src))
        if src.has("comparison.csv"):
            parts.append(csv_html(src.table("comparison.csv"),
                                  "comparison.csv — pulse by pulse, simulated against measured"))
    parts.append("<h2>Figures</h2>")
    for name, title, caption in figs.items:
        with open(os.path.join(figs.out_dir, name), "rb") as f:
            data = base64.b64encode(f.read()).decode("ascii")
        ref = f"{fig_dir_name}/{name}"
        parts.append(f"<figure id='{html.escape(name)}'><h3>{html.escape(title)}</h3>"
                     f"<a href='{html.escape(ref)}'><img alt='{html.escape(title)}' "
                     f"src='data:image/png;base64,{data}'></a>"
                     f"<figcaption>{html.escape(caption)} "
                     f"<a href='{html.escape(ref)}'>{html.escape(ref)}</a></figcaption></figure>")
    parts.append("</body></html>")
    with open(path, "w", encoding="utf-8") as f:
        f.write("\n".join(parts))
