"""One camera rule: scripts/camera_rule.py (VTK, for render_vtp.py and paraview_render.py) gives the camera that
apps/scene_camera.cpp fits for `radwalk pathtrace` (and writes into --paraview-state), on scenes that take each
branch of the rule: a closed room with objects (framed objects), a closed cube with a light (the lit region), two
open squares (outside) and the Cornell box (its own camera)."""
import json
import math
import os
import subprocess
import sys

import pytest
from conftest import CLI, SOURCE

sys.path.insert(0, str(SOURCE / "scripts"))
import camera_rule  # noqa: E402
from vtkmodules.vtkIOXML import vtkXMLPolyDataReader  # noqa: E402

ROOM = """# a closed 4 x 3 x 5 room, normals inward, a light in the ceiling and a block on the floor
mtllib room.mtl
v 0 0 0
v 4 0 0
v 4 0 5
v 0 0 5
v 0 3 0
v 4 3 0
v 4 3 5
v 0 3 5
v 1.5 2.999 2
v 2.5 2.999 2
v 2.5 2.999 3
v 1.5 2.999 3
v 0.5 0 3.5
v 1.5 0 3.5
v 1.5 0 4.5
v 0.5 0 4.5
v 0.5 1 3.5
v 1.5 1 3.5
v 1.5 1 4.5
v 0.5 1 4.5
usemtl wall
f 1 4 3 2
f 5 6 7 8
f 1 5 8 4
f 2 3 7 6
f 1 2 6 5
f 4 8 7 3
usemtl light
f 9 10 11 12
usemtl block
f 17 20 19 18
f 13 17 18 14
f 14 18 19 15
f 15 19 20 16
f 16 20 17 13
"""
ROOM_MTL = """newmtl wall
Kd 0.6 0.6 0.6
newmtl light
Kd 0.5 0.5 0.5
Ke 10 10 10
newmtl block
Kd 0.3 0.4 0.5
"""


def pathtrace_camera_and_vtp(scene, tmp_path, extra=()):
    """The camera `radwalk pathtrace --image` fits (its JSON) and the .vtp of the same patches."""
    js, vtp = tmp_path / "run.json", tmp_path / "run.vtp"
    subprocess.run([CLI, "-q", "pathtrace", str(scene), "--spp", "2", "--image", str(tmp_path / "img.png"),
                    "--width", "8", "--height", "8", "--json", str(js), "-o", str(vtp), *extra], check=True)
    with open(js) as f:
        camera = json.load(f)["camera"]
    reader = vtkXMLPolyDataReader()
    reader.SetFileName(str(vtp))
    reader.Update()
    return camera, reader.GetOutput()


@pytest.mark.parametrize("name", ["room", "cube", "parallel_squares", "cornell_box"])
def test_the_python_rule_gives_pathtraces_camera(name, tmp_path):
    if name == "room":
        (tmp_path / "room.obj").write_text(ROOM)
        (tmp_path / "room.mtl").write_text(ROOM_MTL)
        scene, extra, source = tmp_path / "room.obj", ["--max-edge", "1"], "inside"
    else:
        scene, extra = SOURCE / "meshes" / f"{name}.obj", []
        source = {"cube": "inside", "parallel_squares": "outside", "cornell_box": "cornell_box"}[name]
    cpp, poly = pathtrace_camera_and_vtp(scene, tmp_path, extra)
    position, direction, up, vfov, branch = camera_rule.fit_camera(poly)
    assert cpp["source"] == branch == source
    # Embree traces in single precision and VTK in double: positions agree to 1e-6 of the scene's size.
    lo, hi = camera_rule.bounds(poly)
    size = math.dist(lo, hi)
    assert math.dist(position, cpp["position"]) <= 1e-6 * size, (position, cpp["position"])
    if name != "cube":  # the closed cube's lit directions tie by symmetry: rounding picks one of them
        d = camera_rule._unit(direction)
        assert math.dist(d, cpp["direction"]) <= 1e-6, (d, cpp["direction"])
        assert list(up) == cpp["up"]
    assert math.degrees(vfov) == pytest.approx(cpp["vertical_fov_deg"], rel=1e-12)
    # camera_rule's 10 numbers (ParaView's view): the focal point is pathtrace's look_at, the view up its up made
    # orthogonal to the view direction.
    rule = camera_rule.camera_rule(poly)
    if name != "cube":
        assert math.dist(rule[3:6], cpp["look_at"]) <= 1e-6 * size
        assert math.dist(rule[6:9], camera_rule.view_up(cpp["up"], cpp["direction"])) <= 1e-6
    view = camera_rule._unit([f - p for f, p in zip(rule[3:6], rule[0:3])])
    assert abs(sum(a * b for a, b in zip(rule[6:9], view))) <= 1e-12


def test_the_paraview_state_uses_the_same_camera(tmp_path):
    """--paraview-state writes the camera of the rule: the closed room's state looks from pathtrace's position."""
    (tmp_path / "room.obj").write_text(ROOM)
    (tmp_path / "room.mtl").write_text(ROOM_MTL)
    cpp, _ = pathtrace_camera_and_vtp(tmp_path / "room.obj", tmp_path, ["--max-edge", "1"])
    state = tmp_path / "s.py"
    subprocess.run([CLI, "-q", "solve", str(tmp_path / "room.obj"), "--max-edge", "1", "--rays", "100", "-o",
                    str(tmp_path / "s.vtp"), "--paraview-state", str(state)], check=True)
    text = state.read_text()
    line = next(l for l in text.splitlines() if l.strip().startswith("view.CameraPosition = "))
    position = json.loads(line.split("=", 1)[1])
    assert math.dist(position, cpp["position"]) <= 1e-9 * math.dist([0, 0, 0], [4, 3, 5])
    assert cpp["source"] == "inside"
    # The room's camera frames the block (the objects' branch), not the lit ceiling: the block is in front.
    d = cpp["direction"]
    to_block = [1.0 - cpp["position"][0], 0.5 - cpp["position"][1], 4.0 - cpp["position"][2]]
    assert sum(a * b for a, b in zip(d, to_block)) > 0.9 * math.dist([0, 0, 0], to_block)
