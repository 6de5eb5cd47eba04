"""The column names of shpb's output files, from the output schema: `output_schema.json` beside
this package (share/shpb/ once installed and in the build tree), else the source tree's
src/core/output_schema.json. The C++ writers and the tables of docs/outputs.md take their names
from the same file, so a figure reads exactly the columns that are written.

    CURVE = columns("curve")          # the schema's id of curve.csv
    t.numeric(CURVE.stress_3wave_Pa)  # a name the schema does not hold is an AttributeError

A quantile's point is an underscore in an attribute (`stress_3wave_p2_5_Pa` for
`stress_3wave_p2.5_Pa`). Names in angle brackets (one column per gauge or interface) have no
attribute: `suffix` gives the fixed end of such a name (`<gauge>_measured_strain` →
`_measured_strain`).
"""
from __future__ import annotations

import json
from pathlib import Path
from types import SimpleNamespace

_HERE = Path(__file__).resolve().parent
PLACES = (_HERE.parent / "output_schema.json",
          _HERE.parents[1] / "src" / "core" / "output_schema.json")


def _load() -> dict:
    for place in PLACES:
        if place.is_file():
            return json.loads(place.read_text(encoding="utf-8"))
    raise FileNotFoundError("output_schema.json not found in " + " or ".join(map(str, PLACES)))


SCHEMA = _load()


def columns(file_id: str) -> SimpleNamespace:
    """The columns of one file: an attribute per plain name (its value the name), and FILE."""
    entry = next(f for f in SCHEMA["files"] if f["id"] == file_id)
    names = [c["name"] for c in entry["columns"]]
    # A quantile's point is an underscore in the attribute: `stress_3wave_p2_5_Pa`, as in C++.
    return SimpleNamespace(FILE=entry["file"], **{n.replace(".", "_"): n for n in names
                                                  if n.replace(".", "_").isidentifier()})


def suffix(file_id: str, pattern: str) -> str:
    """The fixed end of a per-gauge name of the schema, e.g. `_measured_strain`."""
    entry = next(f for f in SCHEMA["files"] if f["id"] == file_id)
    if pattern not in (c["name"] for c in entry["columns"]):
        raise KeyError(f"{entry['file']} has no column {pattern} in the output schema")
    return pattern[pattern.rindex(">") + 1:]
