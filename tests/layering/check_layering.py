#!/usr/bin/env python3
"""The layers of the house: every #include "..." in core/, libshell/, solvers/, studies/,
programs/, examples/ and python/ may name only a file of its own layer or of a layer below it.

Usage: check_layering.py <source dir>

Exits 0 if every include keeps the order, 1 (after printing file:line and the rule broken for
each offending include) otherwise, 2 for a bad invocation. Run by the ctest test `layering`.

The order (lowest first) is RANKS below. Within libshell it is the order the folders'
includes actually have: subdivision uses mesh; assembly uses mesh, subdivision and energy;
contact uses assembly and subdivision; analysis uses contact (the contact zones of a state),
assembly, subdivision and mesh; io uses contact, assembly, energy, subdivision and mesh.
Within solvers: stability uses newton; dynamics (the damped-dynamics baseline) uses
stability; continuation uses stability and newton; contact uses newton, stability and
continuation. Folders that do not use each other today (energy and mesh/subdivision, analysis
and io) are still ranked: the lower may not include the higher. Only the programs share a rank: programs/ and examples/ both sit on examples/support, and
python/ (the Python module) on studies; none of them may include another.
"""

import pathlib
import re
import sys

# The layers (folders) from the lowest rank to the highest; folders of one rank may not
# include each other. A file belongs to the layer of the longest folder that contains it
# (examples/support/x.hpp to examples/support, not examples).
RANKS = [
    ["core"],
    ["libshell/mesh"],
    ["libshell/subdivision"],
    ["libshell/energy"],
    ["libshell/assembly"],
    ["libshell/contact"],
    ["libshell/analysis"],
    ["libshell/io"],
    ["solvers/newton"],
    ["solvers/stability"],
    ["solvers/dynamics"],
    ["solvers/continuation"],
    ["solvers/contact"],
    ["studies"],
    ["examples/support"],
    ["programs", "examples", "python"],
]
RANK = {layer: rank for rank, layers in enumerate(RANKS) for layer in layers}
LAYERS = list(RANK)
ORDER = " < ".join(layers[0] if len(layers) == 1 else "{" + ", ".join(layers) + "}"
                   for layers in RANKS)
# The folders whose files are checked.
CHECKED = sorted({layer.split("/")[0] for layer in LAYERS})
# Parts of the tree above every layer: nothing in a layer may include them.
ABOVE_ALL = ["tests", "benchmarks"]
SOURCE_SUFFIXES = {".hpp", ".cpp", ".h", ".inl"}
INCLUDE = re.compile(r'^\s*#\s*include\s*"([^"]+)"')


def layer_of(relative):
    """The layer of a path relative to the source dir (a str with '/'), or None: the longest
    layer folder containing it, unless the path lies in a subfolder of a layer that has
    sublayers (examples/<x>/ other than examples/support/), which is in no layer yet."""
    inside = [layer for layer in LAYERS if relative.startswith(layer + "/")]
    if not inside:
        return None
    layer = max(inside, key=len)
    has_sublayers = any(other.startswith(layer + "/") for other in LAYERS)
    if has_sublayers and "/" in relative[len(layer) + 1:]:
        return None
    return layer


def check(root):
    problems = []
    files = sorted(p for top in CHECKED if (root / top).is_dir()
                   for p in (root / top).rglob("*")
                   if p.is_file() and p.suffix in SOURCE_SUFFIXES)
    for path in files:
        relative = path.relative_to(root).as_posix()
        own = layer_of(relative)
        # A file of a checked folder outside every layer (e.g. a new libshell/<folder>) has no
        # place in the order yet: it must be given one.
        if own is None:
            problems.append(f"{relative}:1: the folder of this file is not a layer; give it "
                            f"its place in RANKS in {pathlib.Path(__file__).name}")
            continue
        lines = path.read_text(encoding="utf-8", errors="replace").splitlines()
        for number, line in enumerate(lines, start=1):
            match = INCLUDE.match(line)
            if not match:
                continue
            target = match.group(1)
            where = f"{relative}:{number}"
            if any(target == top or target.startswith(top + "/") for top in ABOVE_ALL):
                problems.append(f'{where}: #include "{target}": {own} may not include '
                                f"{target.split('/')[0]}/, which is above every layer")
                continue
            if not (root / target).is_file():
                # Relative to the including file (same folder): allowed only if it resolves.
                beside = (path.parent / target).resolve()
                if beside.is_file() and beside.is_relative_to(root.resolve()):
                    target = beside.relative_to(root.resolve()).as_posix()
                else:
                    problems.append(f'{where}: #include "{target}": not a file of the tree '
                                    "(project headers are included by their path from the "
                                    "source dir; system and third-party ones with <...>)")
                    continue
            theirs = layer_of(target)
            if theirs is None:
                problems.append(f'{where}: #include "{target}": the included file is in no '
                                "layer")
                continue
            if RANK[theirs] > RANK[own]:
                problems.append(f'{where}: #include "{target}": {own} may not include '
                                f"{theirs}, a layer above it (a layer includes only its own "
                                "files and those of the layers below it)")
            elif RANK[theirs] == RANK[own] and theirs != own:
                problems.append(f'{where}: #include "{target}": {own} may not include '
                                f"{theirs}, a layer of the same rank (neither includes the "
                                "other)")
    return len(files), problems


def main(argv):
    if len(argv) != 2:
        print("usage: check_layering.py <source dir>", file=sys.stderr)
        return 2
    root = pathlib.Path(argv[1])
    if not all((root / top).is_dir() for top in ("libshell", "solvers")):
        print(f"{root} is not the growshell source dir", file=sys.stderr)
        return 2
    count, problems = check(root)
    for p in problems:
        print(p)
    if problems:
        print(f"layering: {len(problems)} problem(s) in {count} files; the layer order is "
              f"{ORDER}")
        return 1
    print(f"layering: {count} files, every include keeps the order {ORDER}")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
