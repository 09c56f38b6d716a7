#!/usr/bin/env python3
"""The office walk-through of `radwalk exchange` (docs/heat-exchange.md, "Walk-through: an office in winter").

Usage: office_exchange.py [--radwalk BUILD/apps/radwalk] [--work DIR] [--max-edge M] [--rays N] [--solver S]
                          [--build-only] [-- EXTRA radwalk exchange OPTIONS]

Builds a furnished office (5 m x 2.8 m x 4 m, in metres) from Debian's sweethome3d-furniture: a desk with its
hutch, an office chair, a filing cabinet with a printer on it (on 1 mm feet), a full bookcase, a radiator under the
window and a plant, each scaled to the width, height and depth of its furniture catalogue (PluginFurnitureCatalog.properties)
and placed on the floor (or the cabinet). The room's six walls are one conforming grid (the window is a cell of the
window wall, so every edge is shared and the room stays closed). Each model's MTL is copied with the thermal
statements added to every material block (radwalk_emissivity and radwalk_temperature or radwalk_heat_flux; the
table THERMAL below, per object), its textures beside it. Then runs

    radwalk exchange office.obj --max-edge M --rays N --contact-faces exclude --ambient-temperature 293.15
        --group-by object --groups groups.csv
        --group-factors group_factors.csv --csv patches.csv --json exchange.json -o office.vtp

and prints the table per object (area, Q with its standard error, radiant temperature) and the energy balance with
its error bars, from the JSON. The furniture is the installed /usr/share/sweethome3d/furniture, or downloaded with
apt-get download and unpacked with dpkg -x into DIR/.. (tests/realmesh/run_sweethome_room.py's helper).
"""
import argparse
import json
import os
import re
import subprocess
import sys
import time
import zipfile

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "tests", "realmesh"))
from run_sweethome_room import furniture_dir  # noqa: E402

ROOM = (5.0, 2.8, 4.0)              # x (width), y (height, up), z (depth), metres
WINDOW = (1.5, 3.5, 0.9, 2.3)       # x from, x to, y from, y to, on the wall z = 0 (the outside wall)

# Per object: emissivity and either ("T", kelvin) or ("q", W/m^2 net leaving). Room parts first.
THERMAL = {
    "floor": (0.95, ("T", 293.15)),           # screed under linoleum, held by the heated slab's mass
    "ceiling": (0.90, ("T", 293.15)),         # plaster
    "outside_wall": (0.90, ("T", 290.15)),    # the cold wall's inner surface, in winter
    "inside_walls": (0.90, ("q", 0.0)),       # walls to heated offices: adiabatic, re-radiating
    "window": (0.84, ("T", 283.15)),          # the inner pane of double glazing (soda-lime glass, eps 0.84)
    "radiator": (0.95, ("T", 328.15)),        # painted steel panel radiator at 55 C
    "printer": (0.90, ("T", 308.15)),         # a printer's casing at 35 C, warm from standby
    "desk": (0.90, ("q", 0.0)),               # furniture: re-radiating (adiabatic) surfaces
    "office-chair": (0.90, ("q", 0.0)),
    "filing-cabinet": (0.85, ("q", 0.0)),     # painted metal
    "full-bookcase": (0.90, ("q", 0.0)),
    "plant": (0.95, ("q", 0.0)),
}

# (archive, model, object name, x, z, elevation, turn) with (x, z) the footprint centre in metres and turn the
# rotation about the vertical in quarter turns (the catalogue's models face +z).
MODELS = [
    ("KatorLegaz.sh3f", "custom-desk", "desk", 2.8, 3.52, 0.0, 2),
    ("KatorLegaz.sh3f", "office-chair", "office-chair", 2.8, 2.55, 0.0, 2),
    ("KatorLegaz.sh3f", "filing-cabinet", "filing-cabinet", 4.6, 3.6, 0.0, 2),
    ("Scopia.sh3f", "inkjet_and_scanner_printer", "printer", 4.6, 3.6, 0.601, 2),  # on 1 mm feet
    ("KatorLegaz.sh3f", "full-bookcase", "full-bookcase", 0.2, 2.0, 0.0, 1),
    ("BlendSwap-CC-0.sh3f", "radiator", "radiator", 2.5, 0.16, 0.12, 0),
    ("BlendSwap-CC-0.sh3f", "littlePlant", "plant", 4.5, 0.5, 0.0, 0),
]


def catalogue_size(archive_path, model):
    """(width, height, depth) in metres of the catalogue entry whose model is .../model/model.obj."""
    z = zipfile.ZipFile(archive_path)
    props = z.read("PluginFurnitureCatalog.properties").decode("latin-1")
    entries = dict(re.findall(r"^(\w+#\d+)=(.*)$", props, flags=re.M))
    for key, value in entries.items():
        if key.startswith("model#") and value.strip().endswith("/" + model + "/" + model + ".obj"):
            n = key.split("#")[1]
            return tuple(float(entries[k + "#" + n]) / 100.0 for k in ("width", "height", "depth"))
    raise SystemExit("office_exchange.py: %s has no catalogue entry for %s" % (archive_path, model))


# Models whose faces are drawn one-sided although their backs are seen (open drawers and shelves, back-to-back
# duplicates, thin parts): radwalk_two_sided 1, so that what reaches a back is re-radiated, not lost at 0 K.
TWO_SIDED = set()  # {"filing-cabinet", ...}: see docs/heat-exchange.md (contacts of two-sided faces)


def thermal_lines(name):
    eps, (kind, value) = THERMAL[name]
    return ["radwalk_emissivity %g" % eps,
            ("radwalk_temperature %g" if kind == "T" else "radwalk_heat_flux %g") % value] + \
        (["radwalk_two_sided 1"] if name in TWO_SIDED else [])


def place_model(furniture, work, out, vertex_base, archive, model, name, cx, cz, elevation, turn):
    """Appends the model's OBJ statements to out (vertices placed, indices offset); returns its vertex count."""
    path = os.path.join(furniture, archive)
    width, height, depth = catalogue_size(path, model)
    z = zipfile.ZipFile(path)
    members = [m for m in z.namelist() if m.split("/")[1:2] == [model] and not m.endswith("/")]
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
            # Every material block gets the object's thermal statements; names prefixed with the object.
            text = re.sub(r"^(\s*newmtl\s+)(.*)$",
                          lambda g: g.group(1) + name + "__" + g.group(2).strip() + "\n" +
                          "\n".join(thermal_lines(name)), text, flags=re.M)
            with open(os.path.join(model_dir, base), "w", encoding="latin-1") as f:
                f.write(text)
        else:
            with open(os.path.join(model_dir, base), "wb") as f:
                f.write(data)
    lines = obj_text.splitlines()
    coords = [tuple(float(x) for x in l.split()[1:4]) for l in lines if l.split()[:1] == ["v"]]
    lo = [min(c[k] for c in coords) for k in range(3)]
    hi = [max(c[k] for c in coords) for k in range(3)]
    size = (width, height, depth)
    scale = [size[k] / (hi[k] - lo[k]) for k in range(3)]
    # Into its box centred on the origin in x and z, standing on y = 0, turned, then moved to its spot.
    cos_t, sin_t = [(1, 0), (0, 1), (-1, 0), (0, -1)][turn % 4]
    out.append("o " + name)
    count = 0
    for l in lines:
        t = l.split()
        if not t:
            continue
        if t[0] == "v":
            x = scale[0] * (float(t[1]) - 0.5 * (lo[0] + hi[0]))
            y = scale[1] * (float(t[2]) - lo[1])
            zz = scale[2] * (float(t[3]) - 0.5 * (lo[2] + hi[2]))
            xr, zr = cos_t * x + sin_t * zz, -sin_t * x + cos_t * zz
            out.append("v %.7f %.7f %.7f" % (xr + cx, y + elevation, zr + cz))
            count += 1
        elif t[0] == "f":
            refs = []
            for c in t[1:]:
                i = int(c.split("/")[0])
                refs.append(str(i + vertex_base) if i > 0 else str(i))
            out.append("f " + " ".join(refs))
        elif t[0] == "usemtl":
            out.append("usemtl " + name + "__" + l.split(None, 1)[1].strip())
        elif t[0] == "mtllib":
            out.append("mtllib " + name + "/" + l.split(None, 1)[1].strip())
        elif t[0] in ("o", "g"):
            out.append("g " + name + "/" + (l.split(None, 1)[1].strip() if len(t) > 1 else ""))
        elif t[0] in ("l", "s", "vt", "vn"):
            out.append(l)
    return count


def room_grid(out, vertex_base):
    """The six walls as one conforming grid of rectangles (faces pointing into the room); returns the vertex count."""
    X, Y, Z = ROOM
    xs = sorted({0.0, WINDOW[0], WINDOW[1], X})
    ys = sorted({0.0, WINDOW[2], WINDOW[3], Y})
    zs = [0.0, Z]
    index = {}
    vertices = []

    def v(p):
        key = tuple(round(c, 9) for c in p)
        if key not in index:
            vertices.append(key)
            index[key] = vertex_base + len(vertices)
        return index[key]

    faces = {k: [] for k in ("floor", "ceiling", "outside_wall", "inside_walls", "window")}
    # Each wall: its grid in two axes and the inward normal's sign; corners counter-clockwise seen from inside.
    for a in range(len(xs) - 1):
        for c in range(len(zs) - 1):
            x0, x1, z0, z1 = xs[a], xs[a + 1], zs[c], zs[c + 1]
            faces["floor"].append([v((x0, 0, z0)), v((x0, 0, z1)), v((x1, 0, z1)), v((x1, 0, z0))])      # +y
            faces["ceiling"].append([v((x0, Y, z0)), v((x1, Y, z0)), v((x1, Y, z1)), v((x0, Y, z1))])    # -y
    for a in range(len(xs) - 1):
        for b in range(len(ys) - 1):
            x0, x1, y0, y1 = xs[a], xs[a + 1], ys[b], ys[b + 1]
            is_window = WINDOW[0] <= x0 and x1 <= WINDOW[1] and WINDOW[2] <= y0 and y1 <= WINDOW[3]
            faces["window" if is_window else "outside_wall"].append(
                [v((x0, y0, 0)), v((x1, y0, 0)), v((x1, y1, 0)), v((x0, y1, 0))])                        # +z
            faces["inside_walls"].append([v((x0, y0, Z)), v((x0, y1, Z)), v((x1, y1, Z)), v((x1, y0, Z))])  # -z
    for b in range(len(ys) - 1):
        for c in range(len(zs) - 1):
            y0, y1, z0, z1 = ys[b], ys[b + 1], zs[c], zs[c + 1]
            faces["inside_walls"].append([v((0, y0, z0)), v((0, y1, z0)), v((0, y1, z1)), v((0, y0, z1))])  # +x
            faces["inside_walls"].append([v((X, y0, z0)), v((X, y0, z1)), v((X, y1, z1)), v((X, y1, z0))])  # -x
    for p in vertices:
        out.append("v %g %g %g" % p)
    for name, quads in faces.items():
        out.append("o " + name)
        out.append("usemtl " + name)
        for q in quads:
            out.append("f " + " ".join(str(i) for i in q))
    return len(vertices)


def build_office(furniture, work):
    os.makedirs(work, exist_ok=True)
    with open(os.path.join(work, "office.mtl"), "w") as f:
        for name in ("floor", "ceiling", "outside_wall", "inside_walls", "window"):
            f.write("newmtl %s\nKd 0.7 0.7 0.7\n%s\n\n" % (name, "\n".join(thermal_lines(name))))
    out = ["# an office furnished with sweethome3d-furniture models (scripts/office_exchange.py), metres, y up",
           "mtllib office.mtl"]
    vertices = room_grid(out, 0)
    for archive, model, name, cx, cz, elevation, turn in MODELS:
        vertices += place_model(furniture, work, out, vertices, archive, model, name, cx, cz, elevation, turn)
    path = os.path.join(work, "office.obj")
    with open(path, "w", encoding="latin-1") as f:
        f.write("\n".join(out) + "\n")
    return path


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--radwalk", default=os.path.join(HERE, "..", "build", "apps", "radwalk"))
    ap.add_argument("--work", default="office")
    ap.add_argument("--max-edge", default="0.4")
    ap.add_argument("--rays", default="1000")
    ap.add_argument("--solver", default="auto")
    ap.add_argument("--build-only", action="store_true")
    ap.add_argument("extra", nargs="*")
    a = ap.parse_args()
    work = os.path.abspath(a.work)
    office = build_office(furniture_dir(work), work)
    print("wrote " + office, flush=True)
    if a.build_only:
        return 0
    f = lambda name: os.path.join(work, name)  # noqa: E731
    cmd = [a.radwalk, "exchange", office, "--max-edge", a.max_edge, "--rays", a.rays, "--solver", a.solver,
           "--contact-faces", "exclude", "--ambient-temperature", "293.15",
           "--group-by", "object", "--groups", f("groups.csv"), "--group-factors", f("group_factors.csv"),
           "--csv", f("patches.csv"), "--json", f("exchange.json"), "-o", f("office.vtp"),
           "--paraview-state", f("office_state.py")] + a.extra
    print("$ " + " ".join(cmd), flush=True)
    start = time.time()
    r = subprocess.run(cmd)
    seconds = time.time() - start
    if r.returncode != 0:
        print("office_exchange.py: radwalk exchange exited %d" % r.returncode, file=sys.stderr)
        return r.returncode
    j = json.load(open(f("exchange.json")))
    x = j["exchange"]
    sol = j["solution"]
    print("\n%d patches; %s: %s, relative residual %.3g, %.1f s (the whole run %.1f s)"
          % (j.get("patches", {}).get("count", 0) if isinstance(j.get("patches"), dict) else len(open(f("patches.csv")).readlines()) - 1,
             sol.get("method"), sol.get("status"), sol.get("residual", float("nan")), sol.get("seconds", 0), seconds))
    print("\n%-16s %9s %12s %10s %11s" % ("object", "area m^2", "Q W", "+- W", "T_rad K"))
    for g in sorted(x["groups"], key=lambda g: -abs(g["Q"])):
        print("%-16s %9.3f %12.2f %10.2f %11.2f" % (g["name"], g["area"], g["Q"], g["Q_se"], g["T_radiant"]))
    print("\nenergy balance (W): sum of Q %.3f (+- %.3f); to the ambient %.3f; into backs of one-sided faces %.3f "
          "(+- %.3f); residual %.3f (+- %.3f, the form factors' reciprocity defect): %.2f standard errors"
          % (x["sum_Q"], x["sum_Q_se"], x["to_ambient"], x["lost_to_back_faces"], x["lost_to_back_faces_se"],
             x["balance_residual"], x["balance_residual_se"],
             abs(x["balance_residual"]) / max(x["balance_residual_se"], 1e-300)))
    return 0


if __name__ == "__main__":
    sys.exit(main())
