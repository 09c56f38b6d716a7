#!/usr/bin/env python3
"""Error against rays from bench_error_vs_rays' CSV, as an SVG log-log chart (no plotting library needed).

Usage: scripts/plot_error_vs_rays.py CSV PATCHES OUT.svg
One line per method: the median over seeds of the error e (in %) against the median rays traced, at each budget;
dashed horizontal lines at the issue-14 levels 0.8 % and 0.3 %.
"""
import csv
import math
import statistics
import sys


def main(path, patches, out):
    runs = {}
    for row in csv.DictReader(open(path)):
        if row["patches"] != patches:
            continue
        key = (row["method"], float(row["budget"]))
        runs.setdefault(key, []).append((float(row["rays"]), 100 * float(row["error"])))
    curves = {}
    for (method, budget), rs in sorted(runs.items(), key=lambda kv: kv[0][1]):
        curves.setdefault(method, []).append(
            (statistics.median(r for r, _ in rs), statistics.median(e for _, e in rs)))
    W, H, L, R, T, B = 800, 420, 70, 290, 20, 50
    x0, x1, y0, y1 = math.log10(5e4), math.log10(1e7), math.log10(0.1), math.log10(200)
    X = lambda r: L + (math.log10(r) - x0) / (x1 - x0) * (W - L - R)
    Y = lambda e: T + (y1 - math.log10(e)) / (y1 - y0) * (H - T - B)
    colours = ["#888", "#bbb", "#a6761d", "#1b9e77", "#7570b3", "#d95f02", "#e7298a", "#66a61e", "#e6ab02",
               "#1f78b4", "#b15928", "#6a3d9a"]
    svg = [f'<svg xmlns="http://www.w3.org/2000/svg" width="{W}" height="{H}" font-family="sans-serif" font-size="11">',
           f'<rect width="{W}" height="{H}" fill="white"/>']
    for k in range(5, 8):
        for m in (1, 2, 5):
            r = m * 10 ** k
            if 5e4 <= r <= 1e7:
                svg.append(f'<line x1="{X(r):.1f}" y1="{T}" x2="{X(r):.1f}" y2="{H - B}" stroke="#eee"/>')
                svg.append(f'<text x="{X(r):.1f}" y="{H - B + 14}" text-anchor="middle">{r:.0e}</text>')
    for e in (0.1, 0.3, 0.8, 1, 3, 10, 30, 100):
        style = 'stroke="#c00" stroke-dasharray="4 3"' if e in (0.3, 0.8) else 'stroke="#eee"'
        svg.append(f'<line x1="{L}" y1="{Y(e):.1f}" x2="{W - R}" y2="{Y(e):.1f}" {style}/>')
        svg.append(f'<text x="{L - 6}" y="{Y(e) + 4:.1f}" text-anchor="end">{e:g} %</text>')
    svg.append(f'<text x="{(L + W - R) / 2}" y="{H - 12}" text-anchor="middle">rays traced</text>')
    svg.append(f'<text x="14" y="{(T + H - B) / 2}" transform="rotate(-90 14 {(T + H - B) / 2})" '
               f'text-anchor="middle">error e</text>')
    for i, (method, pts) in enumerate(curves.items()):
        c = colours[i % len(colours)]
        d = " ".join(f"{X(r):.1f},{Y(e):.1f}" for r, e in pts)
        svg.append(f'<polyline points="{d}" fill="none" stroke="{c}" stroke-width="2"/>')
        for r, e in pts:
            svg.append(f'<circle cx="{X(r):.1f}" cy="{Y(e):.1f}" r="3" fill="{c}"/>')
        svg.append(f'<text x="{W - R + 10}" y="{T + 16 * i + 10}" fill="{c}">{method}</text>')
    svg.append(f'<text x="{W - R + 10}" y="{T + 16 * len(curves) + 20}">{patches} patches, Cornell box</text>')
    svg.append("</svg>")
    open(out, "w").write("\n".join(svg) + "\n")


if __name__ == "__main__":
    main(*sys.argv[1:4])
