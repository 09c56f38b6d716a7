#!/usr/bin/env python3
"""Per material: a run's area-weighted mean B against the path tracer's on the run's own elements.

`radwalk solve SCENE OPTIONS` writes its final elements (.vtp, CSV with each element's material); the reference
is `radwalk pathtrace` of that .vtp with --spp N (as bench/target_error.py). Per material m, over each table's own
reflecting non-emitting elements (the path tracer may split the .vtp's faces otherwise; a material's mean does not
depend on the tiling), all channels together (scripts/patch_comparison.py, material_means):
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
import json
import math
import os
import shlex
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import target_error as te  # noqa: E402  (cpu_of)
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "scripts"))
import patch_comparison as pc  # noqa: E402  (the tables, their matching, the measured error, the material means)


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
        run, pt = pc.read_table(run_csv), pc.read_table(pt_csv)
        _, _, unmatched = pc.matched(run, pt)
        e, _, noise, _ = pc.measured_error(run, pt)
        print("run: %s %s; %d elements, CPU %.1f s, measured e %.4f (pt noise %.4f)%s" % (
            os.path.basename(a.scene), a.run, len(run["row"]), cpu, e, noise,
            "" if unmatched == 0 else ", %d elements not in the path tracer's reading" % unmatched))
        run_json = json.load(open(os.path.join(d, "run.json")))
        own = run_json.get("target_error", {}).get("groups") or run_json.get("error_estimate", {}).get("materials") or []
        own = {g["name"]: g for g in own}
        print("%-12s %8s %10s %10s %8s %8s %11s %4s %8s %8s %8s %7s" % (
            "material", "elements", "mean", "mean_pt", "d %", "sigma %", "sigma_ind %", "ok", "stat %", "bound %",
            "bar %", "|d|/bar"))
        worst = worst_bar = 0.0
        for m, g in pc.material_means(run, pt).items():
            ok = abs(g.d) <= max(0.02, 2.5 * g.sigma)
            worst = max(worst, abs(g.d) / max(0.02, 2.5 * g.sigma))
            columns = ""
            o = own.get(m)
            if o:
                # The run's own error bar of the mean with the path tracer's noise of it.
                bar = math.sqrt(o["total"] ** 2 + g.s_ref_rel ** 2)
                worst_bar = max(worst_bar, abs(g.d) / bar)
                columns = " %8.2f %8.2f %8.2f %7.2f %s" % (
                    100 * o["statistical"], 100 * o.get("statistical_bound", o["statistical"]), 100 * bar,
                    abs(g.d) / bar, o.get("statistical_kind", ""))
            print("%-12s %8d %10.4g %10.4g %+8.2f %8.2f %11.2f %4s%s" % (
                m, g.elements, g.mean, g.mean_ref, 100 * g.d, 100 * g.sigma, 100 * g.sigma_ind, "yes" if ok else "NO",
                columns))
        print("largest |d| / max(2 %%, 2.5 sigma) = %.2f" % worst)
        if own:
            print("largest |d| / bar = %.2f (the run's own error bar of each mean with the path tracer's noise)" % worst_bar)


if __name__ == "__main__":
    sys.exit(main())
