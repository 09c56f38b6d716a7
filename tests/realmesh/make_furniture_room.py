#!/usr/bin/env python3
"""Writes a raw "furniture room" OBJ + MTL with the defects of real modelling-tool exports.

Usage: make_furniture_room.py OUT_DIR  ->  OUT_DIR/furniture_room.obj, furniture_room.mtl, furniture_room.json

Debian's sweethome3d-furniture ships 820 furniture models (OBJ + MTL inside .sh3f zip files), but this test
needs none of them: it writes its own room the way exporters do (metres, y up):

  room      a closed 5 m x 2.8 m x 4 m box facing in; the ceiling a 3 x 3 grid around a 1 m x 1 m light in its
            centre (the walls' top edges meet the grid points in T-junctions);
  table     a rounded-rectangle top, a single sheet (a 24-gon, one face, no thickness), on four square legs
            whose bottom faces lie on the floor (contacts) and whose tops are open;
  sofa      an L-profile frame (its two side faces are concave hexagons), standing on the floor, with a 4 x 4 seat
            cushion whose corners are displaced out of plane (16 non-planar quads);
  shelf     two side panels with a chamfered top (pentagons) standing on the floor with their backs against a
            wall (back-to-back contacts), and four boards between them, each a single sheet;
  stool     a 64-sided cylinder (64-gon caps, the bottom one on the floor);
  zero-area triangles, as `assimp export -tri` leaves them (three distinct collinear corners);
  unwelded vertices: every face of the furniture has its own copies of its corners (as exporters split vertices by
            normal or texture coordinate), so nothing is shared by index;
  materials: several, some with one-letter names that are substrings of the MTL keywords (w, e, l, t); one object
            per piece of furniture with groups; the sheets' materials are two-sided (`radwalk_two_sided 1`), as the
            manual recommends for thin parts (docs/two-sided.md).

The JSON manifest lists what was put in (counts per defect, input faces per object, the room's faces as
rectangles), so the test can compute its expectations from it.
"""
import json
import math
import sys
from pathlib import Path

X, Y, Z = 5.0, 2.8, 4.0  # room size (m)


class Obj:
    """Collects vertices (1-based) and faces with their object, group and material."""

    def __init__(self):
        self.v = []
        self.lines = []
        self.faces = {}  # object -> input faces
        self.obj = None
        self.count = {"polygons": 0, "polygon_sides": [], "concave_polygons": 0, "bent_quads": 0, "zero_area": 0,
                      "triangles_from_polygons": 0}

    def vertex(self, p):
        self.v.append(tuple(float(c) for c in p))
        return len(self.v)

    def start(self, obj=None, group=None, material=None):
        if obj is not None:
            self.obj = obj
            self.lines.append("o " + obj)
        if group is not None:
            self.lines.append("g " + group)
        if material is not None:
            self.lines.append("usemtl " + material)

    def face(self, points, weld=None):
        """A face through `points` (counter-clockwise seen from the front); its own vertices unless `weld` gives
        their indices."""
        idx = weld if weld is not None else [self.vertex(p) for p in points]
        self.lines.append("f " + " ".join(str(i) for i in idx))
        self.faces[self.obj] = self.faces.get(self.obj, 0) + 1
        if len(idx) > 4:
            self.count["polygons"] += 1
            self.count["polygon_sides"].append(len(idx))
            self.count["triangles_from_polygons"] += len(idx) - 2


def sub(a, b):
    return [a[k] - b[k] for k in range(3)]


def cross(a, b):
    return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]


def box(o, x0, x1, y0, y1, z0, z1, bottom=True, top=True, skip=()):
    """An axis-aligned box, faces facing out, each face with its own corners (unwelded)."""
    faces = {
        "-y": [(x0, y0, z0), (x1, y0, z0), (x1, y0, z1), (x0, y0, z1)],
        "+y": [(x0, y1, z0), (x0, y1, z1), (x1, y1, z1), (x1, y1, z0)],
        "-z": [(x0, y0, z0), (x0, y1, z0), (x1, y1, z0), (x1, y0, z0)],
        "+z": [(x0, y0, z1), (x1, y0, z1), (x1, y1, z1), (x0, y1, z1)],
        "-x": [(x0, y0, z0), (x0, y0, z1), (x0, y1, z1), (x0, y1, z0)],
        "+x": [(x1, y0, z0), (x1, y1, z0), (x1, y1, z1), (x1, y0, z1)],
    }
    for key, pts in faces.items():
        if (key == "-y" and not bottom) or (key == "+y" and not top) or key in skip:
            continue
        o.face(pts)


def prism(o, profile, axis_lo, axis_hi, plane, skip_edges=()):
    """Extrudes a polygon `profile` of (a, b) points, counter-clockwise seen from the +axis end, along the third
    axis from axis_lo to axis_hi. plane 'zy': profile in (z, y), extruded along x; 'xy': in (x, y), along z.
    Writes the two caps (n-gons) and one quad per profile edge (except skip_edges), faces facing out."""
    def at(p, s):
        a, b = p
        return (s, b, a) if plane == "zy" else (a, b, s)
    n = len(profile)
    hi = [at(p, axis_hi) for p in profile]
    lo = [at(p, axis_lo) for p in reversed(profile)]
    o.face(hi)
    o.face(lo)
    for k in range(n):
        if k in skip_edges:
            continue
        a, b = profile[k], profile[(k + 1) % n]
        o.face([at(a, axis_lo), at(b, axis_lo), at(b, axis_hi), at(a, axis_hi)])


def check_outward(points, centre):
    """True when the face's normal points away from `centre` (a sanity check on the writer's windings)."""
    n = [0.0, 0.0, 0.0]
    for k in range(len(points)):
        c = cross(points[k], points[(k + 1) % len(points)])
        n = [n[i] + c[i] for i in range(3)]
    mid = [sum(p[i] for p in points) / len(points) for i in range(3)]
    return sum(n[i] * (mid[i] - centre[i]) for i in range(3)) > 0


def main():
    out_dir = Path(sys.argv[1])
    out_dir.mkdir(parents=True, exist_ok=True)
    o = Obj()
    o.lines += ["# A raw furniture room, written by tests/realmesh/make_furniture_room.py: n-gons, bent quads,",
                "# zero-area triangles, unwelded vertices, single-sheet parts, objects standing on the floor.",
                "mtllib furniture_room.mtl"]
    room_rects = []  # the room's faces as (side a, side b), for the patch-count expectation

    # --- the room (welded, as a modeller's box), facing in ---
    corner = {}
    for i, p in enumerate([(0, 0, 0), (X, 0, 0), (X, 0, Z), (0, 0, Z), (0, Y, 0), (X, Y, 0), (X, Y, Z), (0, Y, Z)]):
        corner[i] = o.vertex(p)
    gx, gz = [0.0, 2.0, 3.0, X], [0.0, 1.5, 2.5, Z]
    grid = {(ix, iz): o.vertex((gx[ix], Y, gz[iz])) for iz in range(4) for ix in range(4)}
    o.start("room", "floor", "floor")
    o.face(None, weld=[corner[0], corner[3], corner[2], corner[1]])
    room_rects.append((X, Z))
    o.start(None, "walls", "w")
    for q in ([0, 1, 5, 4], [2, 3, 7, 6]):
        o.face(None, weld=[corner[k] for k in q])
        room_rects.append((X, Y))
    for q in ([3, 0, 4, 7], [1, 2, 6, 5]):
        o.face(None, weld=[corner[k] for k in q])
        room_rects.append((Z, Y))
    o.start(None, "ceiling", "e")
    for iz in range(3):
        for ix in range(3):
            if (ix, iz) == (1, 1):
                continue
            o.face(None, weld=[grid[(ix, iz)], grid[(ix + 1, iz)], grid[(ix + 1, iz + 1)], grid[(ix, iz + 1)]])
            room_rects.append((gx[ix + 1] - gx[ix], gz[iz + 1] - gz[iz]))
    o.start(None, "light", "l")
    o.face(None, weld=[grid[(1, 1)], grid[(2, 1)], grid[(2, 2)], grid[(1, 2)]])
    room_rects.append((1.0, 1.0))
    room_faces = sum(o.faces.values())

    # --- table: a single-sheet rounded top (24-gon) on four legs standing on the floor ---
    tx0, tx1, tz0, tz1, ty, r = 1.0, 2.3, 1.3, 2.1, 0.75, 0.08
    top = []
    for cx, cz, a0 in ((tx1 - r, tz0 + r, -90), (tx1 - r, tz1 - r, 0), (tx0 + r, tz1 - r, 90), (tx0 + r, tz0 + r, 180)):
        for k in range(6):
            a = math.radians(a0 + 90 * k / 5)
            top.append((cx + r * math.cos(a), ty, cz + r * math.sin(a)))
    # Counter-clockwise seen from above (+y): in (x, z) with y up that is clockwise in (x, z); reverse.
    top = list(reversed(top))
    assert check_outward(top, (1.65, 0.0, 1.7))
    o.start("table", "top", "t")
    o.face(top)
    o.start(None, "legs", "wood")
    for lx, lz in ((tx0 + 0.1, tz0 + 0.1), (tx1 - 0.15, tz0 + 0.1), (tx0 + 0.1, tz1 - 0.15), (tx1 - 0.15, tz1 - 0.15)):
        box(o, lx, lx + 0.05, 0.0, ty, lz, lz + 0.05, top=False)
    # zero-area triangles along two legs' vertical edges (collinear corners)
    for lx, lz in ((tx0 + 0.1, tz0 + 0.1), (tx1 - 0.15, tz1 - 0.15)):
        o.face([(lx, 0.0, lz), (lx, ty / 2, lz), (lx, ty, lz)])
        o.count["zero_area"] += 1

    # --- sofa: L-profile frame (concave hexagon sides) and a bumpy 4 x 4 seat cushion ---
    sx0, sx1 = 2.8, 4.6
    profile = [(3.0, 0.0), (3.9, 0.0), (3.9, 0.9), (3.75, 0.9), (3.75, 0.45), (3.0, 0.45)]  # (z, y)
    # Seen from +x the (z, y) plane has z pointing to the left: the profile runs counter-clockwise reversed.
    o.start("sofa", "frame", "sofa")
    prism(o, list(reversed(profile)), sx0, sx1, "zy", skip_edges=(0,))
    o.count["concave_polygons"] += 2
    # the seat (the profile's edge (3.75, 0.45) - (3.0, 0.45)) is the cushion
    o.start(None, "cushion", "cushion")
    nx, nz = 4, 4
    lift = 0.03
    seat = {}
    for i in range(nx + 1):
        for j in range(nz + 1):
            x = sx0 + (sx1 - sx0) * i / nx
            z = 3.0 + (3.75 - 3.0) * j / nz
            interior = 0 < i < nx and 0 < j < nz
            seat[(i, j)] = (x, 0.45 + (lift if interior and (i + j) % 2 == 0 else 0.0), z)
    for i in range(nx):
        for j in range(nz):
            o.face([seat[(i, j)], seat[(i, j + 1)], seat[(i + 1, j + 1)], seat[(i + 1, j)]])
            o.count["bent_quads"] += 1
    # zero-area triangles on the cushion's front edge
    for i in range(nx):
        a, b = seat[(i, 0)], seat[(i + 1, 0)]
        o.face([a, [(a[k] + b[k]) / 2 for k in range(3)], b])
        o.count["zero_area"] += 1

    # --- shelf: pentagonal side panels against the wall x = 0, four single-sheet boards ---
    side = [(0.0, 0.0), (0.35, 0.0), (0.35, 1.7), (0.25, 1.8), (0.0, 1.8)]  # (x, y), counter-clockwise from +z
    o.start("shelf", "panels", "wood")
    for z0, z1 in ((0.3, 0.32), (1.28, 1.3)):
        prism(o, side, z0, z1, "xy")
    o.start(None, "boards", "shelf")
    for y in (0.4, 0.8, 1.2, 1.6):
        o.face([(0.0, y, 0.32), (0.0, y, 1.28), (0.35, y, 1.28), (0.35, y, 0.32)])

    # --- stool: a 64-sided cylinder standing on the floor ---
    cx, cz, rad, h, n = 3.7, 1.5, 0.2, 0.45, 64
    ring = [(cx + rad * math.cos(2 * math.pi * k / n), cz + rad * math.sin(2 * math.pi * k / n)) for k in range(n)]
    o.start("stool", None, "stool")
    o.face([(x, h, z) for x, z in reversed(ring)])  # top, facing +y
    o.face([(x, 0.0, z) for x, z in ring])  # bottom, facing -y, on the floor
    for k in range(n):
        (xa, za), (xb, zb) = ring[k], ring[(k + 1) % n]
        o.face([(xa, 0.0, za), (xa, h, za), (xb, h, zb), (xb, 0.0, zb)])

    lines = o.lines[:3] + ["v %.9g %.9g %.9g" % p for p in o.v] + o.lines[3:]
    (out_dir / "furniture_room.obj").write_text("\n".join(lines) + "\n")
    (out_dir / "furniture_room.mtl").write_text(
        "# one-letter names (w, e, l, t) are substrings of the keywords newmtl / usemtl\n"
        "newmtl floor\nKd 0.5 0.42 0.35\n\n"
        "newmtl w\nKd 0.75 0.72 0.68\n\n"
        "newmtl e\nKd 0.8 0.8 0.8\n\n"
        "newmtl l\nKd 0.78 0.78 0.78\nKe 12 11 9\n\n"
        "newmtl t\nKd 0.55 0.35 0.2\nradwalk_two_sided 1\n\n"
        "newmtl wood\nKd 0.45 0.3 0.18\n\n"
        "newmtl sofa\nKd 0.2 0.3 0.6\n\n"
        "newmtl cushion\nKd 0.3 0.45 0.7\n\n"
        "newmtl shelf\nKd 0.65 0.6 0.5\nradwalk_two_sided 1\n\n"
        "newmtl stool\nKd 0.7 0.2 0.15\n")
    furniture = {k: v for k, v in o.faces.items() if k != "room"}
    manifest = dict(o.count)
    manifest.update({"input_faces": sum(o.faces.values()), "room_faces": room_faces, "room_rectangles": room_rects,
                     "furniture_input_faces": sum(furniture.values()), "faces_per_object": o.faces,
                     "materials": ["floor", "w", "e", "l", "t", "wood", "sofa", "cushion", "shelf", "stool"],
                     "two_sided_materials": ["t", "shelf"], "room_size": [X, Y, Z]})
    (out_dir / "furniture_room.json").write_text(json.dumps(manifest, indent=1) + "\n")


if __name__ == "__main__":
    main()
