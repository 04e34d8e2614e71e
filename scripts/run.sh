#!/usr/bin/env bash
# The main job: build ffsim in Release and run it. Writes everything under out/.
# (Until the paper's traces land - issue #8 - the job is `ffsim --version` and the
# demo, which writes the test-pattern images and prints their content hashes.)
set -euo pipefail
cd "$(dirname "$0")/.."
jobs=${FFSIM_JOBS:-$(nproc)}
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build build -j "$jobs"
./build/ffsim --version
./build/ffsim demo --out out/demo
