#!/usr/bin/env bash
# Moves the accuracy baseline on purpose (ci/GATES.md, "Moving the baseline"): runs every suite of
# ci/gates.yaml with BUILD_DIR's phdslam (or takes the finished results of RESULTS_DIR), prints
# the paired verdict of the new results against the old baseline and, when they pass it, writes
# them as the new baseline (ci/baseline/: one table per suite and baseline.json, the header with
# the commit, the date and that verdict). Commit the new baseline with the change that moved it.
#
#   ci/update-baseline.sh BUILD_DIR [--results RESULTS_DIR] [--accept-inferior REASON]
#
# A new baseline that fails the paired tier is refused unless --accept-inferior gives the reason
# (the header then records it, and every later gate run prints it).
# PHDSLAM_GATES_FILE=FILE updates the baseline of another gates file.
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
if [[ $# -lt 1 || "$1" == "-h" || "$1" == "--help" ]]; then
  sed -n '2,13p' "$0" | sed 's/^# \{0,1\}//'
  [[ $# -ge 1 ]] && exit 0
  exit 2
fi
build="$1"
shift
results=""
accept=()
while [[ $# -gt 0 ]]; do
  case "$1" in
    --results) results="${2:?--results needs a folder}"; shift 2 ;;
    --accept-inferior) accept=(--accept-inferior "${2:?--accept-inferior needs a reason}"); shift 2 ;;
    *) echo "update-baseline: unknown argument '$1'" >&2; exit 2 ;;
  esac
done
gates="${PHDSLAM_GATES_FILE:-$here/gates.yaml}"
if [[ -z "$results" ]]; then
  tmp="$(mktemp -d "${TMPDIR:-/tmp}/phdslam-baseline.XXXXXX")"
  trap 'rm -rf "$tmp"' EXIT
  results="$tmp/results"
  # Runs the regression; its gate verdict is printed again below against the old baseline.
  PHDSLAM_GATES_FILE="$gates" PHDSLAM_GATES_TIERS=anchor "$here/check-gates.sh" "$build" "$results" \
    || [[ $? -eq 1 ]]
fi
python=python3
command -v python3 >/dev/null && python3 -c "import yaml" 2>/dev/null || python=/usr/bin/python3
exec "$python" "$here/gates.py" update-baseline --gates "$gates" --results "$results" "${accept[@]}"
