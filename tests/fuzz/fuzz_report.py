#!/usr/bin/python3
"""Mutation fuzzer for the readers of `shpb report` (tools/shpb_report/reading.py — Table: the CSV
files; Source: an output folder's known files and summary.json), the part that reads
user-reachable files.

usage: fuzz_report.py [--whole] SECONDS [SEED_FOLDER]

Each round copies the seed folder (default: tests/fuzz/corpus/fuzz_report/), mutates one file
(bit flips, byte insertions and deletions, duplicated or truncated lines, deep JSON nesting, NUL
bytes, huge numbers), and reads it as the report does. Contract: the readers either succeed or
raise ReportError (the one-line exit-2 error); anything else would be reported as an internal
error (exit 4) and is a crash here: the input is saved in the current folder as
crash-report-<file> and the run fails. With --whole each round runs the whole report (every
figure and the page, about a second a round) under the same contract: a figure must not fail on a
file its reader accepted.
"""
import os
import random
import shutil
import sys
import tempfile
import time
import traceback

HERE = os.path.dirname(os.path.abspath(__file__))
sys.dont_write_bytecode = True  # leave no __pycache__ in the source tree
sys.path.insert(0, os.path.join(HERE, "..", "..", "tools"))
from shpb_report import reading  # noqa: E402

HANDLED = (reading.ReportError,)  # what the report prints as one line with exit 2


def mutate(data, rng):
    data = bytearray(data)
    for _ in range(rng.randint(1, 8)):
        op = rng.randrange(7)
        pos = rng.randrange(len(data) + 1)
        if op == 0 and data:
            data[min(pos, len(data) - 1)] ^= 1 << rng.randrange(8)
        elif op == 1:
            data[pos:pos] = bytes([rng.randrange(256)])
        elif op == 2:
            del data[pos:pos + rng.randint(1, 16)]
        elif op == 3:
            data[pos:pos] = rng.choice([b",", b"\n", b"\r", b"\0", b"nan", b"inf", b"1e999",
                                        b"-", b"\"", b"{", b"[", b"\xff\xfe"])
        elif op == 4:
            lines = data.split(b"\n")
            if lines:
                i = rng.randrange(len(lines))
                lines.insert(i, lines[i])
                data = bytearray(b"\n".join(lines))
        elif op == 5:
            data = data[:pos]
        else:
            depth = rng.choice([10, 1000, 100000])
            data[pos:pos] = b"[" * depth + b"]" * depth
    return bytes(data)


def read_folder(folder):
    src = reading.Source(folder, ".")
    for keys in (("warnings",), ("windows", "incident", "start_s"), ("bars", 0, "name")):
        src.value(*keys, kind=reading.NUMBER)
        src.value(*keys)
    for name in src.files:
        if name.endswith(".csv"):
            table = src.table(name)
            for column in table.names:
                try:
                    table.numeric(column)
                except reading.ReportError:
                    pass


def whole_report(folder):
    from shpb_report import main as report  # matplotlib: only for --whole
    report.build(folder)


def main(argv):
    whole = "--whole" in argv
    argv = [a for a in argv if a != "--whole"]
    run = whole_report if whole else read_folder
    seconds = float(argv[1]) if len(argv) > 1 else 60
    seeds = argv[2] if len(argv) > 2 else os.path.join(HERE, "corpus", "fuzz_report")
    names = sorted(n for n in os.listdir(seeds) if not n.startswith("."))
    rng = random.Random(1)
    work = tempfile.mkdtemp(prefix="shpb-fuzz-report-")
    runs = 0
    end = time.monotonic() + seconds
    try:
        while time.monotonic() < end:
            folder = os.path.join(work, "case")
            shutil.rmtree(folder, ignore_errors=True)
            shutil.copytree(seeds, folder)
            victim = rng.choice(names)
            with open(os.path.join(seeds, victim), "rb") as f:
                data = mutate(f.read(), rng)
            with open(os.path.join(folder, victim), "wb") as f:
                f.write(data)
            runs += 1
            try:
                run(folder)
            except HANDLED:
                pass
            except Exception:  # noqa: BLE001 - any other exception is the finding
                crash = os.path.abspath(f"crash-report-{victim}")
                with open(crash, "wb") as f:
                    f.write(data)
                traceback.print_exc()
                print(f"fuzz: fuzz_report: CRASH after {runs} runs; input saved as {crash}")
                return 1
    finally:
        shutil.rmtree(work, ignore_errors=True)
    mode = " (whole report)" if whole else ""
    print(f"fuzz: fuzz_report{mode}: {runs} executions in {seconds:g} s, no crash")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
