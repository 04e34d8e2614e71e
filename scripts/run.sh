#!/usr/bin/env bash
# The main job: build ffsim in Release and run it. Writes everything under out/.
# Replays the paper's traces (traces/kautz-*.trace, traces/bump-only.trace) for the
# single bump-mapped polygon, the magnified polygon and the terrain, and writes the
# images, out/report.md and out/report.json (issue 8; `ffsim paper-report --help`).
set -euo pipefail
cd "$(dirname "$0")/.."
jobs=${FFSIM_JOBS:-$(nproc)}
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build build -j "$jobs"
./build/ffsim --version
./build/ffsim paper-report --out out --threads "$jobs"
