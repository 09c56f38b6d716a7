#!/usr/bin/env python3
"""Coverage and sharpness of radwalk's statistical error estimate B_se (docs/theory/error_estimate.md).

Runs `radwalk solve` once as a reference with many rays (its own B_se included in the comparison) and then with the
given options for each seed, and prints for the (patch, channel) values of the reflecting, non-emitting patches:
  coverage  - the fraction with |B - B_ref| <= 1.96 sqrt(B_se^2 + B_se_ref^2) (95 % if B_se is right),
  sharpness - the area-weighted RMS of B_se over the RMS of B - B_ref (1 if B_se is right),
  e, e_est  - the measured relative error sqrt(sum A (B - B_ref)^2 / sum A B_ref^2) and the estimated one.
Example (the figures of docs/theory/error_estimate.md):
  python3 bench/error_coverage.py --scene meshes/cornell_box.obj --max-edge 100 --seeds 30 \\
      --reference "--rays 400000 --sobol-rays --emitter-columns 400000" --run "--rays 1000 --sobol-rays --emitter-columns 333"
"""
import argparse
import csv
import os
import shlex
import subprocess
import sys
import tempfile

import numpy as np


def solve(radwalk, scene, max_edge, seed, options, path):
    cmd = [radwalk, "solve", scene, "--max-edge", str(max_edge), "--seed", str(seed), "--csv", path, "-q"]
    subprocess.run(cmd + shlex.split(options), check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    rows = list(csv.DictReader(open(path)))
    get = lambda k: np.array([[float(r[k + "_" + c]) for c in "rgb"] for r in rows])
    return get("B"), get("B_se"), get("E"), get("rho"), np.array([float(r["area"]) for r in rows])


def main():
    here = os.path.dirname(os.path.abspath(__file__))
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--radwalk", default=os.path.join(here, "..", "build", "apps", "radwalk"))
    p.add_argument("--scene", default=os.path.join(here, "..", "meshes", "cornell_box.obj"))
    p.add_argument("--max-edge", type=float, default=100)
    p.add_argument("--seeds", type=int, default=30)
    p.add_argument("--reference", default="--rays 400000 --sobol-rays --emitter-columns 400000")
    p.add_argument("--run", default="--rays 1000 --sobol-rays --emitter-columns 333")
    a = p.parse_args()
    with tempfile.TemporaryDirectory() as tmp:
        B_ref, se_ref, E, rho, A = solve(a.radwalk, a.scene, a.max_edge, 999999, a.reference, os.path.join(tmp, "ref.csv"))
        keep = (E.max(1) == 0)[:, None] & (rho > 0) & (B_ref > 0)
        W = np.repeat(A[:, None], 3, 1)[keep]
        inside = total = 0
        err2 = est2 = 0.0
        for s in range(1, a.seeds + 1):
            B, se, *_ = solve(a.radwalk, a.scene, a.max_edge, s, a.run, os.path.join(tmp, "run.csv"))
            d = (B - B_ref)[keep]
            inside += int((np.abs(d) <= 1.96 * np.sqrt(se[keep] ** 2 + se_ref[keep] ** 2)).sum())
            total += d.size
            err2 += float((W * d ** 2).sum())
            est2 += float((W * se[keep] ** 2).sum())
    size2 = float((W * B_ref[keep] ** 2).sum()) * a.seeds
    print("scene %s --max-edge %g, %d seeds of: %s" % (os.path.basename(a.scene), a.max_edge, a.seeds, a.run))
    print("coverage %.3f of %d values, sharpness %.3f, e %.4f, e_est %.4f" %
          (inside / total, total, np.sqrt(est2 / err2), np.sqrt(err2 / size2), np.sqrt(est2 / size2)))


if __name__ == "__main__":
    sys.exit(main())
