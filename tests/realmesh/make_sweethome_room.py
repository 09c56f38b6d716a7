#!/usr/bin/env python3
"""Builds a closed room furnished with raw models of Debian's sweethome3d-furniture (tests/realmesh).

Usage: make_sweethome_room.py FURNITURE_DIR WORK_DIR  -> WORK_DIR/room.obj and a JSON of what each model holds

Each model's OBJ statements are copied as written (faces with 2 corners, repeated corners, back-to-back faces,
self-intersecting polygons, textures with Kd 1 stay as the exporter wrote them); the only changes are what putting
ten files into one room needs: vertices scaled so that the model's largest extent is 120 cm and moved onto a spot
of the floor (y up, as the models are), absolute vertex indices offset by the vertices before the model, and
material names prefixed with the model's name (each model's MTL is copied beside its textures with the names
prefixed, its map_Kd lines untouched). The room (12 m x 3 m x 6 m, in cm) is written inside out, its faces
pointing outwards, and a 2 m x 2 m light panel hangs 10 cm below the ceiling, facing down.
Written per model: its input face range and its area as drawn, 1/2 |sum_k p_k x p_(k+1)| per face (Newell) over
its f statements after scaling.
"""
import json
import os
import re
import shutil
import sys
import zipfile

# (archive, model directory): the defects each brings are in the test's docstring.
MODELS = [
    ("KatorLegaz.sh3f", "cafe-chair"),
    ("BlendSwap-CC-0.sh3f", "cupcake"),
    ("KatorLegaz.sh3f", "filing-cabinet"),
    ("BlendSwap-CC-0.sh3f", "islandExtension"),
    ("KatorLegaz.sh3f", "painted-bench"),
    ("BlendSwap-CC-0.sh3f", "stove"),
    ("BlendSwap-CC-0.sh3f", "tatami"),
    ("BlendSwap-CC-0.sh3f", "wardrobeWithSlidingDoors"),
    ("KatorLegaz.sh3f", "full-bookcase"),
    ("BlendSwap-CC-0.sh3f", "tableWithTablecloth"),
]
SIZE = 120.0  # cm
ROOM = (1200.0, 300.0, 600.0)


def newell_area(points):
    sx = sy = sz = 0.0
    n = len(points)
    for k in range(n):
        a, b = points[k], points[(k + 1) % n]
        sx += a[1] * b[2] - a[2] * b[1]
        sy += a[2] * b[0] - a[0] * b[2]
        sz += a[0] * b[1] - a[1] * b[0]
    return 0.5 * (sx * sx + sy * sy + sz * sz) ** 0.5


def main(furniture, work):
    os.makedirs(work, exist_ok=True)
    out = ["# a closed room furnished with raw sweethome3d-furniture models (make_sweethome_room.py)",
           "mtllib room.mtl"]
    with open(os.path.join(work, "room.mtl"), "w") as f:
        f.write("newmtl room_wall\nKd 0.6 0.6 0.6\nnewmtl room_light\nKd 0.5 0.5 0.5\nKe 10 10 10\n")
    vertices = 0
    faces = 0
    info = []
    for slot, (archive, name) in enumerate(MODELS):
        z = zipfile.ZipFile(os.path.join(furniture, archive))
        members = [m for m in z.namelist() if m.split("/")[1:2] == [name] and not m.endswith("/")]
        model_dir = os.path.join(work, name)
        os.makedirs(model_dir, exist_ok=True)
        obj_text = None
        for m in members:
            data = z.read(m)
            base = m.split("/")[-1]
            if base.lower().endswith(".obj"):
                obj_text = data.decode("latin-1")
            elif base.lower().endswith(".mtl"):
                text = data.decode("latin-1")
                text = re.sub(r"^(\s*newmtl\s+)(.*)$", lambda g: g.group(1) + name + "__" + g.group(2), text, flags=re.M)
                with open(os.path.join(model_dir, base), "w", encoding="latin-1") as f:
                    f.write(text)
            else:
                with open(os.path.join(model_dir, base), "wb") as f:
                    f.write(data)
        lines = obj_text.splitlines()
        coords = [tuple(float(x) for x in l.split()[1:4]) for l in lines if l.split()[:1] == ["v"]]
        lo = [min(c[k] for c in coords) for k in range(3)]
        hi = [max(c[k] for c in coords) for k in range(3)]
        scale = SIZE / max(hi[k] - lo[k] for k in range(3))
        # Slots on a 5 x 2 grid, 2.2 m apart, standing on the floor (y = 0).
        cx = 150.0 + (slot % 5) * 220.0
        cz = 150.0 + (slot // 5) * 300.0
        shift = (cx - scale * 0.5 * (lo[0] + hi[0]), -scale * lo[1], cz - scale * 0.5 * (lo[2] + hi[2]))
        placed = []
        first_face = faces
        area = 0.0
        out.append("o " + name)
        for l in lines:
            t = l.split()
            if not t:
                out.append(l)
                continue
            if t[0] == "v":
                p = tuple(scale * float(t[k + 1]) + shift[k] for k in range(3))
                placed.append(p)
                out.append("v %.9g %.9g %.9g" % p)
            elif t[0] == "f":
                corners = []
                refs = []
                for c in t[1:]:
                    i = int(c.split("/")[0])
                    refs.append(str(i + vertices) if i > 0 else str(i))
                    corners.append(i - 1 if i > 0 else len(placed) + i)
                out.append("f " + " ".join(refs))
                if len(corners) >= 3:
                    area += newell_area([placed[c] for c in corners])
                faces += 1
            elif t[0] == "usemtl":
                out.append("usemtl " + name + "__" + l.split(None, 1)[1].strip())
            elif t[0] == "mtllib":
                out.append("mtllib " + name + "/" + l.split(None, 1)[1].strip())
            elif t[0] in ("o", "g"):
                out.append(t[0] + " " + name + "/" + (l.split(None, 1)[1].strip() if len(t) > 1 else ""))
            else:
                out.append(l)
        vertices += len(placed)
        info.append({"model": archive + ":" + name, "name": name, "first_face": first_face, "end_face": faces,
                     "area_as_drawn_cm2": area})
    # The room, inside out (faces pointing out of the box), and the light panel facing down.
    X, Y, Z = ROOM
    box = [(0, 0, 0), (X, 0, 0), (0, Y, 0), (X, Y, 0), (0, 0, Z), (X, 0, Z), (0, Y, Z), (X, Y, Z)]
    out.append("o room")
    out.append("usemtl room_wall")
    for p in box:
        out.append("v %g %g %g" % p)
    b = vertices
    for q in [(0, 4, 6, 2), (1, 3, 7, 5), (0, 1, 5, 4), (2, 6, 7, 3), (0, 2, 3, 1), (4, 5, 7, 6)]:  # outward
        out.append("f " + " ".join(str(b + 1 + k) for k in q))
    vertices += 8
    out.append("o light")
    out.append("usemtl room_light")
    y = Y - 10
    for p in [(500, y, 200), (700, y, 200), (700, y, 400), (500, y, 400)]:
        out.append("v %g %g %g" % p)
    out.append("f %d %d %d %d" % (vertices + 1, vertices + 2, vertices + 3, vertices + 4))  # normal -y
    with open(os.path.join(work, "room.obj"), "w", encoding="latin-1") as f:
        f.write("\n".join(out) + "\n")
    with open(os.path.join(work, "models.json"), "w") as f:
        json.dump(info, f, indent=1)


if __name__ == "__main__":
    main(sys.argv[1], sys.argv[2])
