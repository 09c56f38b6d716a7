#!/usr/bin/env python3
"""Coverage and sharpness of radwalk's total error estimate B_err against the continuous radiosity.

B_err = sqrt(B_se^2 + B_disc^2) (docs/theory/discretisation_error.md) claims to cover the difference between the
discrete solution and the continuous radiosity averaged over each patch. The continuous reference is radwalk's
path tracer (patch averages, `radwalk pathtrace --spp N`, with its own B_se); for each seed `radwalk solve` runs
with the given options, and the script prints, over the reflecting, non-emitting patches that are not hidden (the
path tracer gives them B > 0) and their channels:
  coverage    - the fraction with |B - B_pt| <= 1.96 sqrt(B_err^2 + B_se_pt^2) (95 % if B_err is right),
  sharpness   - the area-weighted RMS of B_err over the RMS of B - B_pt with the path tracer's own noise taken
                out (1 if B_err is right),
  e, e_est    - the measured relative error sqrt(sum A (B - B_pt)^2 / sum A B_pt^2) (path-tracer noise taken out)
                and the estimated one, with its statistical and discretisation parts.
Example:
  python3 bench/total_error_coverage.py --scene meshes/cornell_box.obj --max-edge 100 --seeds 5 --spp 4096 \\
      --run "--rays 1000 --sobol-rays --emitter-columns 333"
"""
import argparse
import csv
import os
import shlex
import subprocess
import sys
import tempfile

import numpy as np


def run(cmd, path):
    subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    rows = list(csv.DictReader(open(path)))
    get = lambda k: np.array([[float(r[k + "_" + c]) for c in "rgb"] for r in rows]) if k + "_r" in rows[0] else None
    return {k: get(k) for k in ("B", "B_se", "B_disc", "B_err", "E", "rho")} | {"area": np.array([float(r["area"]) for r in rows])}


def main():
    here = os.path.dirname(os.path.abspath(__file__))
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--radwalk", default=os.path.join(here, "..", "build", "apps", "radwalk"))
    p.add_argument("--scene", default=os.path.join(here, "..", "meshes", "cornell_box.obj"))
    p.add_argument("--max-edge", type=float, default=100)
    p.add_argument("--seeds", type=int, default=5)
    p.add_argument("--spp", type=int, default=4096)
    p.add_argument("--scene-options", default="", help="options for both commands (--unit, --scale, ...)")
    p.add_argument("--run", default="--rays 1000 --sobol-rays --emitter-columns 333")
    a = p.parse_args()
    common = ["--max-edge", str(a.max_edge), "-q"] + shlex.split(a.scene_options)
    with tempfile.TemporaryDirectory() as tmp:
        path = os.path.join(tmp, "pt.csv")
        pt = run([a.radwalk, "pathtrace", a.scene, "--spp", str(a.spp), "--seed", "999999", "--csv", path] + common, path)
        keep = (pt["E"].max(1) == 0)[:, None] & (pt["rho"] > 0) & (pt["B"] > 0)
        W = np.repeat(pt["area"][:, None], 3, 1)[keep]
        inside = total = 0
        err2 = noise2 = est2 = stat2 = disc2 = 0.0
        for s in range(1, a.seeds + 1):
            path = os.path.join(tmp, "run.csv")
            r = run([a.radwalk, "solve", a.scene, "--seed", str(s), "--csv", path] + common + shlex.split(a.run), path)
            d = (r["B"] - pt["B"])[keep]
            err = r["B_err"][keep]
            inside += int((np.abs(d) <= 1.96 * np.sqrt(err ** 2 + pt["B_se"][keep] ** 2)).sum())
            total += d.size
            err2 += float((W * d ** 2).sum())
            noise2 += float((W * pt["B_se"][keep] ** 2).sum())
            est2 += float((W * err ** 2).sum())
            stat2 += float((W * r["B_se"][keep] ** 2).sum())
            disc2 += float((W * r["B_disc"][keep] ** 2).sum())
    size2 = float((W * pt["B"][keep] ** 2).sum()) * a.seeds
    measured2 = max(err2 - noise2, 0.0)
    print("scene %s --max-edge %g %s, %d seeds of: %s; path tracer --spp %d (its noise e %.4f)" %
          (os.path.basename(a.scene), a.max_edge, a.scene_options, a.seeds, a.run, a.spp, np.sqrt(noise2 / size2)))
    print("coverage %.3f of %d values, sharpness %.3f, e %.4f, e_est %.4f (statistical %.4f, discretisation %.4f)" %
          (inside / total, total, np.sqrt(est2 / measured2) if measured2 > 0 else float("inf"), np.sqrt(measured2 / size2),
           np.sqrt(est2 / size2), np.sqrt(stat2 / size2), np.sqrt(disc2 / size2)))


if __name__ == "__main__":
    sys.exit(main())
