#!/usr/bin/python3
"""Discretisation error: the discrete radiosity solution against the continuous path tracer, as patches shrink.

For each --max-edge L, on the same patches:
  discrete   = radwalk solve (direct or Gauss-Seidel) of F estimated with --rays rays per patch, twice with
               different seeds (their difference measures the form-factor noise);
  continuous = radwalk pathtrace patch averages with --spp samples per patch (with standard errors).
Error measure: area-weighted RMS over patches and channels of (B_discrete - B_continuous), relative to the
area-weighted RMS of B_continuous, both over the reflecting patches only: emitters (E > 0) are left out, since
their B is mostly their own emission (exact in both models) and would dominate the RMS of B, and so are patches
whose rays hit the back of another patch (hidden under the blocks). The statistical floor of that difference is sqrt(ff_noise^2 + pt_noise^2); what exceeds it is the
discretisation error (constant radiosity per patch).

Writes results/discretisation/discretisation.csv and discretisation.png.
Usage: /usr/bin/python3 scripts/experiments/discretisation_error.py [--max-edges 200,100,50,25] [--rays 4000]
       [--spp 4096] [--radwalk build/apps/radwalk] [--out results/discretisation]
"""
import argparse
import csv
import math
import os
import subprocess


def run(cmd):
    subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL)


def read(path):
    with open(path) as f:
        return list(csv.DictReader(f))


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--scene", default="meshes/cornell_box.obj")
    p.add_argument("--max-edges", default="200,100,50,25")
    p.add_argument("--rays", type=int, default=4000)
    p.add_argument("--spp", type=int, default=4096)
    p.add_argument("--radwalk", default=os.environ.get("RADWALK", "build/apps/radwalk"))
    p.add_argument("--out", default="results/discretisation")
    a = p.parse_args()
    os.makedirs(a.out, exist_ok=True)

    rows = []
    for L in a.max_edges.split(","):
        d1, d2, pt = (os.path.join(a.out, f"{name}_{L}.csv") for name in ("discrete_s1", "discrete_s2", "pathtrace"))
        base = [a.radwalk, "-q"]
        run(base + ["solve", a.scene, "--max-edge", L, "--rays", str(a.rays), "--seed", "1", "--csv", d1])
        run(base + ["solve", a.scene, "--max-edge", L, "--rays", str(a.rays), "--seed", "2", "--csv", d2])
        run(base + ["pathtrace", a.scene, "--max-edge", L, "--spp", str(a.spp), "--seed", "3", "--csv", pt])
        r1, r2, rp = read(d1), read(d2), read(pt)
        num = ff = se2 = den = area = 0.0
        for x, y, z in zip(r1, r2, rp):
            if float(x["back_hits"]) > 0 or float(y["back_hits"]) > 0:
                continue
            if any(float(x["E_" + c]) > 0 for c in "rgb"):
                continue  # emitters: their B is mostly E, which both models have exactly
            A = float(x["area"])
            area += A
            for c in "rgb":
                b1, b2, bp = float(x["B_" + c]), float(y["B_" + c]), float(z["B_" + c])
                num += A * (b1 - bp) ** 2
                ff += A * (b1 - b2) ** 2 / 2  # variance of one discrete solution from form-factor noise
                se2 += A * float(z["B_se_" + c]) ** 2
                den += A * bp ** 2
        rel = lambda v: math.sqrt(v / den)
        floor = math.sqrt((ff + se2) / den)
        excess = math.sqrt(max(num - ff - se2, 0.0) / den)
        rows.append({"max_edge": L, "patches": len(r1), "rms_rel_difference": rel(num), "ff_noise": rel(ff),
                     "pt_noise": rel(se2), "noise_floor": floor, "discretisation": excess})
        print(f"max edge {L:>5}: {len(r1):6d} patches, RMS relative difference {rel(num):.4f}, "
              f"noise floor {floor:.4f} (form factors {rel(ff):.4f}, path tracer {rel(se2):.4f}), "
              f"discretisation {excess:.4f}")

    with open(os.path.join(a.out, "discretisation.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0]))
        w.writeheader()
        w.writerows(rows)

    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    n = [r["patches"] for r in rows]
    fig, ax = plt.subplots(figsize=(6, 4.2))
    ax.loglog(n, [r["rms_rel_difference"] for r in rows], "o-", label="discrete - continuous (measured)")
    ax.loglog(n, [r["discretisation"] for r in rows], "s-", label="discretisation error (measured - noise)")
    ax.loglog(n, [r["noise_floor"] for r in rows], "^--", label="noise floor (form factors + path tracer)")
    ax.set_xlabel("patches")
    ax.set_ylabel("area-weighted RMS difference / RMS B")
    ax.set_title(f"{os.path.basename(a.scene)}: {a.rays} rays/patch, {a.spp} spp")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend()
    fig.tight_layout()
    fig.savefig(os.path.join(a.out, "discretisation.png"), dpi=120)
    print("wrote", os.path.join(a.out, "discretisation.csv"), "and discretisation.png")


if __name__ == "__main__":
    main()
