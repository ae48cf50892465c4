#!/usr/bin/env bash
# The test command: installs what is missing (Chromium included, for the report-rendering test),
# builds the release preset as a unity build (PHDSLAM_UNITY_BUILD=ON; warnings are errors), checks
# formatting and runs clang-tidy on the project's sources (ci/run-lint.sh), runs every unit test
# with CTest (the folders' layering check, ci/check_layers.py, among them), the Slurm test, the
# accuracy regression gates (ci/check-gates.sh: the suites of ci/gates.yaml against ci/baseline/,
# ci/GATES.md) and their short mutation check, then the libFuzzer targets for 20 s each
# (ci/run-fuzz.sh, under ASan + UBSan). Exits non-zero on any failure.
#
#   ci/run-tests.sh              release build + lint + unit tests + Slurm test + gates + fuzzing
#   ci/run-tests.sh --sanitize   also build and run the unit tests under ASan + UBSan, and the main
#                                job on one seed under valgrind (ci/run-valgrind.sh)
set -euo pipefail
cd "$(dirname "$0")/.."
# Each stage prints its wall time, so a slow CI run shows where the time went.
# A stage that fails ends the run and says which stage it was.
stage() {
  local name=$1 start=$SECONDS
  shift
  if ! "$@"; then
    echo "run-tests: stage '$name' failed after $((SECONDS - start)) s" >&2
    exit 1
  fi
  echo "run-tests: $name took $((SECONDS - start)) s" >&2
}
stage install ci/install-deps.sh --browser --slurm
# The report-rendering test runs in headless Chromium; here a missing browser is a failure.
export PHDSLAM_REQUIRE_CHROMIUM=1

jobs=$(nproc 2>/dev/null || echo 2)
stage configure cmake --preset release -DPHDSLAM_UNITY_BUILD=ON >/dev/null
stage build cmake --build --preset release -j "$jobs"
stage lint ci/run-lint.sh build/release
stage ctest ctest --preset release
# A single-node Slurm cluster runs an experiment as a job array (needs root to start daemons).
if [[ "$(id -u)" -eq 0 ]]; then
  stage slurm ci/run-slurm-test.sh build/release/apps/phdslam
else
  echo "run-tests: not root, Slurm test skipped (ci/run-slurm-test.sh)" >&2
fi

if [[ "${1:-}" == "--sanitize" ]]; then
  stage sanitize-configure cmake --preset sanitize >/dev/null
  stage sanitize-build cmake --build --preset sanitize -j "$jobs"
  stage sanitize-ctest ctest --preset sanitize
  stage valgrind ci/run-valgrind.sh
fi

# The accuracy gates (ci/gates.yaml: exact, paired and anchor tiers against ci/baseline/), then
# the short form of their mutation check: a mutant must fail them, neutral changes must pass.
stage gates ci/check-gates.sh build/release
stage mutation-check /usr/bin/python3 ci/mutation_check.py short --build build/release
stage fuzz ci/run-fuzz.sh 20
echo "run-tests: all stages passed in $SECONDS s" >&2
