#!/usr/bin/env bash
# Builds the libFuzzer targets of fuzz/ with clang under AddressSanitizer + UndefinedBehavior-
# Sanitizer (build/fuzz, PHDSLAM_FUZZ=ON) and runs each for SECONDS (default 20), as many at once
# as there are cores, on a seed corpus made at run time from the data files (the synthetic scenario
# from the data folder, $PHDSLAM_DATA else ../shared/datasets, or from the repository's copy in
# datasets/data; Victoria Park and MRCLAM seeds only when the data folder holds them, and then
# CI=true or PHDSLAM_REQUIRE_DATA=1 makes their absence an error) and the experiment files. Prints
# each target's executions per second and total executions; exits non-zero when a target crashes,
# leaks or trips a sanitizer (the input is kept as build/fuzz/artifacts/<target>-crash-*; turn it
# into a regression test).
#
#   ci/run-fuzz.sh          20 s per target (what ci/run-tests.sh runs)
#   ci/run-fuzz.sh 600      longer, on demand
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=${1:-20}
root=$(pwd)
data=${PHDSLAM_DATA:-$root/../shared/datasets}
build=build/fuzz
targets=(mat_file victoria_park tum_trajectory map_csv experiment_file mrclam scenario_options
  ingest_readers)

# -O1 with line tables only, as fuzzing builds usually are: about a quarter quicker to compile than
# RelWithDebInfo's -O2 -g, and a sanitizer's stack trace still names file and line.
# The build's output is kept in a log and printed when it fails, so a target that no longer links
# names its missing symbol instead of ending the stage without a word.
mkdir -p "$build"
build_log=$build/build.log
if ! { cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -gline-tables-only -DNDEBUG" -DCMAKE_CXX_COMPILER=clang++-14 \
  -DPHDSLAM_FUZZ=ON -DPHDSLAM_BUILD_TESTS=OFF -DPHDSLAM_BUILD_BENCHMARKS=OFF \
  -DPHDSLAM_WITH_CERES=OFF -DPHDSLAM_WITH_MRPT=OFF -DPHDSLAM_UNITY_BUILD=ON &&
  cmake --build "$build" -j "$(nproc 2>/dev/null || echo 2)" --target "${targets[@]/#/fuzz_}"; } \
  >"$build_log" 2>&1; then
  grep -E "error|FAILED" "$build_log" | head -20 >&2 || tail -20 "$build_log" >&2
  echo "run-fuzz: building the fuzz targets failed (the whole log: $build_log)" >&2
  exit 1
fi

# Seed corpus, rebuilt on every call from the real files.
corpus=$build/corpus
rm -rf "$corpus" && mkdir -p "$corpus"/{mat_file,victoria_park,tum_trajectory,map_csv,experiment_file,mrclam} \
  "$corpus"/{scenario_options,ingest_readers}
synthetic=$data/phdslam3-synthetic/Environment_SLAM.mat
[[ -f "$synthetic" ]] || synthetic=datasets/data/phdslam3-synthetic/Environment_SLAM.mat
cp "$synthetic" "$corpus/mat_file/"
# A data set absent from the data folder leaves its targets with the other seeds (or none, where
# libFuzzer starts from an empty input); in CI it is an error.
have_data_set() {
  if [[ -f "$data/$2" ]]; then return 0; fi
  if [[ "${CI:-}" == "true" || "${PHDSLAM_REQUIRE_DATA:-}" == "1" ]]; then
    echo "run-fuzz: data set '$1' not in the data folder '$data' (no $2): required here" >&2
    exit 1
  fi
  echo "run-fuzz: data set '$1' not in the data folder '$data' (no $2): its seeds skipped" >&2
  return 1
}
if have_data_set victoria-park victoria-park/measurements.dat; then
  cp "$data/victoria-park/aa3_gpsx.mat" "$corpus/mat_file/"
  { printf '\x00'; head -n 60 "$data/victoria-park/measurements.dat"; } >"$corpus/victoria_park/m"
  { printf '\x01'; head -n 60 "$data/victoria-park/inputs.dat"; } >"$corpus/victoria_park/i"
  awk 'NR <= 60 { printf "%s %s %s 0 0 0 %.6f %.6f\n", $1, $2, $3, sin($3 / 2), cos($3 / 2) }' \
    "$data/victoria-park/inputs.dat" >"$corpus/tum_trajectory/t.tum"
else
  printf '0 0 0 0 0 0 0 1\n1 1 0.5 0 0 0 0 1\n' >"$corpus/tum_trajectory/t.tum"
fi
cp validation/experiments/*.yaml "$corpus/experiment_file/"
mrclam=$data/utias-mrclam/MRCLAM_Dataset6
if have_data_set mrclam utias-mrclam/MRCLAM_Dataset6/Robot1_Measurement.dat; then
  awk 'BEGIN { print "x,y,weight,pxx,pxy,pyy" } !/^#/ && NF >= 3 { print $2 "," $3 ",1,0.01,0,0.01" }' \
    "$mrclam/Landmark_Groundtruth.dat" >"$corpus/map_csv/m.csv"
  { printf '\x02'; head -n 64 "$mrclam/Robot1_Groundtruth.dat"; } >"$corpus/mrclam/g"
  { printf '\x03'; head -n 64 "$mrclam/Robot1_Odometry.dat"; } >"$corpus/mrclam/o"
  { printf '\x04'; head -n 64 "$mrclam/Robot1_Measurement.dat"; } >"$corpus/mrclam/m"
  { printf '\x00'; cat "$mrclam/Barcodes.dat"; } >"$corpus/mrclam/b"
else
  printf 'x,y,weight,pxx,pxy,pyy\n1,2,1,0.01,0,0.01\n' >"$corpus/map_csv/m.csv"
fi
# Scenario options: the first byte picks generated (0), scphd-sim (1) or glmb-sim (2).
printf '\x00speed=2\nlandmarks=50\nclutter_rate=3\ninitial_pose=[1,2,0.5]\n' \
  >"$corpus/scenario_options/g"
printf '\x01circle_radius=30\nmap_inner_radius=5\nmeasurement_noise_cov=[0.1,0.01]\n' \
  >"$corpus/scenario_options/s"
printf '\x02data_protocol="single-realisation"\nlandmark_offset=0.5\n' \
  >"$corpus/scenario_options/l"
# Ingest readers: the first byte picks trajectory.tum (0), map.csv (1), pose_cov.csv (2),
# maps.csv (3), association.csv (4) or timing.csv (5).
printf '\x01x,y,weight,pxx,pxy,pyy\n1,2,0.5,0.1,0,0.1\n' >"$corpus/ingest_readers/m"
printf '\x02step,pxx,pxy,pxt,pyy,pyt,ptt\n0,1,0,0,1,0,1\n3,2,0.1,0,1,0,0.5\n' \
  >"$corpus/ingest_readers/p"
printf '\x03step,x,y\n0,1,1\n5,2,2\n' >"$corpus/ingest_readers/s"
printf '\x04step,index,x,y\n1,0,1,1\n' >"$corpus/ingest_readers/a"
printf '\x05step,ms\n0,1\n1,1\n2,1\n3,1\n4,1\n5,1\n' >"$corpus/ingest_readers/t"
printf '\x00# t x y z qx qy qz qw\n0 0 0 0 0 0 0 1\n1 1 0 0 0 0 0 1\n' \
  >"$corpus/ingest_readers/j"

mkdir -p "$build/artifacts"
# The targets write their input to files under $TMPDIR (fuzz/fuzz_input_file.h): keep them here.
export TMPDIR=$root/$build/tmp
rm -rf "$TMPDIR" && mkdir -p "$TMPDIR"
# libFuzzer runs on one core: the targets run side by side, one per core (each for its full
# SECONDS), and the table lists them in the order above once all have finished.
jobs=$(nproc 2>/dev/null || echo 2)
run_target() {
  local t=$1 result=ok
  if ! "$build/fuzz/fuzz_$t" "$corpus/$t" -max_total_time="$seconds" -print_final_stats=1 \
      -max_len=262144 -rss_limit_mb=2048 -timeout=10 \
      -artifact_prefix="$build/artifacts/$t-" >"$build/fuzz_$t.log" 2>&1; then
    result=FAILED
  fi
  echo "$result" >"$build/fuzz_$t.result"
}
running=0
for t in "${targets[@]}"; do
  rm -f "$build/fuzz_$t.result"
  if ((running >= jobs)); then
    wait -n || true
    running=$((running - 1))
  fi
  run_target "$t" &
  running=$((running + 1))
done
wait

status=0
printf '%-16s %10s %12s %8s\n' target "execs/s" "total execs" result
for t in "${targets[@]}"; do
  log=$build/fuzz_$t.log
  result=$(cat "$build/fuzz_$t.result" 2>/dev/null || echo FAILED)
  [[ $result == ok ]] || status=1
  execs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log" | tail -1)
  rate=$(sed -n 's/^stat::average_exec_per_sec: *//p' "$log" | tail -1)
  printf '%-16s %10s %12s %8s\n' "$t" "${rate:-?}" "${execs:-?}" "$result"
  if [[ $result != ok ]]; then
    grep -E "ERROR|runtime error|terminate|Test unit written" "$log" | head -5 >&2 || true
  fi
done
exit $status
