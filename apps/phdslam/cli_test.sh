#!/usr/bin/env bash
# End-to-end checks of the phdslam program: help, list, exit codes of usage errors, a short
# Monte Carlo run with its files, resume, and evaluate.
#   cli_test.sh <phdslam binary> <data dir> <scratch dir>
set -u
phdslam="$1"
data_dir="$2"
scratch="$3"
failures=0

fail() {
  echo "FAIL: $*" >&2
  failures=$((failures + 1))
}

# expect_exit <code> <command...>: runs the command, keeps stdout/stderr in $scratch/{out,err}.
expect_exit() {
  local want="$1"
  shift
  "$@" >"$scratch/out" 2>"$scratch/err"
  local got=$?
  if [ "$got" -ne "$want" ]; then
    fail "exit $got (want $want): $* -- stderr: $(cat "$scratch/err")"
  fi
}

expect_in() {  # expect_in <file> <fixed string>
  grep -qF -- "$2" "$1" || fail "'$2' not in $1: $(head -c 2000 "$1")"
}

rm -rf "$scratch"
mkdir -p "$scratch"
out="$scratch/results"

expect_exit 0 "$phdslam" --help
expect_in "$scratch/out" "run"
expect_in "$scratch/out" "evaluate"
expect_exit 0 "$phdslam" run --help
for option in --scenario --estimator --particles --seeds --out --data-dir --steps --jobs \
    --experiment-name --pd --clutter-rate --set --quiet; do
  expect_in "$scratch/out" "$option"
done
expect_exit 0 "$phdslam" evaluate --help
expect_in "$scratch/out" "--truth-trajectory"
expect_in "$scratch/out" "--time-tolerance"
expect_exit 0 "$phdslam" list
expect_in "$scratch/out" "paper-synthetic"
expect_in "$scratch/out" "odometry"

# Usage errors: exit 2 and one line on stderr.
common=(--scenario paper-synthetic --data-dir "$data_dir" --out "$out" --quiet)
expect_exit 2 "$phdslam"
expect_exit 2 "$phdslam" run "${common[@]}" --estimator odometry --seeds 5-2
expect_in "$scratch/err" "reversed"
[ "$(wc -l <"$scratch/err")" -eq 1 ] || fail "usage error is not one line: $(cat "$scratch/err")"
expect_exit 2 "$phdslam" run "${common[@]}" --estimator nosuch --seeds 1
expect_in "$scratch/err" "unknown estimator 'nosuch'"
expect_exit 2 "$phdslam" run "${common[@]}" --estimator odometry --seeds 1 --set foo=1
expect_in "$scratch/err" "unknown parameter 'foo'"
expect_exit 2 "$phdslam" run "${common[@]}" --estimator odometry --seeds 1 --pd 1.5
expect_exit 2 "$phdslam" run --scenario nosuch --estimator odometry --seeds 1 --out "$out"
expect_exit 2 "$phdslam" run "${common[@]}" --estimator odometry --seeds 1 --bogus
expect_exit 2 "$phdslam" evaluate --map "$scratch/out"
[ -e "$out/runs" ] && fail "a usage error left runs behind"

# A short run.
expect_exit 0 "$phdslam" run "${common[@]}" --estimator odometry --particles 1 --seeds 1-2 \
  --steps 30 --jobs 2
expect_in "$scratch/out" "summary: $out/summary.csv"
for f in summary.csv runs.csv config.json timing.json truth_map.csv truth/seed-1/truth.tum \
    runs/odometry-N1/seed-1/steps.csv runs/odometry-N1/seed-1/trajectory.tum \
    runs/odometry-N1/seed-1/map.csv runs/odometry-N1/seed-2/metrics.json; do
  [ -s "$out/$f" ] || fail "missing $out/$f"
done
expect_in "$out/summary.csv" \
  "estimator,particles,runs,steps,pos_rmse_m,heading_rmse_deg,gospa_mean_m,gospa_std_m,ess_pct,resampling_pct,ms_per_step_mean"
expect_in "$out/summary.csv" "odometry,1,2,30,"

# Resume: nothing is recomputed; the table is printed without --quiet.
expect_exit 0 "$phdslam" run --scenario paper-synthetic --data-dir "$data_dir" --out "$out" \
  --estimator odometry --seeds 1-2 --steps 30
expect_in "$scratch/out" "2 already finished, 0 computed"
expect_in "$scratch/out" "pos RMSE"
# Other settings into the same folder are refused.
expect_exit 2 "$phdslam" run "${common[@]}" --estimator odometry --seeds 3 --steps 40
expect_in "$scratch/err" "other settings"

# evaluate
run1="$out/runs/odometry-N1/seed-1"
expect_exit 0 "$phdslam" evaluate --truth-map "$out/truth_map.csv" --map "$run1/map.csv"
for key in '"gospa"' '"localisation"' '"missed"' '"false"' '"n_missed"' '"n_false"' '"ospa"'; do
  expect_in "$scratch/out" "$key"
done
expect_exit 0 "$phdslam" evaluate --truth-map "$out/truth_map.csv" --map "$out/truth_map.csv"
expect_in "$scratch/out" '"gospa": 0.0'
expect_exit 0 "$phdslam" evaluate --truth-trajectory "$out/truth/seed-1/truth.tum" \
  --trajectory "$run1/trajectory.tum"
expect_in "$scratch/out" '"matched": 30'
expect_in "$scratch/out" '"pos_rmse_m"'
expect_exit 0 "$phdslam" evaluate --truth-trajectory "$out/truth/seed-1/truth.tum" \
  --trajectory "$out/truth/seed-1/truth.tum"
expect_in "$scratch/out" '"pos_rmse_m": 0.0'
expect_exit 1 "$phdslam" evaluate --truth-map "$run1/trajectory.tum" --map "$run1/map.csv"

if [ "$failures" -ne 0 ]; then
  echo "$failures check(s) failed" >&2
  exit 1
fi
echo "all phdslam CLI checks passed"
