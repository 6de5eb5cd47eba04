"""Reading an output folder (docs/outputs.md): the CSV tables and summary.json of each producer.

Everything a user can put in a folder is checked here or through the accessors below, so that a
malformed file ends as a ReportError (one `error:` line, exit 2) and never as a traceback:
`Table.numeric` and `Table[...]` name a missing column, `Source.value` gives None for a
summary.json entry that is absent or of another type.
"""
import csv
import json
import math
import os
import re
import stat
from typing import Any, Optional

import numpy as np

from .schema import columns

# Files this package understands, by producer (docs/outputs.md).
KNOWN_FILES = ("gauges.csv", "interfaces.csv", "specimen.csv", "energy.csv", "field.csv",
               "pulses.csv", "curve.csv", "signals.csv", "comparison.csv", "pareto.csv",
               "stability.csv", "summary.json", "raw_signals.csv", "stability_boundary.csv",
               "curves.csv", "fit.json", "calibration.json", "gauge_bands.csv",
               "curve_bands.csv", "draws.csv", "path.csv", "loading.csv")
NUMBER = "number"  # Source.value kind: an int or float, not a bool
# shpb writes no NaN or infinity (an undefined value is an empty field or absent), and no
# quantity it writes comes near 1e100: beyond that a figure's axes overflow (CSV and JSON alike).
LARGEST = 1e100
# shpb's marker in an output folder (core/output_folder.cpp): its signature line, then a line
# "file: <name>" per file or sub-folder it wrote and "fnv1a64: <16 hex digits> <path>" per file,
# the digest FNV-1a 64 of its bytes (core/file_digest.hpp).
OUTPUT_MARKER = ".shpb-output"
OUTPUT_SIGNATURE = "shpb output folder: written by shpb, replaced only by shpb"
NAME_LINE = "file: "
DIGEST_LINE = "fnv1a64: "


class ReportError(Exception):
    """Bad input: printed as one `error:` line, exit code 2."""


def read_text(path: str, limit: Optional[int] = 1 << 16) -> str:
    """The text of a regular file (its first `limit` characters; None: all of it), "" for
    anything else: a FIFO in place of a marker or page must not block the report (opened
    without waiting for a writer), a device not be read."""
    try:
        fd = os.open(path, os.O_RDONLY | os.O_NONBLOCK)
    except OSError:
        return ""
    if not stat.S_ISREG(os.fstat(fd).st_mode):  # a folder, FIFO or device: no text of ours
        os.close(fd)
        return ""
    with open(fd, encoding="utf-8", errors="replace") as f:
        try:
            return f.read(limit)
        except OSError:
            return ""


def recorded_file(line: str) -> Optional[tuple[str, str]]:
    """(digest, path) of a marker's digest line, else None."""
    if not line.startswith(DIGEST_LINE):
        return None
    digest, _, path = line[len(DIGEST_LINE):].partition(" ")
    return digest, path


def marker_lines(path: str, signature: str) -> list[str]:
    """The lines of the marker file `path` (whole) if it opens with `signature` (its first line,
    newline included), else none: a file of another writer, or no file, records nothing."""
    text = read_text(path, None)
    return text.splitlines() if text.startswith(signature) else []


def output_marker_lines(folder: str) -> list[str]:
    """The lines of shpb's marker in `folder`, none if the folder has no marker of shpb's."""
    return marker_lines(os.path.join(folder, OUTPUT_MARKER), OUTPUT_SIGNATURE + "\n")


def written_by_shpb(folder: str) -> set[str]:
    """The names shpb's marker in `folder` records (by name or digest line), none without one."""
    lines = output_marker_lines(folder)
    return ({line[len(NAME_LINE):] for line in lines if line.startswith(NAME_LINE)} |
            {r[1] for r in map(recorded_file, lines) if r})


def slug(text: str) -> str:
    s = re.sub(r"[^A-Za-z0-9]+", "-", text).strip("-").lower()
    return s or "main"


def number(v: Any) -> Optional[float]:
    """A summary.json value as a number: an int or float, not a bool; else None."""
    return float(v) if isinstance(v, (int, float)) and not isinstance(v, bool) else None


def number_pair(v: Any) -> Optional[tuple[float, float]]:
    """[lower, upper] of numbers (an interval of summary.json), or None."""
    if isinstance(v, list) and len(v) == 2 and all(number(x) is not None for x in v):
        return float(v[0]), float(v[1])
    return None


def first_out_of_range(doc: Any) -> Optional[tuple[str, str]]:
    """The JSON path and text of the first number of `doc` that a figure cannot take: NaN and
    Infinity, which Python's json reads though JSON has neither and shpb writes neither, 1e400
    (read as infinity), and any number of LARGEST or more (a figure's axes overflow; a Table's
    rule). Iterative: a document nested as deeply as json reads it is walked without recursion."""
    stack = [("", doc)]
    while stack:
        where, v = stack.pop()
        if isinstance(v, dict):
            stack.extend((f"{where}.{k}" if where else str(k), x)
                         for k, x in reversed(list(v.items())))
        elif isinstance(v, list):
            stack.extend((f"{where}[{i}]", x) for i, x in reversed(list(enumerate(v))))
        elif isinstance(v, float) and not abs(v) < LARGEST:
            return where, ("NaN" if math.isnan(v) else "Infinity" if math.isinf(v) else
                           f"{v:.6g}")
        elif isinstance(v, int) and not isinstance(v, bool) and abs(v) >= LARGEST:
            return where, f"an integer of {len(str(abs(v)))} digits"
    return None


class Table:
    """A numeric CSV with one header row: columns by name as numpy arrays."""

    def __init__(self, path: str) -> None:
        self.path = path
        self.columns = {}
        self.names = []
        self.first_text = {}  # column name -> (line, column, text) of its first non-number
        # utf-8-sig: a byte-order mark (a spreadsheet's save) is no part of the first name.
        try:
            with open(path, newline="", encoding="utf-8-sig", errors="replace") as f:
                reader = csv.reader(f)
                try:
                    rows = list(reader)
                except csv.Error as e:  # an unclosed quote, a NUL byte: not a CSV of numbers
                    raise ReportError(f"{path}: line {reader.line_num}: {e}: comma-separated "
                                      "numbers were expected")
        except OSError as e:  # unreadable (permissions): an input error, not a failed write
            raise ReportError(f"{path}: {e.strerror or e}: a readable file was expected")
        if not rows:
            raise ReportError(f"{path}: line 1: empty file: a header row was expected")
        self.names = [n.strip() for n in rows[0]]
        for j, name in enumerate(self.names, start=1):
            if name in self.names[:j - 1]:
                raise ReportError(f"{path}: line 1, column {j}: {name}: a name of its own was "
                                  f"expected (column {self.names.index(name) + 1} has it)")
        data = []
        self.lines = []  # the line of each row (blank lines are skipped)
        for i, row in enumerate(rows[1:], start=2):
            if not row:
                continue
            if len(row) != len(self.names):
                raise ReportError(f"{path}: line {i}: {len(row)} fields: "
                                  f"{len(self.names)} expected (as in the header)")
            values = []
            for j, text in enumerate(row, start=1):
                try:
                    x = float(text) if text.strip() else math.nan
                except ValueError:
                    values.append(text.strip())
                    self.first_text.setdefault(self.names[j - 1], (i, j, text.strip()))
                    continue
                if text.strip() and not abs(x) < LARGEST:
                    raise ReportError(f"{path}: line {i}, column {j}: {text.strip()}: a finite "
                                      "number (below 1e100 in magnitude) or an empty field was "
                                      "expected")
                values.append(x)
            data.append(values)
            self.lines.append(i)
        self.rows = data
        for j, name in enumerate(self.names):
            col = [r[j] for r in data]
            if all(isinstance(v, float) for v in col):
                self.columns[name] = np.array(col, dtype=float)
            else:
                self.columns[name] = np.array(col, dtype=object)  # text, and NaN where empty

    def __contains__(self, name: str) -> bool:
        return name in self.columns

    def __getitem__(self, name: str) -> np.ndarray:
        """A column as read (numbers or text)."""
        if name not in self.columns:
            raise ReportError(f"{self.path}: header: {','.join(self.names)}: a column "
                              f"{name} was expected")
        return self.columns[name]

    def __len__(self) -> int:
        return len(self.rows)

    def text(self, name: str) -> np.ndarray:
        """A column of names (a test, method, gauge, pulse), as text: a figure is drawn per name
        and labelled with it, so an empty field (read as NaN: one curve per row, each "nan") is
        refused with its place. A name written as a number keeps its digits ("1", "0.5")."""
        col = self[name]
        out = []
        for k, v in enumerate(col):
            if isinstance(v, float) and math.isnan(v):
                raise ReportError(f"{self.path}: line {self.lines[k]}, column "
                                  f"{self.names.index(name) + 1} ({name}): an empty field: a "
                                  "name was expected")
            out.append(v if isinstance(v, str) else f"{v:g}")
        return np.array(out, dtype=object)

    def numeric(self, name: str) -> np.ndarray:
        col = self[name]
        if col.dtype == object:
            line, j, text = self.first_text[name]
            raise ReportError(f"{self.path}: line {line}, column {j} ({name}): {text}: a number "
                              "or an empty field was expected")
        return col


class Source:
    """One output folder: the known files it holds."""

    def __init__(self, folder: str, label: str) -> None:
        self.folder = folder
        self.label = label
        names = set(listing(folder))
        self.files = {}
        for n in KNOWN_FILES:
            path = os.path.join(folder, n)
            try:
                regular = n in names and stat.S_ISREG(os.stat(path).st_mode)
            except FileNotFoundError:  # a dangling link: no such file
                continue
            except OSError as e:  # a folder without search permission, a loop of links
                raise ReportError(f"{path}: {e.strerror or e}: a readable file was expected")
            if regular:
                self.files[n] = path
        # `shpb dispersion -o FILE` names its table as the user chose: it is known by its header.
        self.dispersion = []
        for n in sorted(names):
            path = os.path.join(folder, n)
            if (n.endswith(".csv") and n not in self.files and os.path.isfile(path)
                    and dispersion_table(path)):
                self.files[n] = path
                self.dispersion.append(n)
        # A file shpb wrote here that is gone, or no longer a file, since: its figures are left
        # out, and the page and stderr say so rather than the report drawing less in silence.
        self.missing = [f"{os.path.join(folder, n)}: written by shpb, no longer a file here: "
                        "the figures drawn from it are left out"
                        for n in sorted(written_by_shpb(folder) & set(KNOWN_FILES))
                        if n not in self.files]
        # What the page says of the folder besides its producer's warnings (main.build).
        self.notes = []
        self._tables = {}
        self.summary = {}
        if "summary.json" in self.files:
            path = self.files["summary.json"]
            try:
                with open(path, encoding="utf-8") as f:
                    self.summary = json.load(f)
            except (ValueError, RecursionError) as e:  # JSON, UTF-8, an over-long integer
                raise ReportError(f"{path}: {type(e).__name__}: {e}: valid JSON was expected")
            except OSError as e:
                raise ReportError(f"{path}: {e.strerror or e}: a readable file was expected")
            where = first_out_of_range(self.summary)
            if where is not None:
                raise ReportError(f"{path}: {where[0] or '(the document)'}: {where[1]}: a finite "
                                  "number below 1e100 in magnitude was expected")

    def has(self, name: str) -> bool:
        return name in self.files

    def table(self, name: str) -> Table:
        if name not in self._tables:
            self._tables[name] = Table(self.files[name])
        return self._tables[name]

    def value(self, *keys: Any, kind: Any = None) -> Any:
        """summary.json at keys (object members or list indices), or None when absent or not of
        `kind` (a type, a tuple of types, or NUMBER)."""
        v = self.summary
        for k in keys:
            if isinstance(k, int) and isinstance(v, list) and -len(v) <= k < len(v):
                v = v[k]
            elif isinstance(k, str) and isinstance(v, dict):
                v = v.get(k)
            else:
                return None
        if kind is None or v is None:
            return v
        if kind == NUMBER:
            return number(v)
        return v if isinstance(v, kind) else None

    def png(self, base: str) -> str:
        """Figure file name: `base.png` for DIR itself, `base_<sub-folder>.png` otherwise."""
        return f"{base}.png" if self.label == "." else f"{base}_{slug(self.label)}.png"

    def title(self, text: str) -> str:
        return text if self.label == "." else f"{text} — {self.label}"


def dispersion_table(path: str) -> bool:
    """Whether the CSV file `path` opens with the header of `shpb dispersion`'s table."""
    d = columns("dispersion")
    head = ",".join((d.a_over_lambda, d.c_over_c0, d.cg_over_c0, d.f_a_over_c0))
    try:
        with open(path, "rb") as f:
            first = f.read(len(head) + 1).decode("utf-8", "replace")
    except OSError:  # unreadable: not this table; a known file is checked where it is read
        return False
    return first == head + "\n" or first == head + "\r" or first == head + ","


def listing(folder: str) -> list[str]:
    """The names in `folder`. One that cannot be read is a bad input (exit 2), not a folder
    without output: a campaign's test would be left out of the report without a word."""
    try:
        return os.listdir(folder)
    except OSError as e:
        raise ReportError(f"{folder}: {e.strerror or e}: a readable folder was expected")


def find_sources(folder: str) -> list["Source"]:
    """The folder itself and its immediate sub-folders, those holding a known output file."""
    candidates = [Source(folder, ".")]
    for name in sorted(listing(folder)):
        sub = os.path.join(folder, name)
        # A link back to the folder itself is the folder, drawn once.
        if (os.path.isdir(sub) and name != "figures" and not name.startswith(".")
                and not os.path.samefile(sub, folder)):
            candidates.append(Source(sub, name))
    return [s for s in candidates if any(n != "summary.json" for n in s.files)]
