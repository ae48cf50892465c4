#!/usr/bin/env bash
# Format and static-analysis checks of the project's own C++ sources, warnings as errors, and a
# check that the tracked text files hold no control characters.
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

# Control characters, tabs included (only newline and carriage return pass), in the tracked text
# files: a mangled escape such as "\t" or "\a" in a generated document lands as one.
text_files=(':(glob)**/*.md' ':(glob)**/*.cc' ':(glob)**/*.h' ':(glob)**/*.py' ':(glob)**/*.sh'
  ':(glob)**/*.yaml' ':(glob)**/*.txt' ':(glob)**/*.cmake' ':(glob)**/*.html')
if git grep -n -I -P '[\x00-\x09\x0b\x0c\x0e-\x1f\x7f]' -- "${text_files[@]}"; then
  echo "run-lint: control characters in the text files above" >&2
  exit 1
fi

echo "run-lint: clang-format on $(git ls-files '*.cc' '*.h' | wc -l) files"
git ls-files -z '*.cc' '*.h' | xargs -0 clang-format --dry-run --Werror

mapfile -t sources < <(git ls-files '*.cc' | grep -v '_test\.cc$' | grep -v '^examples/')
# In a unity build (PHDSLAM_UNITY_BUILD=ON, as ci/run-tests.sh builds) clang-tidy checks CMake's
# batch files, each including several sources, so the heavy headers are parsed once per batch:
# the sources are then checked as included files, which the header filter of .clang-tidy (every
# file outside the system include directories) covers as it covers the headers, and
# bugprone-suspicious-include (which would flag the batches' own includes of .cc files) is
# replaced by the grep below. A plain build checks file by file.
if git grep -n -E '^[[:space:]]*#[[:space:]]*include[[:space:]]*"[^"]*\.cc"' -- '*.cc' '*.h'; then
  echo "run-lint: a source includes a .cc file (above)" >&2
  exit 1
fi
mapfile -t units < <(python3 ci/lint_units.py "$build" "${sources[@]/#/$PWD/}")
if ! grep -qx "HeaderFilterRegex: '.\*'" .clang-tidy; then
  echo "run-lint: .clang-tidy's HeaderFilterRegex must be '.*' (every project file)" >&2
  exit 2
fi
echo "run-lint: clang-tidy on ${#sources[@]} files in ${#units[@]} translation units"
jobs=$(nproc 2>/dev/null || echo 2)
printf '%s\0' "${units[@]}" |
  xargs -0 -n 1 -P "$jobs" clang-tidy -p "$build" --quiet --checks=-bugprone-suspicious-include \
    2>/dev/null
echo "run-lint: clean"
