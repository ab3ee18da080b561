#!/usr/bin/env python3
"""The methods' options as the faces show them, generated from their one declaration in the
registry (model/registry.h; read through the Python package, alloycolor's _method_options):
the options table in docs/methods.md and fit's keywords in python/alloycolor/__init__.pyi,
each between its two marker lines. The program's options and their --help lines, and the
package's fit() signature and docstring, are generated from the same declarations when the
program starts and the package is imported.

Usage: PYTHONPATH=build/python python3 scripts/method_options.py [--check]
  --check: write nothing; exit 1 naming each file that differs from what would be written
  (tests/python/test_method_options.py runs it)."""
import argparse
import os
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
DOCS = os.path.join(ROOT, "docs", "methods.md")
STUBS = os.path.join(ROOT, "python", "alloycolor", "__init__.pyi")
BEGIN = "options: generated from the registry by scripts/method_options.py; do not edit"
END = "end of options"
PYTHON_TYPES = {"whole": "int", "number": "float", "choice": "str", "text": "str",
                "flag": "bool"}


def declared_options():
    try:
        import alloycolor
    except ImportError as e:
        sys.exit(f"method_options: the alloycolor Python package ({e}): build it and put "
                 "build/python on PYTHONPATH")
    return alloycolor._core._method_options()


def default_text(option):
    value = option["default"]
    if value is None:
        return "chosen by the method"
    if isinstance(value, bool):
        return "`true`" if value else "`false`"
    return f"`{value}`"


def cell(text):
    return text.replace("|", "\\|")


def markdown_lines(options):
    """The table: one row per option."""
    lines = ["| Python keyword | program | methods | takes | default | what it sets |",
             "|---|---|---|---|---|---|"]
    for o in options:
        lines.append(f"| `{o['name']}` | `{o['flag']}` | {', '.join(o['methods'])} | "
                     f"{cell(o['values'])} | {default_text(o)} | {cell(o['help'])} |")
    return lines


def stub_lines(options):
    """fit's keyword parameters, one per option (indented as the stub's signature)."""
    lines = []
    for o in options:
        kind = PYTHON_TYPES[o["kind"]]
        lines.append(f"        {o['name']}: Optional[{kind}] = ...,")
    return lines


def replaced(text, new_lines, begin_marker, end_marker, path):
    """text with the lines between the marker lines (containing BEGIN and END) replaced."""
    lines = text.split("\n")
    try:
        first = next(i for i, line in enumerate(lines) if begin_marker in line)
        last = next(i for i, line in enumerate(lines) if end_marker in line and i > first)
    except StopIteration:
        sys.exit(f"method_options: {path} lacks the marker lines '{begin_marker}' and "
                 f"'{end_marker}'")
    return "\n".join(lines[:first + 1] + new_lines + lines[last:])


def generated(options):
    """{path: the text it should hold}."""
    out = {}
    with open(DOCS) as f:
        out[DOCS] = replaced(f.read(), markdown_lines(options), BEGIN, END, DOCS)
    with open(STUBS) as f:
        out[STUBS] = replaced(f.read(), stub_lines(options), BEGIN, END, STUBS)
    return out


def stale_files(options):
    """The files whose text differs from what would be generated."""
    stale = []
    for path, text in generated(options).items():
        with open(path) as f:
            if f.read() != text:
                stale.append(path)
    return stale


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--check", action="store_true")
    args = parser.parse_args()
    options = declared_options()
    if args.check:
        stale = stale_files(options)
        for path in stale:
            print(f"method_options: {os.path.relpath(path, ROOT)} is not what the registry "
                  "declares; run scripts/method_options.py", file=sys.stderr)
        return 1 if stale else 0
    for path, text in generated(options).items():
        with open(path + ".tmp", "w") as f:
            f.write(text)
        os.replace(path + ".tmp", path)
        print(f"method_options: wrote {os.path.relpath(path, ROOT)}", file=sys.stderr)
    return 0


if __name__ == "__main__":
    sys.exit(main())
