#!/usr/bin/env bash
# Format and static-analysis checks of the project's own C++ sources, warnings as errors.
#
#   ci/run-lint.sh [BUILD_DIR]   (default build/release; it needs compile_commands.json)
#
# clang-format (.clang-format) checks every tracked .h and .cc file; clang-tidy (.clang-tidy) runs
# on every tracked .cc file that is not a test, two at a time, and its checks of the project's own
# headers come with them (HeaderFilterRegex). Fix formatting with:
#   git ls-files '*.cc' '*.h' | xargs clang-format -i
set -euo pipefail
cd "$(dirname "$0")/.."
build="${1:-build/release}"
if [[ ! -f "$build/compile_commands.json" ]]; then
  echo "run-lint: $build/compile_commands.json is missing: configure the build first" >&2
  exit 2
fi

echo "run-lint: clang-format on $(git ls-files '*.cc' '*.h' | wc -l) files"
git ls-files -z '*.cc' '*.h' | xargs -0 clang-format --dry-run --Werror

mapfile -t sources < <(git ls-files '*.cc' | grep -v '_test\.cc$' | grep -v '^examples/')
echo "run-lint: clang-tidy on ${#sources[@]} files"
jobs=$(nproc 2>/dev/null || echo 2)
printf '%s\0' "${sources[@]}" |
  xargs -0 -n 1 -P "$jobs" clang-tidy -p "$build" --quiet 2>/dev/null
echo "run-lint: clean"
