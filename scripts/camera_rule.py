"""The one camera rule of radwalk's views of a .vtp, shared by scripts/paraview_render.py and scripts/render_vtp.py;
apps/view_camera.h implements the same rule for the ParaView state files (--paraview-state), and
tests/paraview/check_outputs.py checks that the two agree on bundled scenes.

camera_rule(poly) -> [px, py, pz, fx, fy, fz, ux, uy, uz, fov_deg] (position, focal point, view up, vertical field
of view in degrees) for a vtkPolyData written by radwalk, in order:
  - field data `scene` naming a file cornell_box*: the Cornell box's own camera (278 273 -800 looking along +z at
    278 273 0, up +y, 2 atan(0.0125 / 0.035) = 39.31 degrees);
  - a closed scene, i.e. each of PROBES directions (a Fibonacci sphere about +y) from the bounding box's centre c
    first hits the front of a cell: inside, standing on the axis through c at 5 % of the box's depth from its
    front (-z) side, looking along +z at c, up +y, 60 degrees;
  - otherwise outside: looking along +z at c from the -z side, at r / tan(20 degrees) + dz / 2 from c (r: half the
    box's diagonal, dz: its depth), up +y, 40 degrees.
Works with VTK's own Python (python3-vtk9) and with ParaView's pvpython (both have vtkmodules).
"""
import math
import os

from vtkmodules.vtkCommonDataModel import vtkCellLocator, vtkPolygon

try:
    from vtkmodules.vtkCommonCore import reference
except ImportError:  # VTK before 9.1
    from vtkmodules.vtkCommonCore import mutable as reference

PROBES = 64
CORNELL_BOX = [278.0, 273.0, -800.0, 278.0, 273.0, 0.0, 0.0, 1.0, 0.0, 2 * math.degrees(math.atan(0.0125 / 0.035))]


def probe_direction(k):
    """Direction k of the PROBES probe directions (apps/view_camera.h: view_probe_direction)."""
    golden = math.pi * (3.0 - math.sqrt(5.0))
    z = 1.0 - (2.0 * k + 1.0) / PROBES
    r = math.sqrt(max(0.0, 1.0 - z * z))
    return (r * math.cos(golden * k), z, r * math.sin(golden * k))


def scene_name(poly):
    """The field data's `scene` (the scene file radwalk read), or None."""
    a = poly.GetFieldData().GetAbstractArray("scene")
    if a is None or a.GetNumberOfValues() == 0:
        return None
    return str(a.GetVariantValue(0).ToString())


def _cell_normal(poly, cell):
    normals = poly.GetCellData().GetArray("normal")
    if normals is not None and normals.GetNumberOfComponents() == 3:
        return normals.GetTuple3(cell)
    n = [0.0, 0.0, 0.0]
    vtkPolygon.ComputeNormal(poly.GetCell(cell).GetPoints(), n)
    return n


def is_closed(poly, centre, far):
    """True when every probe from centre first hits the front of a cell (within distance far)."""
    if poly.GetNumberOfCells() == 0:
        return False
    locator = vtkCellLocator()
    locator.SetDataSet(poly)
    locator.BuildLocator()
    for k in range(PROBES):
        d = probe_direction(k)
        end = [c + far * x for c, x in zip(centre, d)]
        t, x, pc, sub, cell = reference(0.0), [0.0, 0.0, 0.0], [0.0, 0.0, 0.0], reference(0), reference(-1)
        if not locator.IntersectWithLine(list(centre), end, 1e-12, t, x, pc, sub, cell) or int(cell) < 0:
            return False
        n = _cell_normal(poly, int(cell))
        if not sum(a * b for a, b in zip(n, d)) < 0:
            return False
    return True


def camera_rule(poly):
    """The camera for poly: see the module's doc."""
    scene = scene_name(poly)
    if scene is not None and os.path.basename(scene).startswith("cornell_box"):
        return list(CORNELL_BOX)
    b = poly.GetBounds() if poly.GetNumberOfPoints() else (0.0, 0.0, 0.0, 0.0, 0.0, 0.0)
    lo, hi = (b[0], b[2], b[4]), (b[1], b[3], b[5])
    c = [0.5 * (l + h) for l, h in zip(lo, hi)]
    radius = 0.5 * math.sqrt(sum((h - l) ** 2 for l, h in zip(lo, hi)))
    if is_closed(poly, c, 4 * radius + 1e-12):
        return [c[0], c[1], lo[2] + 0.05 * (hi[2] - lo[2])] + c + [0.0, 1.0, 0.0, 60.0]
    z = c[2] - (radius / math.tan(math.radians(20.0)) + 0.5 * (hi[2] - lo[2]))
    return [c[0], c[1], z] + c + [0.0, 1.0, 0.0, 40.0]
