#!/usr/bin/python3
"""Render a radwalk .vtp solution to PNG with VTK (no ParaView needed).

Colours are the radiance B/pi of each patch (cell field B, or the area-weighted point field with --smooth),
times --exposure, sRGB-encoded and clamped: the same mapping as `radwalk pathtrace --image`, so a radiosity
solution and a path-traced image of the same scene can be compared side by side.

Usage (Debian's VTK is an X build: run it under xvfb-run when there is no display):
    xvfb-run -a -s "-screen 0 1024x1024x24" /usr/bin/python3 scripts/render_vtp.py cb.vtp cb.png [--smooth]
        [--field B] [--size 512] [--camera px py pz tx ty tz ux uy uz fov_deg] [--exposure 1]
Without --camera the camera is fitted to the data: the Cornell box's own camera (position 278 273 -800, looking
along +z, 39.3 degree field of view) when the file's field data name a scene cornell_box*; inside a closed scene
(every probe ray from the bounding box's centre hits a cell) with objects in it (non-emitting cells off the
bounding box's planes: not the room's own floor, walls or ceiling), 60 degrees, looking at the objects'
area-weighted centroid from the point inside that sees the most of them (frame_objects; the rule of
apps/scene_camera.h); in a closed scene without objects at the centre, 60 degrees, looking where the cone of
view holds the most radiance B of non-emitting cells; otherwise from outside, framing the bounding box's sphere (40 degrees) along the
axis or diagonal whose rays see the most B on cell fronts. The camera used is printed.
"""
import argparse
import math
import sys

import vtk
from vtk.util import numpy_support


def srgb(c):
    c = max(0.0, min(1.0, c))
    return 12.92 * c if c <= 0.0031308 else 1.055 * c ** (1 / 2.4) - 0.055


def colours(array, exposure):
    n = array.GetNumberOfTuples()
    out = vtk.vtkUnsignedCharArray()
    out.SetNumberOfComponents(3)
    out.SetNumberOfTuples(n)
    out.SetName("colour")
    for i in range(n):
        b = array.GetTuple3(i)
        out.SetTuple3(i, *(round(255 * srgb(exposure * v / math.pi)) for v in b))
    return out


CORNELL_BOX_CAMERA = [278, 273, -800, 278, 273, 0, 0, 1, 0, 2 * math.degrees(math.atan(0.0125 / 0.035))]


def fibonacci(n):
    """n directions spread evenly over the sphere (a fixed set: the fit is deterministic)."""
    golden = math.pi * (3 - math.sqrt(5))
    out = []
    for k in range(n):
        z = 1 - (2 * k + 1) / n
        r = math.sqrt(max(0.0, 1 - z * z))
        out.append((r * math.cos(golden * k), z, r * math.sin(golden * k)))
    return out


def cell_centroid(poly, cell):
    pts = poly.GetCell(cell).GetPoints()
    n = pts.GetNumberOfPoints()
    return [sum(pts.GetPoint(k)[a] for k in range(n)) / n for a in range(3)]


def frame_objects(poly, lo, hi, centre, probes, hits, first_hit, front, emitted, samples=128):
    """Inside a closed scene with objects, the camera that frames them (apps/scene_camera.h, the same rule): the
    objects are the non-emitting cells whose centroid lies on none of the bounding box's planes (not the room's
    floor, walls or ceiling); the camera looks at their area-weighted centroid with 60 degrees, from the point 0.8
    of the way from the box's centre to a probe hit that sees the most of them (of at most `samples` object cells,
    every k-th: centroid inside the square image, front seen unoccluded). None when there are no objects."""
    tol = 1e-6 * math.dist(lo, hi)
    area = poly.GetCellData().GetArray("area")
    objects, c, total = [], [0.0, 0.0, 0.0], 0.0
    for i in range(poly.GetNumberOfCells()):
        if emitted is not None and any(v > 0 for v in emitted.GetTuple(i)):
            continue
        x = cell_centroid(poly, i)
        if any(abs(x[a] - lo[a]) <= tol or abs(x[a] - hi[a]) <= tol for a in range(3)):
            continue
        w = area.GetValue(i) if area is not None else 1.0
        objects.append((i, x))
        c = [c[a] + w * x[a] for a in range(3)]
        total += w
    if not objects or not total > 0:
        return None
    c = [v / total for v in c]
    sampled = objects[::max(1, len(objects) // samples)]
    tan_half = math.tan(math.radians(30))
    best, best_score = None, 0
    for d, h in zip(probes, hits):
        q = [centre[a] + 0.8 * h[1] * d[a] for a in range(3)]
        f = [c[a] - q[a] for a in range(3)]
        fl = math.sqrt(sum(x * x for x in f))
        f = [x / fl for x in f]
        up = [0, 0, 1] if abs(f[1]) > 0.99 else [0, 1, 0]
        r = [f[1] * up[2] - f[2] * up[1], f[2] * up[0] - f[0] * up[2], f[0] * up[1] - f[1] * up[0]]
        rl = math.sqrt(sum(x * x for x in r))
        r = [x / rl for x in r]
        u = [r[1] * f[2] - r[2] * f[1], r[2] * f[0] - r[0] * f[2], r[0] * f[1] - r[1] * f[0]]
        score = 0
        for i, x in sampled:
            v = [x[a] - q[a] for a in range(3)]
            z = sum(v[a] * f[a] for a in range(3))
            if z <= 0 or abs(sum(v[a] * r[a] for a in range(3))) > z * tan_half or \
                    abs(sum(v[a] * u[a] for a in range(3))) > z * tan_half:
                continue
            dist = math.sqrt(sum(x * x for x in v))
            w = [x / dist for x in v]
            hit = first_hit(q, w, 1.01 * dist)
            if hit is not None and hit[0] == i and front(i, w):
                score += 1
        if score > best_score:
            best, best_score = q + c + up + [60.0], score
    return best


def fit_camera(poly, field):
    """The camera for the data: see the module's doc."""
    fd = poly.GetFieldData()
    scene = fd.GetAbstractArray("scene")
    if scene is not None and scene.GetNumberOfValues() and \
            scene.GetValue(0).split("/")[-1].startswith("cornell_box"):
        return CORNELL_BOX_CAMERA
    b = poly.GetBounds()
    lo, hi = (b[0], b[2], b[4]), (b[1], b[3], b[5])
    centre = [0.5 * (l + h) for l, h in zip(lo, hi)]
    radius = 0.5 * math.dist(lo, hi)
    locator = vtk.vtkCellLocator()
    locator.SetDataSet(poly)
    locator.BuildLocator()
    cell_b = poly.GetCellData().GetArray("B") or field

    def first_hit(origin, d, far):
        t, x, pc = vtk.mutable(0.0), [0.0, 0.0, 0.0], [0.0, 0.0, 0.0]
        sub, cell = vtk.mutable(0), vtk.mutable(-1)
        end = [o + far * di for o, di in zip(origin, d)]
        if not locator.IntersectWithLine(origin, end, 1e-9, t, x, pc, sub, cell):
            return None
        return int(cell), float(t) * far

    def front(cell, d):
        normal = [0.0, 0.0, 0.0]
        pts = poly.GetCell(cell).GetPoints()
        vtk.vtkPolygon.ComputeNormal(pts, normal)
        return sum(n * di for n, di in zip(normal, d)) < 0

    emitted = poly.GetCellData().GetArray("E")

    def brightness(cell):  # the lit surfaces, not the lights themselves
        if emitted is not None and any(v > 0 for v in emitted.GetTuple(cell)):
            return 0.0
        return sum(cell_b.GetTuple3(cell)) if cell_b is not None and cell_b.GetNumberOfComponents() == 3 else 1.0

    far = 4 * radius + 1e-12
    probes = fibonacci(256)
    hits = [first_hit(centre, d, far) for d in probes]
    if all(h is not None for h in hits):
        framed = frame_objects(poly, lo, hi, centre, probes, hits, first_hit, front, emitted)
        if framed is not None:
            return framed
    if all(h is not None for h in hits):  # closed, no objects: look where the cone of view holds the most B
        half = math.radians(30)
        score = [brightness(h[0]) for h in hits]
        best, best_sum = probes[0], -1.0
        for d in probes:
            if abs(d[1]) > 0.9:
                continue
            s = sum(w for e, w in zip(probes, score) if sum(x * y for x, y in zip(d, e)) >= math.cos(half))
            if s > best_sum:
                best, best_sum = d, s
        look = [c + h for c, h in zip(centre, best)]
        return centre + look + [0, 1, 0] + [60.0]
    # Open: frame the bounding sphere from the view whose rays see the most B on cell fronts.
    fov = 40.0
    best_camera, best_seen = None, -1.0
    for d in [(0, 0, 1), (0, 0, -1), (1, 0, 0), (-1, 0, 0), (0, -1, 0), (0, 1, 0), (1, -1, 1), (-1, -1, 1),
              (1, -1, -1), (-1, -1, -1), (1, 1, 1), (-1, 1, 1), (1, 1, -1), (-1, 1, -1)]:
        n = math.sqrt(sum(x * x for x in d))
        d = [x / n for x in d]
        up = [0, 0, 1] if abs(d[1]) > 0.99 else [0, 1, 0]
        distance = radius / math.tan(math.radians(fov / 2)) + 0.5 * sum(abs((h - l) * x) for l, h, x in zip(lo, hi, d))
        position = [c - distance * x for c, x in zip(centre, d)]
        # right and true up of the view, for a 12 x 12 grid of rays over the field of view
        right = [d[1] * up[2] - d[2] * up[1], d[2] * up[0] - d[0] * up[2], d[0] * up[1] - d[1] * up[0]]
        rn = math.sqrt(sum(x * x for x in right))
        right = [x / rn for x in right]
        up2 = [right[1] * d[2] - right[2] * d[1], right[2] * d[0] - right[0] * d[2], right[0] * d[1] - right[1] * d[0]]
        tan = math.tan(math.radians(fov / 2))
        seen = 0.0
        for i in range(12):
            for j in range(12):
                sx, sy = (2 * (i + 0.5) / 12 - 1) * tan, (2 * (j + 0.5) / 12 - 1) * tan
                ray = [x + sx * r + sy * u for x, r, u in zip(d, right, up2)]
                rl = math.sqrt(sum(x * x for x in ray))
                ray = [x / rl for x in ray]
                h = first_hit(position, ray, distance + 2 * radius)
                if h is not None and front(h[0], ray):
                    seen += brightness(h[0]) + 1e-12
        if seen > best_seen:
            best_camera, best_seen = position + centre + up + [fov], seen
    return best_camera


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("vtp")
    p.add_argument("png")
    p.add_argument("--field", default="B")
    p.add_argument("--smooth", action="store_true", help="use the point field (Gouraud shading)")
    p.add_argument("--size", type=int, default=512)
    p.add_argument("--exposure", type=float, default=1.0)
    p.add_argument("--camera", type=float, nargs=10, default=None,
                   help="px py pz tx ty tz ux uy uz fov_deg (default: fitted to the data)")
    a = p.parse_args()

    reader = vtk.vtkXMLPolyDataReader()
    reader.SetFileName(a.vtp)
    reader.Update()
    poly = reader.GetOutput()
    data = poly.GetPointData() if a.smooth else poly.GetCellData()
    field = data.GetArray(a.field)
    if field is None or field.GetNumberOfComponents() != 3:
        sys.exit(f"{a.vtp}: no 3-component {'point' if a.smooth else 'cell'} field '{a.field}'")
    data.SetScalars(colours(field, a.exposure))

    mapper = vtk.vtkPolyDataMapper()
    mapper.SetInputData(poly)
    mapper.SetColorModeToDirectScalars()
    mapper.SetScalarModeToUsePointData() if a.smooth else mapper.SetScalarModeToUseCellData()
    actor = vtk.vtkActor()
    actor.SetMapper(mapper)
    prop = actor.GetProperty()
    prop.SetLighting(False)  # show the radiosity itself, not a shaded surface
    if a.smooth:
        prop.SetInterpolationToGouraud()

    renderer = vtk.vtkRenderer()
    renderer.AddActor(actor)
    renderer.SetBackground(0, 0, 0)
    cam = renderer.GetActiveCamera()
    c = a.camera if a.camera else fit_camera(poly, field)
    print("camera: position %g %g %g, look at %g %g %g, up %g %g %g, fov %g degrees" % tuple(c))
    cam.SetPosition(c[0], c[1], c[2])
    cam.SetFocalPoint(c[3], c[4], c[5])
    cam.SetViewUp(c[6], c[7], c[8])
    cam.SetViewAngle(c[9])
    renderer.ResetCameraClippingRange()

    window = vtk.vtkRenderWindow()
    window.SetOffScreenRendering(1)
    window.SetSize(a.size, a.size)
    window.AddRenderer(renderer)
    window.Render()
    grab = vtk.vtkWindowToImageFilter()
    grab.SetInput(window)
    grab.Update()
    writer = vtk.vtkPNGWriter()
    writer.SetFileName(a.png)
    writer.SetInputConnection(grab.GetOutputPort())
    writer.Write()
    print(f"wrote {a.png}")


if __name__ == "__main__":
    main()
