#!/usr/bin/env bash
# The main job: installs what is missing, builds the release preset (as a unity build,
# PHDSLAM_UNITY_BUILD=ON: half the CPU of building file by file), runs the default experiment
# (validation/experiments/quick.yaml) with the particle traces of the report's Fig. 3
# (--particles-trace, which changes no other result), the single-cluster parent-weighting
# figure's data (phdslam parent-weights) and writes their report. Prints the report's path at the
# end.
#
#   ci/run-main.sh [OUT_DIR]     default OUT_DIR: results/quick
set -euo pipefail
cd "$(dirname "$0")/.."
ci/install-deps.sh

out="${1:-results/quick}"
jobs=$(nproc 2>/dev/null || echo 2)
cmake --preset release -DPHDSLAM_UNITY_BUILD=ON >/dev/null
cmake --build --preset release -j "$jobs" --target phdslam
build/release/apps/phdslam run --experiment validation/experiments/quick.yaml --particles-trace \
  --out "$out"
build/release/apps/phdslam parent-weights --out "$out"
python3 reports/make_report.py "$out"
echo "report: $(cd "$out" && pwd)/report/index.html"
