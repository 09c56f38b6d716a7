#!/usr/bin/env python3
"""What `radwalk solve --target-error E` delivers: its measured error against the path tracer, and its CPU.

For each target E and seed, `radwalk solve SCENE --target-error E` writes its final patches (.vtp) and B; the
continuous reference is `radwalk pathtrace` of that .vtp (the same patches, read back) with --spp N. Printed per
run, over the reflecting non-emitting patches the path tracer sees (B > 0) and their channels:
  patches, rays  - of the last step; steps - solves run;
  e_est          - the run's estimated total error (its JSON's error_estimate.total);
  e              - the measured relative error sqrt(sum A (B - B_pt)^2 / sum A B_pt^2), the path tracer's own
                   noise taken out (sum A B_se_pt^2 subtracted), over the patches matched by centroid and normal;
  e_sd           - the standard deviation of e from the path tracer's noise (both as scripts/patch_comparison.py
                   defines and computes them, shared with bench/per_material.py and the realmesh tests);
  e_stat         - the run's own stated statistical error over the same values (its B_se);
  e_disc         - the measured discretisation error sqrt(max(e^2 - e_stat^2, 0)): the run's noise taken out too,
                   so that runs with different rays a patch compare at equal discretisation error;
  e_disc_sd      - its standard deviation from the path tracer's noise;
  cover, sharp   - the coverage of the run's stated total error B_err (the fraction of values with |B - B_pt| <=
                   1.96 sqrt(B_err^2 + B_se_pt^2): 0.95 if B_err is right) and its sharpness (its RMS over the
                   measured error's: 1 if right), scripts/patch_comparison.py coverage;
  cpu            - user + system CPU seconds of the solve (all its steps).
The same for fixed settings given with --hand (e.g. the README's recommended route at several --max-edge), for
the comparison of CPU at equal measured error. The path tracer reads the .vtp as written (coordinates already
scaled: --scene-options go to the solves only), one-sided (the .vtp holds the back patches the solve made
already: --open-shells one-sided keeps them as they are); the script checks that the patches agree. The target
runs take --target-error's default route (the hierarchical one); --run "--target-route uniform" measures the other.
Example:
  python3 bench/target_error.py --targets 0.03,0.01 --seeds 3 --spp 2048 \\
      --hand "--max-edge 100 --rays 1000" --hand "--max-edge 50 --rays 1000"
"""
import argparse
import json
import os
import resource
import shlex
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "scripts"))
import patch_comparison as pc  # noqa: E402  (the tables, their matching and the measured error)


def cpu_of(cmd):
    """Runs cmd; returns (exit code, CPU seconds of the child)."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    code = subprocess.run(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL).returncode
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    return code, (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)


def main():
    here = os.path.dirname(os.path.abspath(__file__))
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--radwalk", default=os.path.join(here, "..", "build", "apps", "radwalk"))
    p.add_argument("--scene", default=os.path.join(here, "..", "meshes", "cornell_box.obj"))
    p.add_argument("--scene-options", default="", help="options for every command (--unit, --scale, ...)")
    p.add_argument("--targets", default="0.03,0.01")
    p.add_argument("--seeds", type=int, default=3)
    p.add_argument("--first-seed", type=int, default=1, help="the seeds are first-seed .. first-seed + seeds - 1")
    p.add_argument("--spp", type=int, default=2048)
    p.add_argument("--run", default="", help="more options of the --target-error runs (--max-patches, ...)")
    p.add_argument("--hand", action="append", default=[], help="a fixed setting to compare (repeatable)")
    a = p.parse_args()
    scene_options = ["-q"] + shlex.split(a.scene_options)
    runs = [("--target-error %s %s" % (t, a.run)).strip() for t in a.targets.split(",") if t] + a.hand
    print("scene %s %s, path tracer --spp %d on each run's own patches" % (os.path.basename(a.scene), a.scene_options, a.spp))
    print("%-44s %5s %8s %6s %6s %8s %8s %8s %8s %8s %8s %9s %6s %6s %8s" % (
        "run", "seed", "patches", "rays", "steps", "e_est", "e", "e_sd", "pt_noise", "e_stat", "e_disc", "e_disc_sd",
        "cover", "sharp", "cpu_s"))
    with tempfile.TemporaryDirectory() as tmp:
        for options in runs:
            for seed in range(a.first_seed, a.first_seed + a.seeds):
                vtp, run_csv, js, pt_csv = (os.path.join(tmp, n) for n in ("run.vtp", "run.csv", "run.json", "pt.csv"))
                code, cpu = cpu_of([a.radwalk, "solve", a.scene, "--seed", str(seed), "-o", vtp, "--csv", run_csv,
                                    "--json", js] + scene_options + shlex.split(options))
                if code not in (0, 1):
                    print("%-44s %5d failed with exit code %d" % (options, seed, code))
                    continue
                summary = json.load(open(js))
                target = summary.get("target_error", {})
                steps = len(target.get("steps", [])) or 1
                rays = summary.get("rays_per_patch", 0)
                e_est = summary["error_estimate"]["total"]["relative"]
                subprocess.run([a.radwalk, "pathtrace", vtp, "--spp", str(a.spp), "--seed", str(1000 + seed), "--csv",
                                pt_csv, "-q", "--open-shells", "one-sided"], check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
                run_table, pt_table = pc.read_table(run_csv), pc.read_table(pt_csv)
                e, e_sd, noise, unmatched = pc.measured_error(run_table, pt_table)
                e_disc, e_disc_sd, e_stat = pc.measured_discretisation_error(run_table, pt_table)
                cover, _, sharp = pc.coverage(run_table, pt_table)
                print("%-44s %5d %8d %6d %6d %8.4f %8.4f %8.4f %8.4f %8.4f %8.4f %9.4f %6.3f %6.2f %8.2f%s" %
                      (options, seed, summary["patches"], rays, steps, e_est, e, e_sd, noise, e_stat, e_disc,
                       e_disc_sd, cover, sharp, cpu,
                       ("" if code == 0 else "  (target not reached: " + target.get("stop_reason", "?") + ")") +
                       ("" if unmatched == 0 else "  (%d patches not in the path tracer's reading, left out)" % unmatched)))
                sys.stdout.flush()


if __name__ == "__main__":
    sys.exit(main())
