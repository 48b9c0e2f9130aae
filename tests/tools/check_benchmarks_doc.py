#!/usr/bin/env python3
"""docs/BENCHMARKS.md stays a page of current figures: every table has machine, date and command
columns, and every row of it names a date (YYYY-MM-DD) and a command (a backticked command line:
a path such as build/... or scripts/..., or environment assignments before one); the page says
where its history is (`git log -p docs/BENCHMARKS.md`), keeps within MAX_LINES, and tells no
history of its own (no "session N" or "issue N"). Exits 1 naming each row or line at fault.

    check_benchmarks_doc.py [FILE]     (default: docs/BENCHMARKS.md of this repository)

Python 3 standard library only.
"""

import os
import re
import sys

MAX_LINES = 250
HISTORY_LINE = "git log -p docs/BENCHMARKS.md"
REQUIRED_COLUMNS = ("machine", "date", "command")
DATE = re.compile(r"^\d{4}-\d{2}-\d{2}$")
BACKTICKED = re.compile(r"`([^`]+)`")
# The first word of a command line: a path (build/..., scripts/..., /usr/bin/time), an
# environment assignment (ROUNDS=5 ...), or oiiotool (OpenImageIO's tool, on the PATH).
COMMAND_START = re.compile(r"^([A-Z_][A-Z0-9_]*=\S*|\S*/\S+|oiiotool)$")
HISTORY_WORDS = re.compile(r"\b(session|issue)s? \d+", re.IGNORECASE)


def cells(line):
    """The cells of a markdown table row, without the outer pipes."""
    return [c.strip() for c in line.strip().strip("|").split("|")]


def names_a_command(cell):
    for span in BACKTICKED.findall(cell):
        words = span.split()
        if words and COMMAND_START.match(words[0]):
            return True
    return False


def check(path):
    with open(path, encoding="utf-8") as f:
        lines = f.read().split("\n")
    if lines and lines[-1] == "":
        lines.pop()
    errors = []
    shown = os.path.relpath(path)
    if len(lines) > MAX_LINES:
        errors.append(f"{shown}: {len(lines)} lines, more than {MAX_LINES}: keep current figures "
                      f"only, their history is in git")
    if not any(HISTORY_LINE in line for line in lines):
        errors.append(f"{shown}: no line names the history ({HISTORY_LINE})")
    rows = 0
    header = None
    for number, line in enumerate(lines, 1):
        if HISTORY_WORDS.search(line):
            errors.append(f"{shown}:{number}: tells history ({HISTORY_WORDS.search(line).group(0)}):"
                          f" say what a figure is, its date and command")
        if not line.startswith("|"):
            header = None
            continue
        row = cells(line)
        if header is None:
            header = [c.lower() for c in row]
            for column in REQUIRED_COLUMNS:
                if column not in header:
                    errors.append(f"{shown}:{number}: a table without a '{column}' column")
            continue
        if all(re.fullmatch(r":?-+:?", c) for c in row):
            continue  # the separator under the header
        rows += 1
        if len(row) != len(header):
            errors.append(f"{shown}:{number}: {len(row)} cells, the header has {len(header)}")
            continue
        what = row[0] or "(no name)"
        if "date" in header and not DATE.match(row[header.index("date")]):
            errors.append(f"{shown}:{number}: '{what}': no date (YYYY-MM-DD) in the date column")
        if "machine" in header and not row[header.index("machine")]:
            errors.append(f"{shown}:{number}: '{what}': no machine")
        if "command" in header and not names_a_command(row[header.index("command")]):
            errors.append(f"{shown}:{number}: '{what}': the command column names no command "
                          f"(a backticked command line)")
    if rows == 0:
        errors.append(f"{shown}: no figure rows")
    return errors, rows


def main():
    here = os.path.dirname(os.path.abspath(__file__))
    path = sys.argv[1] if len(sys.argv) > 1 else os.path.join(here, "..", "..", "docs",
                                                             "BENCHMARKS.md")
    errors, rows = check(path)
    for error in errors:
        print(error)
    if errors:
        print(f"BENCHMARKS.md: {len(errors)} problem(s)")
        return 1
    print(f"BENCHMARKS.md: {rows} figure rows, each with a machine, a date and a command")
    return 0


if __name__ == "__main__":
    sys.exit(main())
