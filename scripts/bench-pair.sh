#!/bin/bash
# Two ffsim binaries timed on one trace, one thread, alternately on one pinned
# CPU (docs/performance.md 34.2). This machine's vCPUs do not run at one speed
# and a run left to the system lands on either: pinned to one CPU, each round
# runs A and B one right after the other (B first in even rounds), and the
# per-round ratios B / A are summarised by their median and geometric mean.
# Needs `taskset` (util-linux).
#
# usage: scripts/bench-pair.sh BIN_A BIN_B TRACE [ROUNDS [FRAMES [CPU]]] [-- BENCH ARGS...]
#   e.g. scripts/bench-pair.sh /tmp/ffsim-old build/ffsim traces/kautz-imaging-aa.trace 10 100 1 \
#          -- --set scene=1 --set res=128 --set tw=640 --set th=480
# Defaults: 10 rounds of 100 frames on CPU 1 (or 0 on a machine with one).
set -euo pipefail
if [ $# -lt 3 ]; then
  sed -n 2,12p "$0" | sed 's/^# \{0,1\}//'
  exit 2
fi
a=$1 b=$2 trace=$3
shift 3
rounds=10 frames=100 cpu=$(( $(nproc) > 1 ? 1 : 0 ))
if [ $# -gt 0 ] && [ "$1" != "--" ]; then rounds=$1; shift; fi
if [ $# -gt 0 ] && [ "$1" != "--" ]; then frames=$1; shift; fi
if [ $# -gt 0 ] && [ "$1" != "--" ]; then cpu=$1; shift; fi
if [ $# -gt 0 ] && [ "$1" = "--" ]; then shift; fi
for bin in "$a" "$b"; do
  [ -x "$bin" ] || { echo "bench-pair.sh: not an executable: $bin" >&2; exit 2; }
done
[ -f "$trace" ] || { echo "bench-pair.sh: no such trace: $trace" >&2; exit 2; }
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
time_one() {  # binary -> median frame time in ms
  taskset -c "$cpu" "$1" bench --perf --trace "$trace" --repeat "$frames" --threads 1 "${@:2}" > "$tmp/out" 2>&1 ||
    { cat "$tmp/out" >&2; exit 1; }
  grep -o "median [0-9.]* ms" "$tmp/out" | head -1 | awk '{print $2}'
}
ratios=()
for r in $(seq 1 "$rounds"); do
  if [ $((r % 2)) = 1 ]; then ma=$(time_one "$a" "$@"); mb=$(time_one "$b" "$@");
  else mb=$(time_one "$b" "$@"); ma=$(time_one "$a" "$@"); fi
  ratio=$(awk -v x="$mb" -v y="$ma" 'BEGIN { printf "%.3f", x / y }')
  ratios+=("$ratio")
  echo "round $r (cpu$cpu): A $ma ms, B $mb ms, B/A $ratio"
done
printf '%s\n' "${ratios[@]}" | sort -n | awk '{ v[n++] = $1; s += log($1) }
  END { m = n % 2 ? v[(n - 1) / 2] : (v[n / 2 - 1] + v[n / 2]) / 2
        printf "B/A over %d rounds: median %.3f, geometric mean %.3f (%.3f .. %.3f)\n", n, m, exp(s / n), v[0], v[n - 1] }'
