#!/usr/bin/python3
"""Adaptive patching against uniform patching (default scene: the Cornell box): error against patch count.

Meshes compared (same form-factor budget, --rays rays per patch, seed S, direct or Gauss-Seidel solve), on the
Python module radwalk (the scene read once per mesh, nothing written in between):
  uniform   radwalk.solve(radwalk.load(scene, max_edge=L))       for each L in --max-edges (0 = the input faces)
  adaptive  radwalk.solve_adaptive(input faces, refine_tol=TOL, steps=K)   for each TOL in --tols
            (the CLI's `radwalk solve --refine TOL --refine-steps K`)

Error measure (comparable across meshes): every solution is a piecewise-constant function on the surfaces. It is
compared with the continuous solution on one common fine grid: the path tracer's patch averages B_ref on the
uniform --ref-max-edge L_ref patches (--ref-spp samples per patch, seed S + 1000, with standard errors se). Each
fine cell takes the value of the mesh patch that contains its centroid (same input face; point-in-convex-polygon
on the patch plane). Then
    raw^2   = sum_cells,c A (B_mesh - B_ref)^2 / sum A B_ref^2          (area-weighted, over cells and channels)
    noise^2 = sum_cells,c A se^2            / sum A B_ref^2          (the reference's own noise, expected in raw^2)
    error   = sqrt(max(raw^2 - noise^2, 0))                           (relative L2 error of the mesh's solution)
so `error` is the relative L2 distance between the mesh's piecewise-constant radiosity and the true radiosity,
resolved at the fine grid's scale; it includes the mesh's form-factor noise. Errors near `noise` are not resolved
(the chart's grey band). Left out: cells hidden inside the blocks (B_ref = 0 in every channel) and the light's
cells (E > 0: their B is E plus a little reflected light, and E would dominate the norm).

Writes OUT/adaptive_patching.csv (raw data), OUT/adaptive_patching.png (log-log error against patches) and the
.vtp of every mesh (colour by B; the adaptive ones also carry the criterion's `jump` field).
Usage: /usr/bin/python3 scripts/experiments/adaptive_patching.py [--max-edges 0,200,100,50,35,25]
       [--tols 0.4,0.3,0.2,0.15] [--refine-steps 5] [--rays 10000] [--ref-max-edge 10] [--ref-spp 2048]
       [--scale K] [--threads T] [--seed S] [--out results/adaptive_patching] [--replot]
"""
import math
import os

import numpy as np

import rwexp

radwalk = rwexp.import_radwalk()


def polygons(scene):
    """The corners of every patch (k x 3 arrays, k = 3 or 4), from the Scene's points and corners."""
    points, corners = scene.points, scene.corners
    return [points[c[:3] if c[3] < 0 else c] for c in corners]


def map_to_cells(patch_polygons, face, B, cell_face, cell_centroid):
    """B of the patch (same input face) containing each cell centroid; nearest patch centroid if none does."""
    out = np.full((len(cell_face), 3), np.nan)
    by_face = {}
    for k, f in enumerate(face):
        by_face.setdefault(int(f), []).append(k)
    for f, patches in by_face.items():
        cells = np.nonzero(cell_face == f)[0]
        if len(cells) == 0:
            continue
        q = cell_centroid[cells]
        for k in patches:
            P = patch_polygons[k]
            n = sum(np.cross(P[a], P[(a + 1) % len(P)]) for a in range(len(P)))  # Newell's normal
            size = np.linalg.norm(P - P.mean(axis=0), axis=1).max()
            inside = np.ones(len(q), dtype=bool)
            for a in range(len(P)):
                e = P[(a + 1) % len(P)] - P[a]
                side = np.cross(e, q - P[a]) @ n / (np.linalg.norm(n) * np.linalg.norm(e))
                inside &= side >= -1e-9 * size
            out[cells[inside]] = B[k]
        missing = cells[np.isnan(out[cells, 0])]
        if len(missing):
            centres = np.array([patch_polygons[k].mean(axis=0) for k in patches])
            d = np.linalg.norm(cell_centroid[missing][:, None, :] - centres[None, :, :], axis=2)
            out[missing] = B[np.array(patches)[d.argmin(axis=1)]]
    return out


FIELDS = ["kind", "param", "patches", "solves", "ff_seconds", "solve_seconds", "error", "raw_error", "ref_noise",
          "ref_max_edge", "stop"]


def main():
    p = rwexp.parser("adaptive_patching", __doc__)
    p.add_argument("--scene", default=os.path.join(rwexp.MESHES, "cornell_box.obj"))
    p.add_argument("--max-edges", default="0,200,100,50,35,25", help="uniform meshes (mm; 0 = input faces)")
    p.add_argument("--tols", default="0.4,0.3,0.2,0.15", help="adaptive meshes: refine_tol (--refine TOL)")
    p.add_argument("--refine-steps", type=int, default=5)
    p.add_argument("--max-patches", type=int, default=20000)
    p.add_argument("--rays", type=int, default=10000, help="form-factor rays per patch (every mesh)")
    p.add_argument("--ref-max-edge", type=float, default=10, help="reference grid (mm)")
    p.add_argument("--ref-spp", type=int, default=2048, help="path-tracer samples per reference cell")
    p.add_argument("--scale", type=float, default=1, help="multiplies --rays and --ref-spp (default 1)")
    p.add_argument("--replot", action="store_true", help="redraw the chart from OUT/adaptive_patching.csv")
    a = p.parse_args()
    out = rwexp.Folder(a.out)
    if a.replot:
        plot(rwexp.read_table(out.path("adaptive_patching.csv")), out, a.scene)
        return
    rays = max(1, round(a.rays * a.scale))
    ref_spp = max(2, round(a.ref_spp * a.scale))

    # Reference: path-traced averages on the fine grid.
    ref_scene = radwalk.load(a.scene, max_edge=a.ref_max_edge)
    print(f"reference: {len(ref_scene)} cells, {ref_spp} samples each ...", flush=True)
    ref = radwalk.pathtrace(ref_scene, spp=ref_spp, seed=a.seed + 1000, threads=a.threads).averages
    radwalk.write_csv(out.path("reference.csv"), ref_scene, ref.fields)
    cell_face, cell_centroid = np.asarray(ref_scene.face), np.asarray(ref_scene.centroids)
    B_ref, se_ref = np.asarray(ref.B), np.asarray(ref.B_se)
    keep = (B_ref > 0).any(axis=1) & (np.asarray(ref_scene.E) == 0).all(axis=1)  # not hidden, not the light
    w = np.asarray(ref_scene.areas)[keep][:, None]
    norm = float(np.sum(w * B_ref[keep] ** 2))
    noise2 = float(np.sum(w * se_ref[keep] ** 2)) / norm
    print(f"reference: {int((~keep).sum())} cells hidden or emitting, {ref.seconds:.1f} s, relative noise "
          f"{math.sqrt(noise2):.4f}", flush=True)

    def row(kind, param, scene, result, ff_seconds, solves, stop, extra_fields):
        mapped = map_to_cells(polygons(scene), np.asarray(scene.face), np.asarray(result.B), cell_face,
                              cell_centroid)
        raw2 = float(np.sum(w * (mapped[keep] - B_ref[keep]) ** 2)) / norm
        radwalk.write_vtp(out.path(f"{kind}_{param}.vtp"), scene, {**extra_fields, **result.fields},
                          {"kind": kind, "param": str(param), "rays_per_patch": rays, "seed": a.seed})
        r = dict(kind=kind, param=param, patches=len(scene), solves=solves, ff_seconds=ff_seconds,
                 solve_seconds=result.seconds, error=math.sqrt(max(raw2 - noise2, 0.0)), raw_error=math.sqrt(raw2),
                 ref_noise=math.sqrt(noise2), ref_max_edge=a.ref_max_edge, stop=stop)
        print(rwexp.table([r], FIELDS).splitlines()[-1], flush=True)
        return r

    results = []
    print(rwexp.table([], FIELDS))
    for L in a.max_edges.split(","):
        scene = radwalk.load(a.scene, max_edge=float(L))
        ff = radwalk.form_factors(scene, rays=rays, seed=a.seed, threads=a.threads)
        s = radwalk.solve(scene, ff, threads=a.threads)
        results.append(row("uniform", L, scene, s, ff.timings["form_factors"], 1, "", {}))
    base = radwalk.load(a.scene)
    for tol in a.tols.split(","):
        ad = radwalk.solve_adaptive(base, refine_tol=float(tol), steps=a.refine_steps, max_patches=a.max_patches,
                                    rays=rays, seed=a.seed, threads=a.threads)
        results.append(row("adaptive", tol, ad.scene, ad.result, ad.result.timings["form_factors"], len(ad.steps),
                           ad.stop_reason, {"jump": ad.jump}))
    rwexp.write_csv(out.path("adaptive_patching.csv"), results, FIELDS)
    print(f"wrote {out.path('adaptive_patching.csv')}")
    plot(results, out, a.scene)


def plot(results, out, scene):
    plt = rwexp.plt
    fig, ax = plt.subplots(figsize=(6.4, 4.6))
    noise = float(results[0]["ref_noise"])
    n_all = [float(r["patches"]) for r in results]
    ax.axhspan(1e-9, noise, color="0.85", zorder=0, label=f"below the reference's noise ({noise:.3f})")
    for kind, style, label, key in (("uniform", "o-", f"uniform patches, max edge L ({rwexp.length_unit(scene)})", "L"),
                                    ("adaptive", "s-", "adaptive (--refine TOL)", "TOL")):
        rows = sorted((r for r in results if r["kind"] == kind), key=lambda r: float(r["patches"]))
        if not rows:
            continue
        x = [float(r["patches"]) for r in rows]
        y = [max(float(r["error"]), noise / 10) for r in rows]  # an unresolved error is drawn at the band
        ax.plot(x, y, style, label=label, zorder=3)
        for k, (r, xi, yi) in enumerate(zip(rows, x, y)):
            param = f"{float(r['param']):g}"
            if kind == "uniform" and float(r["param"]) == 0:
                param = "faces"
            # Uniform labels above the curve; adaptive ones alternately below and above, so neighbours do not
            # overlap.
            dy = 4 if kind == "uniform" else (-12 if k % 2 == 0 else 6)
            ax.annotate(f"{key}={param}" if param != "faces" else "input faces", (xi, yi),
                        textcoords="offset points", xytext=(3, dy), fontsize=8)
    ax.set_xscale("log")
    ax.set_yscale("log")
    errors = [float(r["error"]) for r in results if float(r["error"]) > 0]
    ax.set_ylim(min(noise / 2, min(errors) / 1.5), max(errors + [noise]) * 1.6)
    ax.set_xlim(min(n_all) / 1.4, max(n_all) * 1.6)
    rwexp.log_ticks(ax)
    ax.set_xlabel("patches (final mesh)")
    ax.set_ylabel("relative L2 error of B")
    ax.set_title(f"{os.path.basename(scene)}: adaptive against uniform patching\nerror against path-traced "
                 f"{float(results[0]['ref_max_edge']):g} {rwexp.length_unit(scene)} cells, reference noise removed",
                 fontsize=10)
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8, loc="upper right")
    rwexp.save(fig, out.path("adaptive_patching.png"))


if __name__ == "__main__":
    main()
