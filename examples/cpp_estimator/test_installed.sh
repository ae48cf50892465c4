#!/usr/bin/env bash
# Installs phdslam from BUILD_DIR into a fresh prefix, configures and builds this example against
# it (find_package(phdslam)), runs it on two seeds of paper-synthetic and checks its results.
#   test_installed.sh BUILD_DIR WORK_DIR [GENERATOR]
set -euo pipefail
build_dir=$1
work=$2
generator=${3:-Ninja}
here=$(cd "$(dirname "$0")" && pwd)
rm -rf "$work"
mkdir -p "$work"
prefix=$work/prefix
cmake --install "$build_dir" --prefix "$prefix" > "$work/install.log"
test -f "$prefix/lib/cmake/phdslam/phdslamConfig.cmake"
test -f "$prefix/include/phdslam/src/filters/estimator.h"
test -x "$prefix/bin/phdslam"
cmake -S "$here" -B "$work/build" -G "$generator" -DCMAKE_BUILD_TYPE=Release \
  -DCMAKE_PREFIX_PATH="$prefix" > "$work/configure.log"
# The example must not see the source tree: its includes come from the prefix (Ninja only).
source_root=$(cd "$here/../.." && pwd)
if [[ -f "$work/build/build.ninja" ]]; then
  grep "INCLUDES = " "$work/build/build.ninja" | grep -q -- "$prefix/include/phdslam"
  if grep "INCLUDES = " "$work/build/build.ninja" | grep -q -- "$source_root\( \|$\)"; then
    echo "the example's build uses the source tree's headers" >&2
    exit 1
  fi
fi
cmake --build "$work/build" -j 2 > "$work/build.log"
"$work/build/nearest_landmark_slam" --out "$work/results" --seeds 1-2 --steps 200 \
  --estimators nearest-landmark,odometry | tee "$work/run.log"
# Every group finished both seeds, and the installed program reads the folder.
rows=$(tail -n +2 "$work/results/summary.csv" | cut -d, -f1-3)
expected=$'nearest-landmark,1,2\nodometry,1,2'
if [[ "$rows" != "$expected" ]]; then
  echo "summary.csv groups: $rows" >&2
  exit 1
fi
"$prefix/bin/phdslam" compare --out "$work/results" --metric gospa_m,pos_rmse_m
grep -q "^gospa_m,nearest-landmark,1,odometry,1,2," "$work/results/comparison.csv"
# The MRPT baselines' plugin (when built): installed beside the libraries, not linked by the
# program, and opened from there by the installed program when it runs an MRPT baseline.
if [[ -f "$build_dir/apps/libphdslam_mrpt_baselines.so" ]]; then
  plugin=$prefix/lib/libphdslam_mrpt_baselines.so
  test -f "$plugin"
  if ldd "$prefix/bin/phdslam" | grep -q libmrpt; then
    echo "the installed phdslam links MRPT" >&2
    exit 1
  fi
  LD_DEBUG=files "$prefix/bin/phdslam" run --scenario paper-synthetic --estimator mrpt-ekf \
    --seeds 1 --steps 20 --jobs 1 --quiet --out "$work/mrpt" 2> "$work/mrpt.log"
  grep -q "file=$plugin " "$work/mrpt.log"
  test -f "$work/mrpt/runs/mrpt-ekf-N1/seed-1/steps.csv"
fi
echo "out-of-tree example built against $prefix and run"
