#!/usr/bin/env bash
# Builds ffsim twice and runs the whole test suite through CTest in each build:
#   build/       Release (-O3), the configuration users run
#   build-asan/  Release + AddressSanitizer + UndefinedBehaviorSanitizer
# Any failure in either build fails the script. A test running longer than
# 20 minutes fails (the slowest take about 160 s under the sanitizers): a hang
# is reported, not waited on.
set -euo pipefail
cd "$(dirname "$0")/.."
jobs=${FFSIM_JOBS:-$(nproc)}
for cfg in "build -DFFSIM_SANITIZE=OFF" "build-asan -DFFSIM_SANITIZE=ON"; do
  set -- $cfg
  dir=$1; shift
  echo "== $dir: configure, build, test"
  cmake -S . -B "$dir" -DCMAKE_BUILD_TYPE=Release "$@" >/dev/null
  cmake --build "$dir" -j "$jobs"
  ctest --test-dir "$dir" --output-on-failure --timeout 1200 -j "$jobs"
done
