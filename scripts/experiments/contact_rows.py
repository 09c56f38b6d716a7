#!/usr/bin/python3
"""The bottom row of the Cornell box's block sides against the path tracer, with and without the contact cut.

For each setting (--contact-cut: the floor cut along the block footprints, and the default without), on the same
patches:
  discrete   = radwalk solve --max-edge L with --rays rays per patch;
  continuous = radwalk pathtrace --max-edge L patch averages with --spp samples per patch (with standard errors).
The bottom row: patches of the blocks' side faces (vertical, off the floor) whose centroid is below --row-height.
Prints per patch the relative error (B_discrete - B_continuous) / B_continuous of the channel sum, and its z.
It runs on the Python module (radwalk.load(..., contact_cut=...)) and prints its figures (no chart).
Usage: PYTHONPATH=build/python /usr/bin/python3 scripts/experiments/contact_rows.py [--max-edge 100] [--rays 20000]
       [--spp 4096]
       [--row-height 50] [--threads T] [--seed S] [--scale K] [--out results/contact_rows]
"""
import argparse
import csv
import os

import numpy as np

import radwalk


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--scene", default="meshes/cornell_box.obj")
    p.add_argument("--max-edge", type=float, default=100)
    p.add_argument("--rays", type=int, default=20000)
    p.add_argument("--spp", type=int, default=4096)
    p.add_argument("--row-height", type=float, default=50.0)
    p.add_argument("--out", default="results/contact_rows")
    p.add_argument("--threads", type=int, default=0, help="threads (default 0: all cores)")
    p.add_argument("--seed", type=int, default=1, help="seeds S (form factors) and S + 2 (path tracer)")
    p.add_argument("--scale", type=float, default=1, help="multiplies --rays and --spp (default 1)")
    a = p.parse_args()
    a.rays, a.spp = max(1, round(a.rays * a.scale)), max(2, round(a.spp * a.scale))
    os.makedirs(a.out, exist_ok=True)
    rows = []
    for label, cut in (("contact cut", True), ("no contact cut", False)):
        print(f"{label}: solving and path tracing ...", flush=True)
        scene = radwalk.load(a.scene, max_edge=a.max_edge, contact_cut=cut)
        discrete = radwalk.solve(scene, radwalk.form_factors(scene, rays=a.rays, seed=a.seed, threads=a.threads),
                                 threads=a.threads)
        continuous = radwalk.pathtrace(scene, spp=a.spp, seed=a.seed + 2, threads=a.threads).averages
        c, n = scene.centroids, scene.normals
        vertical = np.abs(n[:, 1]) < 1e-6
        wall = (c[:, 0] < 1) | (c[:, 0] > 549) | (c[:, 2] > 559)
        row = np.flatnonzero(vertical & ~wall & (c[:, 1] <= a.row_height))
        bd, bp = discrete.B[row].sum(axis=1), continuous.B[row].sum(axis=1)
        se = np.sqrt((continuous.B_se[row] ** 2).sum(axis=1))
        rel, z = (bd - bp) / bp, (bd - bp) / se
        rows += [{"setting": label, "patch": int(i), "face": int(scene.face[i]), "relative_error": r, "z": zz}
                 for i, r, zz in zip(row, rel, z)]
        print(f"{label} ({a.rays} rays/patch, {a.spp} spp): {len(row)} bottom-row patches; relative error of the discrete "
              f"solve, min {rel.min():+.4f}, mean {rel.mean():+.4f}, max {rel.max():+.4f}; |z| max {np.abs(z).max():.1f}")
    with open(os.path.join(a.out, "contact_rows.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0]))
        w.writeheader()
        w.writerows(rows)

if __name__ == "__main__":
    main()
