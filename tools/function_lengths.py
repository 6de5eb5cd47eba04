#!/usr/bin/env python3
"""The longest functions of src/ and python/ (README: no function over 120 lines).

Usage: function_lengths.py DIR [DIR ...] [--max N] [--top K]
Prints the K longest function bodies (lines from the signature's opening brace to the closing
one) and exits 1 when one is longer than N lines. Comments and string literals are blanked
first, so braces inside them do not count; lambdas count as part of the function around them.
"""
import argparse
import pathlib
import re
import sys

CONTROL = re.compile(r"\b(if|for|while|switch|catch|do|else|try)\s*(\(.*)?$", re.S)
SCOPE = re.compile(r"\b(namespace|class|struct|union|enum)\b[^()]*$", re.S)


def blank(text):
    """Comments and string/char literals replaced by spaces (newlines kept)."""
    out, i, n = [], 0, len(text)
    while i < n:
        c = text[i]
        if text.startswith("//", i):
            j = text.find("\n", i)
            j = n if j < 0 else j
            out.append(" " * (j - i))
            i = j
        elif text.startswith("/*", i):
            j = text.find("*/", i + 2)
            j = n if j < 0 else j + 2
            out.append(re.sub(r"[^\n]", " ", text[i:j]))
            i = j
        elif text.startswith('R"', i) and (i == 0 or not (text[i - 1].isalnum() or text[i - 1] == "_")):
            m = re.match(r'R"([^(\s]*)\(', text[i:])
            end = text.find(")" + m.group(1) + '"', i) if m else -1
            j = n if end < 0 else end + len(m.group(1)) + 2
            out.append(re.sub(r"[^\n]", " ", text[i:j]))
            i = j
        elif c in "\"'":
            j = i + 1
            while j < n and text[j] != c:
                j += 2 if text[j] == "\\" else 1
            out.append(" " * (j + 1 - i))
            i = j + 1
        else:
            out.append(c)
            i += 1
    return "".join(out)


def functions(path):
    """(name, first line, line count) of every function body in the file."""
    text = blank(path.read_text(encoding="utf-8"))
    found, stack, head_start = [], [], 0  # stack: ("scope"|"function"|"block", line, name)
    for i, c in enumerate(text):
        if c in ";":
            head_start = i + 1
        elif c == "{":
            head = text[head_start:i].strip()
            inside_function = any(kind == "function" for kind, _, _ in stack)
            if inside_function:
                stack.append(("block", 0, ""))
            elif SCOPE.search(head) or head.endswith("=") or not head:
                stack.append(("scope", 0, ""))
            elif ")" in head and not CONTROL.search(head.split("\n")[-1].strip()):
                name = re.findall(r"([~\w:]+)\s*\(", head)
                stack.append(("function", text.count("\n", 0, i) + 1, name[0] if name else "?"))
            else:
                stack.append(("scope", 0, ""))
            head_start = i + 1
        elif c == "}":
            if stack:
                kind, line, name = stack.pop()
                if kind == "function":
                    found.append((name, line, text.count("\n", 0, i) + 1 - line + 1))
            head_start = i + 1
    return found


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("dirs", nargs="+")
    parser.add_argument("--max", type=int, default=120)
    parser.add_argument("--top", type=int, default=5)
    args = parser.parse_args()
    rows = []
    for path in sorted(p for d in args.dirs for p in pathlib.Path(d).rglob("*.[ch]pp")):
        rows += [(lines, f"{path}:{line}", name) for name, line, lines in functions(path)]
    rows.sort(reverse=True)
    for lines, where, name in rows[: args.top]:
        print(f"{lines:5d}  {where}  {name}")
    over = [r for r in rows if r[0] > args.max]
    if over:
        print(f"{len(over)} function(s) longer than {args.max} lines", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
