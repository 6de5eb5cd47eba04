#!/usr/bin/python3
"""The report's exit codes (docs/commands.md, report): a bad file is exit 2 with one line naming
it; a bug of the report itself (an exception no reader raises) is exit 4 "error: internal", never
exit 2; nothing is written in either case.

usage: report_exit_codes.py SHARE_DIR   (the folder holding report.py and shpb_report/, e.g.
build/share/shpb, as `shpb report` finds it)
"""
import os
import shutil
import subprocess
import sys
import tempfile

FAILURES = []


def check(condition, what):
    if not condition:
        FAILURES.append(what)
        print(f"FAIL: {what}", file=sys.stderr)


def write(path, text):
    with open(path, "w", encoding="utf-8") as f:
        f.write(text)


def run(share, folder, prelude=""):
    """The report run as `shpb report` runs it, after `prelude` (code that plants a bug)."""
    code = (f"import sys; sys.dont_write_bytecode = True; sys.path.insert(0, {share!r})\n"
            f"{prelude}\n"
            f"from shpb_report.main import main\nsys.exit(main(['report.py', {folder!r}]))\n")
    r = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=300)
    return r.returncode, r.stderr


def gauges_folder(root, name, text):
    folder = os.path.join(root, name)
    os.makedirs(folder)
    write(os.path.join(folder, "gauges.csv"), text)
    return folder


def nothing_written(folder):
    return not os.path.exists(os.path.join(folder, "report.html")) and not any(
        n == "figures" or n.startswith(".report") for n in os.listdir(folder))


def main(argv):
    share = os.path.abspath(argv[1])
    try:
        import matplotlib  # noqa: F401
        import numpy  # noqa: F401
    except ImportError:
        print("SKIPPED: python3 with matplotlib and numpy not installed: report exit codes not "
              "checked")
        return 0
    root = tempfile.mkdtemp(prefix="shpb-report-exit-")
    try:
        good = "time_s,incident\n0,0\n1e-6,-1e-4\n2e-6,-2e-4\n"
        # Bad files: exit 2, one line naming the file and the place.
        for name, text, where in (
                ("ragged", "time_s,incident\n0,0\n1e-6\n", "gauges.csv: line 3: 1 fields"),
                ("infinite", "time_s,incident\n0,inf\n1e-6,0\n", "line 2, column 2: inf"),
                ("no_time", "t,incident\n0,0\n", "a column time_s was expected"),
                ("text_time", "time_s,incident\nzero,0\n", "line 2, column 1 (time_s): zero")):
            folder = gauges_folder(root, name, text)
            code, err = run(share, folder)
            check(code == 2, f"{name}: exit {code}, 2 expected ({err.strip()})")
            check(err.startswith(f"error: {folder}/gauges.csv: ") and where in err,
                  f"{name}: message {err!r} should name the file and {where!r}")
            check(err.count("\n") == 1, f"{name}: {err.count(chr(10))} lines, one expected")
            check(nothing_written(folder), f"{name}: something was written")
        # A summary.json of the wrong shape is read defensively: not a bug, not even an error.
        folder = gauges_folder(root, "odd_summary", good)
        write(os.path.join(folder, "summary.json"), '{"warnings": 5, "windows": [1, 2]}')
        code, err = run(share, folder)
        check(code == 0, f"odd summary.json: exit {code}, 0 expected ({err.strip()})")
        # A bug: a figure function raising what no reader raises. Exit 4, one line, no output.
        folder = gauges_folder(root, "bug", good)
        bug = ("import shpb_report.simulate as s\n"
               "def broken(src, figs):\n    return {}['a key the code forgot']\n"
               "s.fig_gauges = broken")
        code, err = run(share, folder, bug)
        check(code == 4, f"a bug: exit {code}, 4 expected ({err.strip()})")
        check(err.startswith("error: internal: shpb report: KeyError: "),
              f"a bug: message {err!r} should say internal")
        check(err.count("\n") == 1, f"a bug: {err.count(chr(10))} lines, one expected")
        check(nothing_written(folder), "a bug: something was written")
    finally:
        shutil.rmtree(root, ignore_errors=True)
    if FAILURES:
        return 1
    print("report exit codes: bad files 2, a bug 4, nothing written")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
