#!/usr/bin/env python3
"""Writes a closed room around the Stanford bunny of Debian's glmark2-data.

Usage: make_bunny_room.py BUNNY_OBJ OUT_DIR  ->  OUT_DIR/bunny_room.obj + OUT_DIR/bunny_room.mtl

The room is 4 m x 3 m x 4 m (x, y up, z), its walls facing in; the ceiling is a 3 x 3 grid whose centre cell
(1 m x 1 m) is the light (Ke 5, so E = 5 pi W/m^2), so the walls' top edges meet the ceiling's grid points in
T-junctions (notes, harmless). The bunny (69,666 triangles, no MTL; y up) is scaled to 1 m high, centred on the
floor and lifted 1 mm off it (its base then touches nothing). Its vertices and faces are copied as they are
(normals and texture coordinates dropped); it gets the material 'bunny' (rho 0.6), floor and walls 'wall'
(rho 0.7, 0.65, 0.6), the ceiling 'ceiling' (rho 0.75), the light 'light' (rho 0.78).
"""
import sys
from pathlib import Path


def main():
    bunny_path, out_dir = Path(sys.argv[1]), Path(sys.argv[2])
    out_dir.mkdir(parents=True, exist_ok=True)
    vertices, faces = [], []
    for line in bunny_path.read_text().splitlines():
        t = line.split()
        if not t:
            continue
        if t[0] == "v":
            vertices.append([float(x) for x in t[1:4]])
        elif t[0] == "f":
            faces.append([int(c.split("/")[0]) for c in t[1:]])
    lo = [min(v[k] for v in vertices) for k in range(3)]
    hi = [max(v[k] for v in vertices) for k in range(3)]
    scale = 1.0 / (hi[1] - lo[1])
    centre = [(lo[k] + hi[k]) / 2 for k in range(3)]
    room = (4.0, 3.0, 4.0)
    def place(v):
        return (2.0 + (v[0] - centre[0]) * scale, 0.001 + (v[1] - lo[1]) * scale, 2.0 + (v[2] - centre[2]) * scale)

    out = ["# A closed room around the Stanford bunny (glmark2-data), written by tests/realmesh/make_bunny_room.py.",
           "mtllib bunny_room.mtl"]
    X, Y, Z = room
    room_v = [(0, 0, 0), (X, 0, 0), (X, 0, Z), (0, 0, Z), (0, Y, 0), (X, Y, 0), (X, Y, Z), (0, Y, Z)]
    # Ceiling grid points (x, z) at 0, 1.5, 2.5, 4.
    grid = [0.0, 1.5, 2.5, 4.0]
    ceiling_v = [(x, Y, z) for z in grid for x in grid]  # index 8 + 4 * iz + ix
    for v in room_v + ceiling_v:
        out.append("v %r %r %r" % v)
    n_room = len(room_v) + len(ceiling_v)
    for v in vertices:
        out.append("v %.9g %.9g %.9g" % place(v))
    def c(ix, iz):
        return 9 + 4 * iz + ix  # 1-based
    out += ["o room", "g floor", "usemtl wall", "f 1 4 3 2"]  # facing up (+y)
    out += ["g walls",
            "f 1 2 6 5",   # z = 0, facing +z
            "f 3 4 8 7",   # z = Z, facing -z
            "f 4 1 5 8",   # x = 0, facing +x
            "f 2 3 7 6"]   # x = X, facing -x
    out += ["g ceiling"]
    for iz in range(3):
        for ix in range(3):
            if (ix, iz) == (1, 1):
                continue
            out += ["usemtl ceiling", "f %d %d %d %d" % (c(ix, iz), c(ix + 1, iz), c(ix + 1, iz + 1), c(ix, iz + 1))]
    out += ["g light", "usemtl light", "f %d %d %d %d" % (c(1, 1), c(2, 1), c(2, 2), c(1, 2))]
    out += ["o bunny", "usemtl bunny"]
    for f in faces:
        out.append("f " + " ".join(str(i + n_room if i > 0 else i) for i in f))
    (out_dir / "bunny_room.obj").write_text("\n".join(out) + "\n")
    (out_dir / "bunny_room.mtl").write_text(
        "newmtl wall\nKd 0.7 0.65 0.6\n\nnewmtl ceiling\nKd 0.75 0.75 0.75\n\n"
        "newmtl light\nKd 0.78 0.78 0.78\nKe 5 5 5\n\nnewmtl bunny\nKd 0.6 0.6 0.6\n")


if __name__ == "__main__":
    main()
