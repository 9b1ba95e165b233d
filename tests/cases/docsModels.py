#!/usr/bin/env python3
"""The README's models table and the tutorials' lists of choices against `spindrift -listModels`,
so that neither drifts from what ships:
  * every (name, kind) row of the README's table is a model -listModels lists, and every model it
    lists has a row (a plugin added without a row, or a row left after a removal, fails);
  * every `type X;  // a | b | c` comment of a kernel, viscosity, integrator or densityDiffusion
    entry in a tutorial's system/sphSchemes names every model of that kind, and only those.

    docsModels.py <spindrift> <source dir>
"""
import glob
import os
import re
import subprocess
import sys


def list_models(solver):
    text = subprocess.run([solver, "-listModels"], check=True, capture_output=True, text=True).stdout
    models, kind = set(), None
    for line in text.splitlines():
        if re.match(r"^[A-Za-z]\w*$", line):
            kind = line
        elif re.match(r"^    \w+$", line) and kind:
            models.add((line.strip(), kind))
    return models


def readme_table(readme):
    rows = set()
    for line in open(readme, encoding="utf-8"):
        m = re.match(r"^\| `(\w+)` \| (\w+) \|", line)
        if m:
            rows.add((m.group(1), m.group(2)))
    return rows


def tutorial_lists(source):
    """(file, block, listed names) of the `type X; // a | b` comments of the tutorials."""
    found = []
    for path in sorted(glob.glob(os.path.join(source, "tutorials", "**", "system", "sphSchemes"), recursive=True)):
        if "/benchmarks/" in path:  # their Allrun swaps a model through a fixed list
            continue
        block = None
        for line in open(path, encoding="utf-8"):
            m = re.match(r"^(\w+)\s*$", line)
            if m:
                block = m.group(1)
            m = re.match(r"^\s*type\s+\w+;\s*//(.*\|.*)$", line)
            if m and block in ("kernel", "viscosity", "integrator", "densityDiffusion"):
                names = {part.strip().split()[0] for part in m.group(1).split("|") if part.strip()}
                found.append((os.path.relpath(path, source), block, names))
    return found


def main():
    solver, source = sys.argv[1], sys.argv[2]
    shipped = list_models(solver)
    kinds = {k for _, k in shipped}
    if len(shipped) < 30 or len(kinds) < 9:
        sys.exit("FAIL: -listModels lists %d models of %d kinds: %s" % (len(shipped), len(kinds), sorted(shipped)))
    table = readme_table(os.path.join(source, "README.md"))
    failures = []
    for name, kind in sorted(shipped - table):
        failures.append("README's models table has no row for %s (%s)" % (name, kind))
    for name, kind in sorted(table - shipped):
        failures.append("README's models table has a row for %s (%s), which -listModels does not list" % (name, kind))
    print("README models table: %d rows, -listModels: %d models of %d kinds" % (len(table), len(shipped), len(kinds)))
    lists = tutorial_lists(source)
    for path, block, names in lists:
        of_kind = {n for n, k in shipped if k == block}
        if names != of_kind:
            failures.append("%s: the %s comment lists %s; the %s models are %s"
                            % (path, block, " | ".join(sorted(names)), block, " | ".join(sorted(of_kind))))
    print("tutorials' lists of choices: %d checked" % len(lists))
    if len(lists) < 5:
        failures.append("only %d lists of choices found in the tutorials' sphSchemes" % len(lists))
    for f in failures:
        print("FAIL: " + f)
    if failures:
        sys.exit(1)
    print("docs against -listModels: OK")


if __name__ == "__main__":
    main()
