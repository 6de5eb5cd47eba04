"""docs/python.md documents exactly what the module exports, as tests/app/test_docs_complete.cpp
checks docs/commands.md and docs/scene-format.md against the code. Its section "## Reference"
holds one table a kind of name, each under a "### " heading:

- "### Functions" (first column `function`): one row a function of shpb.__all__, its signature as
  the module has it (every parameter, in order, with its default);
- "### Errors" (first column `error`): one row an exception class, the class it is (`is a`);
- "### <Class>" (first column `attribute`): one table a class of shpb.__all__, one row each
  public attribute and method (a method with its signature); a `set` column, which a class with
  an assignable attribute must have, says `yes` or `no` for each property.

Both ways: nothing exported is missing, nothing documented is absent; and shpb.__all__ is every
public name of the module. Anywhere in the page, a call of an exported function or of a class's
method (`process(scene, draws=...)`, `Scene.from_dict(d, file=...)`) is a Python call that the
signature takes, and `shpb.<name>` exists; a call whose last argument is `...` abbreviates the
signature, so its leading bare names are the parameters' own (`compare(scene, ...)`)."""
import ast
import inspect
import re

import shpb
from conftest import SOURCE

DOC = "docs/python.md"
REFERENCE = "Reference"


def doc_text():
    return (SOURCE / DOC).read_text(encoding="utf-8")


def split_fences(text):
    """(the page outside fenced code blocks, the code of its ```python blocks)."""
    prose, code, fence = [], [], None
    for line in text.splitlines():
        if line.startswith("```"):
            fence = None if fence is not None else line[3:].strip()
            continue
        if fence is None:
            prose.append(line)
        elif fence == "python":
            code.append(line)
    return "\n".join(prose), "\n".join(code)


def code_spans(text):
    """The text of each `code span` (a span may run over a line break, as Markdown allows)."""
    return [" ".join(s.split()) for s in re.findall(r"`([^`]+)`", text)]


def cells(row):
    """The cells of a table row "| a | b |"."""
    return [c.strip() for c in row.strip().strip("|").split("|")]


def reference_tables(text):
    """{heading: (header cells, [row cells])} of the tables under "## Reference"'s headings."""
    tables, heading, in_reference = {}, None, False
    for line in split_fences(text)[0].splitlines():
        if line.startswith("## "):
            in_reference = line[3:].strip() == REFERENCE
        elif line.startswith("### ") and in_reference:
            heading = line[4:].strip()
        elif line.startswith("|") and in_reference and heading:
            if heading not in tables:
                tables[heading] = (cells(line), [])
            elif not line.startswith("|---"):
                tables[heading][1].append(cells(line))
    return tables


def default_text(node):
    """A default as text: a literal by its repr, a path by its text's (a str is taken for it)."""
    if isinstance(node, ast.Call) and getattr(node.func, "id", "").endswith("Path"):
        node = node.args[0]
    try:
        return repr(ast.literal_eval(node))
    except ValueError:
        return ast.unparse(node)


def parsed_parameters(signature):
    """["name", "name=default", "*args", ...] of a signature text "f(a, b=1)" (annotations and a
    return type, as a pybind11 docstring gives them, ignored), or None if it is not one."""
    try:
        a = ast.parse(f"def {signature}: pass").body[0].args
    except SyntaxError:
        return None
    def named(p, d):
        return p.arg if d is None else f"{p.arg}={default_text(d)}"

    positional = a.posonlyargs + a.args
    defaults = [None] * (len(positional) - len(a.defaults)) + a.defaults
    out = [named(p, d) for p, d in zip(positional, defaults)]
    out += [f"*{a.vararg.arg}"] if a.vararg else []
    out += [named(p, d) for p, d in zip(a.kwonlyargs, a.kw_defaults)]
    return out + ([f"**{a.kwarg.arg}"] if a.kwarg else [])


def parameters(function):
    """The parameters of a Python function or method (without self), or of a pybind11 function
    (from the signature pybind11 writes as its docstring's first line)."""
    try:
        signature = inspect.signature(function)
    except ValueError:
        out = parsed_parameters(function.__doc__.splitlines()[0].split(" -> ")[0])
        return out[1:] if out and out[0] == "self" else out
    out = [str(p.replace(annotation=inspect.Parameter.empty))
           for p in signature.parameters.values()]
    return out[1:] if out and out[0] == "self" else out


def exported():
    names = {n: getattr(shpb, n) for n in shpb.__all__}
    errors = {n: o for n, o in names.items() if inspect.isclass(o) and issubclass(o, Exception)}
    classes = {n: o for n, o in names.items() if inspect.isclass(o) and n not in errors}
    functions = {n: o for n, o in names.items() if inspect.isfunction(o)}
    return functions, classes, errors


def instance_attributes(cls):
    """The public names a Python class's __init__ assigns on self (FolderResult's tables, ...)."""
    if not inspect.isfunction(cls.__dict__.get("__init__")):
        return set()
    tree = ast.parse(inspect.getsource(cls.__init__).strip())
    names = set()
    for node in ast.walk(tree):
        for target in getattr(node, "targets", []):
            for t in (target.elts if isinstance(target, ast.Tuple) else [target]):
                if isinstance(t, ast.Attribute) and getattr(t.value, "id", "") == "self":
                    names.add(t.attr)
    return {n for n in names if not n.startswith("_")}


def members(cls):
    """{public name: ("method", its parameters) or ("property", assignable) or
    ("attribute", None)} of an exported class; constructors are not public (results are made by
    the functions, the scene by Scene.load and Scene.from_dict)."""
    out = {n: ("attribute", None) for n in instance_attributes(cls)}
    for name, value in vars(cls).items():
        if name.startswith("_"):
            continue
        if isinstance(value, property):
            out[name] = ("property", value.fset is not None)
        else:
            out[name] = ("method", parameters(getattr(cls, name)))
    return out


def sole_span(cell, where, bad):
    spans = code_spans(cell)
    if len(spans) != 1:
        bad.append(f"{where}: a row's first cell names {len(spans)} `names`, expected one: {cell}")
        return None
    return spans[0]


def named_rows(rows, where, bad, documented):
    """(name, `span`, cells) of each row, its name the span up to "(": a row naming no one name,
    or a name again, is said in `bad`; the names are gathered in `documented`."""
    for row in rows:
        span = sole_span(row[0], where, bad)
        if span is None:
            continue
        name = span.split("(")[0]
        if name in documented:
            bad.append(f"{where}: `{name}` has two rows")
        documented.add(name)
        yield name, span, row


def check_signature(span, expected, what, where, bad):
    got = parsed_parameters(span)
    if got is None:
        bad.append(f"{where}: `{span}` is not a signature name(parameter, ...) of {what}")
    elif got != expected:
        bad.append(f"{where}: documents `{span}`; {what} is ({', '.join(expected)})")


def function_mismatches(functions, tables):
    where = f'{DOC}, "### Functions"'
    header, rows = tables.get("Functions", ([], []))
    bad = [] if header[:1] == ["function"] else [
        f"{where}: no table whose first column is `function`"]
    documented = set()
    for name, span, _ in named_rows(rows, where, bad, documented):
        if name not in functions:
            bad.append(f"{where}: documents `{span}`, which is not a function of shpb.__all__")
        else:
            check_signature(span, parameters(functions[name]), f"shpb.{name}", where, bad)
    bad += [f"{where}: shpb.{n}{inspect.signature(f)} is not documented"
            for n, f in functions.items() if n not in documented]
    return bad


def error_mismatches(errors, tables):
    where = f'{DOC}, "### Errors"'
    header, rows = tables.get("Errors", ([], []))
    if header[:2] != ["error", "is a"]:
        return [f"{where}: no table whose columns begin `error`, `is a`"]
    bad, documented = [], set()
    for name, _, row in named_rows(rows, where, bad, documented):
        if name not in errors:
            bad.append(f"{where}: documents `{name}`, which is not an exception of shpb.__all__")
        elif code_spans(row[1]) != [errors[name].__bases__[0].__name__]:
            bad.append(f"{where}: `{name}`'s base class is {errors[name].__bases__[0].__name__}, "
                       f"not {row[1]}")
    return bad + [f"{where}: shpb.{n} is not documented" for n in errors if n not in documented]


def class_mismatches(name, cls, table):
    where = f'{DOC}, "### {name}"'
    if table is None:
        return [f'{DOC}: no section "### {name}" under "## {REFERENCE}" for the class '
                f"shpb.{name}"]
    header, rows = table
    real = members(cls)
    bad = [] if header[:1] == ["attribute"] else [
        f"{where}: its table's first column is not `attribute`"]
    setter = header.index("set") if "set" in header else None
    if setter is None and any(kind == "property" and assignable
                              for kind, assignable in real.values()):
        bad.append(f"{where}: no `set` column, and shpb.{name} has assignable attributes")
    documented = set()
    for attribute, span, row in named_rows(rows, where, bad, documented):
        kind, detail = real.get(attribute, (None, None))
        if kind is None:
            bad.append(f"{where}: documents `{span}`, which shpb.{name} does not have")
        elif kind == "method":
            check_signature(span, detail, f"shpb.{name}.{attribute}", where, bad)
        elif "(" in span:
            bad.append(f"{where}: documents `{span}`, but shpb.{name}.{attribute} is no method")
        if setter is not None and kind is not None:
            expected = ("yes" if detail else "no") if kind == "property" else ""
            if row[setter] != expected:
                bad.append(f"{where}: `{attribute}`'s `set` is \"{row[setter]}\", expected "
                           f"\"{expected}\"")
    return bad + [f"{where}: shpb.{name}.{a} ({kind}) is not documented"
                  for a, (kind, _) in real.items() if a not in documented]


def test_all_is_every_public_name():
    public = {n for n, o in vars(shpb).items()
              if not n.startswith("_") and not inspect.ismodule(o)}
    assert public == set(shpb.__all__), (
        f"shpb's public names and shpb.__all__ differ: {sorted(public ^ set(shpb.__all__))}")


def test_reference_documents_every_exported_name_and_nothing_else():
    functions, classes, errors = exported()
    tables = reference_tables(doc_text())
    bad = function_mismatches(functions, tables) + error_mismatches(errors, tables)
    bad += [f"{DOC}: shpb.{n} is neither a function nor a class: no table of \"## {REFERENCE}\" "
            "documents such a name" for n in shpb.__all__
            if n not in {**functions, **classes, **errors}]
    for name, cls in classes.items():
        bad += class_mismatches(name, cls, tables.get(name))
    bad += [f'{DOC}: "### {h}" under "## {REFERENCE}" names nothing shpb exports'
            for h in tables if h not in {"Functions", "Errors", *classes}]
    assert not bad, "\n".join(bad)


def call_arguments(text, start):
    """The text between the parenthesis at `start` and its match (None if it is not closed)."""
    depth, quote = 0, None
    for i in range(start, len(text)):
        c = text[i]
        if quote:
            quote = None if c == quote else quote
        elif c in "\"'":
            quote = c
        elif c in "([{":
            depth += 1
        elif c in ")]}":
            depth -= 1
            if depth == 0:
                return text[start + 1:i]
    return None


def check_call(call, arguments, expected, bad):
    where = f"{DOC}: `{call}({arguments})`"
    # A trailing `...` abbreviates a signature: the names before it are its parameters.
    abbreviated = re.fullmatch(r"(.*?)(?:^|,)\s*\.\.\.", arguments)
    try:
        node = ast.parse(f"f({abbreviated[1] if abbreviated else arguments})", mode="eval").body
    except SyntaxError:
        bad.append(f"{where} is not a Python call")
        return
    names = [p.split("=")[0].lstrip("*") for p in expected]
    positional = [p.split("=")[0] for p in expected if not p.startswith("*")]
    for k in node.keywords:
        if k.arg not in names:
            bad.append(f"{where}: {call} has no parameter {k.arg} ({', '.join(expected)})")
    if len(node.args) > len(positional):
        bad.append(f"{where}: {call} takes {len(positional)} positional arguments "
                   f"({', '.join(expected)})")
    for a, p in zip(node.args if abbreviated else [], positional):
        if isinstance(a, ast.Name) and a.id != p:
            bad.append(f"{where}: {call}'s parameter is {p}, not {a.id} ({', '.join(expected)})")


def test_calls_on_the_page_match_the_signatures():
    functions, classes, _ = exported()
    callables = {n: parameters(f) for n, f in functions.items()}
    for name, cls in classes.items():
        callables.update({f"{name}.{m}": detail
                          for m, (kind, detail) in members(cls).items() if kind == "method"})
    prose, code = split_fences(doc_text())
    bad = []
    for text in code_spans(prose) + [code]:
        for m in re.finditer(r"(?<![\w.])(?:shpb\.)?([A-Za-z_][\w.]*)\(", text):
            if m.group(1) in callables:
                arguments = call_arguments(text, m.end() - 1)
                if arguments is None:
                    bad.append(f"{DOC}: `{text}`: the call of {m.group(1)} is not closed")
                else:
                    check_call(m.group(1), arguments, callables[m.group(1)], bad)
        bad += [f"{DOC}: `{text}` names shpb.{n}, which the module does not have"
                for n in re.findall(r"(?<![\w/])shpb\.(\w+)", text) if not hasattr(shpb, n)]
    assert not bad, "\n".join(bad)
