"""radwalk.load takes the CLI's reading options (orient, open_shells, scale, unit, strict, set, rho_scale) through
the same code (mesh/prepare_mesh.h), and STL, glTF and VTK scenes load through it: the same patches and, solved
on the same seed, the same CSV as the CLI byte for byte."""
import base64
import json
import struct

import numpy
import pytest

import radwalk
from conftest import run_cli, without_run_id

RAYS, SEED = 300, 5

# A closed room 400 x 300 x 250 (cm), faces in, a light just below the ceiling facing down, and an open sheet (a
# table top) inside: as triangles, (corners, group).
L, W, H = 400.0, 300.0, 250.0


def room_triangles():
    tris = []

    def quad(a, b, c, d, group):
        tris.append(((a, b, c), group))
        tris.append(((a, c, d), group))

    p = lambda x, y, z: (x, y, z)
    quad(p(0, 0, 0), p(0, W, 0), p(L, W, 0), p(L, 0, 0), "room")        # floor, +z
    quad(p(0, 0, 0), p(L, 0, 0), p(L, 0, H), p(0, 0, H), "room")        # y = 0, +y
    quad(p(0, W, 0), p(0, W, H), p(L, W, H), p(L, W, 0), "room")        # y = W, -y
    quad(p(0, 0, 0), p(0, 0, H), p(0, W, H), p(0, W, 0), "room")        # x = 0, +x
    quad(p(L, 0, 0), p(L, W, 0), p(L, W, H), p(L, 0, H), "room")        # x = L, -x
    quad(p(0, 0, H), p(0, W, H), p(L, W, H), p(L, 0, H), "room")        # ceiling, -z: the room is one closed shell
    quad(p(150, 100, H - 1), p(150, 200, H - 1), p(250, 200, H - 1), p(250, 100, H - 1), "light")  # -z, below it
    quad(p(100, 100, 70), p(300, 100, 70), p(300, 200, 70), p(100, 200, 70), "table")  # an open sheet, +z
    return tris


def write_stl(path):
    tris = room_triangles()
    out = []
    for group in ("room", "light", "table"):
        out.append("solid %s" % group)
        for (a, b, c), g in tris:
            if g != group:
                continue
            out.append(" facet normal 0 0 0\n  outer loop")
            out += ["   vertex %r %r %r" % v for v in (a, b, c)]
            out.append("  endloop\n endfacet")
        out.append("endsolid %s" % group)
    path.write_text("\n".join(out) + "\n")


def write_obj(path):
    tris = room_triangles()
    lines = ["mtllib room.mtl"]
    for (a, b, c), _ in tris:
        lines += ["v %r %r %r" % v for v in (a, b, c)]
    for group in ("room", "light", "table"):
        lines += ["g " + group, "usemtl " + group]
        lines += ["f %d %d %d" % (3 * k + 1, 3 * k + 2, 3 * k + 3) for k, (_, g) in enumerate(tris) if g == group]
    path.write_text("\n".join(lines) + "\n")
    (path.parent / "room.mtl").write_text("newmtl room\nKd 0.5 0.5 0.5\nnewmtl light\nKd 0 0 0\nKe 1 1 1\n"
                                           "newmtl table\nKd 0.6 0.6 0.6\n")


def write_gltf(path):
    """The room as a glTF 2.0 document: one node and mesh per group, the materials' baseColorFactor and
    emissiveFactor, the buffer as a data: URI."""
    tris = room_triangles()
    blob, meshes, nodes, accessors, views = b"", [], [], [], []
    materials = [{"name": "room", "pbrMetallicRoughness": {"baseColorFactor": [0.5, 0.5, 0.5, 1]}},
                 {"name": "light", "pbrMetallicRoughness": {"baseColorFactor": [0, 0, 0, 1]},
                  "emissiveFactor": [1, 1, 1]},
                 {"name": "table", "pbrMetallicRoughness": {"baseColorFactor": [0.6, 0.6, 0.6, 1]}}]
    for m, group in enumerate(("room", "light", "table")):
        pts = [v for (t, g) in tris if g == group for v in t]
        data = b"".join(struct.pack("<3f", *v) for v in pts)
        views.append({"buffer": 0, "byteOffset": len(blob), "byteLength": len(data)})
        accessors.append({"bufferView": len(views) - 1, "componentType": 5126, "count": len(pts), "type": "VEC3",
                          "min": [min(v[k] for v in pts) for k in range(3)],
                          "max": [max(v[k] for v in pts) for k in range(3)]})
        blob += data
        meshes.append({"name": group, "primitives": [{"attributes": {"POSITION": len(accessors) - 1},
                                                      "material": m, "mode": 4}]})
        nodes.append({"name": group, "mesh": m})
    doc = {"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0, 1, 2]}], "nodes": nodes,
           "meshes": meshes, "materials": materials, "accessors": accessors, "bufferViews": views,
           "buffers": [{"byteLength": len(blob),
                        "uri": "data:application/octet-stream;base64," + base64.b64encode(blob).decode()}]}
    path.write_text(json.dumps(doc))


STL_SET = ["room.Kd=0.5", "light.Kd=0", "light.Ke=1", "table.Kd=0.6"]
UNITS = {"unit": "cm", "scale": 0.01}
UNIT_FLAGS = ["--unit", "cm", "--scale", 0.01]


def cli_and_module_csv(tmp_path, scene_file, flags, **load):
    run_cli("solve", scene_file, "--rays", RAYS, "--seed", SEED, *flags, "--csv", tmp_path / "cli.csv")
    scene = radwalk.load(scene_file, **load)
    ff = radwalk.form_factors(scene, rays=RAYS, seed=SEED)
    result = radwalk.solve(scene, ff)
    radwalk.write_csv(tmp_path / "py.csv", scene, {**ff.diagnostics, **result.fields})
    cli = without_run_id(open(tmp_path / "cli.csv", "rb").read())
    return scene, cli, without_run_id(open(tmp_path / "py.csv", "rb").read())


def set_flags(overrides):
    return [x for o in overrides for x in ("--set", o)]


@pytest.mark.parametrize("flags, load", [
    ([], {}),
    (["--open-shells", "one-sided"], {"open_shells": "one-sided"}),
    (["--open-shells", "two-sided", "--orient", "consistent"], {"open_shells": "two-sided", "orient": "consistent"}),
    (["--orient", "none", "--rho-scale", 0.5], {"orient": "none", "rho_scale": 0.5}),
])
def test_stl_with_the_cli_reading_options_equals_the_cli(tmp_path, flags, load):
    stl = tmp_path / "room.stl"
    write_stl(stl)
    scene, cli, py = cli_and_module_csv(tmp_path, stl, UNIT_FLAGS + set_flags(STL_SET) + flags,
                                        set=STL_SET, **UNITS, **load)
    assert cli == py
    assert cli.count(b"\n") == len(scene.areas) + 1
    assert scene.length_unit == "m" and scene.radiosity_unit == "W/m^2" and scene.unit == "cm"
    assert scene.scale == 0.01
    assert scene.orient == load.get("orient", "outward")
    assert scene.open_shells == load.get("open_shells", "auto")


def test_open_shells_auto_makes_the_table_two_sided_inside_the_closed_room(tmp_path):
    stl = tmp_path / "room.stl"
    write_stl(stl)
    auto = radwalk.load(stl, set=STL_SET)
    one = radwalk.load(stl, set=STL_SET, open_shells="one-sided")
    two = radwalk.load(stl, set=STL_SET, open_shells="two-sided")
    # The table's 2 triangles get a back patch each; the room (closed) does not.
    assert len(auto.areas) == len(one.areas) + 2 == len(two.areas)
    assert any("open shells made two-sided" in w for w in auto.warnings)


def test_obj_gltf_stl_and_vtp_load_through_python_with_the_same_areas(tmp_path):
    obj, stl, gltf = tmp_path / "room.obj", tmp_path / "room.stl", tmp_path / "room.gltf"
    write_obj(obj)
    write_stl(stl)
    write_gltf(gltf)
    vtp = tmp_path / "room.vtp"
    run_cli("patch", obj, "-o", vtp)
    scenes = {"obj": radwalk.load(obj, **UNITS), "stl": radwalk.load(stl, set=STL_SET, **UNITS),
              "gltf": radwalk.load(gltf, **UNITS), "vtp": radwalk.load(vtp, **UNITS)}
    ref = scenes["obj"]
    for name, s in scenes.items():
        assert len(s.areas) == len(ref.areas), name
        # float32 positions (STL, glTF) against the OBJ's doubles: areas of a few m^2 agree to float precision.
        assert abs(s.total_area - ref.total_area) <= 1e-6 * ref.total_area, name
        assert {m.name for m in s.materials} >= {"light", "room", "table"}, name  # named alike in every format


def test_the_refusals_name_the_option(tmp_path):
    stl = tmp_path / "room.stl"
    write_stl(stl)
    with pytest.raises(radwalk.InputError, match=r"--set 'room.Kd=r,g,b'"):
        radwalk.load(stl)  # STL has no reflectance
    with pytest.raises(radwalk.InputError, match=r"unit 'furlong' is not one of mm, cm, m, in, ft"):
        radwalk.load(stl, set=STL_SET, unit="furlong")
    with pytest.raises(radwalk.InputError, match=r"scale .* must be a finite number > 0"):
        radwalk.load(stl, set=STL_SET, scale=0)
    with pytest.raises(radwalk.InputError, match=r"--orient: 'inward' is not one of none, consistent, outward"):
        radwalk.load(stl, set=STL_SET, orient="inward")
    with pytest.raises(radwalk.InputError, match=r"--open-shells: 'both' is not one of auto, one-sided, two-sided"):
        radwalk.load(stl, set=STL_SET, open_shells="both")
    with pytest.raises(radwalk.InputError, match=r"did you mean 'table'"):
        radwalk.load(stl, set=STL_SET + ["tabel.Kd=0.3"])
    with pytest.raises(radwalk.InputError, match=r"rho_scale"):
        radwalk.load(stl, set=STL_SET, rho_scale=-1)


def test_strict_refuses_what_load_repairs(tmp_path):
    obj = tmp_path / "pentagon.obj"
    obj.write_text("v 0 0 0\nv 2 0 0\nv 3 1 0\nv 1 2 0\nv -1 1 0\nf 1 2 3 4 5\n")
    assert len(radwalk.load(obj).areas) == 3  # triangulated, with a warning
    with pytest.raises(radwalk.InputError, match=r"has 5 vertices"):
        radwalk.load(obj, strict=True)


def test_set_overrides_a_material_as_the_cli_does(tmp_path):
    obj = tmp_path / "room.obj"
    write_obj(obj)
    scene = radwalk.load(obj, set="table.Kd=0.25,0.5,0.125")
    # The table's faces (front and back: its two-sided copy keeps the name) have the overridden rho.
    table = [k for k, m in enumerate(scene.materials) if m.name == "table"]
    rho = scene.rho[numpy.isin(scene.material, table)]
    assert rho.shape[0] == 4 and (rho == [0.25, 0.5, 0.125]).all()


def test_notes_say_when_an_orient_given_reorients_a_file_radwalk_wrote(tmp_path):
    """A .obj written by radwalk reads back as written; with orient given, Scene.notes says that it orients the
    faces again (the CLI's note), and without it says nothing of the kind."""
    obj = tmp_path / "room.obj"
    write_obj(obj)
    written = tmp_path / "patches.obj"
    run_cli("patch", obj, "--max-edge", "150", "-o", written)
    note = "orients them again"  # the note "faces as written oriented again"
    again = radwalk.load(str(written), orient="outward")
    assert any(note in n for n in again.notes), again.notes
    kept = radwalk.load(str(written))
    assert not any(note in n for n in kept.notes), kept.notes
    assert len(kept) == len(again)
