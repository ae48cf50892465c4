#!/usr/bin/env bash
# The main job's experiment (validation/experiments/quick.yaml) on one seed and 200 steps under
# valgrind's memcheck, with an optimised build of the program (preset valgrind): exits non-zero on
# any memory error or definite leak, or when the program does not finish. Prints valgrind's error
# and leak summaries.
#
#   ci/run-valgrind.sh [OUT_DIR]     default OUT_DIR: a fresh temporary folder
#
# The preset is the release build without the MRPT baselines (which quick.yaml does not run):
# MRPT loads OpenCV, whose image codecs load libhwy, and libhwy's load-time initialiser executes
# RDTSCP. Valgrind decodes RDTSCP only when the CPU advertises it (`rdtscp` in /proc/cpuinfo),
# which some virtual machines do not although they execute it: there, with MRPT linked, the
# program is killed by SIGILL before main.
set -euo pipefail
cd "$(dirname "$0")/.."
out="${1:-$(mktemp -d)/valgrind}"
log="$out.valgrind.log"
cmake --preset valgrind >/dev/null
cmake --build --preset valgrind -j "$(nproc 2>/dev/null || echo 2)" --target phdslam >/dev/null
status=0
# The program links TCMalloc (cmake/phdslam_malloc.cmake): memcheck replaces its malloc too. TCMalloc
# serves free and delete from one function, which memcheck would report as mismatched frees in
# every library, so that check is off here (the ASan build of --sanitize keeps it); ci/valgrind.supp
# holds TCMalloc's one deliberate leak.
valgrind --error-exitcode=99 --leak-check=full --errors-for-leak-kinds=definite \
  --soname-synonyms='somalloc=*tcmalloc*' --show-mismatched-frees=no \
  --suppressions=ci/valgrind.supp \
  build/valgrind/apps/phdslam run --experiment validation/experiments/quick.yaml --seeds 1 \
  --steps 200 --jobs 1 --quiet --out "$out" >"$log" 2>&1 || status=$?
grep -E "ERROR SUMMARY|definitely lost|indirectly lost" "$log" | sed 's/^==[0-9]*== *//' || true
if [[ $status -eq 99 ]]; then
  echo "valgrind: memory errors or definite leaks (exit 99), log: $log" >&2
elif [[ $status -gt 128 ]]; then
  # The summaries above are then those of a program cut short, not of a finished run.
  grep -m 3 -E "unhandled instruction|Unrecognised instruction|Process terminating" "$log" |
    sed 's/^==[0-9]*== */valgrind: /' >&2 || true
  echo "valgrind: the program was killed by signal $((status - 128)), log: $log" >&2
elif [[ $status -ne 0 ]]; then
  echo "valgrind: the program failed (exit $status), log: $log" >&2
fi
exit $status
