#!/usr/bin/env python3
"""Per material: a run's area-weighted mean B against the path tracer's on the run's own elements.

`radwalk solve SCENE OPTIONS` writes its final elements (.vtp, CSV with each element's material); the reference
is `radwalk pathtrace` of that .vtp with --spp N (as bench/target_error.py). Per material m, over its reflecting
non-emitting elements the path tracer sees, all channels together:
  mean   = sum_i A_i sum_c B_ic / sum_i A_i            (the run's, and the path tracer's likewise)
  d      = mean_run / mean_pt - 1
  sigma  = sqrt(s_run^2 + s_pt^2) / mean_pt,  s_run = sum_i A_i sum_c B_se_ic / (3 sum A) (the run's statistical
           errors added as if fully correlated: a bound whatever their correlation), s_pt = sqrt(sum_i A_i^2
           sum_c se_ic^2) / (3 sum A) (the path tracer's elements are independent);
  ok     = |d| <= max(2 %, 2.5 sigma)   (the issue's criterion);
  sigma_ind: the same with the run's elements taken as independent (sqrt(sum A^2 B_se^2)), for comparison: the
           hierarchical replicates' leaves are positively correlated within a replicate, so the truth lies between.
  And the run's own error bar of each material's mean, from its JSON (target_error.groups, else
  error_estimate.materials; solve/group_mean_error.h): stat (its statistical part, of kind first-order or bound),
  bound (the statistical bound), bar = sqrt(total^2 + (s_pt / mean_pt)^2) (its total error with the path tracer's
  noise) and |d| / bar.
Example (the furniture room of tests/realmesh, in metres):
  python3 bench/per_material.py --scene DIR/furniture_room.obj --spp 4096 --run "--hierarchical --target-error 0.02"
"""
import argparse
import collections
import csv
import json
import math
import os
import shlex
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import target_error as te  # noqa: E402  (its table reading and matching of the rows)

import numpy as np  # noqa: E402


def main():
    here = os.path.dirname(os.path.abspath(__file__))
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--radwalk", default=os.path.join(here, "..", "build", "apps", "radwalk"))
    p.add_argument("--scene", required=True)
    p.add_argument("--run", required=True, help="options of the solve")
    p.add_argument("--spp", type=int, default=4096)
    p.add_argument("--seed", type=int, default=1)
    p.add_argument("--keep", default="", help="a directory to keep the run's files in")
    p.add_argument("--reuse", action="store_true", help="with --keep: read the files kept there, run nothing")
    a = p.parse_args()
    with tempfile.TemporaryDirectory() as tmp:
        d = a.keep or tmp
        os.makedirs(d, exist_ok=True)
        vtp, run_csv, pt_csv = (os.path.join(d, n) for n in ("run.vtp", "run.csv", "pt.csv"))
        code, cpu = (0, float("nan")) if a.reuse else te.cpu_of([a.radwalk, "solve", a.scene, "-q", "--seed", str(a.seed), "-o", vtp, "--csv", run_csv,
                               "--json", os.path.join(d, "run.json")] + shlex.split(a.run))
        if code not in (0, 1):
            raise SystemExit("the solve failed with exit code %d" % code)
        a.reuse or subprocess.run([a.radwalk, "pathtrace", vtp, "--spp", str(a.spp), "--seed", str(1000 + a.seed), "--csv", pt_csv,
                        "-q", "--open-shells", "one-sided"], check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        r, pt, unmatched = te.matched(te.table(run_csv), te.table(pt_csv))
        rows = list(csv.DictReader(open(run_csv)))
        # The materials of the matched rows, in the same order as te.matched keeps them.
        key = te.table(run_csv)["key"]
        scale = np.abs(key[:, :3]).max()
        ptkey = te.table(pt_csv)["key"]
        rk = lambda k: [tuple(x) for x in np.round(np.hstack([k[:, :3] / scale, k[:, 3:]]) * 1e6).astype(np.int64)]
        found = np.array([k in set(rk(ptkey)) for k in rk(key)])
        material = np.array([row["material"] for row in rows])[found]
        e, _, noise, _ = te.measured_error(run_csv, pt_csv)
        print("run: %s %s; %d elements, CPU %.1f s, measured e %.4f (pt noise %.4f)%s" % (
            os.path.basename(a.scene), a.run, len(rows), cpu, e, noise,
            "" if unmatched == 0 else ", %d elements not in the path tracer's reading" % unmatched))
        run_json = json.load(open(os.path.join(d, "run.json")))
        own = run_json.get("target_error", {}).get("groups") or run_json.get("error_estimate", {}).get("materials") or []
        own = {g["name"]: g for g in own}
        print("%-12s %8s %10s %10s %8s %8s %11s %4s %8s %8s %8s %7s" % (
            "material", "elements", "mean", "mean_pt", "d %", "sigma %", "sigma_ind %", "ok", "stat %", "bound %",
            "bar %", "|d|/bar"))
        keep = (pt["E"].max(1) == 0) & (pt["rho"].max(1) > 0)
        groups = collections.OrderedDict()
        for i, m in enumerate(material):
            if keep[i]:
                groups.setdefault(m, []).append(i)
        worst = worst_bar = 0.0
        for m, idx in groups.items():
            idx = np.array(idx)
            A = r["area"][idx]
            S = A.sum()
            mean = float((A[:, None] * r["B"][idx]).sum() / (3 * S))
            mean_pt = float((A[:, None] * pt["B"][idx]).sum() / (3 * S))
            s_run = float((A[:, None] * r["B_se"][idx]).sum() / (3 * S))
            s_pt = math.sqrt(float((A[:, None] ** 2 * pt["B_se"][idx] ** 2).sum())) / (3 * S)
            s_ind = math.sqrt(float((A[:, None] ** 2 * r["B_se"][idx] ** 2).sum())) / (3 * S)
            dd = mean / mean_pt - 1
            sigma = math.sqrt(s_run ** 2 + s_pt ** 2) / mean_pt
            ok = abs(dd) <= max(0.02, 2.5 * sigma)
            worst = max(worst, abs(dd) / max(0.02, 2.5 * sigma))
            g = own.get(m)
            columns = ""
            if g:
                bar = math.sqrt(g["total"] ** 2 + (s_pt / mean_pt) ** 2)
                worst_bar = max(worst_bar, abs(dd) / bar)
                columns = " %8.2f %8.2f %8.2f %7.2f %s" % (100 * g["statistical"], 100 * g.get("statistical_bound", g["statistical"]),
                                                      100 * bar, abs(dd) / bar, g.get("statistical_kind", ""))
            print("%-12s %8d %10.4g %10.4g %+8.2f %8.2f %11.2f %4s%s" % (
                m, len(idx), mean, mean_pt, 100 * dd, 100 * sigma, 100 * math.sqrt(s_ind ** 2 + s_pt ** 2) / mean_pt,
                "yes" if ok else "NO", columns))
        print("largest |d| / max(2 %%, 2.5 sigma) = %.2f" % worst)
        if own:
            print("largest |d| / bar = %.2f (the run's own error bar of each mean with the path tracer's noise)" % worst_bar)


if __name__ == "__main__":
    sys.exit(main())
