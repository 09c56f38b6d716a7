#!/usr/bin/python3
"""The bottom row of the Cornell box's block sides against the path tracer, with and without the contact cut.

For each setting (--contact-cut: the floor cut along the block footprints, and the default without), on the same
patches:
  discrete   = radwalk solve --max-edge L with --rays rays per patch;
  continuous = radwalk pathtrace --max-edge L patch averages with --spp samples per patch (with standard errors).
The bottom row: patches of the blocks' side faces (vertical, off the floor) whose centroid is below --row-height.
Prints per patch the relative error (B_discrete - B_continuous) / B_continuous of the channel sum, and its z.
It runs the radwalk program (not the Python module, whose load has no --contact-cut) and prints its figures (no
chart). Usage: /usr/bin/python3 scripts/experiments/contact_rows.py [--max-edge 100] [--rays 20000] [--spp 4096]
       [--row-height 50] [--threads T] [--seed S] [--scale K] [--radwalk build/apps/radwalk]
       [--out results/contact_rows]
"""
import argparse
import csv
import math
import os
import subprocess


def read(path):
    with open(path) as f:
        return list(csv.DictReader(f))


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--scene", default="meshes/cornell_box.obj")
    p.add_argument("--max-edge", default="100")
    p.add_argument("--rays", type=int, default=20000)
    p.add_argument("--spp", type=int, default=4096)
    p.add_argument("--row-height", type=float, default=50.0)
    p.add_argument("--radwalk", default=os.environ.get("RADWALK", "build/apps/radwalk"))
    p.add_argument("--out", default="results/contact_rows")
    p.add_argument("--threads", type=int, default=0, help="threads (default 0: all cores)")
    p.add_argument("--seed", type=int, default=1, help="seeds S (form factors) and S + 2 (path tracer)")
    p.add_argument("--scale", type=float, default=1, help="multiplies --rays and --spp (default 1)")
    a = p.parse_args()
    a.rays, a.spp = max(1, round(a.rays * a.scale)), max(2, round(a.spp * a.scale))
    os.makedirs(a.out, exist_ok=True)
    for label, extra in (("contact cut", ["--contact-cut"]), ("no contact cut", [])):
        tag = "cut" if not extra else "nocut"
        d, t = os.path.join(a.out, f"solve_{tag}.csv"), os.path.join(a.out, f"pathtrace_{tag}.csv")
        base = [a.radwalk, "-q"]
        scene = [a.scene, "--max-edge", a.max_edge, "--threads", str(a.threads)] + extra
        subprocess.run(base + ["solve"] + scene + ["--rays", str(a.rays), "--seed", str(a.seed), "--csv", d], check=True,
                       stdout=subprocess.DEVNULL)
        subprocess.run(base + ["pathtrace"] + scene + ["--spp", str(a.spp), "--seed", str(a.seed + 2), "--csv", t], check=True,
                       stdout=subprocess.DEVNULL)
        errors = []
        for x, y in zip(read(d), read(t)):
            vertical = abs(float(x["ny"])) < 1e-6
            wall = x["cx"] in ("0", "556") or float(x["cz"]) > 559 or float(x["cx"]) < 1 or float(x["cx"]) > 549
            if not vertical or wall or float(x["cy"]) > a.row_height:
                continue
            bd = sum(float(x["B_" + c]) for c in "rgb")
            bp = sum(float(y["B_" + c]) for c in "rgb")
            se = math.sqrt(sum(float(y["B_se_" + c]) ** 2 for c in "rgb"))
            errors.append(((bd - bp) / bp, (bd - bp) / se, x["patch"], x["face"]))
        print(f"{label} ({a.rays} rays/patch, {a.spp} spp): {len(errors)} bottom-row patches; relative error of the discrete solve, min "
              f"{min(e[0] for e in errors):+.4f}, mean {sum(e[0] for e in errors) / len(errors):+.4f}, max "
              f"{max(e[0] for e in errors):+.4f}; |z| max {max(abs(e[1]) for e in errors):.1f}")


if __name__ == "__main__":
    main()
