#!/usr/bin/env bash
# The main job's experiment (validation/experiments/quick.yaml) on one seed and 200 steps under
# valgrind's memcheck, with the release build: exits non-zero on any memory error or definite
# leak. Prints valgrind's error and leak summaries.
#
#   ci/run-valgrind.sh [OUT_DIR]     default OUT_DIR: a fresh temporary folder
set -euo pipefail
cd "$(dirname "$0")/.."
out="${1:-$(mktemp -d)/valgrind}"
log="$out.valgrind.log"
cmake --build --preset release -j "$(nproc 2>/dev/null || echo 2)" --target phdslam >/dev/null
status=0
# The program links TCMalloc (cmake/phdslam_malloc.cmake): memcheck replaces its malloc too. TCMalloc
# serves free and delete from one function, which memcheck would report as mismatched frees in
# every library, so that check is off here (the ASan build of --sanitize keeps it); ci/valgrind.supp
# holds TCMalloc's one deliberate leak.
valgrind --error-exitcode=99 --leak-check=full --errors-for-leak-kinds=definite \
  --soname-synonyms='somalloc=*tcmalloc*' --show-mismatched-frees=no \
  --suppressions=ci/valgrind.supp \
  build/release/apps/phdslam run --experiment validation/experiments/quick.yaml --seeds 1 \
  --steps 200 --jobs 1 --quiet --out "$out" >"$log" 2>&1 || status=$?
grep -E "ERROR SUMMARY|definitely lost|indirectly lost" "$log" | sed 's/^==[0-9]*== *//'
[[ $status -eq 0 ]] || echo "valgrind: failed (exit $status), log: $log" >&2
exit $status
