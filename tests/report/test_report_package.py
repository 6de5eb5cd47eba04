"""Unit tests of the report package (tools/shpb_report), run by pytest from Debian (ctest
report.package). The end-to-end exit codes are tests/app/report_exit_codes.py."""
import os
import shutil
import subprocess
import sys
import tempfile
import warnings
from pathlib import Path

import pytest

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "tools"))

from shpb_report import main as report_main  # noqa: E402
from shpb_report.drawing import figure_title  # noqa: E402
from shpb_report import sweeps  # noqa: E402
from shpb_report.reading import ReportError, Source, Table  # noqa: E402


def write(folder: Path, name: str, text: str) -> None:
    (folder / name).write_text(text, encoding="utf-8")


def drawn(folder: Path) -> list:
    return report_main.figures_of(Source(str(folder), "."))


def test_a_fit_folder_draws_the_fit_not_a_comparison(tmp_path):
    # fit and compare both write signals.csv: the fit's figure takes precedence, never both.
    write(tmp_path, "signals.csv", "time_s,x\n0,1\n")
    write(tmp_path, "fit.json", "{}")
    drawers = drawn(tmp_path)
    assert len(drawers) == 1
    compare_only = tmp_path / "compare"
    compare_only.mkdir()
    write(compare_only, "signals.csv", "time_s,x\n0,1\n")
    assert len(drawn(compare_only)) == 1
    assert drawn(compare_only)[0] is not drawers[0]


def test_pulses_choose_between_a_test_and_a_bars_together_check(tmp_path):
    test = tmp_path / "test"
    check = tmp_path / "check"
    test.mkdir()
    check.mkdir()
    write(test, "pulses.csv", "time_s,incident,reflected,transmitted\n0,0,0,0\n")
    write(check, "pulses.csv", "time_s,near,far_measured\n0,0,0\n")
    assert len(drawn(test)) == 1 and len(drawn(check)) == 1
    assert drawn(test)[0] is not drawn(check)[0]


def test_a_simulation_folder_gets_one_figure_per_file(tmp_path):
    for name in ("gauges.csv", "field.csv", "specimen.csv", "interfaces.csv", "energy.csv"):
        write(tmp_path, name, "time_s\n0\n")
    assert len(drawn(tmp_path)) == 5


def test_a_row_with_a_missing_field_names_its_line(tmp_path):
    write(tmp_path, "curve.csv", "strain,stress\n0,1\n0.1\n")
    with pytest.raises(ReportError, match=r"line 3: 1 fields: 2 expected"):
        Table(str(tmp_path / "curve.csv"))


def test_an_overflowing_number_is_refused_with_its_place(tmp_path):
    write(tmp_path, "curve.csv", "strain,stress\n0,1e300\n")
    with pytest.raises(ReportError, match=r"line 2, column 2: 1e300"):
        Table(str(tmp_path / "curve.csv"))


def test_a_missing_column_is_named(tmp_path):
    write(tmp_path, "curve.csv", "strain\n0\n")
    with pytest.raises(ReportError, match=r"a column stress_3wave_Pa was expected"):
        Table(str(tmp_path / "curve.csv"))["stress_3wave_Pa"]


def test_summary_values_of_the_wrong_kind_read_as_absent(tmp_path):
    write(tmp_path, "summary.json", '{"peak": true, "rate": 2000, "w": ["a"]}')
    src = Source(str(tmp_path), ".")
    assert src.value("peak", kind="number") is None  # a bool is not a number
    assert src.value("rate", kind="number") == 2000.0
    assert src.value("w", 0) == "a"
    assert src.value("w", 5) is None


def test_a_foreign_figures_folder_is_never_replaced(tmp_path):
    (tmp_path / "figures").mkdir()
    write(tmp_path / "figures", "thesis.png", "mine")
    with pytest.raises(ReportError, match="was not written by shpb report"):
        report_main.check_ownership(str(tmp_path))


def test_the_output_marker_learns_the_report_files_only_if_it_is_shpbs(tmp_path):
    marker = tmp_path / ".shpb-output"
    # FNV-1a 64 of "a" (its published test vector): the digest shpb's C++ side writes.
    (tmp_path / "a.txt").write_bytes(b"a")
    assert report_main.fnv1a64(str(tmp_path / "a.txt")) == "af63dc4c8601ec8c"
    (tmp_path / "a.txt").unlink()
    marker.write_text(report_main.OUTPUT_SIGNATURE + "\nfile: gauges.csv\nfile: figures\n"
                      "fnv1a64: 0123456789abcdef gauges.csv\n"
                      "fnv1a64: 0123456789abcdef figures/old.png\n", encoding="utf-8")
    staged = tmp_path / ".report-host-1-abcd_123"
    staged.mkdir()
    (staged / "energy.png").write_bytes(b"a")
    (tmp_path / "page.html").write_bytes(b"a")
    report_main.tell_output_marker(str(tmp_path), ["figures", "report.html"],
                                   report_main.digest_lines(str(staged), "figures") +
                                   report_main.digest_lines(str(tmp_path / "page.html"),
                                                            "report.html"),
                                   str(tmp_path / ".report-host-1-abcd_123.marker"))
    lines = marker.read_text(encoding="utf-8").splitlines()
    assert "file: figures" in lines and "file: report.html" in lines
    # The replaced figures' digests go, the new files' come, the results' stay.
    assert "fnv1a64: 0123456789abcdef gauges.csv" in lines
    assert "fnv1a64: 0123456789abcdef figures/old.png" not in lines
    assert "fnv1a64: af63dc4c8601ec8c figures/energy.png" in lines
    assert "fnv1a64: af63dc4c8601ec8c report.html" in lines
    foreign = tmp_path / "other"
    foreign.mkdir()
    (foreign / ".shpb-output").write_text("not ours\n", encoding="utf-8")
    report_main.tell_output_marker(str(foreign), ["figures"],
                                   report_main.digest_lines(str(staged), "figures"),
                                   str(foreign / ".report-host-1-abcd_123.marker"))
    assert (foreign / ".shpb-output").read_text(encoding="utf-8") == "not ours\n"
    assert os.listdir(foreign) == [".shpb-output"]


def test_column_names_come_from_the_output_schema():
    # The names the figures read are the schema's (src/core/output_schema.json, the list the C++
    # writers use): a name it does not list fails loudly instead of drawing a figure without it.
    from shpb_report.schema import columns, suffix
    curve = columns("curve")
    assert curve.FILE == "curve.csv"
    assert curve.stress_3wave_Pa == "stress_3wave_Pa"
    with pytest.raises(AttributeError):
        curve.stress_4wave_Pa  # noqa: B018
    assert suffix("compare_signals", "<gauge>_measured_strain") == "_measured_strain"
    with pytest.raises(KeyError):
        suffix("compare_signals", "<gauge>_modelled_strain")


def test_a_plan_folder_draws_the_plan_against_its_criteria(tmp_path):
    # A plan's folder: the predicted signals with the scope settings, the rate and equilibrium
    # against the criteria, the shaper's gain and the search's path, beside the simulation's own.
    write(tmp_path, "summary.json", """{"command": "plan",
      "targets": {"strain_rate_1_s": 1000, "rate_band": 0.1, "equilibrium_ratio_max": 0.05,
                  "equilibrium_before_fraction": 0.25},
      "chosen": {"shaper": {"material": "cu"}},
      "predicted": {"band_fraction": 0.8, "rate_spread": 0.05, "equilibrium_fraction": 0.1},
      "unshaped": {"meets": true, "predicted": {"band_fraction": 0.6, "rate_spread": 0.1,
                                                 "equilibrium_fraction": 0.2}},
      "shaped": null,
      "gauges": [{"gauge": "incident", "peak_strain": -1e-3, "peak_V": -5e-3}],
      "scope": {"range_V": 0.01, "trigger_level_V": -5e-4}}""")
    write(tmp_path, "path.csv",
          "step,striker_length_m,striker_velocity_m_s,shaper,shaper_thickness_m,"
          "shaper_diameter_m,specimen_length_m,plateau_rate_1_s,band_fraction,"
          "equilibrium_fraction,strain_reached,changes,meets\n"
          "0,0.3,10,-1,0,0,0.005,1000,0.6,0.2,0.2,1,1\n1,0.3,12,0,1e-3,1e-2,0.005,990,0.8,0.1,0.2,2,1\n")
    write(tmp_path, "loading.csv",
          "time_s,strain,strain_rate_1_s,front_force_N,back_force_N,equilibrium_ratio,loading\n"
          "0,0,0,0,0,0,0\n1e-6,0.001,1000,10,9,0.1,1\n2e-6,0.002,1000,10,10,0,1\n")
    sim = tmp_path / "simulation"
    sim.mkdir()
    write(sim, "gauges.csv", "time_s,incident\n0,0\n1e-6,-1e-3\n")
    html, count = report_main.build(str(tmp_path))
    figures = set(os.listdir(tmp_path / "figures"))
    assert {"plan_gauges.png", "plan_loading.png", "plan_shaper_gain.png",
            "plan_path.png"} <= figures
    assert "plan_loading.png" in (tmp_path / "report.html").read_text(encoding="utf-8")


def test_the_rigid_link_limit_of_a_stability_map_is_drawn(tmp_path):
    # `study --sweep stability` maps localized bipenalty's rigid-link limit with ε_s/k and R/R_crit
    # 0 (docs/outputs.md, study): a stiffness of 0 has no place on a log axis, where its points
    # vanished with a warning on stderr. Its panel must show every one of them.
    courants = (0.5, 1.0, 1.05)
    rows = [f"localized-bipenalty,{k},{r},{c},1,{int(c <= 1)},1,0"
            for k, r in ((0, 0), (1, 0.5), (100, 0.5)) for c in courants]
    write(tmp_path, "stability.csv", "method,stiffness_factor,mass_ratio,courant,energy_growth,"
          "stable,step_ratio,closings_after_release\n" + "\n".join(rows) + "\n")
    write(tmp_path, "stability_boundary.csv", "method,link,stiffness_factor,mass_ratio,"
          "critical_courant,closed_form_courant,step_ratio\n"
          "localized-bipenalty,unilateral,0,0,1.0,1,1\n"
          "localized-bipenalty,unilateral,1,0.5,1.0,1,1\n")

    class Kept:
        def __init__(self):
            self.figures = []

        def save(self, fig, *caption):
            self.figures.append(fig)

    kept = Kept()
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # matplotlib's "no positive values" warning fails the test
        sweeps.fig_stability(Source(str(tmp_path), "."), kept)
    (fig,) = kept.figures
    panels = [ax for ax in fig.axes if ax.get_visible()]
    rigid = [ax for ax in panels if ax.get_xscale() == "linear"]
    assert len(panels) == 2 and len(rigid) == 1
    low, high = rigid[0].get_xlim()
    shown = [xy for points in rigid[0].collections for xy in points.get_offsets()
             if low <= xy[0] <= high]
    assert len(shown) == len(courants)


def test_a_killed_reports_folder_with_its_marker_cut_short_is_removed(tmp_path):
    # Killed between making its figures folder and finishing the marker's line (the out-of-memory
    # killer, kill -9): the folder holds the marker alone, cut short, and is that run's; the next
    # report removes it. A folder with anything else in it stays (it may be the user's).
    import socket
    dead = 2 ** 22 + 7  # above the largest pid_max a kernel allows (2**22): no process has it
    prefix = f".report-{socket.gethostname()}-{dead}-"
    for cut in ("", report_main.FIGURES_SIGNATURE[:17]):
        folder = tmp_path / (prefix + ("a" * 8 if cut == "" else "b" * 8))
        folder.mkdir()
        write(folder, report_main.FIGURES_MARKER, cut)
    kept = tmp_path / (prefix + "c" * 8)
    kept.mkdir()
    write(kept, report_main.FIGURES_MARKER, report_main.FIGURES_SIGNATURE[:17])
    write(kept, "notes.txt", "the user's")
    report_main.remove_stale_temporaries(str(tmp_path))
    assert sorted(p.name for p in tmp_path.iterdir()) == [kept.name]


def test_a_report_file_the_user_edited_is_never_replaced(tmp_path):
    (tmp_path / "report.html").write_bytes(b"a")
    (tmp_path / ".shpb-output").write_text(
        report_main.OUTPUT_SIGNATURE + "\nfile: report.html\n"
        "fnv1a64: af63dc4c8601ec8c report.html\n", encoding="utf-8")
    assert report_main.edited_since_written(str(tmp_path), ["report.html"]) is None
    (tmp_path / "report.html").write_bytes(b"a, and the user's note")
    with pytest.raises(ReportError, match="was changed since shpb report wrote it"):
        report_main.check_ownership(str(tmp_path))



def test_a_fifo_in_place_of_a_marker_or_page_does_not_block_the_report(tmp_path):
    # A FIFO has no writer: opened as a file it blocks the report forever (docs/commands.md,
    # report: never a hang). It is no marker of shpb's, and no page of the report's.
    write(tmp_path, "gauges.csv", "time_s,incident\n0,0\n1e-6,-1e-4\n")
    os.mkfifo(tmp_path / ".shpb-output")
    html, count = report_main.build(str(tmp_path))
    assert count == 1 and os.path.isfile(html)
    assert (tmp_path / ".shpb-output").is_fifo()
    os.mkfifo(tmp_path / "page")
    assert report_main.read_text(str(tmp_path / "page")) == ""
    # A folder there is no marker either (it was exit 3, "3: cannot be written", the fd named).
    os.remove(tmp_path / ".shpb-output")
    os.mkdir(tmp_path / ".shpb-output")
    assert report_main.build(str(tmp_path))[1] == 1
    other = tmp_path / "other"
    other.mkdir()
    os.mkfifo(other / "report.html")
    with pytest.raises(ReportError, match="report.html: exists and was not written"):
        report_main.check_ownership(str(other))


def test_the_output_marker_keeps_every_line_however_long(tmp_path):
    # A campaign of many tests has a marker of many lines: the report rewrites it with its own
    # files' lines and must keep every other one (a lost line makes shpb refuse the folder).
    lines = [f"fnv1a64: 0123456789abcdef test-{i:05d}/curve.csv" for i in range(4000)]
    text = report_main.OUTPUT_SIGNATURE + "\n" + "\n".join(lines) + "\n"
    assert len(text) > 1 << 17  # beyond any first-part read
    (tmp_path / ".shpb-output").write_text(text, encoding="utf-8")
    (tmp_path / "page.html").write_bytes(b"a")
    report_main.tell_output_marker(str(tmp_path), ["report.html"],
                                   report_main.digest_lines(str(tmp_path / "page.html"),
                                                            "report.html"),
                                   str(tmp_path / ".report-host-1-abcd_123.marker"))
    kept = (tmp_path / ".shpb-output").read_text(encoding="utf-8").splitlines()
    assert kept[1:len(lines) + 1] == lines
    assert "fnv1a64: af63dc4c8601ec8c report.html" in kept


@pytest.mark.parametrize("value, shown", [("NaN", "NaN"), ("-Infinity", "Infinity"),
                                          ("1e400", "Infinity"), ("1" + "0" * 400, "digits"),
                                          ("-1e308", "-1e\\+308")],
                         ids=["NaN", "-Infinity", "1e400", "integer of 401 digits", "-1e308"])
def test_a_number_json_does_not_have_is_refused_with_its_path(tmp_path, value, shown):
    # Python's json reads NaN, Infinity and 1e400 (as infinity), which JSON and shpb never write:
    # shown as "nan" in the page or an axis, or beyond a float in a figure; -1e308 overflowed a
    # plan's axis limits (a bug's exit 4). Exit 2, its path named.
    write(tmp_path, "gauges.csv", "time_s,incident\n0,0\n1e-6,-1e-4\n")
    write(tmp_path, "summary.json", '{"command": "simulate", "bars": [{"final_velocity_m_s": '
          + value + "}]}")
    with pytest.raises(ReportError, match=r"summary.json: bars\[0\].final_velocity_m_s: .*" +
                       shown + ".*a finite number below 1e100 in magnitude was expected"):
        Source(str(tmp_path), ".")


def test_raw_signals_with_a_time_column_alone_draw_nothing(tmp_path):
    # No gauge column: nothing to draw, not a figure of no rows (a bug's exit 4).
    write(tmp_path, "raw_signals.csv", "time_s\n0\n1e-6\n")
    html, count = report_main.build(str(tmp_path))
    assert count == 0 and os.path.isfile(html)


def test_uncertainty_entries_of_the_wrong_kind_are_drawn_without_them(tmp_path):
    # summary.json uncertainty (docs/outputs.md, process) read as every other value: an entry of
    # another kind is absent, never a bug's exit 4.
    write(tmp_path, "summary.json", '{"uncertainty": {"figures": {'
          '"peak_stress_Pa": {"contributions": 5, "interval_95": 7},'
          '"plateau_strain_rate_1_s": {"contributions": [{"input": "a", "share": "x"}, 3],'
          ' "interval_95": [1], "unit": 4}}}}')
    shown = []

    class Kept:
        def save(self, fig, *caption):
            shown.extend(ax.get_title() for ax in fig.axes)

    from shpb_report import process
    process.fig_uncertainty(Source(str(tmp_path), "."), Kept())
    assert shown == ["peak stress", "plateau strain rate"]  # no interval in the titles


def test_a_home_matplotlib_cannot_write_leaves_stderr_to_the_result(tmp_path):
    # Run as a user whose home is read-only, matplotlib warned on stderr at import: the report's
    # output is one line, the result or the error (docs/commands.md, report).
    write(tmp_path, "gauges.csv", "time_s,incident\n0,0\n1e-6,-1e-4\n")
    script = Path(__file__).resolve().parents[2] / "tools" / "report.py"
    env = dict(os.environ, MPLCONFIGDIR="/proc/version/matplotlib")  # no folder can be made there
    r = subprocess.run(["/usr/bin/python3", str(script), str(tmp_path)], env=env,
                       capture_output=True, text=True, timeout=300)
    assert r.returncode == 0 and r.stderr == ""


def test_a_csv_error_names_its_line_column_and_value(tmp_path):
    # docs/commands.md, report: one line naming the file and the line/column/value.
    write(tmp_path, "curve.csv", "time_s,strain\n0,0\n1e-6,0.01\n2e-6,abc\n")
    with pytest.raises(ReportError, match=r"curve.csv: line 4, column 2 \(strain\): abc: a number"):
        Table(str(tmp_path / "curve.csv")).numeric("strain")
    # An unclosed quote takes the lines after it into one field, until the field limit.
    write(tmp_path, "curve.csv", 'time_s,strain\n0,0\n1e-6,"0.01\n' + "2e-6,0.02\n" * 20000)
    with pytest.raises(ReportError, match=r"curve.csv: line \d+: field larger .*comma-separated"):
        Table(str(tmp_path / "curve.csv"))
    write(tmp_path, "curve.csv", "time_s,strain,strain\n0,0,1\n")
    with pytest.raises(ReportError, match=r"line 1, column 3: strain: a name of its own .*col"):
        Table(str(tmp_path / "curve.csv"))


def test_a_byte_order_mark_is_no_part_of_the_first_column_name(tmp_path):
    # A spreadsheet saves UTF-8 with a byte-order mark: time_s is still time_s.
    (tmp_path / "gauges.csv").write_bytes(b"\xef\xbb\xbftime_s,incident\r\n0,0\r\n1e-6,-1e-4\r\n")
    t = Table(str(tmp_path / "gauges.csv"))
    assert t.names == ["time_s", "incident"] and list(t.numeric("time_s")) == [0, 1e-6]


def test_a_bars_together_headline_shows_no_nan_for_a_missing_rms(tmp_path):
    # summary.json rms_of_peak (docs/outputs.md, process) with one of its two values: the page
    # shows that one, and no "nan" for the other.
    from shpb_report.page import headline_html
    write(tmp_path, "summary.json", '{"command": "process", "rms_of_peak": '
          '{"pochhammer_chree": 0.021}}')
    text = headline_html(Source(str(tmp_path), "."))
    assert "2.1 % with Pochhammer–Chree" in text and "nan" not in text.lower()


def test_a_file_the_user_put_in_figures_is_never_removed(tmp_path):
    # docs/outputs.md, Conventions: no file shpb did not write is deleted. The next report
    # replaced figures/ whole, with the user's own file or folder in it.
    write(tmp_path, "gauges.csv", "time_s,incident\n0,0\n1e-6,-1e-4\n")
    report_main.build(str(tmp_path))
    report_main.build(str(tmp_path))  # its own figures are replaced
    for mine in ("figures/mine.png", "figures/notes/a.txt"):
        (tmp_path / mine).parent.mkdir(exist_ok=True)
        (tmp_path / mine).write_text("the user's", encoding="utf-8")
        with pytest.raises(ReportError, match="figures/(mine.png|notes): was not written by "
                                              "shpb report"):
            report_main.build(str(tmp_path))
        assert (tmp_path / mine).read_text(encoding="utf-8") == "the user's"
        os.remove(tmp_path / mine)


def report_as_a_user(folder: Path) -> subprocess.CompletedProcess:
    """tools/report.py run on `folder` as a user the permissions bind (root's access is never
    denied: as nobody, the folder given to it)."""
    command = ["/usr/bin/python3", str(Path(__file__).resolve().parents[2] / "tools" / "report.py"),
               str(folder)]
    if os.geteuid() == 0:
        for p in [folder, *folder.rglob("*")]:
            os.chown(p, 65534, 65534, follow_symlinks=False)
        command = ["setpriv", "--reuid=65534", "--regid=65534", "--clear-groups"] + command
    return subprocess.run(command, capture_output=True, text=True, timeout=300)


@pytest.fixture
def open_folder():
    """A folder another user can reach (pytest's tmp_path is its owner's alone)."""
    folder = Path(tempfile.mkdtemp(prefix="shpb-report-"))
    folder.chmod(0o755)
    yield folder
    for p in [folder, *folder.rglob("*")]:
        if p.is_dir() and not p.is_symlink():
            p.chmod(0o755)
    shutil.rmtree(folder)


def test_a_read_only_figures_folder_is_exit_3_and_leaves_nothing(open_folder):
    # Its figures could not be removed once set aside: they stayed in DIR as a temporary its
    # marker does not list, and shpb refused to replace DIR after (docs/outputs.md, Conventions).
    folder = open_folder
    write(folder, "gauges.csv", "time_s,incident\n0,0\n1e-6,-1e-4\n")
    report_main.build(str(folder))
    (folder / "figures").chmod(0o555)
    before = sorted(os.listdir(folder))
    r = report_as_a_user(folder)
    assert r.returncode == 3, r.stderr
    assert r.stderr.startswith(f"error: {folder}/figures: cannot be written")
    assert sorted(os.listdir(folder)) == before


def test_an_unreadable_folder_is_a_bad_input_never_left_out(open_folder):
    # A campaign's test folder the report cannot read was left out without a word (exit 0, one
    # test fewer), and DIR itself unreadable said "cannot be written" (exit 3): both exit 2.
    for test in ("a", "b"):
        (open_folder / test).mkdir()
        write(open_folder / test, "curve.csv", "time_s,strain,stress_3wave_Pa\n0,0,0\n")
    (open_folder / "b").chmod(0)
    r = report_as_a_user(open_folder)
    assert r.returncode == 2, r.stderr
    assert r.stderr == (f"error: {open_folder}/b: Permission denied: a readable folder was "
                        "expected\n")
    (open_folder / "b").chmod(0o755)
    open_folder.chmod(0o311)  # entered and written, not listed
    r = report_as_a_user(open_folder)
    assert r.returncode == 2 and r.stderr.startswith(f"error: {open_folder}: Permission denied")


def test_an_undefined_value_of_comparison_csv_is_shown_empty(tmp_path):
    # An undefined number is an empty field (docs/outputs.md, Conventions): the page's table of
    # comparison.csv shows it empty, not as "nan".
    write(tmp_path, "signals.csv", "time_s,incident_measured_strain\n0,0\n1e-6,-1e-4\n")
    write(tmp_path, "comparison.csv", "gauge,pulse,window_start_s,window_end_s,nrmse\n"
          "incident,incident,0,1e-6,\n")
    html, _ = report_main.build(str(tmp_path))
    page = Path(html).read_text(encoding="utf-8")
    assert "<td>incident</td><td>incident</td><td>0</td><td>1e-06</td><td></td>" in page
    assert "<td>nan</td>" not in page


def test_an_empty_name_is_refused_with_its_place(tmp_path):
    # A column of names (fit's test, a study's method) with an empty field was read as NaN: one
    # "nan" curve per row (thousands of panels, a bug's exit 4 for an image too large).
    write(tmp_path, "fit.json", "{}")
    write(tmp_path, "signals.csv", "test,gauge,pulse,time_s,measured_strain,start_strain,"
          "fitted_strain\ncu,incident,reflected,0,0,0,0\n,incident,reflected,1e-6,0,0,0\n")
    with pytest.raises(ReportError, match=r"signals.csv: line 3, column 1 \(test\): an empty "
                                          "field: a name was expected"):
        report_main.build(str(tmp_path))
    write(tmp_path, "signals.csv", "test,gauge,pulse,time_s,measured_strain,start_strain,"
          "fitted_strain\n1,incident,reflected,0,0,0,0\n")
    assert list(Table(str(tmp_path / "signals.csv")).text("test")) == ["1"]


def test_a_pareto_run_without_a_resolution_shows_no_nan(tmp_path):
    # An undefined number is an empty field (docs/outputs.md, Conventions): no "nan" annotation.
    from shpb_report import study
    write(tmp_path, "pareto.csv", "method,stepping,resolution,error,wall_time_s,stable,"
          "pareto_front_wall_time\npenalty,global,,0.01,0.5,1,1\npenalty,global,2,0.001,1,1,1\n")
    shown = []

    class Kept:
        def save(self, fig, *caption):
            shown.extend(t.get_text() for ax in fig.axes for t in ax.texts)

    study.fig_pareto(Source(str(tmp_path), "."), Kept())
    assert shown == ["2"]


def test_a_warning_while_drawing_leaves_stderr_to_the_result(tmp_path):
    # numpy's and matplotlib's warnings (a layout that does not fit, a comparison numpy will
    # change) are no result: stderr holds the one result or error line (docs/commands.md).
    write(tmp_path, "gauges.csv", "time_s,incident\n0,0\n1e-6,-1e-4\n")
    tools = Path(__file__).resolve().parents[2] / "tools"
    code = (f"import sys, warnings; sys.path.insert(0, {str(tools)!r})\n"
            "from shpb_report import main, simulate\n"
            "def warn(src, figs):\n"
            "    warnings.warn('constrained_layout not applied', UserWarning)\n"
            "    warnings.warn('elementwise comparison failed', FutureWarning)\n"
            "simulate.fig_gauges = warn\n"
            f"sys.exit(main.main(['report.py', {str(tmp_path)!r}]))\n")
    r = subprocess.run(["/usr/bin/python3", "-c", code], capture_output=True, text=True,
                       timeout=300)
    assert r.returncode == 0 and r.stderr == ""


def test_a_calibration_shot_whose_gauges_are_no_list_is_drawn_without_them(tmp_path):
    # summary.json scenes[].gauges (docs/outputs.md, calibrate) read as every other value: of
    # another kind it is absent (no figure for the shot), never a bug's exit 4.
    from shpb_report import calibrate
    write(tmp_path, "calibration.json", "{}")
    write(tmp_path, "shot-1.csv", "time_s,inc_measured\n0,0\n")
    write(tmp_path, "summary.json", '{"scenes": [{"signals": "shot-1.csv", "gauges": 1.5}]}')
    saved = []

    class Kept:
        def save(self, fig, *caption):
            saved.append(fig)

    calibrate.fig_calibration(Source(str(tmp_path), "."), Kept())
    assert saved == []


def test_a_field_not_on_a_grid_is_refused_not_allocated(tmp_path):
    # field.csv is a time × position grid (docs/outputs.md, simulate): 5000 scattered points
    # asked for 2.5e7 cells (81000 of them, 49 GB: a bug's MemoryError, exit 4). Exit 2.
    rows = "".join(f"{i * 1e-7},{i * 1e-4},{i}\n" for i in range(5000))
    write(tmp_path, "field.csv", "time_s,x_m,stress_Pa\n" + rows)
    with pytest.raises(ReportError, match=r"field.csv: 5000 times × 5000 positions for 5000 rows: "
                                          "a time × position grid was expected"):
        report_main.build(str(tmp_path))
    grid = "".join(f"{i * 1e-7},{j * 1e-2},{i * j}\n" for i in range(200) for j in range(400))
    write(tmp_path, "field.csv", "time_s,x_m,stress_Pa\n" + grid)
    assert report_main.build(str(tmp_path))[1] == 1



def test_a_file_of_hundreds_of_gauges_is_refused_with_its_count(tmp_path):
    # A row of panels per gauge: 300 asked for an image 78080 pixels high, beyond Agg's 2^16
    # (a bug's exit 4 after seconds of drawing). More rows than a figure holds: exit 2, named.
    from shpb_report.drawing import MAX_PANEL_ROWS
    n = MAX_PANEL_ROWS + 1
    write(tmp_path, "raw_signals.csv", "time_s," + ",".join(f"g{i}" for i in range(n)) + "\n"
          + "0," + ",".join("0" for _ in range(n)) + "\n")
    with pytest.raises(ReportError, match=f"raw_signals.csv: {n} gauge columns: at most "
                                          f"{MAX_PANEL_ROWS} were expected"):
        report_main.build(str(tmp_path))


def test_a_pareto_without_a_positive_run_and_a_loading_without_times_draw_nothing_wrong(tmp_path):
    # Nothing to put on the pareto's log axes (no run, or no positive cost), or a plan's loading
    # with undefined times (empty fields, docs/outputs.md Conventions): a bug's exit 4 before
    # (no positive values to log-scale, NaN axis limits). The pareto has no figure then.
    from shpb_report import plan, study
    saved = []

    class Kept:
        def save(self, fig, *caption):
            fig.savefig(tmp_path / "f.png")
            saved.append(caption[0])

    for rows in ("", "penalty,global,1,0,0,1,0\n"):
        write(tmp_path, "pareto.csv", "method,stepping,resolution,error,wall_time_s,stable,"
              "pareto_front_wall_time\n" + rows)
        study.fig_pareto(Source(str(tmp_path), "."), Kept())
    assert saved == []
    write(tmp_path, "loading.csv", "time_s,strain,strain_rate_1_s,front_force_N,back_force_N,"
          "equilibrium_ratio,loading\n,0,1000,1,1,0,1\n,0.001,1000,1,1,0,1\n")
    plan.fig_loading(Source(str(tmp_path), "."), Kept())
    assert saved == ["plan_loading.png"]


def test_a_folder_the_report_cannot_write_into_is_named(tmp_path, monkeypatch, capsys):
    # A read-only DIR (as a user other than root): the error named the hidden temporary folder
    # the report tried to make there, not DIR. Root ignores permissions, so mkdtemp is refused
    # here as the file system would refuse it.
    (tmp_path / "gauges.csv").write_text("time_s,incident\n0,0\n1e-7,1e-4\n", encoding="utf-8")

    def refused(prefix=None, dir=None):
        raise PermissionError(13, "Permission denied", os.path.join(dir, prefix + "abcd1234"))

    monkeypatch.setattr(report_main.tempfile, "mkdtemp", refused)
    assert report_main.main(["report", str(tmp_path)]) == 3
    err = capsys.readouterr().err.strip()
    assert err == f"error: {tmp_path}: cannot be written: Permission denied"



def test_a_file_shpb_wrote_that_is_gone_is_named_not_left_out_in_silence(tmp_path, capsys):
    # A simulate folder whose gauges.csv was removed (or replaced by a folder) since: the report
    # draws what is left, and says on stderr and on the page which file its figures are missing.
    write(tmp_path, "gauges.csv", "time_s,incident\n0,0\n1e-6,-1e-4\n")
    write(tmp_path, "energy.csv", "time_s,total_J\n0,1\n1e-6,1\n")
    (tmp_path / ".shpb-output").write_text(
        report_main.OUTPUT_SIGNATURE + "\ncommand: simulate\nfile: energy.csv\nfile: gauges.csv\n",
        encoding="utf-8")
    assert report_main.main(["report", str(tmp_path)]) == 0
    assert capsys.readouterr().err == ""
    os.remove(tmp_path / "gauges.csv")
    os.mkdir(tmp_path / "gauges.csv")
    assert report_main.main(["report", str(tmp_path)]) == 0
    err = capsys.readouterr().err.splitlines()
    assert err == [f"warning: {tmp_path / 'gauges.csv'}: written by shpb, no longer a file here: "
                   "the figures drawn from it are left out"]
    assert "gauges.csv: written by shpb, no longer a file here" in (
        tmp_path / "report.html").read_text(encoding="utf-8")


def test_a_sub_folder_linking_back_to_the_folder_is_drawn_once(tmp_path):
    write(tmp_path, "gauges.csv", "time_s,incident\n0,0\n1e-6,-1e-4\n")
    os.symlink(".", tmp_path / "again")
    assert [s.label for s in report_main.find_sources(str(tmp_path))] == ["."]


@pytest.mark.parametrize("where", ["mkdtemp", "chmod", "drawing"])
def test_a_signal_at_any_moment_of_the_drawing_leaves_no_temporary(tmp_path, monkeypatch, where):
    # SIGINT/SIGTERM raise KeyboardInterrupt wherever the script is (main._on_signal): landing
    # between the temporary folder's creation and the block that removes it (inside mkdtemp once
    # the folder exists, or at its chmod), it left `.report-…` in DIR after exit 130.
    (tmp_path / "gauges.csv").write_text("time_s,incident\n0,0\n1e-7,1e-4\n", encoding="utf-8")
    made = report_main.tempfile.mkdtemp
    chmod = report_main.os.chmod

    def signalled():
        raise KeyboardInterrupt

    if where == "mkdtemp":
        monkeypatch.setattr(report_main.tempfile, "mkdtemp",
                            lambda **kw: (made(**kw), signalled())[0])
    elif where == "chmod":
        monkeypatch.setattr(report_main.os, "chmod", lambda *a, **kw: signalled())
    else:
        monkeypatch.setattr(report_main, "write_html", lambda *a, **kw: signalled())
    assert report_main.main(["report", str(tmp_path)]) == 130
    monkeypatch.setattr(report_main.os, "chmod", chmod)
    assert [p.name for p in tmp_path.iterdir() if p.name.startswith(".report-")] == []
    assert not (tmp_path / "report.html").exists()


class Kept:
    """A figure collector that keeps the figures, to read what they draw."""

    def __init__(self):
        self.figures = []

    def save(self, fig, *caption):
        self.figures.append(fig)


def band_x(ax):
    """The x-values of every band (fill_between) drawn on `ax`, each as a set."""
    return [{round(x, 9) for x, _ in band.get_paths()[0].vertices} if band.get_paths() else set()
            for band in ax.collections]


def test_a_one_wave_primarys_bands_surround_the_curves_they_belong_to(tmp_path):
    # "primary": "1-wave": the bands are quantiles at the row's 1-wave strain, the rate band the
    # 1-wave rate's (docs/outputs.md, curve.csv). The 3-wave curve is drawn against its own
    # strain: a 3-wave band at the 1-wave strain surrounded no drawn curve, and the rate band
    # was drawn around the 3-wave rate it is not a band of. Here the 1-wave strain is twice the
    # 3-wave strain and the rates differ by 1000 1/s; the last row's band fields are empty.
    from shpb_report import process
    rows = []
    for i in range(6):
        e3, e1 = 0.01 * i, 0.02 * i
        band = ",,,,,,,," if i == 5 else "90e6,100e6,110e6,190e6,200e6,210e6,2900,3000,3100"
        rows.append(f"{1e-6 * i},2000,{e3},200e6,200e6,100e6,{e1},{200e6 * (1 - e1)},0,3000,{e1},"
                    + band)
    write(tmp_path, "curve.csv",
          "time_s,strain_rate_1_s,strain,stress_1wave_Pa,stress_2wave_Pa,stress_3wave_Pa,"
          "true_strain,true_stress_Pa,equilibrium_ratio,strain_rate_1wave_1_s,strain_1wave,"
          "stress_3wave_p2.5_Pa,stress_3wave_p50_Pa,stress_3wave_p97.5_Pa,stress_1wave_p2.5_Pa,"
          "stress_1wave_p50_Pa,stress_1wave_p97.5_Pa,strain_rate_p2.5_1_s,strain_rate_p50_1_s,"
          "strain_rate_p97.5_1_s\n" + "\n".join(rows) + "\n")
    write(tmp_path, "summary.json", '{"command": "process", "test": "compression", "primary": '
          '{"reduction": "1-wave", "strain": "strain_1wave", "stress": "stress_1wave_Pa"}}')
    kept = Kept()
    process.fig_curve(Source(str(tmp_path), "."), kept)
    curves, rates = kept.figures
    ax = curves.axes[0]
    one_wave_x = {round(100 * 0.02 * i, 9) for i in range(5)}  # where the band fields are given
    assert band_x(ax) == [one_wave_x]
    ax = rates.axes[0]
    (band,) = ax.collections
    lo, hi = (min(band.get_paths()[0].vertices[:, 1]), max(band.get_paths()[0].vertices[:, 1]))
    primary = [line for line in ax.get_lines() if "primary" in line.get_label()]
    assert len(primary) == 1 and all(lo <= y <= hi for y in primary[0].get_ydata()[:5])


def test_a_tension_tests_curve_is_labelled_and_overlaid_tension_positive(tmp_path):
    # curve.csv of a "test": "tension" is tension positive, specimen.csv compression positive
    # whatever the test (docs/outputs.md, curve.csv and Conventions). The axes said
    # "compression +" and the model truth of a sibling simulation was drawn mirrored into the
    # third quadrant.
    from shpb_report import process
    write(tmp_path, "curve.csv", "time_s,strain_rate_1_s,strain,stress_1wave_Pa,stress_2wave_Pa,"
          "stress_3wave_Pa,true_strain,true_stress_Pa,equilibrium_ratio\n"
          "0,1000,0,0,0,0,0,0,0\n1e-6,1000,0.05,300e6,300e6,300e6,0.0488,315e6,0\n")
    write(tmp_path, "summary.json", '{"command": "process", "test": "tension"}')
    truth_dir = tmp_path / "simulate"
    truth_dir.mkdir()
    write(truth_dir, "specimen.csv", "time_s,strain,stress_Pa,strain_rate_1_s,true_strain,"
          "true_stress_Pa\n0,0,0,0,0,0\n1e-6,-0.05,-300e6,-1000,-0.0488,-315e6\n")
    kept = Kept()
    truth = Source(str(truth_dir), "simulate").table("specimen.csv")
    process.fig_curve(Source(str(tmp_path), "."), kept, truth)
    labels = [text for fig in kept.figures for ax in fig.axes
              for text in (ax.get_xlabel(), ax.get_ylabel()) if "+" in text]
    assert labels and all("tension +" in text for text in labels)
    truth_lines = [line for fig in kept.figures for ax in fig.axes for line in ax.get_lines()
                   if "truth" in line.get_label()]
    assert len(truth_lines) == 3
    for line in truth_lines:  # the truth's stress-strain and rate, tension positive as the curve
        assert max(line.get_ydata()) > 0 and min(line.get_ydata()) >= 0


def test_a_campaign_draws_each_tests_primary_reduction_in_its_own_sense(tmp_path):
    # The campaign's plot drew every test's 3-wave stress against the 3-wave strain, labelled
    # compression positive, whatever the test's primary reduction and loading.
    from shpb_report import process
    header = ("time_s,strain_rate_1_s,strain,stress_1wave_Pa,stress_2wave_Pa,stress_3wave_Pa,"
              "strain_1wave\n")
    for name, test, primary in (("a", "tension", "3-wave"), ("b", "compression", "1-wave")):
        (tmp_path / name).mkdir()
        write(tmp_path / name, "curve.csv", header + "0,1,0,0,0,0,0\n1,1,0.1,200e6,0,100e6,0.2\n")
        strain, stress = (("strain", "stress_3wave_Pa") if primary == "3-wave"
                          else ("strain_1wave", "stress_1wave_Pa"))
        write(tmp_path / name, "summary.json",
              f'{{"command": "process", "test": "{test}", "primary": {{"reduction": '
              f'"{primary}", "strain": "{strain}", "stress": "{stress}"}}}}')
    write(tmp_path, "campaign.csv", "test\na\nb\n")
    kept = Kept()
    sources = [Source(str(tmp_path / n), n) for n in ("a", "b")]
    process.fig_campaign(str(tmp_path), sources, kept)
    (ax,) = kept.figures[0].axes
    a, b = ax.get_lines()
    assert list(a.get_xdata()) == [0, 10] and list(a.get_ydata()) == [0, 100]
    assert list(b.get_xdata()) == [0, 20] and list(b.get_ydata()) == [0, 200]
    assert "compression +" not in ax.get_xlabel() and "compression +" not in ax.get_ylabel()


def legends_above_their_axes(fig):
    fig.canvas.draw()
    renderer = fig.canvas.get_renderer()
    legends = [(ax.get_legend(), ax) for ax in fig.axes if ax.get_legend() is not None]
    return legends and all(legend.get_window_extent(renderer).y0
                           >= ax.get_window_extent(renderer).y1 for legend, ax in legends)


def test_a_calibration_shots_legend_hides_no_trace_and_the_bands_strain_is_in_percent(tmp_path):
    # A calibration shot's legend sat inside the axes, over the last returning pulse, and a
    # fit's over the pulse's tail; the Monte Carlo's stress-strain panel had its strain as a fraction where every other figure
    # of the report has it in % (docs/outputs.md, report).
    from shpb_report import calibrate, study
    write(tmp_path, "calibration.json", "{}")
    write(tmp_path, "shot-1.csv", "time_s,inc_measured,inc_nominal,inc_fitted,inc_compared\n"
          "0,0,0,0,1\n1e-4,-1e-3,-1e-3,-1e-3,1\n2e-4,0,0,0,1\n")
    write(tmp_path, "summary.json",
          '{"scenes": [{"signals": "shot-1.csv", "gauges": ["inc"], "kind": "bars apart"}],'
          ' "draws": 2}')
    kept = Kept()
    calibrate.fig_calibration(Source(str(tmp_path), "."), kept)
    (fig,) = kept.figures
    assert legends_above_their_axes(fig)
    from shpb_report import fit
    write(tmp_path, "signals.csv", "test,pulse,time_s,measured_strain,start_strain,fitted_strain\n"
          "a,reflected,0,0,0,0\na,reflected,1e-6,1e-3,1e-3,1e-3\n")
    kept = Kept()
    fit.fig_fit(Source(str(tmp_path), "."), kept)
    assert legends_above_their_axes(kept.figures[0])
    write(tmp_path, "gauge_bands.csv", "time_s,inc,inc_p2.5,inc_p50,inc_p97.5\n0,0,0,0,0\n")
    write(tmp_path, "curve_bands.csv", "strain,stress_3wave_Pa,stress_3wave_p2.5_Pa,"
          "stress_3wave_p97.5_Pa\n0,0,0,0\n0.2,300e6,290e6,310e6\n")
    kept = Kept()
    study.fig_monte_carlo(Source(str(tmp_path), "."), kept)
    ax = kept.figures[0].axes[1]
    assert "(%" in ax.get_xlabel() and max(ax.get_lines()[0].get_xdata()) == pytest.approx(20)


def test_a_fits_parameters_are_a_table_of_the_page(tmp_path):
    # A fit's result, summary.json parameters (records by name, docs/outputs.md, fit), was
    # shown only inside the folded summary.json: the page's tables had no fitted value.
    from shpb_report.page import summary_html
    write(tmp_path, "fit.json", "{}")
    write(tmp_path, "summary.json", '{"model": "johnson-cook", "parameters": {"A": {"value": '
          '28870602.4, "unit": "Pa", "interval_95": [26200459.0, 31540745.7]}, "n": {"value": '
          '0.783, "unit": "", "interval_95": [0.76, 0.80]}}}')
    page = summary_html(Source(str(tmp_path), "."))
    tables = page.split("<details>")[0]
    assert "<td>A</td><td>2.88706e+07</td><td>Pa</td>" in tables
    assert "<td>n</td><td>0.783</td>" in tables


def test_a_comparison_without_dispersion_draws_its_simulation_once(tmp_path):
    # Without dispersion (summary.json dispersion false) the simulated and the raw simulated
    # columns are one signal: it was drawn twice, as "simulated (1D, no dispersion)" and
    # "simulated", one line hiding the other and the legend naming two.
    from shpb_report import compare
    write(tmp_path, "signals.csv", "time_s,inc_measured_strain,inc_simulated_strain,"
          "inc_simulated_raw_strain\n0,0,0,0\n1e-6,-1e-3,-1e-3,-1e-3\n")
    for dispersed, lines in (("false", 2), ("true", 3)):
        write(tmp_path, "summary.json", f'{{"command": "compare", "dispersion": {dispersed}}}')
        kept = Kept()
        compare.fig_compare_signals(Source(str(tmp_path), "."), kept)
        assert len(kept.figures[0].axes[0].get_lines()) == lines


def test_a_monte_carlo_studys_contributions_are_drawn_as_bars(tmp_path):
    # study --sweep monte-carlo's shares of the variance (summary.json quantities, records by
    # name) were only a cell of JSON text on the page; process's are bars. Both now are, each
    # bar the share summary.json gives, the title its 95 % interval.
    write(tmp_path, "gauge_bands.csv", "time_s,inc,inc_p2.5,inc_p50,inc_p97.5\n0,0,0,0,0\n")
    write(tmp_path, "summary.json", '{"sweep": "monte-carlo", "draws": 8, "quantities": '
          '{"peak_stress_Pa": {"interval_95": [550e6, 600e6], "unit": "Pa", "contributions": '
          '[{"value": "specimen.A", "share": 0.6}, {"value": "striker.velocity", "share": 0.3}]}}}')
    names = [d.__name__ if hasattr(d, "__name__") else d for d in drawn(tmp_path)]
    assert len(names) == 2
    from shpb_report import study
    kept = Kept()
    study.fig_monte_carlo_contributions(Source(str(tmp_path), "."), kept)
    (ax,) = kept.figures[0].axes
    widths = sorted(round(bar.get_width(), 9) for bar in ax.patches)
    assert widths == [30, 60]
    assert [t.get_text() for t in ax.get_yticklabels()] == ["striker.velocity", "specimen.A"]
    assert "550 to 600 MPa" in ax.get_title()


def test_the_time_equilibrium_holds_from_is_also_given_on_the_figures_clock(tmp_path):
    # time_to_equilibrium_s counts from the window start (docs/outputs.md, process), the rate
    # and equilibrium figure's axis is the faces' clock: "holds from 12.4 µs" could not be
    # found on an axis running from 400 to 480 µs. The headline gives both.
    from shpb_report.page import headline_html
    write(tmp_path, "summary.json", '{"command": "process", "time_to_equilibrium_s": 12.4e-6, '
          '"equilibrium": {"fraction_of_loaded_time": 0.93, '
          '"holds_until_unloading_from_s": 412e-6}}')
    page = headline_html(Source(str(tmp_path), "."))
    assert "12.4 µs after the window start (412 µs at the faces" in page


def test_a_stability_maps_legend_is_one_and_lies_over_no_run(tmp_path):
    # Each panel had its own legend in its lower left corner, over the stable runs of low
    # stiffness and Courant number (nine copies in a localized-bipenalty map). One legend now,
    # above the first panel, naming every entry of every panel.
    rows = [f"localized-bipenalty,{k},{r},{c},1,1,1,0"
            for k, r in ((0, 0), (1, 0.5), (100, 2)) for c in (0.1, 0.5)]
    write(tmp_path, "stability.csv", "method,stiffness_factor,mass_ratio,courant,energy_growth,"
          "stable,step_ratio,closings_after_release\n" + "\n".join(rows) + "\n")
    kept = Kept()
    sweeps.fig_stability(Source(str(tmp_path), "."), kept)
    (fig,) = kept.figures
    legends = [ax.get_legend() for ax in fig.axes if ax.get_legend() is not None]
    assert len(legends) == 1 and legends_above_their_axes(fig)
    assert {t.get_text() for t in legends[0].get_texts()} == {"stable", "unstable"}


def test_a_stability_map_marks_the_stable_runs_that_rattle(tmp_path):
    # The stability map shows where each method rattles (docs/outputs.md, study): a stable run
    # whose link closes again after its release with a force above the charted share is drawn
    # apart from the clean stable runs, and one without such a force is not.
    share = sweeps.RATTLE_SHARE
    rows = ["localized-bipenalty,1,0.5,0.5,1,1,1,0,0,0",
            f"localized-bipenalty,1,0.5,0.9,1,1,1,12,3,{3 * share}",
            f"localized-bipenalty,1,0.5,0.95,1,1,1,40,0,{share / 2}",
            "localized-bipenalty,1,0.5,1.05,1e3,0,1,0,0,"]
    write(tmp_path, "stability.csv", "method,stiffness_factor,mass_ratio,courant,energy_growth,"
          "stable,step_ratio,closings_after_release,meetings_after_unloading,"
          "force_after_unloading_share\n" + "\n".join(rows) + "\n")
    kept = Kept()
    sweeps.fig_stability(Source(str(tmp_path), "."), kept)
    (fig,) = kept.figures
    (ax,) = [a for a in fig.axes if a.get_visible()]
    drawn = {c.get_label(): [tuple(xy) for xy in c.get_offsets()] for c in ax.collections}
    rattling = [label for label in drawn if label.startswith("stable, closes again")]
    assert len(rattling) == 1 and drawn[rattling[0]] == [(1.0, 0.9)]
    assert sorted(drawn["stable"]) == [(1.0, 0.5), (1.0, 0.95)]
    assert drawn["unstable"] == [(1.0, 1.05)]


def test_a_dispersion_table_under_any_name_is_drawn(tmp_path):
    # `shpb dispersion -o FILE` writes one table named as the user chose; a folder holding it
    # was refused ("no gauges.csv, curve.csv, ... or other shpb output", exit 2). It is known by
    # its header and drawn: the phase and group velocities against a/Λ and frequency, as read.
    write(tmp_path, "bar-19mm.csv", "a_over_lambda,c_over_c0,cg_over_c0,f_a_over_c0,frequency_Hz\n"
          "0,1,1,0,0\n0.5,0.7,0.4,0.35,90000\n1,0.6,0.55,0.6,150000\n")
    write(tmp_path, "notes.csv", "a,b\n1,2\n")  # another table: not a dispersion one
    (src,) = report_main.find_sources(str(tmp_path))
    assert src.dispersion == ["bar-19mm.csv"]
    from shpb_report import dispersion
    kept = Kept()
    dispersion.fig_dispersion(src, kept)
    (fig,) = kept.figures
    by_a, by_f = fig.axes
    phase = by_a.get_lines()[0]
    assert list(phase.get_xdata()) == [0, 0.5, 1] and list(phase.get_ydata()) == [1, 0.7, 0.6]
    assert list(by_f.get_lines()[1].get_xdata()) == [0, 90, 150]  # kHz
    assert list(by_f.get_lines()[1].get_ydata()) == [1, 0.4, 0.55]
    assert "kHz" in by_f.get_xlabel() and "a/Λ" in by_a.get_xlabel()
    html, count = report_main.build(str(tmp_path))
    assert count == 1


class Titled(report_main.Figures):
    """The report's own figure collector (it gives an untitled figure the page's title), keeping
    each figure to read what it draws."""

    def __init__(self, folder):
        super().__init__(str(folder))
        self.figures = []

    def save(self, fig, *rest):
        super().save(fig, *rest)
        self.figures.append(fig)


def test_a_simulation_in_which_nothing_moves_draws_no_empty_figure_and_says_so(tmp_path):
    # A scene whose bars all rest (striker velocity 0) records zeros: the report drew six empty
    # figures (gauges, wave diagram, specimen twice, interfaces, energy) and said nothing.
    write(tmp_path, "gauges.csv", "time_s,incident,transmitted\n0,0,0\n1e-6,0,-0\n")
    write(tmp_path, "interfaces.csv", "time_s,striker-incident_force_N\n0,0\n1e-6,0\n")
    write(tmp_path, "energy.csv", "time_s,kinetic_J,strain_J,contact_J,dissipated_J,total_J\n"
          "0,0,0,0,0,0\n1e-6,0,0,0,0,0\n")
    write(tmp_path, "field.csv", "time_s,x_m,stress_Pa\n0,0,0\n0,1,0\n1e-6,0,0\n1e-6,1,0\n")
    write(tmp_path, "specimen.csv", "time_s,strain,stress_Pa,strain_rate_1_s\n0,0,0,0\n"
          "1e-6,0,0,0\n")
    assert drawn(tmp_path) == []
    html, count = report_main.build(str(tmp_path))
    assert count == 0
    assert "nothing moves in this simulation" in Path(html).read_text(encoding="utf-8")
    # One gauge that moves, and every figure is drawn.
    write(tmp_path, "gauges.csv", "time_s,incident,transmitted\n0,0,0\n1e-6,-1e-6,0\n")
    assert len(drawn(tmp_path)) == 5


def test_the_energy_legend_lies_over_no_line_and_every_figure_has_a_title(tmp_path):
    # The energy figure's legend sat in the upper right, over the total (flat at the top of its
    # panel); the bars-together figure had no title at all, nor had the plan's.
    from shpb_report import plan, simulate
    write(tmp_path, "energy.csv", "time_s,kinetic_J,strain_J,contact_J,dissipated_J,total_J\n"
          "0,78,0,0,0,78\n1e-4,39,39,0,0,78\n2e-4,20,21,0,37,78\n")
    kept = Titled(tmp_path)
    simulate.fig_energy(Source(str(tmp_path), "."), kept)
    (fig,) = kept.figures
    assert legends_above_their_axes(fig)
    assert figure_title(fig) == "Energy history"
    write(tmp_path, "pulses.csv", "time_s,near,far_measured,far_pochhammer_chree,far_time_shift\n"
          "0,0,0,0,0\n1e-6,-1e-3,-1e-3,-1e-3,-1e-3\n")
    write(tmp_path, "summary.json", '{"command": "process", "near_gauge": "near", "far_gauge": '
          '"far", "distance_m": 2.0, "rms_of_peak": {"pochhammer_chree": 0.004, '
          '"time_shift": 0.03}}')
    kept = Titled(tmp_path)
    report_main.process.fig_bar_check(Source(str(tmp_path), "."), kept)
    title = figure_title(kept.figures[0])
    assert "near moved to far over 2 m" in title
    assert "0.4 % with Pochhammer–Chree, 3 % with a time shift" in title
    write(tmp_path, "loading.csv", "time_s,strain,strain_rate_1_s,front_force_N,back_force_N,"
          "equilibrium_ratio,loading\n0,0,1000,1,1,0,1\n1e-6,0.001,1000,1,1,0,1\n")
    kept = Titled(tmp_path)
    plan.fig_loading(Source(str(tmp_path), "."), kept)
    assert figure_title(kept.figures[0]) == "Planned test: rate and equilibrium"


def test_a_plans_equilibrium_ratio_is_drawn_over_the_loading_alone(tmp_path):
    # After the loading the specimen unloads, its face forces ring about small values and R
    # (their ratio) swung between 0 and 200 %: the panel was filled with noise. R is judged over
    # the loading (docs/outputs.md, loading.csv): it is drawn there alone.
    from shpb_report import plan
    rows = [f"{i * 1e-6},0,1000,1,1,{0.5 if i >= 6 else 0.01},{1 if 2 <= i < 6 else 0}"
            for i in range(10)]
    write(tmp_path, "loading.csv", "time_s,strain,strain_rate_1_s,front_force_N,back_force_N,"
          "equilibrium_ratio,loading\n" + "\n".join(rows) + "\n")
    kept = Kept()
    plan.fig_loading(Source(str(tmp_path), "."), kept)
    ratio_axes = kept.figures[0].axes[1]
    line = next(line for line in ratio_axes.get_lines() if line.get_label().startswith("R = 2"))
    x, y = line.get_xdata(), line.get_ydata()
    shown = [round(t, 9) for t, v in zip(x, y) if v == v]
    assert shown == [2, 3, 4, 5] and max(v for v in y if v == v) == 1.0


def test_uncertainty_panels_are_titled_in_words_with_the_interval_and_its_unit(tmp_path):
    # The panels were titled with summary.json's keys ("flow_stress_Pa_at_strain_0.1").
    from shpb_report import process
    write(tmp_path, "summary.json", '{"uncertainty": {"figures": {'
          '"flow_stress_Pa_at_strain_0.1": {"interval_95": [210.7e6, 233.7e6], "unit": "Pa", '
          '"contributions": [{"input": "a", "share": 0.5}]},'
          '"mean_strain_rate_1_s": {"interval_95": [2869, 2974], "unit": "1/s", '
          '"contributions": [{"input": "a", "share": 0.5}]}}}}')
    kept = Kept()
    process.fig_uncertainty(Source(str(tmp_path), "."), kept)
    titles = [ax.get_title() for ax in kept.figures[0].axes]
    assert titles == ["flow stress at strain 0.1\n95 %: 210.7 to 233.7 MPa",
                      "mean strain rate\n95 %: 2869 to 2974 1/s"]


def test_a_simulations_specimen_equilibrium_is_drawn_over_its_loading_alone(tmp_path):
    # The loading ends at the specimen's largest strain (docs/methods.md §6), as process judges
    # equilibrium and plan's panel draws it. After it the unloaded specimen's face stresses ring
    # about zero (here 40 and -10 MPa against a 300 MPa peak: their sum beyond the ratio's 2 %
    # floor), and their ratio, 2 x 50 / 30 = 3.3, spiked to the top of the panel. A tension test's specimen.csv is
    # compression positive too: its loading ends at its most negative strain.
    from shpb_report import simulate
    for sense in (1, -1):
        rows = []
        for i in range(20):
            loading = i <= 10
            strain = sense * (0.01 * i if loading else 0.1 - 0.001 * (i - 10))
            front = sense * (300e6 if loading else 40e6 * (-1) ** i)
            back = sense * (300e6 if loading else -10e6 * (-1) ** i)
            rows.append(f"{1e-6 * i},{strain},{sense * 1000},{(front + back) / 2},{front},{back}")
        write(tmp_path, "specimen.csv", "time_s,strain,strain_rate_1_s,stress_Pa,front_stress_Pa,"
              "back_stress_Pa\n" + "\n".join(rows) + "\n")
        kept = Kept()
        simulate.fig_specimen(Source(str(tmp_path), "."), kept)
        ratio_axes = kept.figures[1].axes[1]
        (ratio,) = [line for line in ratio_axes.get_lines() if line.get_label() != "5 %"]
        time, r = ratio.get_xdata(), ratio.get_ydata()
        assert all(v == 0 for v in r[time <= 10]) and all(v != v for v in r[time > 10])


def test_a_processed_curve_is_drawn_from_where_its_face_forces_first_agree(tmp_path):
    # The rows before summary.json's equilibrium.first_s are the ring-up (docs/methods.md §6):
    # here a tensile 3-wave stress of -40 MPa at the first two rows of a compression test, which
    # no contact carries. The curves start at the first row in equilibrium; the ring-up is one
    # dotted line of its own.
    from shpb_report import process
    rows = ["0,1000,0,0,-80e6,-40e6,0,-40e6,2", "1e-6,1000,0.001,0,-80e6,-40e6,0.001,-40e6,2"]
    rows += [f"{1e-6 * i},1000,{0.001 * i},300e6,300e6,300e6,{0.001 * i},300e6,0"
             for i in range(2, 8)]
    write(tmp_path, "curve.csv", "time_s,strain_rate_1_s,strain,stress_1wave_Pa,stress_2wave_Pa,"
          "stress_3wave_Pa,true_strain,true_stress_Pa,equilibrium_ratio\n" + "\n".join(rows)
          + "\n")
    write(tmp_path, "summary.json", '{"command": "process", "test": "compression", '
          '"equilibrium": {"first_s": 2e-6}}')
    kept = Kept()
    process.fig_curve(Source(str(tmp_path), "."), kept)
    ax = kept.figures[0].axes[0]
    for line in ax.get_lines():
        y = line.get_ydata()
        if "ring-up" in line.get_label():
            assert min(y) == -40 and len(y) == 3  # joined to the first row in equilibrium
        else:
            assert all(v != v for v in y[:2]) and min(y[2:]) == 300
