#!/usr/bin/python3
"""View factors of a mesh as a scipy.sparse matrix, exported as Matrix Market (.mtx).

Default: two unit squares at a right angle sharing an edge (meshes/perpendicular_squares.obj), whose view factor
has a closed form, F = 0.200043776 (docs/reference data C-14). Writes F.mtx (radwalk's writer, as
`radwalk formfactors -o F.mtx`) and F_scipy.mtx (scipy.io.mmwrite of the same matrix).
"""
import argparse
from pathlib import Path

import numpy as np
import scipy.io
import scipy.sparse

import radwalk

parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
parser.add_argument("--scene", default="meshes/perpendicular_squares.obj", help="scene (default: %(default)s)")
parser.add_argument("--max-edge", type=float, default=0.25, help="patch size (default: %(default)s)")
parser.add_argument("--scale", type=float, default=1.0, help="multiplies the rays per patch (default: 1)")
parser.add_argument("--seed", type=int, default=1, help="random seed (default: 1)")
parser.add_argument("--threads", type=int, default=0, help="threads (default: 0, all cores)")
parser.add_argument("--out", default=".", help="directory of the .mtx files (default: .)")
args = parser.parse_args()

scene = radwalk.load(args.scene, max_edge=args.max_edge)
ff = radwalk.form_factors(scene, rays=max(1, int(100000 * args.scale)), seed=args.seed, threads=args.threads)
F = ff.F  # scipy.sparse.csr_matrix (float32), a view of radwalk's matrix
print(f"{F.shape[0]} patches, {F.nnz} non-zeros, row sums in [{F.sum(axis=1).min():.4f}, {F.sum(axis=1).max():.4f}]")

# Face to face: F_ab = sum over patches i of a, j of b of A_i F_ij / A_a (S: patch -> input face indicator).
S = scipy.sparse.csr_matrix((np.ones(len(scene)), (np.arange(len(scene)), scene.face)))
A = scene.areas
F_faces = scipy.sparse.diags(1 / (S.T @ A)) @ S.T @ scipy.sparse.diags(A) @ F.astype(np.float64) @ S
print("face-to-face view factors:\n", F_faces.toarray().round(5))
if Path(args.scene).name == "perpendicular_squares.obj":
    print(f"F(0 -> 1) = {F_faces[0, 1]:.5f}, closed form 0.20004")

out = Path(args.out)
radwalk.write_matrix_market(out / "F.mtx", ff, scene)
scipy.io.mmwrite(str(out / "F_scipy.mtx"), F)
assert abs(scipy.io.mmread(str(out / "F.mtx")) - F).max() < 1e-6  # the two files hold the same matrix
print(f"wrote {out / 'F.mtx'} and {out / 'F_scipy.mtx'}")
