#!/usr/bin/env python3
"""Checks that the runner's folders (validation/runner/*/) include one another in one direction.

  ci/check_runner_layers.py ROOT [--test-only LAYER]... LAYER:DEPENDENCY,DEPENDENCY... ...
  ci/check_runner_layers.py --self-test

The layers come lowest first, as validation/runner/CMakeLists.txt declares them (it passes them
to this check through CTest, test validation_runner_layering); a layer may name only layers given
before it. Fails (exit 1, one line per problem) when
  - a source file (.h, .cc) lies at ROOT's top level,
  - a folder of ROOT is not a layer,
  - a file includes "validation/runner/<folder>/..." of a folder that is neither its own nor one
    its layer depends on, directly or through other layers (a back-edge or a sideways edge), or a
    header at ROOT's top level,
  - a file that is not a test (*_test.cc) includes a --test-only layer (the test helpers).
--self-test builds small folders with such faults in a temporary directory and exits 0 when
every fault is reported and a clean folder passes.
"""

from __future__ import annotations

import re
import sys
import tempfile
from pathlib import Path

INCLUDE = re.compile(r'^\s*#\s*include\s*"validation/runner/([^"]+)"', re.MULTILINE)
SOURCE_SUFFIXES = {".h", ".cc"}


def parse_layers(specs: list[str]) -> tuple[dict[str, set[str]], list[str]]:
    """The transitive dependencies of every layer, and the problems of the table itself."""
    closure: dict[str, set[str]] = {}
    problems = []
    for spec in specs:
        name, _, deps = spec.partition(":")
        if name in closure:
            problems.append(f"layer '{name}' is declared twice")
            continue
        reach: set[str] = set()
        for dep in filter(None, deps.split(",")):
            if dep not in closure:
                problems.append(f"layer '{name}' depends on '{dep}', which is not declared before it")
                continue
            reach |= {dep} | closure[dep]
        closure[name] = reach
    return closure, problems


def check(root: Path, specs: list[str], test_only: set[str]) -> list[str]:
    closure, problems = parse_layers(specs)
    for path in sorted(root.iterdir()):
        if path.is_file() and path.suffix in SOURCE_SUFFIXES:
            problems.append(f"{path.name}: a source file at the top level; move it into the "
                            "folder of its concept")
        elif path.is_dir() and path.name not in closure:
            problems.append(f"{path.name}/: a folder that is not a layer; declare it in "
                            "validation/runner/CMakeLists.txt")
    for layer, reach in closure.items():
        folder = root / layer
        if not folder.is_dir():
            continue
        for path in sorted(folder.rglob("*")):
            if path.suffix not in SOURCE_SUFFIXES:
                continue
            is_test = path.name.endswith("_test.cc")
            text = path.read_text(encoding="utf-8", errors="replace")
            for match in INCLUDE.finditer(text):
                target = match.group(1)
                line = text.count("\n", 0, match.start()) + 1
                where = f"{path.relative_to(root)}:{line}"
                target_layer, slash, _ = target.partition("/")
                if not slash:
                    problems.append(f"{where}: includes validation/runner/{target}, a top-level "
                                    "header")
                elif target_layer in test_only and not is_test:
                    problems.append(f"{where}: includes the test helpers "
                                    f"validation/runner/{target} outside a test")
                elif target_layer != layer and target_layer not in reach | test_only:
                    allowed = ", ".join(sorted(reach)) or "none"
                    problems.append(f"{where}: layer '{layer}' includes validation/runner/{target} "
                                    f"of layer '{target_layer}' (it may use: {allowed})")
    return problems


def self_test() -> int:
    layers = ["testing:", "low:", "high:low"]
    cases = {
        "clean": ({"low/a.h": "", "high/b.cc": '#include "validation/runner/low/a.h"\n',
                   "high/b_test.cc": '#include "validation/runner/testing/t.h"\n',
                   "testing/t.h": ""}, 0),
        "back-edge": ({"low/a.cc": '#include "validation/runner/high/b.h"\n', "high/b.h": ""}, 1),
        "top-level file": ({"loose.cc": "", "low/a.h": ""}, 1),
        "top-level include": ({"low/a.cc": '#include "validation/runner/loose.h"\n'}, 1),
        "unknown folder": ({"other/c.h": ""}, 1),
        "test helper outside a test": (
            {"high/b.cc": '#include "validation/runner/testing/t.h"\n'}, 1),
    }
    failed = 0
    for name, (files, expected) in cases.items():
        with tempfile.TemporaryDirectory() as directory:
            root = Path(directory)
            for relative, text in files.items():
                (root / relative).parent.mkdir(parents=True, exist_ok=True)
                (root / relative).write_text(text)
            problems = check(root, layers, {"testing"})
        if (len(problems) > 0) != (expected > 0):
            print(f"self-test '{name}': expected {'a problem' if expected else 'none'}, got "
                  f"{problems}")
            failed += 1
    _, table_problems = parse_layers(["high:low", "low:"])
    if not table_problems:
        print("self-test 'dependency declared later': not reported")
        failed += 1
    print("check_runner_layers self-test: " + ("failed" if failed else "passed"))
    return 1 if failed else 0


def main(argv: list[str]) -> int:
    if argv == ["--self-test"]:
        return self_test()
    if not argv:
        print(__doc__, file=sys.stderr)
        return 2
    root = Path(argv[0])
    test_only: set[str] = set()
    specs = []
    rest = iter(argv[1:])
    for argument in rest:
        if argument == "--test-only":
            test_only.add(next(rest, ""))
        else:
            specs.append(argument)
    problems = check(root, specs, test_only)
    for problem in problems:
        print(f"check_runner_layers: {problem}")
    if problems:
        return 1
    print(f"check_runner_layers: {len(specs)} layers of {root}, every include goes down")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
