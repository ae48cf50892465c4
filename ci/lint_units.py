#!/usr/bin/env python3
"""Prints the translation units clang-tidy checks, one per line (used by ci/run-lint.sh).

    ci/lint_units.py BUILD_DIR SOURCE...

SOURCE... are the project's sources to check (absolute paths). In a unity build
(PHDSLAM_UNITY_BUILD=ON) the build compiles CMake's batch files (.../Unity/unity_N_cxx.cxx), each
including several sources; a batch is printed when every source it includes is one to check, and
its sources are then covered by it. Every source no batch covers is printed itself, so a plain
build prints exactly SOURCE... Exits with 2, naming the file, when compile_commands.json is
missing or malformed.
"""

import json
import re
import sys
from pathlib import Path

INCLUDE = re.compile(r'^#include\s+"([^"]+)"\s*$')


def batch_sources(batch: Path) -> list[str]:
    """The sources a CMake unity batch file includes, as absolute paths."""
    sources = []
    for line in batch.read_text(encoding="utf-8").splitlines():
        match = INCLUDE.match(line.strip())
        if match:
            sources.append(str(Path(match.group(1)).resolve()))
    return sources


def compiled_files(build: Path) -> list[str]:
    database = build / "compile_commands.json"
    try:
        entries = json.loads(database.read_text(encoding="utf-8"))
        return [str(Path(entry["directory"], entry["file"]).resolve()) for entry in entries]
    except (OSError, ValueError, KeyError, TypeError) as error:
        print(f"lint_units: {database}: {error}", file=sys.stderr)
        sys.exit(2)


def lint_units(build: Path, sources: list[str]) -> list[str]:
    wanted = {str(Path(source).resolve()) for source in sources}
    units, covered = [], set()
    for compiled in compiled_files(build):
        if "/Unity/unity_" not in compiled:
            continue
        included = batch_sources(Path(compiled))
        if included and all(source in wanted for source in included):
            units.append(compiled)
            covered.update(included)
    units += sorted(wanted - covered)
    return units


def main() -> None:
    if len(sys.argv) < 2:
        print(__doc__, file=sys.stderr)
        sys.exit(2)
    for unit in lint_units(Path(sys.argv[1]), sys.argv[2:]):
        print(unit)


if __name__ == "__main__":
    main()
