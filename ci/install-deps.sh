#!/usr/bin/env bash
# Installs the Debian 12 packages phdslam needs to build, test (clang-14 and its runtime for the
# libFuzzer targets, valgrind) and report.
# Idempotent: installs only what is missing and prints nothing when everything is present.
# Uses sudo only when not running as root.
#
#   ci/install-deps.sh            build + tests + reports (everything but the browser)
#   ci/install-deps.sh --browser  also Debian's chromium, for the report-rendering test
#   ci/install-deps.sh --slurm    also slurm-wlm and munge, for the Slurm test (ci/run-slurm-test.sh)
# (options may be combined)
set -euo pipefail

packages=(
  build-essential cmake ninja-build pkg-config
  libeigen3-dev libceres-dev libmatio-dev
  libmrpt-slam-dev libmrpt-maps-dev libmrpt-obs-dev libmrpt-bayes-dev libmrpt-poses-dev
  libmrpt-random-dev libmrpt-system-dev libmrpt-math-dev libmrpt-core-dev
  libgtest-dev libgmock-dev libbenchmark-dev
  libyaml-cpp-dev nlohmann-json3-dev libcli11-dev zlib1g-dev libtcmalloc-minimal4
  python3 python3-matplotlib python3-numpy python3-scipy python3-yaml
  clang-format clang-tidy lld
  clang-14 libclang-rt-14-dev valgrind
  curl unzip  # phdslam data fetch: downloads and the MRCLAM archive
)
for option in "$@"; do
  case "$option" in
    --browser) packages+=(chromium) ;;
    --slurm) packages+=(slurm-wlm munge) ;;
    *) echo "install-deps: unknown option '$option' (--browser, --slurm)" >&2; exit 2 ;;
  esac
done

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done
[[ ${#missing[@]} -eq 0 ]] && exit 0

SUDO=""
if [[ "$(id -u)" -ne 0 ]]; then SUDO="sudo"; fi
echo "install-deps: installing ${#missing[@]} package(s): ${missing[*]}" >&2
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
$SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
echo "install-deps: done" >&2
