#!/usr/bin/env bash
# Accuracy regression gates: runs every suite of ci/gates.yaml with the phdslam program of
# BUILD_DIR into RESULTS_DIR/<suite>/, then gates them (phdslam gate, ci/gates.py): the exact tier
# against the stored baseline (ci/baseline/), the paired tier and the anchor tier (ci/GATES.md).
# Exits 0 when every gate passes, 1 when a run or a gate fails, 2 for bad input.
#
#   ci/check-gates.sh BUILD_DIR [RESULTS_DIR] [-- RUN_ARGS...]
#
# RESULTS_DIR (default: a fresh temporary folder, removed afterwards) must not exist yet; give it
# to keep the results (e.g. build/gates; reports/make_report.py build/gates/phd3 draws them).
# RUN_ARGS are appended to every regression run, except that `--set NAME:key=value` goes only to
# the runs whose estimators include NAME: `-- --set phd3:max_hypotheses=2` gates that mutant.
# PHDSLAM_GATES_FILE=FILE gates with another gates file; PHDSLAM_GATES_TIERS=exact,paired,anchor
# chooses the tiers. How to move the baseline on purpose: ci/update-baseline.sh and ci/GATES.md.
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"

usage() { sed -n '2,15p' "$0" | sed 's/^# \{0,1\}//'; }
if [[ $# -lt 1 || "$1" == "-h" || "$1" == "--help" ]]; then
  usage
  [[ $# -ge 1 ]] && exit 0
  exit 2
fi
build="$1"
shift
out=""
if [[ $# -gt 0 && "$1" != "--" ]]; then
  out="$1"
  shift
fi
extra=()
if [[ $# -gt 0 ]]; then
  if [[ "$1" != "--" ]]; then
    echo "check-gates: unexpected argument '$1' (run arguments follow --)" >&2
    exit 2
  fi
  shift
  extra=("$@")
fi
gates="${PHDSLAM_GATES_FILE:-$here/gates.yaml}"
tiers="${PHDSLAM_GATES_TIERS:-exact,paired,anchor}"

phdslam=""
for candidate in "$build/apps/phdslam/phdslam" "$build/apps/phdslam"; do
  if [[ -f "$candidate" && -x "$candidate" ]]; then phdslam="$candidate"; break; fi
done
if [[ -z "$phdslam" ]]; then
  echo "check-gates: no phdslam program in $build (looked for apps/phdslam/phdslam and" \
       "apps/phdslam); build it first: cmake --build $build --target phdslam" >&2
  exit 2
fi
# The checker needs PyYAML: prefer the system interpreter (Debian python3-yaml).
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

if [[ -n "$out" ]]; then
  if [[ -e "$out" ]]; then
    echo "check-gates: $out already exists; give a new folder (results must come from this build)" >&2
    exit 2
  fi
else
  tmp="$(mktemp -d "${TMPDIR:-/tmp}/phdslam-gates.XXXXXX")"
  trap 'rm -rf "$tmp"' EXIT
  out="$tmp/results"
fi

# The extra arguments of one run: everything, but `--set NAME:...` only where NAME runs.
extra_for() {
  local estimators=",$1,"
  local i=0
  while [[ $i -lt ${#extra[@]} ]]; do
    local word="${extra[$i]}"
    if [[ "$word" == "--set" && $((i + 1)) -lt ${#extra[@]} ]]; then
      local value="${extra[$((i + 1))]}"
      local name="${value%%:*}"
      if [[ "$value" != *:* || "$name" == *=* || "$estimators" == *",$name,"* ]]; then
        printf '%s\n%s\n' "$word" "$value"
      fi
      i=$((i + 2))
      continue
    fi
    printf '%s\n' "$word"
    i=$((i + 1))
  done
}

run_args="$("$python" "$here/gates.py" run-args --gates "$gates")" || exit 2
run_failed=0
start=$SECONDS
while IFS=$'\t' read -r -a words; do
  [[ ${#words[@]} -eq 0 ]] && continue
  suite="${words[0]}"
  args=("${words[@]:1}")
  estimators=""
  for ((j = 0; j < ${#args[@]}; j++)); do
    [[ "${args[$j]}" == "--estimator" ]] && estimators="${args[$((j + 1))]}"
  done
  mapfile -t added < <(extra_for "$estimators")
  run_start=$SECONDS
  echo "check-gates: phdslam run ${args[*]} ${added[*]} --out $out/$suite" >&2
  if ! "$phdslam" run "${args[@]}" "${added[@]}" --out "$out/$suite" --quiet >/dev/null; then
    echo "check-gates: the run above failed (its gates will fail too)" >&2
    run_failed=1
  fi
  echo "check-gates: ... took $((SECONDS - run_start)) s" >&2
done <<< "$run_args"
echo "check-gates: regression runs took $((SECONDS - start)) s" >&2

status=0
"$phdslam" gate --gates "$gates" --results "$out" --tiers "$tiers" \
  ${PHDSLAM_GATES_CSV:+--csv "$PHDSLAM_GATES_CSV"} || status=$?
if [[ $run_failed -ne 0 && $status -eq 0 ]]; then status=1; fi
exit "$status"
