#!/usr/bin/env python3
"""The two-thread frames of `ffsim bench --perf --trace F --threads 1,2` taken
apart, as an SVG of stacked bars (docs/performance.md 38).

usage: scripts/plot-taken-apart.py OUT.svg FILE...
  FILE: the bench's output for one or more traces (each block starts with
  "traces/NAME.trace: WxH"). One bar per block: the serial part, the split
  time (the split work at the speed it reached) and the caller's waits, with a
  tick at half the one-thread frame (two threads at exactly 2x).
"""
import re
import sys


def parse(paths):
    rows = []
    for path in paths:
        cur = None
        for line in open(path):
            m = re.match(r"(?:\S*/)?kautz-(\S+)\.trace: (\d+x\d+)", line) or re.match(r"(?:\S*/)?(\S+)\.trace: (\d+x\d+)", line)
            if m:
                cur = {"name": m.group(1) + " " + m.group(2)}
                rows.append(cur)
                continue
            if cur is None:
                continue
            m = re.match(r"  1 thread:  median ([\d.]+) ms", line)
            if m:
                cur["t1"] = float(m.group(1))
            m = re.match(r"  2 threads taken apart: serial part ([\d.]+) \+ split work ([\d.]+) ms on one core at ([\d.]+)x"
                         r" \(machine ceiling ([\d.]+)x\) = ([\d.]+) \+ the caller's waits for the other threads' last tasks"
                         r" ([\d.]+) = ([\d.]+) ms", line)
            if m:
                cur.update(serial=float(m.group(1)), speed=float(m.group(3)), split=float(m.group(5)),
                           waits=float(m.group(6)), t2=float(m.group(7)))
    return [r for r in rows if "t2" in r and "t1" in r]


def svg(rows):
    w, left, right, bar, gap, top = 760, 190, 30, 22, 12, 40
    h = top + len(rows) * (bar + gap) + 60
    # Each bar as a share of its own one-thread frame: 0.5 is linear in threads.
    scale = (w - left - right) / 1.0
    out = [f'<svg xmlns="http://www.w3.org/2000/svg" width="{w}" height="{h}" font-family="sans-serif" font-size="12">',
           f'<text x="{left}" y="18" font-size="14">Two-thread frame as a share of the one-thread frame (0.5: linear)</text>']
    colours = [("serial part", "#d95f02"), ("split work at its speed", "#1b9e77"), ("caller's waits", "#7570b3")]
    for k, (label, c) in enumerate(colours):
        x = left + k * 190
        out.append(f'<rect x="{x}" y="{h - 30}" width="12" height="12" fill="{c}"/>'
                   f'<text x="{x + 16}" y="{h - 20}">{label}</text>')
    for tick in (0, 0.25, 0.5, 0.75, 1.0):
        x = left + tick * scale
        out.append(f'<line x1="{x:.1f}" y1="{top - 6}" x2="{x:.1f}" y2="{h - 44}" stroke="#bbb" '
                   f'stroke-dasharray="{"none" if tick == 0.5 else "3,3"}"/>'
                   f'<text x="{x:.1f}" y="{top - 10}" text-anchor="middle">{tick:g}</text>')
    for i, r in enumerate(rows):
        y = top + i * (bar + gap)
        out.append(f'<text x="{left - 8}" y="{y + bar * 0.7:.1f}" text-anchor="end">{r["name"]}</text>')
        x = left
        for value, (_, c) in zip((r["serial"], r["split"], r["waits"]), colours):
            width = value / r["t1"] * scale
            out.append(f'<rect x="{x:.1f}" y="{y}" width="{width:.1f}" height="{bar}" fill="{c}"/>')
            x += width
        out.append(f'<text x="{x + 6:.1f}" y="{y + bar * 0.7:.1f}">{r["t1"] / r["t2"]:.2f}x '
                   f'(split work at {r["speed"]:.2f}x)</text>')
    out.append("</svg>")
    return "\n".join(out) + "\n"


def main():
    if len(sys.argv) < 3:
        sys.stderr.write(__doc__)
        return 2
    rows = parse(sys.argv[2:])
    if not rows:
        sys.stderr.write("plot-taken-apart.py: no taken-apart lines in " + " ".join(sys.argv[2:]) + "\n")
        return 1
    with open(sys.argv[1], "w") as f:
        f.write(svg(rows))
    return 0


if __name__ == "__main__":
    sys.exit(main())
