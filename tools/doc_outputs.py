#!/usr/bin/env python3
"""Printed output in the documentation, checked against the executable.

A Markdown file marks a block of real output with one or more comment lines, each a command run
from the project root, followed by a fenced code block:

    <!-- shpb-output: validate experiments/classic-al6061/scene.json -->
    ```text
    ...what the command prints (stdout, then stderr)...
    ```

With several marker lines the commands run in order and the block shows each as `$ shpb ARGS`
followed by what it printed. Outputs go under results/ (ignored by git). `--check` exits 1 and
prints a diff when a block differs from what the executable prints now; `--update` rewrites the
blocks (`make docs`). Figures that change from run to run (wall and CPU times) are masked, and
progress lines left out.

The column tables of docs/outputs.md come from the output schema (src/core/output_schema.json, the
list the C++ writers and the report take their names from): a line

    <!-- shpb-schema: curve -->

(the schema's id of a file) is followed by the table of that file's columns, checked and rewritten
like the printed output.

Every command a page shows (`shpb CMD ...`, `build/shpb CMD ...`, in code or in prose) is also
checked for its options: each `-x` or `--name` after the command must be one that `shpb CMD
--help` lists (both modes; a wrong one is reported with its file and line, and is not rewritten).

Usage: doc_outputs.py (--check | --update) SHPB_EXE FILE.md...
"""
from __future__ import annotations

import difflib
import json
import re
import shlex
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
MARKER = re.compile(r"^<!-- shpb-output: (.+?) -->$")
SCHEMA_MARKER = re.compile(r"^<!-- shpb-schema: ([a-z_]+) -->$")
SCHEMA = ROOT / "src" / "core" / "output_schema.json"
# Progress lines on stderr ("simulating: 40%"): left out of the documented output.
PROGRESS = re.compile(r"^[a-z ]+: \d+%$")
# Times of a run (solve, wall, CPU): the only figures a deterministic run does not repeat.
VOLATILE = [
    (re.compile(r"\b(\d+(?:\.\d+)?) ?(s|ms) (wall|CPU|processor)\b"), r"<time> \3"),
    (re.compile(r"\b(solve|wall time|in) (\d+(?:\.\d+)?(?:e-?\d+)?) ?(s|ms)\b"), r"\1 <time>"),
]


def mask(text: str) -> str:
    for pattern, replacement in VOLATILE:
        text = pattern.sub(replacement, text)
    return text


def run(exe: str, commands: list[str]) -> str:
    shown = []
    for command in commands:
        result = subprocess.run([exe, *shlex.split(command)], cwd=ROOT, capture_output=True,
                                text=True, timeout=600, check=False)
        # Paths as a reader at the project root sees them, wherever the clone lies.
        printed = (result.stdout + result.stderr).rstrip("\n").replace(f"{ROOT}/", "")
        printed = "\n".join(line.rstrip() for line in printed.split("\n")
                             if not PROGRESS.match(line))
        if len(commands) > 1:
            shown.append(f"$ shpb {command}")
        if printed:
            shown.append(printed)
        if result.returncode not in (0,):
            shown.append(f"(exit {result.returncode})")
    return "\n".join(shown)


def blocks(lines: list[str]):
    """(first marker line, commands, fence start, fence end) of every marked block."""
    i = 0
    while i < len(lines):
        commands = []
        start = i
        while i < len(lines) and MARKER.match(lines[i]):
            commands.append(MARKER.match(lines[i]).group(1))
            i += 1
        if commands:
            if i >= len(lines) or not lines[i].startswith("```"):
                raise SystemExit(f"{start + 1}: a shpb-output marker must be followed by a fenced block")
            end = i + 1
            while end < len(lines) and lines[end] != "```":
                end += 1
            if end >= len(lines):
                raise SystemExit(f"{i + 1}: fenced block not closed")
            yield start, commands, i, end
            i = end + 1
        else:
            i += 1


def schema_table(file_id: str) -> list[str]:
    """The Markdown table of one file's columns in the output schema."""
    files = json.loads(SCHEMA.read_text(encoding="utf-8"))["files"]
    entry = next((f for f in files if f["id"] == file_id), None)
    if entry is None:
        raise SystemExit(f"{SCHEMA}: no file with id {file_id!r}")
    # A column written under a condition ("only") says so after its meaning.
    rows = [f"| `{c['name']}` | {c['unit']} | {c['meaning']}"
            + (f" (only {c['only']})" if "only" in c else "") + " |" for c in entry["columns"]]
    return ["| column | unit | meaning |", "|---|---|---|", *rows]


def schema_blocks(lines: list[str]):
    """(file id, table start, table end) of every table marked as generated from the schema."""
    for i, line in enumerate(lines):
        match = SCHEMA_MARKER.match(line)
        if match:
            end = i + 1
            while end < len(lines) and lines[end].startswith("|"):
                end += 1
            yield match.group(1), i + 1, end


# A command shown on a page: `shpb CMD` and its arguments up to the end of the code span, the
# table cell, a comment or the line.
SHOWN_COMMAND = re.compile(r"\bshpb (validate|simulate|process|compare|dispersion|study|fit|calibrate"
                           r"|plan|report)\b([^`|#\n]*)")
# An option among the arguments: a dash and a letter, not inside a path or a word (`-1`, `a-b` and
# `results/x-y` are none).
SHOWN_OPTION = re.compile(r"(?<![\w/.-])(--?[A-Za-z][A-Za-z0-9-]*)")


def unknown_options(exe: str, files: list[str]) -> list[str]:
    """file:line: the options of shown commands that the command's --help does not list."""
    known: dict[str, set[str]] = {}
    found = []
    for name in files:
        for number, line in enumerate(Path(name).read_text(encoding="utf-8").split("\n"), 1):
            for command, arguments in SHOWN_COMMAND.findall(line):
                if command not in known:
                    text = subprocess.run([exe, command, "--help"], capture_output=True, text=True,
                                          check=False).stdout
                    known[command] = set(SHOWN_OPTION.findall(text))
                found += [f"{name}:{number}: shpb {command}: {option}: not an option of the command"
                          for option in SHOWN_OPTION.findall(arguments)
                          if option not in known[command]]
    return found


def main(argv: list[str]) -> int:
    if len(argv) < 4 or argv[1] not in ("--check", "--update"):
        print(__doc__.strip().splitlines()[-1], file=sys.stderr)
        return 2
    update, exe, files = argv[1] == "--update", argv[2], argv[3:]
    unknown = unknown_options(exe, files)
    if unknown:
        print("\n".join(unknown), file=sys.stderr)
        return 1
    stale = 0
    for name in files:
        path = Path(name)
        original = path.read_text(encoding="utf-8").split("\n")
        lines, out = original, list(original)
        for file_id, start, end in reversed(list(schema_blocks(lines))):
            table = schema_table(file_id)
            if lines[start:end] != table:
                stale += 1
                if not update:
                    diff = difflib.unified_diff(lines[start:end], table,
                                                f"{name}:{start + 1} (documented)",
                                                f"{SCHEMA.name} ({file_id})", lineterm="")
                    print("\n".join(diff))
                out[start:end] = table
        lines, out = out, list(out)  # the printed outputs' blocks, in the updated tables' lines
        # Replace from the last block up so earlier line numbers stay valid.
        for start, commands, fence, end in reversed(list(blocks(lines))):
            documented = mask("\n".join(lines[fence + 1:end]))
            printed = run(exe, commands)
            if mask(printed) != documented:
                stale += 1
                where = f"{name}:{start + 1}"
                if not update:
                    diff = difflib.unified_diff(documented.split("\n"), mask(printed).split("\n"),
                                                f"{where} (documented)", "printed now", lineterm="")
                    print("\n".join(diff))
                out[fence + 1:end] = printed.split("\n") if printed else []
        if update and out != original:
            path.write_text("\n".join(out), encoding="utf-8")
            print(f"updated {name}")
    if stale and not update:
        print(f"{stale} documented output(s) or column table(s) differ from what shpb prints or "
              "the output schema lists now: run `make docs`",
              file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
