#!/usr/bin/env bash
# End-to-end checks of the phdslam program: help, list, exit codes of usage errors, a short
# Monte Carlo run with its files, resume, evaluate, experiment files, sweeps, shards and their
# merge, particle traces and paired comparisons.
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
for command in run merge compare evaluate list export ingest; do
  expect_in "$scratch/out" "$command"
done
expect_exit 0 "$phdslam" run --help
for option in --scenario --estimator --particles --seeds --out --data-dir --steps --jobs \
    --experiment-name --pd --clutter-rate --set --scenario-set --quiet --experiment --shard \
    --particles-trace; do
  expect_in "$scratch/out" "$option"
done
expect_exit 0 "$phdslam" merge --help
expect_exit 0 "$phdslam" compare --help
expect_in "$scratch/out" "--metric"
expect_exit 0 "$phdslam" evaluate --help
expect_in "$scratch/out" "--truth-trajectory"
expect_in "$scratch/out" "--time-tolerance"
expect_exit 0 "$phdslam" list
expect_in "$scratch/out" "paper-synthetic"
expect_in "$scratch/out" "odometry"
expect_in "$scratch/out" "gibbs_samples = 1000 (an integer >= 1): "
# One estimator's parameters from the table that parses --set; an unknown name lists the known.
expect_exit 0 "$phdslam" list --estimator phd3
expect_in "$scratch/out" "max_hypotheses = 50 (an integer >= 0): "
expect_exit 2 "$phdslam" list --estimator phd4
expect_in "$scratch/err" "unknown estimator 'phd4' (known: odometry, phd1"

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
expect_exit 2 "$phdslam" run --estimator odometry --seeds 1 --out "$out"
expect_in "$scratch/err" "--scenario is required"
expect_exit 2 "$phdslam" run "${common[@]}" --estimator odometry --seeds 1 --shard 3/2
expect_in "$scratch/err" "--shard '3/2'"
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
expect_exit 2 "$phdslam" evaluate --truth-map "$out/truth_map.csv" --map "$run1/map.csv" --c 1e308
expect_in "$scratch/err" "overflow"
awk '/^#/ { print; next } { $1 = $1 + 1e6; print }' "$run1/trajectory.tum" >"$scratch/late.tum"
expect_exit 2 "$phdslam" evaluate --truth-trajectory "$out/truth/seed-1/truth.tum" \
  --trajectory "$scratch/late.tum"
expect_in "$scratch/err" "do not overlap in time"
printf '0 1 2 0 0 0 0 1\n0 1 2 0 0 0 0 1\n' >"$scratch/twice.tum"
expect_exit 1 "$phdslam" evaluate --truth-trajectory "$scratch/twice.tum" \
  --trajectory "$scratch/twice.tum"
expect_in "$scratch/err" "twice.tum:2: time stamp 0 repeats that of line 1"

# An option without its value is named (not "--out is required").
expect_exit 2 "$phdslam" run --scenario generated --estimator odometry --seeds --out "$scratch/nv"
expect_in "$scratch/err" "--seeds needs a value"

# SIGTERM and SIGHUP stop like Ctrl-C: runs in progress finish, the summary is written, exit 130.
for signal in TERM HUP; do
  "$phdslam" run --scenario paper-synthetic --data-dir "$data_dir" --estimator phd3 --particles 10 \
    --seeds 1-100000 --steps 200 --jobs 1 --quiet --out "$scratch/term$signal" >/dev/null \
    2>"$scratch/err" &
  term_pid=$!
  # The signal handler is in place before the results folder is locked: wait for the lock (slow
  # under the sanitizers and valgrind) instead of a fixed time.
  for _ in $(seq 1200); do
    [ -e "$scratch/term$signal/phdslam.lock" ] && break
    sleep 0.1
  done
  [ -e "$scratch/term$signal/phdslam.lock" ] || fail "SIG$signal: the run did not start within 120 s"
  kill -$signal "$term_pid"
  wait "$term_pid"
  term_exit=$?
  [ "$term_exit" -eq 130 ] || fail "SIG$signal: exit $term_exit (want 130): $(cat "$scratch/err")"
  [ -f "$scratch/term$signal/summary.csv" ] || fail "SIG$signal: no summary.csv"
  [ ! -e "$scratch/term$signal/phdslam.lock" ] || fail "SIG$signal: the lock file stayed"
done

# A worker thread that cannot be created (here: too little address space for 150 thread stacks)
# leaves the run going on fewer threads, with a message; if memory then runs out, no further run
# starts (exit 1, "no further run was started") and a rerun with one job computes the rest;
# nothing is lost, nothing is left behind, and the program never aborts. The limit
# is found for this build: the smallest address space (300 MB - 2 GB) in which the program starts,
# plus 100 MB. A sanitizer build reserves terabytes of shadow memory and never starts under any of
# them, so the check is skipped there.
vlimit=""
for mb in $(seq 300 50 2000); do
  if (ulimit -v $((mb * 1024)) && "$phdslam" list >/dev/null 2>&1); then vlimit=$(((mb + 100) * 1024)); break; fi
done
if [ -n "$vlimit" ]; then
  (ulimit -v "$vlimit" && "$phdslam" run --scenario generated --estimator odometry --seeds 1-40 \
    --steps 20 --jobs 150 --quiet --out "$scratch/threads") >/dev/null 2>"$scratch/err"
  threads_exit=$?
  expect_in "$scratch/err" "could not start worker thread"
  if [ "$threads_exit" -eq 1 ]; then
    expect_in "$scratch/err" "no further run was started"
  elif [ "$threads_exit" -ne 0 ]; then
    fail "--jobs 150 under ulimit -v $vlimit: exit $threads_exit: $(cat "$scratch/err")"
  fi
  [ -z "$(find "$scratch/threads" -name '*.tmp-*')" ] || fail "--jobs 150: temporary files left"
  (ulimit -v "$vlimit" && "$phdslam" run --scenario generated --estimator odometry --seeds 1-40 \
    --steps 20 --jobs 1 --quiet --out "$scratch/threads") >/dev/null 2>"$scratch/err" ||
    fail "--jobs 1 rerun under ulimit -v $vlimit: $(cat "$scratch/err")"
  [ "$(($(wc -l <"$scratch/threads/runs.csv") - 1))" -eq 40 ] || fail "--jobs 150 + rerun: not all 40 runs"
else
  echo "cli_test: the program does not start under any address-space limit up to 2 GB (a sanitizer build?): thread-creation check skipped" >&2
fi

# Files of a results folder with the timing columns (ms, ms_*) dropped.
without_timing() {
  awk -F, 'NR == 1 { for (i = 1; i <= NF; i++) drop[i] = ($i == "ms" || $i ~ /^ms_/) }
           { line = ""
             for (i = 1; i <= NF; i++) if (!drop[i]) line = line $i ","
             print line }' "$1"
}
expect_same_results() {  # expect_same_results <folder a> <folder b>
  local a="$1" b="$2" f
  for f in summary.csv runs.csv; do
    cmp -s <(without_timing "$a/$f") <(without_timing "$b/$f") || fail "$f differs: $a $b"
  done
  [ "$(cd "$a" && find runs -type f | sort)" = "$(cd "$b" && find runs -type f | sort)" ] ||
    fail "run files differ: $a $b"
  for f in $(cd "$a" && find runs -name steps.csv); do
    cmp -s <(without_timing "$a/$f") <(without_timing "$b/$f") || fail "$f differs: $a $b"
  done
  for f in $(cd "$a" && find runs -name map.csv -o -name trajectory.tum); do
    cmp -s "$a/$f" "$b/$f" || fail "$f differs: $a $b"
  done
}

# Experiment files: errors name the file, line and key.
exp="$scratch/small.yaml"
cat >"$exp" <<YAML
scenario: paper-synthetic
estimators:
  - phd3
  - name: odometry
    particles: [1]
particles: [1, 3]
seeds: 1-3
steps: 30
jobs: 2
YAML
printf 'scenario: paper-synthetic\nestimators: [odometry]\nseeds: 1\npartcles: [1]\n' \
  >"$scratch/typo.yaml"
expect_exit 2 "$phdslam" run --experiment "$scratch/typo.yaml" --out "$scratch/typo" --quiet
expect_in "$scratch/err" "typo.yaml:4: unknown key 'partcles'"
printf 'scenario: paper-synthetic\nestimators: [phd3, nosuch]\nseeds: 1\n' >"$scratch/bad.yaml"
expect_exit 2 "$phdslam" run --experiment "$scratch/bad.yaml" --out "$scratch/bad" --quiet
expect_in "$scratch/err" "bad.yaml: unknown estimator 'nosuch'"
expect_exit 2 "$phdslam" run --experiment "$scratch/missing.yaml" --out "$scratch/bad" --quiet
printf 'scenario: paper-synthetic\nestimators: [odometry]\nseeds: 1\nname: caf\xe9\n' \
  >"$scratch/latin1.yaml"
expect_exit 2 "$phdslam" run --experiment "$scratch/latin1.yaml" --out "$scratch/bad" --quiet
expect_in "$scratch/err" "latin1.yaml: line 4, column 10: not valid UTF-8 (byte 0xE9)"
[ -e "$scratch/typo" ] || [ -e "$scratch/bad" ] && fail "a bad experiment file left results"
# A folder name that is not UTF-8 is a legal Linux path: config.json records it with U+FFFD.
odd_dir="$scratch/dir$(printf '\xff')"
mkdir -p "$odd_dir"
printf 'scenario: paper-synthetic\nestimators: [odometry]\nseeds: 1\nsteps: 5\n' >"$odd_dir/e.yaml"
expect_exit 0 "$phdslam" run --experiment "$odd_dir/e.yaml" --out "$odd_dir/results" --quiet
expect_in "$odd_dir/results/config.json" "dir$(printf '\xef\xbf\xbd')/e.yaml"

# The whole experiment, then two shards merged: the same results.
whole="$scratch/whole"
expect_exit 0 "$phdslam" run --experiment "$exp" --data-dir "$data_dir" --out "$whole" \
  --particles-trace
expect_in "$scratch/out" "runs: 9 planned"
expect_in "$whole/config.json" '"experiment": "small"'
expect_in "$whole/config.json" '"experiment_file"'
expect_in "$whole/runs/phd3-N3/seed-1/steps.csv" "map_components,ms,nees"
expect_in "$whole/summary.csv" ",nees_mean,nees_lower_95,nees_upper_95,nees_fraction_inside,"
expect_in "$whole/runs/phd3-N3/seed-2/particles.csv" "step,particle,x,y,log_weight"
[ -e "$whole/runs/odometry-N1/seed-1/particles.csv" ] && fail "odometry wrote particles.csv"
for i in 1 2; do
  expect_exit 0 "$phdslam" run --experiment "$exp" --data-dir "$data_dir" \
    --out "$scratch/shard$i" --shard "$i/2" --quiet --particles-trace
done
expect_in "$scratch/shard1/timing.json" '"shard": "1/2"'
expect_exit 0 "$phdslam" merge --out "$scratch/merged" "$scratch/shard1" "$scratch/shard2"
expect_in "$scratch/out" "9 runs copied"
expect_same_results "$whole" "$scratch/merged"
# Command-line options override the file's values; other settings are refused by merge.
expect_exit 0 "$phdslam" run --experiment "$exp" --data-dir "$data_dir" --out "$scratch/longer" \
  --steps 40 --seeds 4 --estimator odometry --quiet
[ "$(wc -l <"$scratch/longer/runs.csv")" -eq 2 ] || fail "--seeds/--estimator did not override"
expect_in "$scratch/longer/config.json" '"--steps"'
expect_exit 2 "$phdslam" merge --out "$scratch/merged2" "$whole" "$scratch/longer"
expect_in "$scratch/err" "other settings"

# Paired comparisons.
expect_exit 0 "$phdslam" compare --out "$whole" --metric gospa_m,pos_rmse_m,heading_rmse_deg
expect_in "$whole/comparison.csv" "metric,estimator_a,particles_a,estimator_b,particles_b,n,"
expect_in "$whole/comparison.csv" "gospa_m,odometry,1,phd3,1,3,3,"
expect_exit 2 "$phdslam" compare --out "$whole" --metric nosuch
expect_in "$scratch/err" "no metric column 'nosuch'"

# A sweep: one folder per value and sweep.csv.
sweep="$scratch/sweep.yaml"
printf 'scenario: paper-synthetic\nestimators: [odometry]\nseeds: 1-2\nsteps: 20\n' >"$sweep"
printf 'sweep: {parameter: pd, values: [0.8, 0.9]}\n' >>"$sweep"
expect_exit 0 "$phdslam" run --experiment "$sweep" --data-dir "$data_dir" --out "$scratch/swept" \
  --quiet
expect_in "$scratch/out" "sweep: $scratch/swept/sweep.csv"
expect_in "$scratch/swept/sweep.csv" "pd,estimator,particles,runs,"
expect_in "$scratch/swept/sweep.csv" "0.9,odometry,1,2,20,"
expect_in "$scratch/swept/sweep-pd-0.8/config.json" '"detection_probability": 0.8'
expect_exit 2 "$phdslam" run --experiment "$sweep" --data-dir "$data_dir" --out "$scratch/sw2" \
  --pd 0.5 --quiet
expect_in "$scratch/err" "is swept"

# Scenario options on the command line, recorded in config.json; bad keys and values name the key.
gen=(--scenario generated --estimator odometry --seeds 1 --steps 20 --quiet)
expect_exit 0 "$phdslam" run "${gen[@]}" --out "$scratch/gen" --scenario-set landmarks=12 \
  --scenario-set 'measurement_noise_cov=[0.5,0.001]'
expect_in "$scratch/gen/config.json" '"landmarks": 12'
expect_exit 2 "$phdslam" run "${gen[@]}" --out "$scratch/gen2" --scenario-set lanmarks=12
expect_in "$scratch/err" "unknown parameter 'lanmarks'"
expect_exit 2 "$phdslam" run "${gen[@]}" --out "$scratch/gen2" --scenario-set landmarks=1.5
expect_in "$scratch/err" "parameter 'landmarks': expected an integer, got 1.5"
expect_exit 0 "$phdslam" list
expect_in "$scratch/out" "corridor_half_width"

# The map OSPA cut-off: a setting recorded in config.json, never resumed with another value.
glmb=(--scenario glmb-sim --estimator phd3 --particles 5 --seeds 1 --steps 20 --quiet)
expect_exit 0 "$phdslam" run "${glmb[@]}" --out "$scratch/glmb" --map-ospa-cutoff 0.5 \
  --scenario-set data_protocol=single-realisation
expect_in "$scratch/glmb/config.json" '"map_ospa_c": 0.5'
expect_in "$scratch/glmb/config.json" '"data_protocol": "single-realisation"'
expect_in "$scratch/glmb/runs/phd3-N5/seed-1/steps.csv" "map_ospa_m"
expect_exit 2 "$phdslam" run "${glmb[@]}" --out "$scratch/glmb" --map-ospa \
  --scenario-set data_protocol=single-realisation
expect_in "$scratch/err" "map_ospa_c"
expect_exit 2 "$phdslam" run "${glmb[@]}" --out "$scratch/glmb3" --map-ospa-cutoff 0
expect_exit 2 "$phdslam" run "${glmb[@]}" --out "$scratch/glmb3" --scenario-set data_protocol=x
expect_in "$scratch/err" "data_protocol"

# A grid over a scenario option and an estimator parameter: one folder per point, one column
# per parameter; sweep errors name the parameter.
grid="$scratch/grid.yaml"
printf 'scenario: generated\nestimators: [phd3]\nseeds: 1\nsteps: 15\nsweep:\n' >"$grid"
printf '  - {parameter: landmarks, values: [10, 20]}\n' >>"$grid"
printf '  - {parameter: "phd3:max_hypotheses", values: [5, 50]}\n' >>"$grid"
expect_exit 0 "$phdslam" run --experiment "$grid" --out "$scratch/grid" --quiet
expect_in "$scratch/grid/sweep.csv" "landmarks,phd3:max_hypotheses,estimator,particles,runs,"
expect_in "$scratch/grid/sweep.csv" "20,50,phd3,1,1,15,"
expect_in "$scratch/grid/sweep-landmarks-20-phd3.max_hypotheses-5/config.json" '"landmarks": 20'
expect_in "$scratch/grid/sweep-landmarks-20-phd3.max_hypotheses-5/config.json" \
  '"max_hypotheses": 5'
printf 'scenario: generated\nestimators: [phd3]\nseeds: 1\nsweep: {parameter: landmark, values: [1]}\n' \
  >"$scratch/bad.yaml"
expect_exit 2 "$phdslam" run --experiment "$scratch/bad.yaml" --out "$scratch/bad" --quiet
expect_in "$scratch/err" "sweep parameter 'landmark' (value 1) is not particles"
printf 'scenario: generated\nestimators: [phd3]\nseeds: 1\nsweep: {parameter: landmarks, values: [1, x]}\n' \
  >"$scratch/bad.yaml"
expect_exit 2 "$phdslam" run --experiment "$scratch/bad.yaml" --out "$scratch/bad" --quiet
expect_in "$scratch/err" "sweep point landmarks = x:"
expect_in "$scratch/err" "parameter 'landmarks': expected an integer"
printf 'scenario: generated\nestimators: [phd3]\nseeds: 1\nsweep: {parameter: landmarks, values: []}\n' \
  >"$scratch/bad.yaml"
expect_exit 2 "$phdslam" run --experiment "$scratch/bad.yaml" --out "$scratch/bad" --quiet
expect_in "$scratch/err" "bad.yaml:4: 'sweep.values' of 'landmarks': expected a non-empty list"
[ -e "$scratch/bad" ] && fail "a sweep error left a results folder behind"

# export and ingest: an external filter's round trip (here the export's own truth as the
# "estimate", so its position RMSE is 0), exit codes and errors naming the file.
expect_exit 0 "$phdslam" export --help
for option in --scenario --seeds --steps --pd --clutter-rate --scenario-set --data-dir --out; do
  expect_in "$scratch/out" "$option"
done
expect_exit 0 "$phdslam" ingest --help
for option in --from --estimator --out --export --experiment-name --particles --description; do
  expect_in "$scratch/out" "$option"
done
ex="$scratch/export"
expect_exit 2 "$phdslam" export --scenario paper-synthetic --out "$ex"
expect_in "$scratch/err" "--seeds is required"
expect_exit 0 "$phdslam" export --scenario paper-synthetic --seeds 1-2 --steps 20 \
  --data-dir "$data_dir" --out "$ex"
(cd "$ex" && sha256sum --quiet -c SHA256SUMS) || fail "export checksums do not verify"
expect_in "$ex/seed-2/measurements.csv" "step,index,range,bearing"
ext="$scratch/external"
for s in 1 2; do
  mkdir -p "$ext/seed-$s"
  cp "$ex/truth/seed-$s/trajectory.tum" "$ext/seed-$s/trajectory.tum"
  cp "$ex/truth/seed-$s/map.csv" "$ext/seed-$s/map.csv"
done
ing="$scratch/ingested"
expect_exit 0 "$phdslam" run --scenario paper-synthetic --seeds 1-2 --steps 20 \
  --data-dir "$data_dir" --estimator odometry --out "$ing" --quiet
expect_exit 0 "$phdslam" ingest --from "$ext" --export "$ex" --estimator truth-copy \
  --data-dir "$data_dir" --out "$ing"
expect_in "$ing/summary.csv" "truth-copy,1,2,20,0,"
awk -F, '$1 == "truth-copy" && $7 == 0 {found = 1} END {exit !found}' "$ing/summary.csv" ||
  fail "the ingested truth does not have GOSPA 0"
expect_in "$ing/summary.csv" "odometry,1,2,20,"
expect_exit 0 "$phdslam" compare --out "$ing"
expect_in "$ing/comparison.csv" "gospa_m,odometry,1,truth-copy,1,2,"
expect_exit 2 "$phdslam" ingest --from "$ext" --export "$ex" --estimator phd3 --out "$ing"
expect_in "$scratch/err" "registered estimator"
expect_exit 2 "$phdslam" ingest --from "$ext" --export "$ex" --estimator x --steps 5 --out "$ing"
expect_exit 1 "$phdslam" ingest --from "$ext" --export "$ex" --seeds 1-3 --estimator x \
  --data-dir "$data_dir" --out "$scratch/ingest-missing"
expect_in "$scratch/err" "seed 3 is not in this export"
sed -i '5s/^[0-9.e-]* /nan /' "$ext/seed-2/trajectory.tum"
expect_exit 1 "$phdslam" ingest --from "$ext" --export "$ex" --estimator x \
  --data-dir "$data_dir" --out "$scratch/ingest-nan"
expect_in "$scratch/err" "seed-2/trajectory.tum:5"

# data: check and fetch against a local copy (no network); the synthetic scenario needs no data
# folder.
expect_exit 0 "$phdslam" data check --data-dir "$scratch/no-data"
expect_in "$scratch/out" "synthetic: present (the repository's copy"
expect_in "$scratch/out" "victoria-park: missing (phdslam data fetch victoria-park)"
expect_in "$scratch/out" "missing   $scratch/no-data/utias-mrclam/MRCLAM_Dataset6/Barcodes.dat"
expect_exit 2 "$phdslam" data fetch kitti --data-dir "$scratch/fetched"
expect_in "$scratch/err" "unknown data set 'kitti'"
expect_exit 2 "$phdslam" data
mirror="$scratch/mirror/phdslam3-synthetic"
mkdir -p "$mirror"
cp "$(dirname "$0")/../../datasets/data/phdslam3-synthetic/Environment_SLAM.mat" "$mirror/"
expect_exit 0 "$phdslam" data fetch synthetic --from "file://$scratch/mirror" \
  --data-dir "$scratch/fetched"
expect_in "$scratch/out" "synthetic: 1 files installed, 0 already verified"
expect_exit 0 "$phdslam" data check --data-dir "$scratch/fetched"
expect_in "$scratch/out" "verified  $scratch/fetched/phdslam3-synthetic/Environment_SLAM.mat"
printf 'x' | dd of="$mirror/Environment_SLAM.mat" bs=1 seek=200 conv=notrunc 2>/dev/null
printf 'x' | dd of="$scratch/fetched/phdslam3-synthetic/Environment_SLAM.mat" bs=1 seek=200 \
  conv=notrunc 2>/dev/null
expect_exit 1 "$phdslam" data check --data-dir "$scratch/fetched"
expect_in "$scratch/out" "corrupt   $scratch/fetched/phdslam3-synthetic/Environment_SLAM.mat (SHA-256"
expect_exit 1 "$phdslam" data fetch synthetic --from "$scratch/mirror" --data-dir "$scratch/fetched"
expect_in "$scratch/err" "phdslam3-synthetic/Environment_SLAM.mat: the copy from"
if ls -A "$scratch/fetched/phdslam3-synthetic" | grep -q part; then
  fail "a temporary download was left behind: $(ls -A "$scratch/fetched/phdslam3-synthetic")"
fi

if [ "$failures" -ne 0 ]; then
  echo "$failures check(s) failed" >&2
  exit 1
fi
echo "all phdslam CLI checks passed"
