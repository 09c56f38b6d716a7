#!/usr/bin/python3
"""Discretisation error: the discrete radiosity solution against the continuous path tracer, as patches shrink.

For each --max-edge L, on the same patches (the Python module radwalk: each scene loaded once):
  discrete   = radwalk.solve (direct or Gauss-Seidel) of F estimated with --rays rays per patch, twice with
               seeds S and S + 1 (their difference measures the form-factor noise);
  continuous = radwalk.pathtrace patch averages with --spp samples per patch, seed S + 2 (with standard errors).
Error measure: area-weighted RMS over patches and channels of (B_discrete - B_continuous), relative to the
area-weighted RMS of B_continuous, both over the reflecting patches only: emitters (E > 0) are left out, since
their B is mostly their own emission (exact in both models) and would dominate the RMS of B, and so are patches
whose rays hit the back of another patch (hidden under the blocks). The statistical floor of that difference is sqrt(ff_noise^2 + pt_noise^2); what exceeds it is the
discretisation error (constant radiosity per patch).

Writes OUT/discretisation.csv and discretisation.png, and per L the per-patch CSVs of the three solutions
(discrete_s1_L.csv, discrete_s2_L.csv: as `radwalk solve --csv`; pathtrace_L.csv: as `radwalk pathtrace --csv`).
The chart (discretisation.png): the measured difference, the discretisation error (what exceeds the noise floor;
an open triangle on the floor where it does not) and the noise floor as a grey band, against patch count.
Usage: /usr/bin/python3 scripts/experiments/discretisation_error.py [--max-edges 0,200,100,50,25] [--rays 20000]
       [--spp 4096] [--scale K] [--seed S] [--threads T] [--out results/discretisation] [--replot]
"""
import argparse
import csv
import math
import os

import numpy as np

import rwexp

radwalk = rwexp.import_radwalk()


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--scene", default="meshes/cornell_box.obj")
    p.add_argument("--max-edges", default="0,200,100,50,25", help="patch levels, mm (0: the input faces)")
    p.add_argument("--rays", type=int, default=20000, help="rays per patch of each F (default 20000)")
    p.add_argument("--spp", type=int, default=4096, help="path-traced samples per patch (default 4096)")
    p.add_argument("--scale", type=float, default=1, help="multiplies --rays and --spp (default 1)")
    p.add_argument("--seed", type=int, default=1, help="seeds S, S + 1 (form factors) and S + 2 (path tracer)")
    p.add_argument("--threads", type=int, default=0, help="threads (default 0: all cores)")
    p.add_argument("--out", default="results/discretisation")
    p.add_argument("--replot", action="store_true", help="redraw the chart from OUT/discretisation.csv")
    a = p.parse_args()
    if a.replot:
        rows = rwexp.read_table(os.path.join(a.out, "discretisation.csv"))
        plot(rows, a, int(rows[0]["rays"]), int(rows[0]["spp"]))
        return
    os.makedirs(a.out, exist_ok=True)
    rays, spp = max(1, round(a.rays * a.scale)), max(2, round(a.spp * a.scale))

    rows = []
    for L in a.max_edges.split(","):
        scene = radwalk.load(a.scene, max_edge=float(L))
        solutions = []
        for k, seed in enumerate((a.seed, a.seed + 1)):
            ff = radwalk.form_factors(scene, rays=rays, seed=seed, threads=a.threads)
            s = radwalk.solve(scene, ff, threads=a.threads)
            radwalk.write_csv(os.path.join(a.out, f"discrete_s{k + 1}_{L}.csv"), scene, {**ff.diagnostics, **s.fields})
            solutions.append((s.B, ff.back_hits))
        pt = radwalk.pathtrace(scene, spp=spp, seed=a.seed + 2, threads=a.threads).averages
        radwalk.write_csv(os.path.join(a.out, f"pathtrace_{L}.csv"), scene, pt.fields)
        (B1, back1), (B2, back2) = solutions
        num = ff_var = se2 = den = area = 0.0
        for i in range(len(scene)):
            if back1[i] > 0 or back2[i] > 0:
                continue
            if (scene.E[i] > 0).any():
                continue  # emitters: their B is mostly E, which both models have exactly
            A = float(scene.areas[i])
            area += A
            for c in range(3):
                b1, b2, bp = float(B1[i, c]), float(B2[i, c]), float(pt.B[i, c])
                num += A * (b1 - bp) ** 2
                ff_var += A * (b1 - b2) ** 2 / 2  # variance of one discrete solution from form-factor noise
                se2 += A * float(pt.B_se[i, c]) ** 2
                den += A * bp ** 2
        rel = lambda v: math.sqrt(v / den)
        floor = math.sqrt((ff_var + se2) / den)
        excess = math.sqrt(max(num - ff_var - se2, 0.0) / den)
        rows.append({"max_edge": L, "rays": rays, "spp": spp, "patches": len(scene), "rms_rel_difference": rel(num), "ff_noise": rel(ff_var),
                     "pt_noise": rel(se2), "noise_floor": floor, "discretisation": excess})
        print(f"max edge {L:>5}: {len(scene):6d} patches, RMS relative difference {rel(num):.4f}, "
              f"noise floor {floor:.4f} (form factors {rel(ff_var):.4f}, path tracer {rel(se2):.4f}), "
              f"discretisation {excess:.4f}", flush=True)

    with open(os.path.join(a.out, "discretisation.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0]))
        w.writeheader()
        w.writerows(rows)

    plot(rows, a, rays, spp)


def plot(rows, a, rays, spp):
    plt = rwexp.plt
    n = np.array([r["patches"] for r in rows], dtype=float)
    floor = np.array([r["noise_floor"] for r in rows])
    measured = np.array([r["rms_rel_difference"] for r in rows])
    excess = np.array([r["discretisation"] for r in rows])
    fig, ax = plt.subplots(figsize=(6.4, 5.4))
    ax.fill_between(n, floor / 100, floor, color="0.85", step=None, zorder=0,
                    label="noise floor (form factors + path tracer)")
    ax.plot(n, measured, "o-", color="tab:blue", label="measured: discrete - continuous")
    ok = excess > 0
    ax.plot(n[ok], excess[ok], "s-", color="tab:red", label="discretisation error: sqrt(measured$^2$ - floor$^2$)")
    if (~ok).any():
        ax.plot(n[~ok], floor[~ok], "v", color="tab:red", mfc="white", ms=8, linestyle="none",
                label="not resolved (measured below the floor)")
    for x, y, r in zip(n, measured, rows):
        L = float(r["max_edge"])
        ax.annotate("input faces" if L == 0 else f"L = {L:g} {rwexp.length_unit(a.scene)}", (x, y),
                    textcoords="offset points", xytext=(4, 5), fontsize=8)
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlim(n.min() / 1.5, n.max() * 1.8)
    lo = min([floor.min()] + list(excess[ok]))
    ax.set_ylim(lo / 1.6, measured.max() * 1.8)
    rwexp.log_ticks(ax)
    ax.set_xlabel("patches (uniform, max edge L)")
    ax.set_ylabel("area-weighted RMS difference / RMS B")
    ax.set_title(f"{os.path.basename(a.scene)}: discrete against continuous radiosity\n"
                 f"F of {rays} rays/patch (two seeds), path tracer {spp} samples/patch", fontsize=10)
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8, loc="upper center", bbox_to_anchor=(0.5, -0.16), ncol=2, frameon=False)
    fig.tight_layout()
    fig.savefig(os.path.join(a.out, "discretisation.png"), dpi=120)
    rwexp.plt.close(fig)
    print("wrote", os.path.join(a.out, "discretisation.csv"), "and discretisation.png")


if __name__ == "__main__":
    main()
