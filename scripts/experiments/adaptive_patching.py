#!/usr/bin/python3
"""Adaptive patching against uniform patching (default scene: the Cornell box): error against patch count.

Meshes compared (same form-factor budget, --rays rays per patch, direct or Gauss-Seidel solve):
  uniform   radwalk solve --max-edge L            for each L in --max-edges (0 = the 37 input faces)
  adaptive  radwalk solve --refine TOL --refine-steps K   for each TOL in --tols, starting from the input faces

Error measure (comparable across meshes): every solution is a piecewise-constant function on the surfaces. It is
compared with the continuous solution on one common fine grid: the path tracer's patch averages B_ref on the
uniform --max-edge L_ref patches (--ref-max-edge, --ref-spp samples per patch, with standard errors se). Each
fine cell takes the value of the mesh patch that contains its centroid (same input face; point-in-convex-polygon
on the patch plane). Then
    raw^2   = sum_cells,c A (B_mesh - B_ref)^2 / sum A B_ref^2          (area-weighted, over cells and channels)
    noise^2 = sum_cells,c A se^2            / sum A B_ref^2          (the reference's own noise, expected in raw^2)
    error   = sqrt(max(raw^2 - noise^2, 0))                           (relative L2 error of the mesh's solution)
so `error` is the relative L2 distance between the mesh's piecewise-constant radiosity and the true radiosity,
resolved at the fine grid's scale; it includes the mesh's form-factor noise. Left out: cells hidden inside the
blocks (B_ref = 0 in every channel) and the light's cells (E > 0: their B is E plus a little reflected light, and
E would dominate the norm).

Writes OUT/adaptive_patching.csv, OUT/adaptive_patching.png (log-log error against patches), the .vtp of every
mesh (colour by B; the adaptive ones also carry the criterion's `jump` field) and commands.txt.
Usage: /usr/bin/python3 scripts/experiments/adaptive_patching.py [--max-edges 0,200,100,50,35,25]
       [--tols 0.4,0.3,0.2,0.15] [--refine-steps 5] [--rays 10000] [--ref-max-edge 10] [--ref-spp 2048]
       [--scale K] [--radwalk build/apps/radwalk] [--out results/adaptive_patching]
"""
import math
import os
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import rwexp  # noqa: E402
from rwexp import plt  # noqa: E402


def read_vtp_patches(path):
    """Polygons (list of k x 3 arrays), input face and B (N x 3) of a radwalk .vtp."""
    import vtk
    from vtk.util.numpy_support import vtk_to_numpy

    reader = vtk.vtkXMLPolyDataReader()
    reader.SetFileName(path)
    reader.Update()
    poly = reader.GetOutput()
    points = vtk_to_numpy(poly.GetPoints().GetData()).astype(float)
    cells = poly.GetPolys()
    offsets = vtk_to_numpy(cells.GetOffsetsArray())
    connectivity = vtk_to_numpy(cells.GetConnectivityArray())
    polygons = [points[connectivity[offsets[k]:offsets[k + 1]]] for k in range(len(offsets) - 1)]
    data = poly.GetCellData()
    face = vtk_to_numpy(data.GetArray("face")).astype(int)
    B = vtk_to_numpy(data.GetArray("B")).astype(float).reshape(-1, 3)
    return polygons, face, B


def map_to_cells(polygons, face, B, cell_face, cell_centroid):
    """B of the patch (same input face) containing each cell centroid; nearest patch centroid if none does."""
    out = np.full((len(cell_face), 3), np.nan)
    by_face = {}
    for k, f in enumerate(face):
        by_face.setdefault(f, []).append(k)
    for f, patches in by_face.items():
        cells = np.nonzero(cell_face == f)[0]
        if len(cells) == 0:
            continue
        q = cell_centroid[cells]
        for k in patches:
            P = polygons[k]
            # Newell's normal: polygons may list T-junction points on their edges (collinear corners).
            n = sum(np.cross(P[a], P[(a + 1) % len(P)]) for a in range(len(P)))
            size = np.linalg.norm(P - P.mean(axis=0), axis=1).max()
            inside = np.ones(len(q), dtype=bool)
            for a in range(len(P)):
                e = P[(a + 1) % len(P)] - P[a]
                side = np.cross(e, q - P[a]) @ n / (np.linalg.norm(n) * np.linalg.norm(e))
                inside &= side >= -1e-9 * size
            out[cells[inside]] = B[k]
        missing = cells[np.isnan(out[cells, 0])]
        if len(missing):
            centres = np.array([polygons[k].mean(axis=0) for k in patches])
            d = np.linalg.norm(cell_centroid[missing][:, None, :] - centres[None, :, :], axis=2)
            out[missing] = B[np.array(patches)[d.argmin(axis=1)]]
    return out


def main():
    p = rwexp.parser("adaptive_patching", __doc__.splitlines()[0])
    p.add_argument("--scene", default=os.path.join(rwexp.MESHES, "cornell_box.obj"))
    p.add_argument("--max-edges", default="0,200,100,50,35,25", help="uniform meshes (mm; 0 = input faces)")
    p.add_argument("--tols", default="0.4,0.3,0.2,0.15", help="adaptive meshes: --refine TOL")
    p.add_argument("--refine-steps", type=int, default=5)
    p.add_argument("--max-patches", type=int, default=20000)
    p.add_argument("--rays", type=int, default=10000, help="form-factor rays per patch (every mesh)")
    p.add_argument("--ref-max-edge", type=float, default=10, help="reference grid (mm)")
    p.add_argument("--ref-spp", type=int, default=2048, help="path-tracer samples per reference cell")
    p.add_argument("--scale", type=float, default=1, help="multiplies --rays and --ref-spp")
    p.add_argument("--plot-only", action="store_true", help="redraw the chart from the CSV")
    a = p.parse_args()
    out_csv = os.path.join(a.out, "adaptive_patching.csv")
    if a.plot_only:
        plot(rwexp.read_csv(out_csv), a.out, a.scene)
        return
    rw = rwexp.Radwalk(a.radwalk, a.out, a.threads)
    rays = str(int(a.rays * a.scale))

    # Reference: path-traced averages on the fine grid.
    ref_csv = rw.path("reference.csv")
    ref = rw.run(["pathtrace", a.scene, "--max-edge", a.ref_max_edge, "--spp", int(a.ref_spp * a.scale),
                  "--seed", a.seed + 1000, "--csv", ref_csv], rw.path("reference.json"))
    rows = rwexp.read_csv(ref_csv)
    cell_face = np.array([r["face"] for r in rows], dtype=int)
    cell_area = np.array([r["area"] for r in rows])
    cell_centroid = np.array([[r["cx"], r["cy"], r["cz"]] for r in rows])
    B_ref = np.array([[r["B_r"], r["B_g"], r["B_b"]] for r in rows])
    se_ref = np.array([[r["B_se_r"], r["B_se_g"], r["B_se_b"]] for r in rows])
    E_ref = np.array([[r["E_r"], r["E_g"], r["E_b"]] for r in rows])
    keep = (B_ref > 0).any(axis=1) & (E_ref == 0).all(axis=1)  # not hidden inside a block, not the light
    w = cell_area[keep][:, None]
    norm = float(np.sum(w * B_ref[keep] ** 2))
    noise2 = float(np.sum(w * se_ref[keep] ** 2)) / norm
    print(f"reference: {len(rows)} cells ({int((~keep).sum())} hidden or emitting), {ref['wall']:.1f} s, "
          f"relative noise {math.sqrt(noise2):.4f}")

    def measure(kind, param, args):
        name = f"{kind}_{param}"
        vtp = rw.path(name + ".vtp")
        r = rw.run(["solve", a.scene, "--rays", rays, "--seed", a.seed, "-o", vtp] + args, rw.path(name + ".json"))
        polygons, face, B = read_vtp_patches(vtp)
        mapped = map_to_cells(polygons, face, B, cell_face, cell_centroid)
        raw2 = float(np.sum(w * (mapped[keep] - B_ref[keep]) ** 2)) / norm
        js = r["json"]
        row = dict(kind=kind, param=param, patches=len(polygons), solves=len(js.get("refine", {}).get("steps", [1])),
                   seconds=r["wall"], error=math.sqrt(max(raw2 - noise2, 0.0)), raw_error=math.sqrt(raw2),
                   ref_noise=math.sqrt(noise2), stop=js.get("refine", {}).get("stop_reason", ""))
        print(rwexp.table([row], list(row.keys())).splitlines()[-1])
        return row

    results = []
    for L in a.max_edges.split(","):
        results.append(measure("uniform", L, ["--max-edge", L]))
    for tol in a.tols.split(","):
        results.append(measure("adaptive", tol, ["--refine", tol, "--refine-steps", a.refine_steps,
                                                 "--max-patches", a.max_patches]))
    fields = ["kind", "param", "patches", "solves", "seconds", "error", "raw_error", "ref_noise", "stop"]
    rwexp.write_csv(out_csv, results, fields)
    print(f"wrote {out_csv}")
    print(rwexp.table(results, fields, "relative L2 error of B against the path-traced fine grid"))
    plot(results, a.out, a.scene)


def plot(results, out, scene):
    fig, ax = plt.subplots(figsize=(6.4, 4.6))
    for kind, style, label, key in (("uniform", "o-", "uniform --max-edge L (mm)", "L"),
                                    ("adaptive", "s-", "adaptive --refine TOL", "TOL")):
        rows = sorted((r for r in results if r["kind"] == kind), key=lambda r: float(r["patches"]))
        if not rows:
            continue
        x = [float(r["patches"]) for r in rows]
        y = [float(r["error"]) for r in rows]
        ax.plot(x, y, style, label=label)
        for r, xi, yi in zip(rows, x, y):
            param = r["param"] if isinstance(r["param"], str) else f"{r['param']:g}"
            ax.annotate(f"{key}={param}", (xi, yi), textcoords="offset points", xytext=(4, 4), fontsize=7)
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("patches (final mesh)")
    ax.set_ylabel("relative L2 error of B (against path-traced fine grid)")
    ax.set_title(f"{os.path.basename(scene)}: adaptive against uniform patching")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend()
    rwexp.save(fig, os.path.join(out, "adaptive_patching.png"))


if __name__ == "__main__":
    main()
