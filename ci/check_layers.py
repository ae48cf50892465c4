#!/usr/bin/env python3
"""Checks that the project's folders and files include one another in one direction.

  ci/check_layers.py [ROOT]   (default: the repository this file lies in)

Reads every tracked C++ file of ROOT (.h, .cc; every file under ROOT when it is not a git work
tree) and its `#include "..."` lines, each resolved beside the including file first, then from
ROOT (the project's one include directory). Fails (exit 1, one line per problem, naming the file,
the line and the edge) when

  - a file of a layer includes a file of a layer that its own does not depend on, directly or
    through other layers (a back-edge or a sideways edge). The layers of a folder are the rows of
    LAYERS below, lowest first; the runner's (validation/runner/) are the layers its
    CMakeLists.txt declares with phdslam_runner_layer(), which are also its libraries' links;
  - a file outside a test (*_test.cc, test_*.h) includes a layer of test helpers;
  - a file includes a files-only folder (reports/, ci/: they read the program's files and are
    none of its C++), or a files-only folder holds C++ that includes the project's;
  - a folder that has layers holds a C++ file at its top level, or a folder holding C++ that is
    not one of its layers;
  - sibling folders, at any depth, include one another in a circle (found from the includes
    alone, so a folder without a table of layers is covered too);
  - files include one another in a circle, where a header and its source (x.h and x.cc of one
    folder) count as one unit: x.cc including y.h while y.h includes x.h is a circle.

The self-test is ci/tests/test_check_layers.py (CTest: layering_self_test).
"""

from __future__ import annotations

import re
import subprocess
import sys
from dataclasses import dataclass, field
from pathlib import Path, PurePosixPath

SOURCE_SUFFIXES = (".h", ".cc")
INCLUDE = re.compile(r'^[ \t]*#[ \t]*include[ \t]*"([^"]+)"', re.MULTILINE)
RUNNER = "validation/runner"
RUNNER_DECLARATION = re.compile(r"^[ \t]*phdslam_runner_layer\(([^)]*)\)", re.MULTILINE)
RUNNER_KEYWORDS = {"DEPENDS", "LIBS", "PRIVATE_LIBS", "TEST_HELPERS"}

# The layers of each folder, lowest first: (name, the layers it may include, kind). A layer may
# include its own files and those of the layers it names, and theirs in turn. Kinds: "code";
# "test helpers", which only tests may include; "files only", which nothing of the C++ includes
# and which includes none of it. oracle/ and reference/ are siblings: the known-association
# oracle and the external baselines each stand on the data sets alone.
LAYERS: dict[str, tuple[tuple[str, tuple[str, ...], str], ...]] = {
    "": (
        ("src", (), "code"),
        ("datasets", ("src",), "code"),
        ("oracle", ("datasets",), "code"),
        ("reference", ("datasets",), "code"),
        ("validation", ("oracle", "reference"), "code"),
        ("apps", ("validation",), "code"),
        ("benchmarks", ("validation",), "code"),
        ("examples", ("validation",), "code"),
        ("fuzz", ("validation",), "code"),
        ("reports", (), "files only"),
        ("ci", (), "files only"),
    ),
    "src": (
        ("core", (), "code"),
        ("testing", ("core",), "test helpers"),
        ("models", ("core",), "code"),
        ("assignment", ("core",), "code"),
        ("phd", ("models",), "code"),
        ("filters", ("phd", "assignment"), "code"),
        ("glmb", ("filters",), "code"),
    ),
}


@dataclass
class Layer:
    kind: str
    reach: set[str] = field(default_factory=set)


@dataclass(frozen=True)
class Include:
    source: str
    line: int
    target: str

    def where(self) -> str:
        return f"{self.source}:{self.line}"


def runner_layers(root: Path) -> tuple[tuple[str, tuple[str, ...], str], ...]:
    """The runner's layers as validation/runner/CMakeLists.txt declares them (none without it)."""
    cmake = root / RUNNER / "CMakeLists.txt"
    if not cmake.is_file():
        return ()
    rows = []
    for match in RUNNER_DECLARATION.finditer(cmake.read_text(encoding="utf-8")):
        words = match.group(1).split()
        depends, keyword = [], None
        for word in words[1:]:
            if word in RUNNER_KEYWORDS:
                keyword = word
            elif keyword == "DEPENDS":
                depends.append(word)
        kind = "test helpers" if "TEST_HELPERS" in words else "code"
        rows.append((words[0], tuple(depends), kind))
    return tuple(rows)


def layer_tables(root: Path, tables: dict | None) -> tuple[dict[str, dict[str, Layer]], list[str]]:
    """Every folder's layers with their transitive reach, and the problems of the tables."""
    tables = dict(LAYERS if tables is None else tables)
    tables.setdefault(RUNNER, runner_layers(root))
    resolved, problems = {}, []
    for scope, rows in tables.items():
        layers: dict[str, Layer] = {}
        for name, depends, kind in rows:
            if name in layers:
                problems.append(f"{scope or '.'}: layer '{name}' is declared twice")
                continue
            layer = Layer(kind)
            for dependency in depends:
                if dependency not in layers:
                    problems.append(f"{scope or '.'}: layer '{name}' depends on '{dependency}', "
                                    "which is not declared before it")
                    continue
                layer.reach |= {dependency} | layers[dependency].reach
            layers[name] = layer
        if layers:
            resolved[scope] = layers
    return resolved, problems


def tracked_sources(root: Path) -> list[str]:
    if (root / ".git").exists():
        # Tracked files and new ones not yet added (a file being written is checked too).
        command = ["git", "-C", str(root), "ls-files", "-z", "--cached", "--others",
                   "--exclude-standard"]
        listed = subprocess.run(command, capture_output=True, check=True, text=True).stdout
        names = [name for name in listed.split("\0") if name]
    else:
        names = [path.relative_to(root).as_posix() for path in root.rglob("*") if path.is_file()]
    return sorted(name for name in names
                  if name.endswith(SOURCE_SUFFIXES) and (root / name).is_file())


def read_includes(root: Path, sources: list[str]) -> list[Include]:
    """The project's includes of every source, each resolved to a tracked file."""
    known = set(sources)
    includes = []
    for source in sources:
        text = (root / source).read_text(encoding="utf-8", errors="replace")
        folder = PurePosixPath(source).parent
        for match in INCLUDE.finditer(text):
            written = match.group(1)
            beside = (folder / written).as_posix()
            target = beside if beside in known else written if written in known else None
            if target is not None:
                includes.append(Include(source, text.count("\n", 0, match.start()) + 1, target))
    return includes


def is_test(path: str) -> bool:
    name = PurePosixPath(path).name
    return name.endswith("_test.cc") or name.startswith("test_")


def scope_of(path: str, scope: str) -> str | None:
    """The first folder of path below scope, '' for a file directly in scope, None outside it."""
    prefix = f"{scope}/" if scope else ""
    if not path.startswith(prefix):
        return None
    first, slash, _ = path[len(prefix):].partition("/")
    return first if slash else ""


def check_edge(include: Include, scope: str, layers: dict[str, Layer]) -> str | None:
    source_layer = scope_of(include.source, scope)
    target_layer = scope_of(include.target, scope)
    if source_layer is None and target_layer is None:
        return None
    edge = f"{include.source} -> {include.target}"
    target = layers.get(target_layer or "")
    if target is not None and target.kind == "files only":
        return f"{include.where()}: includes {include.target} of the files-only folder " \
               f"'{scope_of(include.target, scope)}' ({edge})"
    if source_layer is None or target_layer is None or source_layer == target_layer:
        return None
    source = layers.get(source_layer)
    if target is not None and target.kind == "test helpers" and not is_test(include.source):
        return f"{include.where()}: includes the test helpers {include.target} outside a test"
    if source is None or target is None or target.kind == "test helpers":
        return None
    if source.kind == "files only":
        return f"{include.where()}: the files-only folder '{source_layer}' includes C++ ({edge})"
    if target_layer not in source.reach:
        allowed = ", ".join(sorted(source.reach)) or "none"
        where = f"{scope}/" if scope else ""
        return f"{include.where()}: back-edge {where}{source_layer} -> {where}{target_layer} " \
               f"({edge}; {where}{source_layer} may include: {allowed})"
    return None


def check_folders(sources: list[str], tables: dict[str, dict[str, Layer]]) -> list[str]:
    problems = []
    for scope, layers in tables.items():
        strays = set()
        for source in sources:
            first = scope_of(source, scope)
            if first == "" and scope:
                problems.append(f"{source}: a source file at the top level of {scope}/; move it "
                                "into the folder of its concept")
            elif first and first not in layers:
                strays.add(first)
        for stray in sorted(strays):
            table = f"{RUNNER}/CMakeLists.txt" if scope == RUNNER else "ci/check_layers.py"
            problems.append(f"{scope + '/' if scope else ''}{stray}/: a folder of C++ that is "
                            f"not a layer; declare it in {table}")
    return problems


def strongly_connected(graph: dict[str, set[str]]) -> list[list[str]]:
    """Tarjan's components of more than one node, each sorted, iteratively."""
    index: dict[str, int] = {}
    low: dict[str, int] = {}
    on_stack: set[str] = set()
    stack: list[str] = []
    components = []
    for start in sorted(graph):
        if start in index:
            continue
        work = [(start, iter(sorted(graph[start])))]
        index[start] = low[start] = len(index)
        stack.append(start)
        on_stack.add(start)
        while work:
            node, successors = work[-1]
            advanced = False
            for successor in successors:
                if successor not in index:
                    index[successor] = low[successor] = len(index)
                    stack.append(successor)
                    on_stack.add(successor)
                    work.append((successor, iter(sorted(graph.get(successor, ())))))
                    advanced = True
                    break
                if successor in on_stack:
                    low[node] = min(low[node], index[successor])
            if advanced:
                continue
            work.pop()
            if work:
                low[work[-1][0]] = min(low[work[-1][0]], low[node])
            if low[node] == index[node]:
                component = []
                while True:
                    member = stack.pop()
                    on_stack.discard(member)
                    component.append(member)
                    if member == node:
                        break
                if len(component) > 1:
                    components.append(sorted(component))
    return components


def report_circles(kind: str, edges: dict[tuple[str, str], Include]) -> list[str]:
    graph: dict[str, set[str]] = {}
    for source, target in edges:
        graph.setdefault(source, set()).add(target)
        graph.setdefault(target, set())
    problems = []
    for component in strongly_connected(graph):
        members = set(component)
        inside = [f"{a} -> {b} ({include.where()})" for (a, b), include in sorted(edges.items())
                  if a in members and b in members]
        problems.append(f"a circle of {kind} {', '.join(component)}: " + "; ".join(inside))
    return problems


def unit_of(path: str) -> str:
    """A header and its source are one unit: folder/stem (a test is its own unit)."""
    return path.rsplit(".", 1)[0]


def folder_edge(include: Include) -> tuple[str, str] | None:
    """The sibling folders an include joins, below the folder the two paths share."""
    source = PurePosixPath(include.source).parts
    target = PurePosixPath(include.target).parts
    shared = 0
    while shared < min(len(source), len(target)) - 1 and source[shared] == target[shared]:
        shared += 1
    if shared >= len(source) - 1 or shared >= len(target) - 1:
        return None
    return "/".join(source[:shared + 1]), "/".join(target[:shared + 1])


def check_circles(includes: list[Include]) -> list[str]:
    units: dict[tuple[str, str], Include] = {}
    folders: dict[tuple[str, str], Include] = {}
    for include in includes:
        edge = (unit_of(include.source), unit_of(include.target))
        if edge[0] != edge[1]:
            units.setdefault(edge, include)
        joined = folder_edge(include)
        if joined is not None:
            folders.setdefault(joined, include)
    return report_circles("folders", folders) + report_circles("files", units)


def check(root: Path, tables: dict | None = None) -> list[str]:
    """Every problem of the tree at root; tables replaces LAYERS (and the runner's) when given."""
    resolved, problems = layer_tables(root, tables)
    sources = tracked_sources(root)
    includes = read_includes(root, sources)
    problems += check_folders(sources, resolved)
    for include in includes:
        for scope, layers in resolved.items():
            problem = check_edge(include, scope, layers)
            if problem is not None:
                problems.append(problem)
    return problems + check_circles(includes)


def main(argv: list[str]) -> int:
    if len(argv) > 1 or argv[:1] in (["-h"], ["--help"]):
        print(__doc__, file=sys.stderr)
        return 0 if argv[:1] in (["-h"], ["--help"]) else 2
    root = Path(argv[0]) if argv else Path(__file__).resolve().parent.parent
    problems = check(root)
    for problem in problems:
        print(f"check_layers: {problem}")
    if problems:
        return 1
    print(f"check_layers: {len(tracked_sources(root))} files of {root}, every include goes down "
          "and none goes round")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
