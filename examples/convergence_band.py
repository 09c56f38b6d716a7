#!/usr/bin/python3
"""Convergence of one random-walk estimator with its theoretical error band (matplotlib, writes a PNG).

For walk counts n = 16, 32, ..., the estimate of one patch's radiosity B_i (red channel) from n walks, against
the direct solve's B_i and the band B_i +- 1.96 sqrt(var_theory / n) from the exact per-walk variance
(radwalk.exact_variance): about 95 % of the points fall inside. Writes convergence_band.png and .csv.
"""
import argparse
import csv
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np

import radwalk

parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
parser.add_argument("--scene", default="meshes/cube.obj", help="scene (default: %(default)s)")
parser.add_argument("--method", default="gather-collision", choices=radwalk.walk_methods())
parser.add_argument("--patch", type=int, default=0, help="patch to follow (default: 0)")
parser.add_argument("--scale", type=float, default=1.0, help="multiplies the largest walk count (default: 1)")
parser.add_argument("--seed", type=int, default=1, help="random seed (default: 1)")
parser.add_argument("--threads", type=int, default=0, help="threads (default: 0, all cores)")
parser.add_argument("--out", default=".", help="directory of the outputs (default: .)")
args = parser.parse_args()

scene = radwalk.load(args.scene)
ff = radwalk.form_factors(scene, rays=10000, seed=args.seed, threads=args.threads)
exact = radwalk.solve(scene, ff, solver="direct").B[args.patch, 0]
var = radwalk.exact_variance(scene, ff, method=args.method)[args.patch, 0]
gathering = args.method.startswith("gather")
counts = 2 ** np.arange(4, int(np.log2(max(32, 2 ** 16 * args.scale))) + 1)
estimates = []
for n in counts:
    budget = {"walks_per_patch": int(n), "patches": [args.patch]} if gathering else {"particles": int(n)}
    r = radwalk.random_walk(scene, ff, method=args.method, seed=args.seed, threads=args.threads, **budget)
    estimates.append(r.B[args.patch, 0])

half = 1.96 * np.sqrt(var / counts)
fig, ax = plt.subplots(figsize=(6, 4))
ax.fill_between(counts, exact - half, exact + half, alpha=0.3, label="B ± 1.96 √(var_theory / n)")
ax.axhline(exact, color="k", lw=0.8, label="direct solve")
ax.plot(counts, estimates, "o-", label=args.method)
ax.set_xscale("log", base=2)
ax.set_xlabel("walks n" + (" per patch" if gathering else " (particles)"))
ax.set_ylabel(f"B of patch {args.patch}, red (W per unit length²)")
ax.set_title(f"{Path(args.scene).name}: {args.method}")
ax.legend()
fig.tight_layout()
out = Path(args.out)
fig.savefig(out / "convergence_band.png", dpi=120)
with open(out / "convergence_band.csv", "w", newline="") as f:
    csv.writer(f).writerows([("n", "estimate", "exact", "half_width_95"), *zip(counts, estimates, [exact] * len(counts), half)])
inside = np.mean(np.abs(np.array(estimates) - exact) <= half)
print(f"{inside:.0%} of {len(counts)} estimates inside the 95 % band; wrote {out / 'convergence_band.png'}")
