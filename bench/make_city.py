#!/usr/bin/env python3
"""Writes a generated city block for bench_scale and the 10^7-patch runs: a ground plane with a grid of box
buildings of random heights (a fixed seed: the same mesh every time), lit by an emitting "sky" panel facing down
above it. Quads only, one-sided, normals outwards (counter-clockwise seen from outside); buildings have no bottom
face (it would lie on the ground, facing it). Light escapes between the panel and the ground (an open scene).

    bench/make_city.py OUT.obj [--blocks 20] [--seed 1]

writes OUT.obj and OUT.mtl. Units: metres; blocks of 30 m with 10 m streets; heights 6 to 60 m. Patch counts
come from radwalk's --max-edge (e.g. about 10^7 patches at --max-edge 0.5 with 20 x 20 blocks: see
docs/scaling.md)."""
import argparse
import random
from pathlib import Path


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("out")
    ap.add_argument("--blocks", type=int, default=20)
    ap.add_argument("--seed", type=int, default=1)
    a = ap.parse_args()
    rng = random.Random(a.seed)
    out = Path(a.out)
    block, street = 30.0, 10.0
    size = a.blocks * (block + street) + street
    v, faces = [], []

    def quad(material, *corners):
        base = len(v) + 1
        v.extend(corners)
        faces.append((material, [base, base + 1, base + 2, base + 3]))

    # Ground (normal +z) and the sky panel at 100 m (normal -z), both over the whole block.
    quad("ground", (0, 0, 0), (size, 0, 0), (size, size, 0), (0, size, 0))
    quad("sky", (0, 0, 100), (0, size, 100), (size, size, 100), (size, 0, 100))
    for bx in range(a.blocks):
        for by in range(a.blocks):
            x0, y0 = street + bx * (block + street), street + by * (block + street)
            x1, y1 = x0 + block, y0 + block
            h = rng.uniform(6, 60)
            m = rng.choice(["concrete", "brick", "glass"])
            quad(m, (x0, y0, h), (x1, y0, h), (x1, y1, h), (x0, y1, h))  # roof, +z
            quad(m, (x0, y0, 0), (x1, y0, 0), (x1, y0, h), (x0, y0, h))  # -y
            quad(m, (x1, y0, 0), (x1, y1, 0), (x1, y1, h), (x1, y0, h))  # +x
            quad(m, (x1, y1, 0), (x0, y1, 0), (x0, y1, h), (x1, y1, h))  # +y
            quad(m, (x0, y1, 0), (x0, y0, 0), (x0, y0, h), (x0, y1, h))  # -x
    mtl = out.with_suffix(".mtl")
    mtl.write_text(
        "# bench/make_city.py materials: Kd = rho, Ke = emitted radiance\n"
        "newmtl ground\nKd 0.3 0.3 0.3\nKe 0 0 0\n\n"
        "newmtl concrete\nKd 0.6 0.6 0.55\nKe 0 0 0\n\n"
        "newmtl brick\nKd 0.5 0.25 0.2\nKe 0 0 0\n\n"
        "newmtl glass\nKd 0.2 0.25 0.3\nKe 0 0 0\n\n"
        "newmtl sky\nKd 0 0 0\nKe 1 1 1.2\n")
    with open(out, "w") as f:
        f.write(f"# bench/make_city.py --blocks {a.blocks} --seed {a.seed}\nmtllib {mtl.name}\n")
        for p in v:
            f.write("v %g %g %g\n" % p)
        current = None
        for m, idx in faces:
            if m != current:
                f.write(f"usemtl {m}\n")
                current = m
            f.write("f " + " ".join(map(str, idx)) + "\n")


if __name__ == "__main__":
    main()
