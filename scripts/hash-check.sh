#!/usr/bin/env bash
# The hash check of docs/performance.md (since section 35): every trace in
# traces/ replayed on one and on two threads, each in two sizes, and the hash
# lines it prints (the `hash` outputs and the final hash of every buffer)
# written to OUT. Two binaries whose OUT files are byte for byte the same leave
# every output bit as it was. 64 replays:
#   the paper's traces (a `scene` parameter): scene 0 at its own size and at
#     zoom 8 (512x512), scene 1 at its own size and at 640x480 with res 128;
#   the others: their own size and --size 640x480.
#
# usage: scripts/hash-check.sh BIN OUT
#   e.g. scripts/hash-check.sh /tmp/ffsim-old /tmp/old.txt; scripts/hash-check.sh build/ffsim /tmp/new.txt;
#        cmp /tmp/old.txt /tmp/new.txt
set -euo pipefail
if [ $# -ne 2 ]; then
  sed -n 2,13p "$0" | sed 's/^# \{0,1\}//'
  exit 2
fi
bin=$(realpath "$1") out=$(realpath -m "$2")
[ -x "$bin" ] || { echo "hash-check.sh: not an executable: $1" >&2; exit 2; }
cd "$(dirname "$0")/.."
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
: > "$out"
for t in traces/*.trace; do
  "$bin" info "$t" > "$tmp/info"
  if grep -q "^  scene =" "$tmp/info"; then
    cases=("--set scene=0" "--set scene=0 --set zoom=8" "--set scene=1"
           "--set scene=1 --set res=128 --set tw=640 --set th=480")
  else
    cases=("" "--size 640x480")
  fi
  for c in "${cases[@]}"; do
    for threads in 1 2; do
      echo "== $t $c threads=$threads" >> "$out"
      # shellcheck disable=SC2086  # (c is a list of arguments)
      "$bin" replay "$t" $c --threads "$threads" --out "$tmp/out" > "$tmp/log" 2>&1 ||
        { echo "hash-check.sh: $t $c --threads $threads failed:" >&2; cat "$tmp/log" >&2; exit 1; }
      grep -E "^(hash|final) " "$tmp/log" >> "$out"
    done
  done
done
echo "$(grep -c '^==' "$out") replays, $(grep -vc '^==' "$out") hash lines in $out"
