#!/usr/bin/env bash
# Accuracy regression gates: runs the regression definition of ci/thresholds.yaml with the phdslam
# program of BUILD_DIR into a fresh results folder, then checks its summary.csv against the gates
# (ci/check_gates.py). Exits 1 when a run fails or any gate fails (a gate without a band fails).
#
#   ci/check-gates.sh BUILD_DIR [RESULTS_DIR]
#
# RESULTS_DIR (default: a fresh temporary folder, removed afterwards) must not exist yet; give it
# to keep the results, e.g. build/gates, and look at them with reports/make_report.py.
# PHDSLAM_GATES_THRESHOLDS=FILE checks another thresholds file (used by the tests).
# How to move a baseline on purpose: ci/GATES.md.
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"

if [[ $# -lt 1 || $# -gt 2 || "$1" == "-h" || "$1" == "--help" ]]; then
  sed -n '2,11p' "$0" | sed 's/^# \{0,1\}//'
  [[ $# -ge 1 && ( "$1" == "-h" || "$1" == "--help" ) ]] && exit 0
  exit 2
fi
build="$1"
thresholds="${PHDSLAM_GATES_THRESHOLDS:-$here/thresholds.yaml}"

phdslam=""
for candidate in "$build/apps/phdslam/phdslam" "$build/apps/phdslam"; do
  if [[ -f "$candidate" && -x "$candidate" ]]; then phdslam="$candidate"; break; fi
done
if [[ -z "$phdslam" ]]; then
  echo "check-gates: no phdslam program in $build (looked for apps/phdslam/phdslam and" \
       "apps/phdslam); build it first: cmake --build $build --target phdslam" >&2
  exit 2
fi

# The checker needs PyYAML: prefer the system interpreter (Debian python3-yaml) when the first
# python3 on PATH lacks it.
python=""
for candidate in python3 /usr/bin/python3; do
  if command -v "$candidate" >/dev/null 2>&1 && "$candidate" -c "import yaml" 2>/dev/null; then
    python="$candidate"; break
  fi
done
if [[ -z "$python" ]]; then
  echo "check-gates: no python3 with PyYAML; install python3-yaml (ci/install-deps.sh)" >&2
  exit 2
fi

if [[ $# -eq 2 ]]; then
  out="$2"
  if [[ -e "$out" ]]; then
    echo "check-gates: $out already exists; give a new folder (results must come from this build)" >&2
    exit 2
  fi
else
  tmp="$(mktemp -d "${TMPDIR:-/tmp}/phdslam-gates.XXXXXX")"
  trap 'rm -rf "$tmp"' EXIT
  out="$tmp/results"
fi

run_failed=0
while IFS=$'\t' read -r -a args; do
  [[ ${#args[@]} -eq 0 ]] && continue
  echo "check-gates: phdslam run ${args[*]} --out $out" >&2
  if ! "$phdslam" run "${args[@]}" --out "$out" --quiet >/dev/null; then
    echo "check-gates: the run above failed (its gates will fail too)" >&2
    run_failed=1
  fi
done < <("$python" "$here/check_gates.py" "$thresholds" --run-args)

if [[ ! -f "$out/summary.csv" ]]; then
  echo "check-gates: no summary.csv in $out: every regression run failed" >&2
  exit 1
fi

status=0
"$python" "$here/check_gates.py" "$thresholds" "$out/summary.csv" || status=$?
if [[ $run_failed -ne 0 && $status -eq 0 ]]; then status=1; fi
exit "$status"
