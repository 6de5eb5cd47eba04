"""Shared fixtures: the executable and the source tree (set by CTest: SHPB_EXE, SHPB_SOURCE_DIR),
and the command's output read back as numbers."""
import csv
import json
import os
import pathlib
import shutil
import subprocess

import numpy as np
import pytest

SOURCE = pathlib.Path(os.environ.get("SHPB_SOURCE_DIR", pathlib.Path(__file__).parents[2]))
EXE = os.environ.get("SHPB_EXE", str(SOURCE / "build" / "shpb"))
EXPERIMENTS = sorted(p.parent.name for p in (SOURCE / "experiments").glob("*/scene.json"))


def run_command(*args, cwd=None):
    """The executable's exit code, stdout and stderr."""
    p = subprocess.run([EXE, *map(str, args)], capture_output=True, text=True, cwd=cwd)
    return p.returncode, p.stdout, p.stderr


def read_csv(path):
    """A CSV of the command as {column: float64 array}: the shortest round-trip text each value
    was written with parses back to the very double (an empty cell is NaN; a column of text
    stays a list of strings)."""
    with open(path, newline="") as f:
        rows = list(csv.reader(f))
    header, body = rows[0], rows[1:]
    table = {}
    for i, name in enumerate(header):
        cells = [r[i] for r in body]
        try:
            table[name] = np.array([float(c) if c else np.nan for c in cells])
        except ValueError:
            table[name] = cells
    return table


def columns(table):
    """{column: numpy array} of a result table (a pandas DataFrame or a dict of arrays)."""
    return {name: np.asarray(table[name]) for name in table}


def scene_dir(tmp_path, experiment):
    """A copy of an experiment's folder two levels deep in tmp_path, beside links to the
    repository's specimens/ (relative material paths resolve as in the repository)."""
    (tmp_path / "specimens").symlink_to(SOURCE / "specimens")
    folder = tmp_path / "experiments" / experiment
    shutil.copytree(SOURCE / "experiments" / experiment, folder)
    return folder


@pytest.fixture
def classic_json():
    return json.loads((SOURCE / "experiments" / "classic-al6061" / "scene.json").read_text())
