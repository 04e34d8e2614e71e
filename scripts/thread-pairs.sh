#!/bin/bash
# One trace on one and on two threads, alternately, at several window sizes of
# the terrain (docs/performance.md 37). This machine's speed changes from
# minute to minute, so each round times one thread and two threads one right
# after the other (two first in even rounds) and reads the speed-up against the
# machine's own ceiling, measured by the two-thread run just before its frames
# (a cache-resident loop per thread, docs/performance.md 24.3). Per round it
# prints both frame times, the two-thread run's serial part, the ceiling, the
# speed-up, the machine bound T1 / (serial + (T1 - serial) / min(ceiling, 2))
# (docs/performance.md 33) and the speed-up's share of that bound; then the
# medians per window.
#
# usage: scripts/thread-pairs.sh BIN TRACE [ROUNDS [FRAMES]] [-- WxH ...]
#   e.g. scripts/thread-pairs.sh build/ffsim traces/kautz-geforce-aa.trace 8 60 -- 640x480 1280x960
# Defaults: 8 rounds of 60 frames per run, windows 640x480 and 1280x960.
set -euo pipefail
if [ $# -lt 2 ]; then
  sed -n 2,15p "$0" | sed 's/^# \{0,1\}//'
  exit 2
fi
bin=$1 trace=$2
shift 2
rounds=8 frames=60
if [ $# -gt 0 ] && [ "$1" != "--" ]; then rounds=$1; shift; fi
if [ $# -gt 0 ] && [ "$1" != "--" ]; then frames=$1; shift; fi
if [ $# -gt 0 ] && [ "$1" = "--" ]; then shift; fi
windows=("$@")
[ ${#windows[@]} -gt 0 ] || windows=(640x480 1280x960)
[ -x "$bin" ] || { echo "thread-pairs.sh: not an executable: $bin" >&2; exit 2; }
[ -f "$trace" ] || { echo "thread-pairs.sh: no such trace: $trace" >&2; exit 2; }
for w in "${windows[@]}"; do
  [[ $w =~ ^[0-9]+x[0-9]+$ ]] || { echo "thread-pairs.sh: a window is WxH, like 640x480: $w" >&2; exit 2; }
done
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
run() {  # threads WxH -> the bench's output in $tmp/out
  "$bin" bench --perf --trace "$trace" --set scene=1 --set res=128 --set tw="${2%x*}" --set th="${2#*x}" \
    --repeat "$frames" --threads "$1" > "$tmp/out" 2>&1 || { cat "$tmp/out" >&2; exit 1; }
}
field() {  # pattern -> the number after it in $tmp/out
  grep -o "$1 [0-9.]*" "$tmp/out" | head -1 | awk '{print $NF}'
}
printf "%-10s %5s %9s %9s %9s %8s %8s %8s %7s\n" window round t1_ms t2_ms serial_ms ceiling speedup bound share
for w in "${windows[@]}"; do
  for r in $(seq 1 "$rounds"); do
    one() { run 1 "$w"; t1=$(grep -o "median [0-9.]* ms" "$tmp/out" | head -1 | awk '{print $2}'); }
    two() {
      run 2 "$w"
      t2=$(grep -o "fragments; median [0-9.]* ms" "$tmp/out" | head -1 | awk '{print $3}')
      serial=$(grep -o "serial part.*median [0-9.]* ms" "$tmp/out" | grep -o "median [0-9.]*" | awk '{print $2}')
      ceiling=$(grep -o "just before these frames[^:]*: [0-9.]*x" "$tmp/out" | grep -o "[0-9.]*x$" | tr -d x)
    }
    if [ $((r % 2)) = 1 ]; then one; two; else two; one; fi
    awk -v w="$w" -v r="$r" -v t1="$t1" -v t2="$t2" -v s="$serial" -v c="$ceiling" 'BEGIN {
      m = c < 1 ? 1 : (c > 2 ? 2 : c); b = t1 / (s + (t1 - s) / m); sp = t1 / t2
      printf "%-10s %5d %9.3f %9.3f %9.3f %8.2f %8.2f %8.2f %7.2f\n", w, r, t1, t2, s, c, sp, b, sp / b }' |
      tee -a "$tmp/rows"
  done
done
echo "medians per window:"
for w in "${windows[@]}"; do
  awk -v w="$w" '$1 == w { n++; sp[n] = $7; c[n] = $6; sh[n] = $9 }
    function median(a, n,   i, j, t) {
      for (i = 2; i <= n; i++) { t = a[i]; for (j = i - 1; j >= 1 && a[j] > t; j--) a[j + 1] = a[j]; a[j + 1] = t }
      return n % 2 ? a[(n + 1) / 2] : (a[n / 2] + a[n / 2 + 1]) / 2 }
    END { ms = median(sp, n); mc = median(c, n); mh = median(sh, n)  # (sorts each: sp[1], sp[n] are min, max)
      printf "  %-10s speed-up %.2fx (%.2f .. %.2f), ceiling %.2fx, share of the machine bound %.2f\n",
        w, ms, sp[1], sp[n], mc, mh }' "$tmp/rows"
done
