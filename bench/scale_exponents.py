#!/usr/bin/env python3
"""Reads bench_scale outputs and prints, per stage, CPU seconds and peak GB at each N and the exponent a of
CPU time ~ N^a fitted by least squares on log-log over the sizes given (and between the last two sizes).

    bench/scale_exponents.py bench/results/scale_cornell.txt [more files ...]"""
import math
import re
import sys


def parse(path):
    sizes, rows, n, patching = [], {}, None, None
    for line in open(path):
        m = re.match(r"\s+(\d+) patches$", line)
        if m:  # printed after the patching stage: that row belongs to this N
            n = int(m.group(1))
            sizes.append(n)
            if patching:
                rows.setdefault("patching", {})[n] = patching
            continue
        m = re.match(r"\s+([a-z -]+?)\s+([\d.]+) s wall\s+([\d.]+) s cpu\s+([\d.]+) GB peak", line)
        if m:
            stage, value = m.group(1).strip(), (float(m.group(3)), float(m.group(4)))
            if stage == "patching":
                patching = value
            elif n:
                rows.setdefault(stage, {})
                if stage == "raw embree" and n in rows[stage]:  # timed twice: the faster (less loaded) run
                    value = min(value, rows[stage][n])
                rows[stage][n] = value
    return sizes, rows


def slope(xs, ys):
    lx = [math.log(x) for x in xs]
    ly = [math.log(max(y, 1e-3)) for y in ys]
    mx, my = sum(lx) / len(lx), sum(ly) / len(ly)
    sxx = sum((a - mx) ** 2 for a in lx)
    return sum((a - mx) * (b - my) for a, b in zip(lx, ly)) / sxx if sxx > 0 else float("nan")


for path in sys.argv[1:]:
    sizes, rows = parse(path)
    print(f"{path}: N = {', '.join(map(str, sizes))}")
    print(f"{'stage':14s} " + " ".join(f"{n:>16d}" for n in sizes) + "   exponent (all, last two)")
    for stage, by_n in rows.items():
        ns = [n for n in sizes if n in by_n]
        cells = " ".join(f"{by_n[n][0]:7.2f}s {by_n[n][1]:5.2f}GB" if n in by_n else " " * 16 for n in sizes)
        big = [n for n in ns if by_n[n][0] >= 0.05]  # CPU times below 0.05 s are below the clock's resolution here
        a = slope(big, [by_n[n][0] for n in big]) if len(big) >= 2 else float("nan")
        b = slope(big[-2:], [by_n[n][0] for n in big[-2:]]) if len(big) >= 2 else float("nan")
        print(f"{stage:14s} {cells}   {a:5.2f} {b:5.2f}")
    print()
