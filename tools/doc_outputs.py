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

The keys of a JSON file a command writes (`summary.json`, `plan.json`, or what `validate --json`
prints) are checked against the table or paragraph that documents them: a line

    <!-- shpb-keys: summary.json: simulate experiments/classic-al6061/scene.json -o results/x -q -->

(the file in the command's `-o` or `--plan` folder, or `stdout`, then the command) is followed by that table or
paragraph. Every file and folder the command wrote must be named in backquotes in the page's section
that holds the line, and in the first line of `shpb CMD --help` where that line says what it writes. Every key the file holds must be named there in backquotes (`bars[]`, `quantities.<name>`
name `bars` and `quantities`), and every key of an object it holds (of every element, for an array
of objects) named in the key's table row, or in the paragraph; a key a table row names outside its
parentheses must be in the file unless the row says when it is written ("only ..."). Every
`summary.json` holds `version`, the shpb that wrote it.

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
import shutil
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
MARKER = re.compile(r"^<!-- shpb-output: (.+?) -->$")
SCHEMA_MARKER = re.compile(r"^<!-- shpb-schema: ([a-z_]+) -->$")
KEYS_MARKER = re.compile(r"^<!-- shpb-keys: ([^:]+): (.+?) -->$")
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


def documented_names(text: str) -> set[str]:
    """The keys text names in backquotes: `bars[]` and `quantities.<name>` name bars and quantities."""
    return {re.split(r"[\[.<]", name, maxsplit=1)[0] for name in re.findall(r"`([^`]+)`", text)}


def names(text: str, key: str) -> bool:
    """True if text names key: as a word, or by a backquoted pattern (`nrmse_<pulse>_before`)."""
    if re.search(rf"(?<![\w-]){re.escape(key)}(?![\w-])", text):
        return True
    patterns = [re.escape(n) for n in re.findall(r"`([^`]*<[^`]+)`", text)]
    return any(re.fullmatch(re.sub(r"<[^>]+>", r"[^\\s]+", p), key) for p in patterns)


def outside_parentheses(text: str) -> str:
    depth, kept = 0, []
    for c in text:
        depth += c == "("
        if depth == 0:
            kept.append(c)
        depth -= c == ")" and depth > 0
    return "".join(kept)


def written_json(exe: str, what: str, command: str):
    words = shlex.split(command)
    if "--plan" in words:  # a plan folder must be new: the one this check made before goes
        shutil.rmtree(ROOT / words[words.index("--plan") + 1], ignore_errors=True)
    result = subprocess.run([exe, *shlex.split(command)], cwd=ROOT, capture_output=True, text=True,
                            timeout=600, check=False)
    if result.returncode != 0:
        raise SystemExit(f"shpb {command}: exit {result.returncode}: {result.stderr.strip()}")
    if what == "stdout":
        return json.loads(result.stdout), None
    words = shlex.split(command)
    folder = ROOT / next(words[i + 1] for i, w in enumerate(words)
                         if w in ("-o", "--output", "--plan"))
    return json.loads((folder / what).read_text(encoding="utf-8")), folder


def section(lines: list[str], number: int) -> str:
    """The text of the `## ` section that holds line number."""
    start = next(i for i in range(number, -1, -1) if lines[i].startswith("## "))
    end = next((i for i in range(number + 1, len(lines)) if lines[i].startswith("## ")), len(lines))
    return "\n".join(lines[start:end])


def names_file(names: list[str], name: str) -> bool:
    """True if one of names is the file or folder `name`: as written (a folder with or without its
    `/`), or with a number as a capital K or N (`shot-K.csv` names shot-1.csv)."""
    patterns = [re.sub(r"(?<![A-Za-z])([KN])(?![A-Za-z])", r"\\d+", re.escape(n.rstrip("/")))
                for n in names]
    return any(re.fullmatch(p, name.rstrip("/")) for p in patterns)


def file_mismatches(exe: str, where: str, command: str, folder: Path, text: str) -> list[str]:
    """The files of an output folder that its page section, or its command's --help line saying
    what it writes, does not name (a folder with a marker of its own, a campaign's test, aside)."""
    written = sorted(p.name + ("/" if p.is_dir() else "") for p in folder.iterdir()
                     if p.name != ".shpb-output" and not (p / ".shpb-output").exists())
    found = [f"{where}: writes {name}, which its section does not name" for name in written
             if not names_file(re.findall(r"`([^`]+)`", text), name)]
    described = subprocess.run([exe, command.split()[0], "--help"], capture_output=True, text=True,
                               check=False).stdout.split("\n")[0]
    if "write" in described:
        found += [f"{where}: writes {name}, which `shpb {command.split()[0]} --help` does not name"
                  for name in written
                  if not names_file(re.findall(r"[\w./-]+", described), name)]
    return found


def nested_keys(value) -> set[str]:
    """The keys of an object, or of every object of an array."""
    items = value if isinstance(value, list) else [value]
    return {k for item in items if isinstance(item, dict) for k in item}


def key_mismatches(exe: str, name: str, lines: list[str]) -> list[str]:
    """file:line: the keys of each marked JSON file that its table or paragraph does not match."""
    found = []
    for number, line in enumerate(lines):
        match = KEYS_MARKER.match(line)
        if not match:
            continue
        what, command = match.groups()
        end = number + 1
        while end < len(lines) and lines[end].strip():
            end += 1
        block = lines[number + 1:end]
        written, folder = written_json(exe, what, command)
        where = f"{name}:{number + 1}: {what} of shpb {command.split()[0]}"
        if what == "summary.json" and "version" not in written:
            found.append(f"{where}: holds no `version` (every summary.json names the shpb that "
                         "wrote it)")
        if folder is not None:
            found += file_mismatches(exe, where, command, folder, section(lines, number))
        rows = {}  # key -> its table row, for the keys a row names outside its parentheses
        for row in block:
            if row.startswith("|") and not re.match(r"^\|\s*(key|-+)\s*\|", row):
                first = row.split("|")[1]
                for key in documented_names(outside_parentheses(first)):
                    rows[key] = row
        named = documented_names("\n".join(block))
        for key, value in written.items():
            if key not in named:
                found.append(f"{where}: writes `{key}`, which the documentation does not name")
                continue
            if isinstance(value, dict) and value and all(isinstance(v, dict) for v in value.values()):
                continue  # a map of records by a name of the data (fit's parameters): not keys
            text = rows.get(key, "\n".join(block))
            found += [f"{where}: writes `{key}` with `{inner}`, which its documentation does not name"
                      for inner in sorted(nested_keys(value)) if not names(text, inner)]
        found += [f"{where}: documents `{key}`, which it does not write (a row for a key written "
                  "only sometimes says when: \"only ...\")"
                  for key, row in rows.items() if key not in written and "only" not in row]
    return found


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
    mismatched = [m for name in files
                  for m in key_mismatches(exe, name, Path(name).read_text(encoding="utf-8").split("\n"))]
    if mismatched:
        print("\n".join(mismatched), file=sys.stderr)
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
