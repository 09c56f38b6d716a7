#!/usr/bin/python3
"""Measurements of a sensor: walks from the sensor, from the sources, importance-driven, or solve everywhere.

For sensors of growing size on the floor of the Cornell box (1 patch, 2, 4, ... up to the whole floor and then
every white patch), measures M = <R, B>_A with each method of `radwalk measure` and reports its efficiency (the median time of --repeat runs)
M^2 / (per-walk variance x seconds per walk) (relative: walks per
second needed for a relative error of 1 is its inverse): the exact per-walk variance (--theory, matrix kernel) where it is
finite, the sample variance otherwise (marked). The same form factors (one `radwalk formfactors` run) serve every
method. Writes adjoint.csv (raw data) and adjoint.png (efficiency against sensor area) to --out.

Run from the repository root after building:
    /usr/bin/python3 scripts/experiments/adjoint.py --out results/adjoint
"""

import argparse
import csv
import json
import math
import os
import subprocess
import sys
import time

REPO = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
METHODS = [
    ("gather-collision", "from the sensor, collision", {}),
    ("gather-expected-value", "from the sensor, expected value", {}),
    ("shoot-collision", "from the sources (= solve everywhere, then <R, B>)", {}),
    ("importance-gather", "importance from the sensor (2 sweeps)", {"--importance-sweeps": "2"}),
    ("importance-shoot", "importance from the sources (2 sweeps)", {"--importance-sweeps": "2"}),
]


def run(cmd, log):
    log.write(" ".join(cmd) + "\n")
    r = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    if r.returncode != 0:
        sys.exit("adjoint.py: radwalk failed (%d): %s\n%s" % (r.returncode, " ".join(cmd), r.stderr.strip()))
    return r


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--radwalk", default=os.environ.get("RADWALK", os.path.join(REPO, "build", "apps", "radwalk")))
    p.add_argument("--out", default=os.path.join("results", "adjoint"))
    p.add_argument("--threads", type=int, default=1, help="threads per radwalk run (default 1: timings per core)")
    p.add_argument("--seed", type=int, default=1)
    p.add_argument("--scale", type=float, default=1.0, help="multiplies the walk count (default 100,000)")
    p.add_argument("--max-edge", type=float, default=100.0)
    p.add_argument("--repeat", type=int, default=3, help="runs per point; the timing is their median (default 3)")
    args = p.parse_args()
    os.makedirs(args.out, exist_ok=True)
    log = open(os.path.join(args.out, "commands.txt"), "w")
    scene = os.path.join(REPO, "meshes", "cornell_box.obj")
    common = [scene, "--max-edge", str(args.max_edge), "--threads", str(args.threads), "--seed", str(args.seed), "-q"]

    # The patches (centroids, normals, materials) and one F for every run.
    patches_csv = os.path.join(args.out, "patches.csv")
    run([args.radwalk, "patch"] + common + ["-o", os.path.join(args.out, "patches.vtp"), "--csv", patches_csv], log)
    F = os.path.join(args.out, "F.mtx")
    run([args.radwalk, "formfactors"] + common + ["--rays", "2000", "-o", F], log)
    rows = list(csv.DictReader(open(patches_csv)))
    floor = [r for r in rows if float(r["ny"]) > 0.99 and float(r["cy"]) < 1e-6 and float(r["E_r"]) == 0]
    white = [r for r in rows if abs(float(r["rho_r"]) - float(rows[int(floor[0]["patch"])]["rho_r"])) < 1e-12
             and float(r["E_r"]) == 0]
    # Sensors: the floor patches nearest the floor's centre, 1, 2, 4, ..., then the whole floor, then every white
    # patch.
    cx = sum(float(r["cx"]) for r in floor) / len(floor)
    cz = sum(float(r["cz"]) for r in floor) / len(floor)
    floor.sort(key=lambda r: (float(r["cx"]) - cx) ** 2 + (float(r["cz"]) - cz) ** 2)
    sizes, n = [], 1
    while n < len(floor):
        sizes.append(("floor", n))
        n *= 2
    sizes += [("floor", len(floor)), ("white", len(white))]

    walks = max(1000, int(100000 * args.scale))

    def point(response, method, extra, **row):
        """One method on one response: the median time of --repeat runs, the exact variance where finite."""
        out = os.path.join(args.out, "m.json")
        cmd = [args.radwalk, "measure"] + common + ["--form-factors", F, "--response", response, "--method", method,
                                                    "--walks", str(walks), "--theory", "--json", out]
        for k, v in extra.items():
            cmd += [k, v]
        seconds = []
        for _ in range(max(1, args.repeat)):
            run(cmd, log)
            m = json.load(open(out))["measurement"]
            seconds.append(m["seconds"])
        m["seconds"] = sorted(seconds)[len(seconds) // 2]
        var_t = m.get("var_per_walk_theory") or [None] * 3
        exact = var_t[0] is not None and math.isfinite(var_t[0])
        var = var_t[0] if exact else m["var_per_walk"][0]
        per_walk = m["seconds"] / (m["walks_total"] * (3 if method.startswith("importance") else 1))
        efficiency = m["M"][0] ** 2 / (var * per_walk) if var > 0 else float("inf")
        return dict(row, method=method, M_r=m["M"][0], se_r=m["M_se"][0], var_per_walk_r=var,
                    rel_var_per_walk_r=var / m["M"][0] ** 2, variance_exact=int(exact), seconds=m["seconds"],
                    walks=m["walks_total"], seconds_per_walk=per_walk, efficiency=efficiency)

    def sensor_file(patches):
        path = os.path.join(args.out, "sensor.csv")
        with open(path, "w") as f:
            f.write("patch,w\n")
            for r in patches:
                f.write("%s,1\n" % r["patch"])
        return "csv:%s:w" % path

    table = []
    sweeps = [0, 1, 2, 4, 8, 16]
    total = len(sizes) * len(METHODS) + len(METHODS) + 2 * 2 * len(sweeps)
    done = 0
    start = time.time()

    def progress():
        nonlocal done
        done += 1
        print("adjoint.py: %d/%d points, %.0f s elapsed" % (done, total, time.time() - start), file=sys.stderr)

    for kind, n in sizes:
        sensor = floor[:n] if kind == "floor" else white
        area = sum(float(r["area"]) for r in sensor)
        for method, label, extra in METHODS:
            table.append(point(sensor_file(sensor), method, extra, sensor=kind, patches=n, area=area, sweeps=""))
            progress()
    # The camera's view (the scene's default camera, 64 x 64 pixels): M is the mean pixel radiance.
    camera = []
    for method, label, extra in METHODS:
        camera.append(point("camera", method, dict(extra, **{"--width": "64", "--height": "64"}), sensor="camera",
                            patches="", area="", sweeps=""))
        progress()
    # The importance's quality: K Jacobi sweeps (defensive 0.1), for one floor patch and for the white patches.
    quality = []
    for kind, sensor in (("floor", floor[:1]), ("white", white)):
        for method in ("importance-gather", "importance-shoot"):
            for k in sweeps:
                quality.append(point(sensor_file(sensor), method, {"--importance-sweeps": str(k)}, sensor=kind,
                                     patches=len(sensor), area="", sweeps=k))
                progress()
    with open(os.path.join(args.out, "adjoint.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(table[0].keys()))
        w.writeheader()
        w.writerows(table + camera + quality)

    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, (ax, bx) = plt.subplots(1, 2, figsize=(13, 4.8), gridspec_kw={"width_ratios": [1.4, 1]})
    for method, label, _ in METHODS:
        pts = [t for t in table if t["method"] == method]
        xs = [t["area"] / 1e6 for t in pts]
        ys = [t["efficiency"] for t in pts]
        line, = ax.plot(xs, ys, marker="o", label=label)
        for t, x, y in zip(pts, xs, ys):
            if not t["variance_exact"]:
                ax.plot([x], [y], marker="x", color="k", markersize=9)
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("sensor area (m$^2$; Cornell box in mm, 1 m$^2$ = 10$^6$ mm$^2$)")
    ax.set_ylabel("relative efficiency M$^2$ / (variance per walk x s per walk)")
    ax.set_title("Measuring one sensor: red channel, %d patches, 1 thread" % len(rows))
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8, title="x: exact variance infinite (sample variance shown)", title_fontsize=8)
    for kind, style in (("floor", "-"), ("white", "--")):
        for method, colour in (("importance-gather", "C3"), ("importance-shoot", "C4")):
            pts = [q for q in quality if q["sensor"] == kind and q["method"] == method]
            bx.plot([q["sweeps"] for q in pts], [q["rel_var_per_walk_r"] for q in pts], style, color=colour,
                    marker="o", label="%s, %s" % (method, "one floor patch" if kind == "floor" else "white patches"))
            for q in pts:
                if not q["variance_exact"]:
                    bx.plot([q["sweeps"]], [q["rel_var_per_walk_r"]], marker="x", color="k", markersize=9)
    bx.set_xscale("symlog", linthresh=1)
    bx.set_yscale("log")
    bx.set_xlabel("importance from K Jacobi sweeps (defensive fraction 0.1)")
    bx.set_ylabel("relative variance per walk, var / M$^2$")
    bx.set_title("The variance falls as the importance improves")
    bx.grid(True, which="both", alpha=0.3)
    bx.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(os.path.join(args.out, "adjoint.png"), dpi=120)
    for c in camera:
        print("adjoint.py: camera view, %s: M = %.4g, relative variance per walk %.3g, efficiency %.3g"
              % (c["method"], c["M_r"], c["rel_var_per_walk_r"], c["efficiency"]), file=sys.stderr)
    print("adjoint.py: wrote %s and %s" % (os.path.join(args.out, "adjoint.csv"), os.path.join(args.out, "adjoint.png")),
          file=sys.stderr)


if __name__ == "__main__":
    main()
