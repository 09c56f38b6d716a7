#!/usr/bin/env python3
"""CTest (label realmesh): `--target-error 0.02` on the furniture room, per material against the path tracer.

Usage: run_furniture_target.py RADWALK SOURCE_DIR WORK_DIR

`radwalk solve ROOM --target-error 0.02 --target-route R` (R: hierarchical, the default, and uniform; the defaults
otherwise: the contact cut, each material's mean held within the target) writes its final patches (leaves); `radwalk pathtrace` of that .vtp averages the continuous radiosity over the same patches.
Per material m, over each table's own reflecting non-emitting patches (the path tracer, reading the .vtp back, may split
faces otherwise; a material's mean does not depend on the tiling), all channels together (scripts/patch_comparison.py,
material_means, shared with bench/per_material.py):
  d_m = mean_run / mean_pt - 1,
  sigma_m = sqrt(s_run^2 + s_pt^2) / mean_pt   (s_run: the run's B_se added as if fully correlated, a bound;
                                                s_pt: the path tracer's, its patches independent).
Checked:
  1. the issue's criterion |d_m| <= max(2 %, 2.5 sigma_m) for every material, on each route;
  2. the run's own error bar of each material's mean (JSON target_error.groups: total_g, which holds the
     discretisation estimate and the first-order statistical part) covers d_m: |d_m| <= z sqrt(total_g^2 +
     (s_pt / mean_pt)^2), z the two-sided normal quantile at alpha = 0.01 Sidak-corrected over the materials;
  3. a negative control: the uniform route with `--target-each none` (the per-patch target alone, which stops at
     its start) fails criterion 1 on at least one material (the sofa, +5 % measured when this test was written; on
     the hierarchical route the per-patch target alone left it at +2.06 %, too near 2 % for a control).
About 50 s on 2 cores (three solves and three path traces at 4096 samples per patch). Why 4096: at 1024 the path
tracer's stated error of a material's mean understates its spread (the shelf of a 1,995-leaf run over eight seeds:
0.31186 with a spread of 0.0017 for a stated 0.0008, the floor 1.6 times its stated; rare bright paths into the
shelf's cubbies), and one seed read the shelf 1.3 % high, 3.9 stated standard errors.
"""
import json
import math
import os
import statistics
import subprocess
import sys

SPP = "4096"
TARGET = "0.02"
ALPHA = 0.01

failures = []


def expect(condition, what):
    print(("ok: " if condition else "FAILED: ") + what)
    if not condition:
        failures.append(what)


def per_material(radwalk, scene, work, name, options):
    """Solves with options, path traces the result; returns the run's JSON and {material: (d, sigma, s_pt_rel)}."""
    import patch_comparison as pc
    vtp, run_csv, pt_csv, js = (os.path.join(work, name + x) for x in (".vtp", ".csv", "_pt.csv", ".json"))
    r = subprocess.run([radwalk, "solve", scene, "-q", "--seed", "1", "-o", vtp, "--csv", run_csv, "--json", js] +
                       options, capture_output=True, text=True)
    expect(r.returncode == 0, "%s: solve %s exits 0 (%d)" % (name, " ".join(options), r.returncode))
    subprocess.run([radwalk, "pathtrace", vtp, "--spp", SPP, "--seed", "1001", "--csv", pt_csv, "-q",
                    "--open-shells", "one-sided"], check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    run, pt = pc.read_table(run_csv), pc.read_table(pt_csv)
    _, _, unmatched = pc.matched(run, pt)
    out = {m: (g.d, g.sigma, g.s_ref_rel) for m, g in sorted(pc.material_means(run, pt).items())}
    print("%s: %d patches (%d without a patch of the same centroid in the path tracer's reading; the means need none)"
          % (name, len(run["row"]), unmatched))
    return json.load(open(js)), out


def main():
    radwalk, source_dir, work = sys.argv[1], sys.argv[2], sys.argv[3]
    try:
        import numpy  # noqa: F401
    except ImportError:
        print("SKIPPED: needs python3-numpy")
        return 77
    sys.path.insert(0, os.path.join(source_dir, "scripts"))
    os.makedirs(work, exist_ok=True)
    subprocess.run([sys.executable, os.path.join(source_dir, "tests/realmesh/make_furniture_room.py"), work],
                   check=True, stdout=subprocess.DEVNULL)
    scene = os.path.join(work, "furniture_room.obj")

    for route in ("hierarchical", "uniform"):
        j, means = per_material(radwalk, scene, work, route, ["--target-error", TARGET, "--target-route", route])
        t = j["target_error"]
        expect(t["reached"] and t["each"] == "material" and t["route"] == route,
               "%s: the run reached its target holding each material's mean" % route)
        bars = {g["name"]: g["total"] for g in t["groups"]}
        z = statistics.NormalDist().inv_cdf(1 - (1 - (1 - ALPHA) ** (1.0 / len(means))) / 2)
        print("%-10s %8s %8s %9s %8s" % ("material", "d %", "sigma %", "bar %", "z"))
        for m, (d, sigma, s_pt) in means.items():
            bar = math.hypot(bars.get(m, float("nan")), s_pt)
            print("%-10s %+8.2f %8.2f %9.2f %8.2f" % (m, 100 * d, 100 * sigma, 100 * bar, abs(d) / bar))
            expect(abs(d) <= max(0.02, 2.5 * sigma), "%s, %s: |d| %.2f %% <= max(2 %%, 2.5 sigma = %.2f %%)"
                   % (route, m, 100 * abs(d), 250 * sigma))
            expect(abs(d) <= z * bar, "%s, %s: its own error bar covers d (|d| / bar %.2f <= z %.2f)"
                   % (route, m, abs(d) / bar, z))

    _, control = per_material(radwalk, scene, work, "none",
                              ["--target-error", TARGET, "--target-route", "uniform", "--target-each", "none"])
    failing = [m for m, (d, sigma, _) in control.items() if abs(d) > max(0.02, 2.5 * sigma)]
    print("--target-each none: d = %s" % ", ".join("%s %+.2f %%" % (m, 100 * v[0]) for m, v in control.items()))
    expect(len(failing) > 0, "negative control: the per-patch target alone leaves a material outside (%s)"
           % ", ".join(failing))
    if failures:
        print("%d check(s) failed" % len(failures))
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
