#!/usr/bin/env python3
"""How far the path tracer's stated B_se holds, by its variance of the variance (VOV).

Runs `radwalk pathtrace SCENE --spp N --seed s --csv` for s = 1..S and, per patch, channel and seed k, the z-score
of B_k against the mean of the other S - 1 seeds:
  z = (B_k - mean_{j != k} B_j) / sqrt(se_k^2 + sum_j se_j^2 / (S (S - 1)))
(the second term the variance of the others' mean, from the seeds' mean stated variance). Where B_se is honest z
has unit variance and |z| > 3 in 0.27 % of cases (normal). The table groups the cases by that seed's own VOV
(B_vov), so it shows whether a large VOV marks the estimates whose stated error is not to be trusted; then per
material the spread of the material's mean over the seeds against its stated error (the mean over the seeds of
sqrt(sum A_i^2 se_i^2) / sum A_i, channel g).
Example (the leaves of a furniture-room run):
  radwalk solve furniture_room.obj --target-error 0.02 --seed 2 -o leaves.vtp
  python3 bench/pathtrace_standard_error.py --scene leaves.vtp --spp 1024 --seeds 8
  python3 bench/pathtrace_standard_error.py --scene meshes/cornell_box.obj --spp 256 \
      --options "--integrator implicit --max-edge 100"
"""
import argparse
import csv
import math
import os
import shlex
import subprocess
import tempfile

BINS = [(0, 0.01), (0.01, 0.03), (0.03, 0.1), (0.1, 0.2), (0.2, math.inf)]


def main():
    here = os.path.dirname(os.path.abspath(__file__))
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--scene", required=True)
    p.add_argument("--spp", type=int, default=1024)
    p.add_argument("--seeds", type=int, default=8)
    p.add_argument("--options", default="", help="more options for radwalk pathtrace (e.g. '--integrator implicit')")
    p.add_argument("--radwalk", default=os.path.join(here, "..", "build", "apps", "radwalk"))
    a = p.parse_args()
    if a.seeds < 3:
        raise SystemExit("--seeds must be at least 3")
    with tempfile.TemporaryDirectory() as tmp:
        runs = []
        for s in range(1, a.seeds + 1):
            out = os.path.join(tmp, f"pt{s}.csv")
            subprocess.run([a.radwalk, "pathtrace", a.scene, "--spp", str(a.spp), "--seed", str(s), "--csv", out, "-q"]
                           + shlex.split(a.options),
                           check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
            with open(out) as f:
                runs.append(list(csv.DictReader(f)))
    S, n = len(runs), len(runs[0])
    cases = []  # (vov, z)
    for i in range(n):
        for c in "rgb":
            B = [float(r[i]["B_" + c]) for r in runs]
            se = [float(r[i]["B_se_" + c]) for r in runs]
            if max(se) == 0:
                continue
            var_others = sum(x * x for x in se) / (S * (S - 1))
            for k in range(S):
                m = (sum(B) - B[k]) / (S - 1)
                cases.append((float(runs[k][i]["vov_" + c]), (B[k] - m) / math.sqrt(se[k] ** 2 + var_others)))
    print(f"{a.scene} {a.options}: {n} patches, {a.spp} samples, {S} seeds")
    print("| VOV | cases | rms z | abs(z) > 3 |")
    print("|---|---|---|---|")
    for lo, hi in BINS:
        zs = [z for v, z in cases if lo <= v < hi]
        if not zs:
            continue
        big = sum(abs(z) > 3 for z in zs)
        print(f"| [{lo}, {hi}) | {len(zs)} | {math.sqrt(sum(z * z for z in zs) / len(zs)):.2f} | "
              f"{big} ({100 * big / len(zs):.2f} %) |")
    print("\n| material | patches | mean spread / stated | largest VOV |")
    print("|---|---|---|---|")
    for mat in sorted({r["material"] for r in runs[0]}):
        idx = [i for i in range(n) if runs[0][i]["material"] == mat]
        A = [float(runs[0][i]["area"]) for i in idx]
        means = [sum(x * float(r[i]["B_g"]) for x, i in zip(A, idx)) / sum(A) for r in runs]
        stated = [math.sqrt(sum((x * float(r[i]["B_se_g"])) ** 2 for x, i in zip(A, idx))) / sum(A) for r in runs]
        mm = sum(means) / S
        spread = math.sqrt(sum((x - mm) ** 2 for x in means) / (S - 1))
        rms_stated = math.sqrt(sum(x * x for x in stated) / S)
        vov = max(float(r[i]["vov_g"]) for r in runs for i in idx)
        print(f"| {mat} | {len(idx)} | {spread / rms_stated if rms_stated > 0 else 0:.2f} | {vov:.3f} |")


if __name__ == "__main__":
    main()
