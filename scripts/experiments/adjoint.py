#!/usr/bin/python3
"""Measurements of a sensor: walks from the sensor, from the sources, importance-driven, or solve everywhere.

For sensors of growing size on the floor of the Cornell box (1 patch, 2, 4, ... up to the whole floor and then
every white patch), measures M = <R, B>_A with each method of radwalk.measure (the Python module; the CLI's
`radwalk measure`) and reports its efficiency M^2 / (per-walk variance x seconds per walk) (relative: walks per
second needed for a relative error of 1 is its inverse): the exact per-walk variance (theory, matrix kernel) where
it is finite, the sample variance otherwise (marked). The seconds are the median of --repeat runs (the chart's
bars span the fastest to the slowest). The same form factors (traced once) serve every method. Writes adjoint.csv
(raw data) and adjoint.png (efficiency against sensor area; the variance against the importance's quality) to
--out, and prints one progress line per point.

Run from the repository root after building:
    /usr/bin/python3 scripts/experiments/adjoint.py --out results/adjoint
"""

import math
import os
import sys
import time

import numpy as np

import rwexp

radwalk = rwexp.import_radwalk()
METHODS = [
    ("gather-collision", "from the sensor, collision", {}),
    ("gather-expected-value", "from the sensor, expected value", {}),
    ("shoot-collision", "from the sources (= solve everywhere, then <R, B>)", {}),
    ("importance-gather", "importance from the sensor (2 sweeps)", {"importance_sweeps": 2}),
    ("importance-shoot", "importance from the sources (2 sweeps)", {"importance_sweeps": 2}),
]


def main():
    p = rwexp.parser("adjoint", __doc__)
    p.set_defaults(threads=1)
    p.add_argument("--scale", type=float, default=1.0, help="multiplies the walk count (default 100,000)")
    p.add_argument("--max-edge", type=float, default=100.0, help="patch size (mm, default 100)")
    p.add_argument("--repeat", type=int, default=3, help="runs per point; the timing is their median (default 3)")
    p.add_argument("--replot", action="store_true", help="redraw the chart from OUT/adjoint.csv")
    args = p.parse_args()
    out = rwexp.Folder(args.out)
    if args.replot:
        rows = rwexp.read_table(out.path("adjoint.csv"))
        sized = [r for r in rows if r["sensor"] != "camera" and math.isnan(r["sweeps"])]
        swept = [r for r in rows if math.isfinite(r["sweeps"])]
        plot(sized, swept, int(rows[0]["scene_patches"]), out)
        return
    scene = radwalk.load(os.path.join(rwexp.MESHES, "cornell_box.obj"), max_edge=args.max_edge)
    ff = radwalk.form_factors(scene, rays=2000, seed=args.seed, threads=args.threads)  # one F for every run
    c, n_, E, rho, A = scene.centroids, scene.normals, scene.E, scene.rho, scene.areas
    floor = [i for i in range(len(scene)) if n_[i, 1] > 0.99 and c[i, 1] < 1e-6 and E[i, 0] == 0]
    white = [i for i in range(len(scene)) if abs(rho[i, 0] - rho[floor[0], 0]) < 1e-12 and E[i, 0] == 0]
    # Sensors: the floor patches nearest the floor's centre, 1, 2, 4, ..., then the whole floor, then every white
    # patch.
    cx, cz = np.mean(c[floor, 0]), np.mean(c[floor, 2])
    floor.sort(key=lambda i: (c[i, 0] - cx) ** 2 + (c[i, 2] - cz) ** 2)
    sizes, n = [], 1
    while n < len(floor):
        sizes.append(("floor", n))
        n *= 2
    sizes += [("floor", len(floor)), ("white", len(white))]

    walks = max(1000, int(100000 * args.scale))

    def point(response, method, extra, **row):
        """One method on one response: the median time of --repeat runs, the exact variance where finite."""
        seconds = []
        for _ in range(max(1, args.repeat)):
            m = radwalk.measure(scene, response, ff, method=method, walks=walks, theory=True, seed=args.seed,
                                threads=args.threads, **extra)
            seconds.append(m.seconds)
        med, lo, hi = rwexp.median_spread(seconds)
        exact = math.isfinite(m.var_per_walk_theory[0])
        var = m.var_per_walk_theory[0] if exact else m.var_per_walk[0]
        per_walk = 1 / (m.walks_total * (3 if method.startswith("importance") else 1))
        eff = lambda t: m.M[0] ** 2 / (var * t * per_walk) if var > 0 else float("inf")  # noqa: E731
        return dict(row, scene_patches=len(scene), method=method, M_r=m.M[0], se_r=m.M_se[0], var_per_walk_r=var,
                    rel_var_per_walk_r=var / m.M[0] ** 2, variance_exact=int(exact), seconds=med, seconds_min=lo,
                    seconds_max=hi, walks=m.walks_total, seconds_per_walk=med * per_walk, efficiency=eff(med),
                    efficiency_min=eff(hi), efficiency_max=eff(lo))

    def sensor(patches):
        R = np.zeros(len(scene))
        R[patches] = 1
        return R

    table = []
    sweeps = [0, 1, 2, 4, 8, 16]
    total = len(sizes) * len(METHODS) + len(METHODS) + 2 * 2 * len(sweeps)
    done = 0
    start = time.time()

    def progress():
        nonlocal done
        done += 1
        print("adjoint.py: %d/%d points, %.0f s elapsed" % (done, total, time.time() - start), file=sys.stderr,
              flush=True)

    for kind, n in sizes:
        patch_list = floor[:n] if kind == "floor" else white
        area = float(sum(A[i] for i in patch_list))
        for method, label, extra in METHODS:
            table.append(point(sensor(patch_list), method, extra, sensor=kind, patches=n, area=area, sweeps=""))
            progress()
    # The camera's view (the scene's default camera, 64 x 64 pixels): M is the mean pixel radiance.
    camera = []
    for method, label, extra in METHODS:
        camera.append(point("camera", method, dict(extra, width=64, height=64), sensor="camera",
                            patches="", area="", sweeps=""))
        progress()
    # The importance's quality: K Jacobi sweeps (defensive 0.1), for one floor patch and for the white patches.
    quality = []
    for kind, patch_list in (("floor", floor[:1]), ("white", white)):
        for method in ("importance-gather", "importance-shoot"):
            for k in sweeps:
                quality.append(point(sensor(patch_list), method, {"importance_sweeps": k}, sensor=kind,
                                     patches=len(patch_list), area="", sweeps=k))
                progress()
    rwexp.write_csv(out.path("adjoint.csv"), table + camera + quality, list(table[0].keys()), digits=9)
    plot(table, quality, len(scene), out)
    for c in camera:
        print("adjoint.py: camera view, %s: M = %.4g, relative variance per walk %.3g, efficiency %.3g"
              % (c["method"], c["M_r"], c["rel_var_per_walk_r"], c["efficiency"]), file=sys.stderr)
    print("adjoint.py: wrote %s and %s" % (out.path("adjoint.csv"), out.path("adjoint.png")), file=sys.stderr)


def plot(table, quality, patches, out):
    plt = rwexp.plt
    fig, (ax, bx) = plt.subplots(1, 2, figsize=(13, 6.2), gridspec_kw={"width_ratios": [1.4, 1]})
    for method, label, _ in METHODS:
        pts = [t for t in table if t["method"] == method]
        xs = [t["area"] / 1e6 for t in pts]
        ys = [t["efficiency"] for t in pts]
        err = [[t["efficiency"] - t["efficiency_min"] for t in pts], [t["efficiency_max"] - t["efficiency"] for t in pts]]
        ax.errorbar(xs, ys, yerr=err, marker="o", capsize=2, elinewidth=0.8, label=label)
        for t, x, y in zip(pts, xs, ys):
            if not t["variance_exact"]:
                ax.plot([x], [y], marker="x", color="k", markersize=9)
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("sensor area (m$^2$; Cornell box in mm, 1 m$^2$ = 10$^6$ mm$^2$)")
    ax.set_ylabel("relative efficiency M$^2$ / (variance per walk x s per walk)")
    ax.set_title("Measuring one sensor: red channel, %d patches; bars: fastest to slowest run" % patches,
                 fontsize=10)
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8, title="x: exact variance infinite (sample variance shown)", title_fontsize=8,
              loc="upper center", bbox_to_anchor=(0.5, -0.14), ncol=2, frameon=False)
    for kind, style in (("floor", "-"), ("white", "--")):
        for method, colour in (("importance-gather", "C3"), ("importance-shoot", "C4")):
            pts = [q for q in quality if q["sensor"] == kind and q["method"] == method]
            bx.plot([q["sweeps"] for q in pts], [q["rel_var_per_walk_r"] for q in pts], style, color=colour,
                    marker="o", label="%s, %s" % (method, "one floor patch" if kind == "floor" else "white patches"))
            for q in pts:
                if not q["variance_exact"]:
                    bx.plot([q["sweeps"]], [q["rel_var_per_walk_r"]], marker="x", color="k", markersize=9)
    bx.set_xscale("symlog", linthresh=1)
    ks = sorted({q["sweeps"] for q in quality})
    bx.set_xticks(ks)
    bx.set_xticklabels([f"{k:g}" for k in ks])
    bx.minorticks_off()
    bx.set_yscale("log")
    bx.set_xlabel("importance from K Jacobi sweeps (defensive fraction 0.1)")
    bx.set_ylabel("relative variance per walk, var / M$^2$")
    bx.set_title("The variance falls as the importance improves")
    bx.grid(True, which="both", alpha=0.3)
    bx.legend(fontsize=8, loc="upper center", bbox_to_anchor=(0.5, -0.14), ncol=1, frameon=False)
    rwexp.log_ticks(ax)
    rwexp.log_ticks(bx, x=False)
    fig.tight_layout()
    fig.savefig(out.path("adjoint.png"), dpi=120)
    plt.close(fig)


if __name__ == "__main__":
    main()
