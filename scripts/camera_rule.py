"""The one camera rule of radwalk's views, in Python: apps/scene_camera.cpp (fit_scene_camera, the camera of
`radwalk pathtrace`, `measure --response camera` and the ParaView state files of --paraview-state) computed the
same way on a .vtp radwalk wrote, for scripts/paraview_render.py and scripts/render_vtp.py.
tests/python/test_camera_rule.py checks that the two give the same camera on a few scenes (closed with objects,
closed without, open, the Cornell box).

camera_rule(poly) -> [px, py, pz, fx, fy, fz, ux, uy, uz, fov_deg] (position, focal point, view up, vertical field
of view in degrees) for a vtkPolyData written by radwalk (cell data `normal`, `E`, `area`; field data `scene`):
  - field data `scene` naming a file cornell_box*: the Cornell box's own camera (278 273 -800 looking along +z,
    up +y, 2 atan(0.0125 / 0.035) = 39.31 degrees);
  - a closed scene (a point inside from which every one of PROBES probe rays, a Fibonacci sphere about +y, first
    hits the front of a cell: the bounding box's centre, else one of the six points a quarter of the box's size
    away from it along an axis): when the scene has objects (non-emitting cells whose area centroid is on none of
    the bounding box's six planes) the camera looks at their area-weighted centroid with a 60 degree field of
    view from the point, 0.8 of the way from the enclosed point to a probe hit, that sees the most of them (at
    most 256 sampled object cells whose centroid is in its square image and whose front it sees unoccluded);
    without objects it stands at the enclosed point, 60 degrees, looking where the cone of half-angle 30 degrees
    holds the most directly lit probe hits (unoccluded irradiance from the emitting cells' centroids), or along
    the longest probe without emitters;
  - otherwise outside: 40 degrees, framing the bounding box's sphere, along the first of +z, -z, +x, -x, -y, +y
    and the eight diagonals whose 24 x 24 pixel-centre rays hit the most fronts (emitters count twice).
  Up is +y unless the view is within about 8 degrees of it (then +z). The focal point is on the view axis, level
  with the box's centre, at least a quarter of its diagonal in front (apps/scene_camera.h, camera_focal_point).
The rays are its own (Moller-Trumbore on the cells' fan triangles with numpy, double precision) where the C++ traces with Embree (single precision), so a
hit at an edge or a tie between two candidates can in principle go the other way; the test measures agreement.
Cost: at most 7 x 512 probe rays, 512 x 256 rays to sample the objects, and for an empty room 512 x (emitting
cells) shadow rays, each a VTK query from Python (seconds for scenes of 10^4 to 10^5 cells).
Works with VTK's own Python (python3-vtk9) and with ParaView's pvpython (both have vtkmodules).
"""
import math
import os

import numpy as np
from vtkmodules.vtkCommonDataModel import vtkPolygon

PROBES = 512           # apps/scene_camera.h: kProbeRays
OBJECT_SAMPLES = 256   # frame_objects: kObjectSamples
OUTSIDE_PIXELS = 24    # the outside views' n x n pixel-centre rays
CORNELL_BOX = [278.0, 273.0, -800.0, 0.0, 0.0, 1.0, 0.0, 1.0, 0.0, 2 * math.degrees(math.atan(0.0125 / 0.035))]
OUTSIDE_DIRECTIONS = [(0, 0, 1), (0, 0, -1), (1, 0, 0), (-1, 0, 0), (0, -1, 0), (0, 1, 0), (1, -1, 1), (-1, -1, 1),
                      (1, -1, -1), (-1, -1, -1), (1, 1, 1), (-1, 1, 1), (1, 1, -1), (-1, 1, -1)]


def _add(a, b):
    return [x + y for x, y in zip(a, b)]


def _sub(a, b):
    return [x - y for x, y in zip(a, b)]


def _mul(s, a):
    return [s * x for x in a]


def _dot(a, b):
    return sum(x * y for x, y in zip(a, b))


def _cross(a, b):
    return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]


def _norm(a):
    return math.sqrt(_dot(a, a))


def _unit(a):
    n = _norm(a)
    return [x / n for x in a]


def probe_direction(k, n=PROBES):
    """Direction k of n on a Fibonacci sphere about +y (apps/scene_camera.cpp: probe_direction)."""
    golden = math.pi * (3.0 - math.sqrt(5.0))
    z = 1.0 - (2.0 * k + 1.0) / n
    r = math.sqrt(max(0.0, 1.0 - z * z))
    return [r * math.cos(golden * k), z, r * math.sin(golden * k)]


def up_for(d):
    return [0.0, 0.0, 1.0] if abs(_unit(d)[1]) > 0.99 else [0.0, 1.0, 0.0]


def scene_name(poly):
    """The field data's `scene` (the scene file radwalk read), or None."""
    a = poly.GetFieldData().GetAbstractArray("scene")
    if a is None or a.GetNumberOfValues() == 0:
        return None
    return str(a.GetVariantValue(0).ToString())


class _Scene:
    """The cells of a radwalk .vtp as the rule needs them: normals, emission, areas, centroids, a ray locator."""

    def __init__(self, poly):
        self.poly = poly
        n = poly.GetNumberOfCells()
        self.n = n
        self.lo, self.hi = bounds(poly)
        cd = poly.GetCellData()
        normals, E, area = cd.GetArray("normal"), cd.GetArray("E"), cd.GetArray("area")
        self.normal, self.emits, self.area, self.centroid, self.E_sum = [], [], [], [], []
        for i in range(n):
            cell = poly.GetCell(i)
            pts = [cell.GetPoints().GetPoint(k) for k in range(cell.GetNumberOfPoints())]
            if normals is not None:
                self.normal.append(list(normals.GetTuple3(i)))
            else:
                nn = [0.0, 0.0, 0.0]
                vtkPolygon.ComputeNormal(cell.GetPoints(), nn)
                self.normal.append(nn)
            e = E.GetTuple3(i) if E is not None else (0.0, 0.0, 0.0)
            self.emits.append(any(x > 0 for x in e))
            self.E_sum.append(sum(e))
            # Area centroid by a fan from the first corner (the display polygon's T-junction points lie on its
            # edges, so this is the patch's centroid).
            total, c = 0.0, [0.0, 0.0, 0.0]
            for k in range(1, len(pts) - 1):
                a = 0.5 * _norm(_cross(_sub(pts[k], pts[0]), _sub(pts[k + 1], pts[0])))
                c = _add(c, _mul(a / 3.0, _add(_add(pts[0], pts[k]), pts[k + 1])))
                total += a
            self.centroid.append(_mul(1.0 / total, c) if total > 0 else list(pts[0]))
            self.area.append(area.GetValue(i) if area is not None else total)
        self.far = 4.0 * _norm(_sub(self.hi, self.lo)) + 1e-12
        # The cells as fan triangles (corner 0, k, k + 1), each with its cell: the rays are cast against them all at
        # once. VTK's locators were not used: on the same .vtp, ParaView's vtkModifiedBSPTree missed 52 of a closed
        # cube's 512 centre probes and Debian's vtkStaticCellLocator 6 of a furnished room's.
        a, b, c, owner = [], [], [], []
        for i in range(n):
            cell = poly.GetCell(i)
            pts = [cell.GetPoints().GetPoint(k) for k in range(cell.GetNumberOfPoints())]
            for k in range(1, len(pts) - 1):
                a.append(pts[0]), b.append(pts[k]), c.append(pts[k + 1]), owner.append(i)
        self.tri_a = np.array(a, dtype=float).reshape(-1, 3)
        self.tri_e1 = np.array(b, dtype=float).reshape(-1, 3) - self.tri_a
        self.tri_e2 = np.array(c, dtype=float).reshape(-1, 3) - self.tri_a
        self.tri_cell = np.array(owner, dtype=int)
        self.tri_normal = np.array([self.normal[i] for i in owner], dtype=float).reshape(-1, 3)

    def intersect(self, origin, direction, tmax=None):
        """(distance, cell, front) of the first hit of the ray within (0, tmax], or None (Moller-Trumbore)."""
        length = self.far if tmax is None else tmax
        if len(self.tri_cell) == 0:
            return None
        o, d = np.asarray(origin, dtype=float), np.asarray(direction, dtype=float)
        p = np.cross(d, self.tri_e2)
        det = np.einsum("ij,ij->i", self.tri_e1, p)
        ok = np.abs(det) > 1e-300
        inv = np.where(ok, 1.0 / np.where(ok, det, 1.0), 0.0)
        s_ = o - self.tri_a
        u = np.einsum("ij,ij->i", s_, p) * inv
        q = np.cross(s_, self.tri_e1)
        v = (q @ d) * inv
        t = np.einsum("ij,ij->i", self.tri_e2, q) * inv
        eps = 1e-12 * self.far
        hit = ok & (u >= 0) & (v >= 0) & (u + v <= 1) & (t > eps) & (t <= length)
        if not hit.any():
            return None
        # Coincident cells (the front and back patch of a two-sided face) are hit at the same t: the side facing the
        # ray is the one it meets, as Embree reports it.
        back = (self.tri_normal @ d) >= 0
        k = int(np.argmin(np.where(hit, t * (1 + 1e-9 * back), np.inf)))
        c = int(self.tri_cell[k])
        return float(t[k]), c, _dot(self.normal[c], direction) < 0


def _enclosed(scene, p):
    hits = []
    for k in range(PROBES):
        h = scene.intersect(p, probe_direction(k))
        if h is None or not h[2]:
            return None
        hits.append(h)
    return hits


def _direct_irradiance(scene, i, x, emitters, eps):
    total = 0.0
    for j in emitters:
        d = _sub(scene.centroid[j], x)
        r2 = _dot(d, d)
        if not r2 > 0:
            continue
        r = math.sqrt(r2)
        w = _mul(1.0 / r, d)
        ci, cj = _dot(scene.normal[i], w), -_dot(scene.normal[j], w)
        if ci <= 0 or cj <= 0:
            continue
        origin = _add(x, _mul(eps, scene.normal[i]))
        if scene.intersect(origin, w, r * (1 - 1e-6)) is not None:
            continue
        total += scene.E_sum[j] * scene.area[j] * ci * cj / (math.pi * r2)
    return total


def _inside_camera(scene, p, hits):
    vfov = math.radians(60.0)
    emitters = [j for j in range(scene.n) if scene.emits[j]]
    eps = 1e-6 * _norm(_sub(scene.hi, scene.lo))
    score, total, longest = [0.0] * PROBES, 0.0, 0
    for k in range(PROBES):
        t, i, _ = hits[k]
        if t > hits[longest][0]:
            longest = k
        if scene.emits[i]:
            continue
        score[k] = _direct_irradiance(scene, i, _add(p, _mul(t, probe_direction(k))), emitters, eps)
        total += score[k]
    best = probe_direction(longest)
    if total > 0:
        cos_half = math.cos(0.5 * vfov)
        dirs = [probe_direction(k) for k in range(PROBES)]
        best_sum = -1.0
        for a in range(PROBES):
            d = dirs[a]
            if abs(d[1]) > 0.9:
                continue
            s = sum(score[b] for b in range(PROBES) if _dot(d, dirs[b]) >= cos_half)
            if s > best_sum:
                best_sum, best = s, d
    return p, best, up_for(best), vfov


def _object_cells(scene):
    tol = 1e-6 * _norm(_sub(scene.hi, scene.lo))
    out = []
    for i in range(scene.n):
        if scene.emits[i]:
            continue
        c = scene.centroid[i]
        if not any(abs(c[a] - scene.lo[a]) <= tol or abs(c[a] - scene.hi[a]) <= tol for a in range(3)):
            out.append(i)
    return out


def _frame_objects(scene, p, hits, objects):
    if not objects:
        return None
    area = sum(scene.area[i] for i in objects)
    if not area > 0:
        return None
    c = _mul(1.0 / area, [sum(scene.area[i] * scene.centroid[i][a] for i in objects) for a in range(3)])
    stride = max(1, len(objects) // OBJECT_SAMPLES)
    vfov = math.radians(60.0)
    tan_half = math.tan(0.5 * vfov)
    best_score, best = 0, None
    for k in range(PROBES):
        q = _add(p, _mul(0.8 * hits[k][0], probe_direction(k)))
        f = _unit(_sub(c, q))
        up = up_for(f)
        r = _unit(_cross(f, up))
        u = _cross(r, f)
        score = 0
        for n in range(0, len(objects), stride):
            i = objects[n]
            d = _sub(scene.centroid[i], q)
            z = _dot(d, f)
            if not z > 0 or abs(_dot(d, r)) > z * tan_half or abs(_dot(d, u)) > z * tan_half:
                continue
            h = scene.intersect(q, _unit(d))
            if h is not None and h[2] and h[1] == i:
                score += 1
        if score > best_score:
            best_score, best = score, (q, f, up, vfov)
    return best


def _outside_camera(scene):
    lo, hi = scene.lo, scene.hi
    centre = _mul(0.5, _add(lo, hi))
    radius = 0.5 * _norm(_sub(hi, lo))
    vfov = math.radians(40.0)
    size = _sub(hi, lo)

    def view_from(d):
        d = _unit(list(d))
        distance = radius / math.tan(0.5 * vfov) + 0.5 * sum(abs(s * x) for s, x in zip(size, d))
        return _sub(centre, _mul(distance, d)), d, up_for(d), vfov

    cam = view_from((0, 0, 1))
    if scene.n == 0:
        return cam
    n, best = OUTSIDE_PIXELS, -1.0
    for d in OUTSIDE_DIRECTIONS:
        c2 = view_from(d)
        position, forward, up, _ = c2
        right = _unit(_cross(forward, up))
        true_up = _cross(right, forward)
        half = math.tan(0.5 * vfov)
        seen = 0.0
        for y in range(n):
            for x in range(n):
                sx = (2.0 * (x + 0.5) / n - 1.0) * half
                sy = (1.0 - 2.0 * (y + 0.5) / n) * half
                ray = _unit(_add(_add(forward, _mul(sx, right)), _mul(sy, true_up)))
                h = scene.intersect(position, ray)
                if h is not None and h[2]:
                    seen += 2 if scene.emits[h[1]] else 1
        if seen > best:
            best, cam = seen, c2
    return cam


def bounds(poly):
    """The bounding box (lo, hi) of poly's points."""
    b = poly.GetBounds() if poly.GetNumberOfPoints() else (0.0, 0.0, 0.0, 0.0, 0.0, 0.0)
    return [b[0], b[2], b[4]], [b[1], b[3], b[5]]


def focal_point(lo, hi, position, direction):
    """apps/scene_camera.h, camera_focal_point: on the axis, level with the box's centre, at least a quarter of
    the box's diagonal in front."""
    d = _unit(direction)
    centre = _mul(0.5, _add(lo, hi))
    distance = max(_dot(_sub(centre, position), d), 0.25 * _norm(_sub(hi, lo)) + 1e-12)
    return _add(position, _mul(distance, d))


def fit_camera(poly):
    """(position, direction, up, vfov in radians, source) by the rule of the module's doc."""
    scene_file = scene_name(poly)
    if scene_file is not None and os.path.basename(scene_file).startswith("cornell_box"):
        c = CORNELL_BOX
        return c[0:3], c[3:6], c[6:9], math.radians(c[9]), "cornell_box"
    scene = _Scene(poly)
    if scene.n > 0:
        centre = _mul(0.5, _add(scene.lo, scene.hi))
        q = _mul(0.25, _sub(scene.hi, scene.lo))
        starts = [centre, _add(centre, [q[0], 0, 0]), _sub(centre, [q[0], 0, 0]), _add(centre, [0, q[1], 0]),
                  _sub(centre, [0, q[1], 0]), _add(centre, [0, 0, q[2]]), _sub(centre, [0, 0, q[2]])]
        for p in starts:
            hits = _enclosed(scene, p)
            if hits is None:
                continue
            framed = _frame_objects(scene, p, hits, _object_cells(scene))
            cam = framed if framed is not None else _inside_camera(scene, p, hits)
            return cam[0], cam[1], cam[2], cam[3], "inside"
    cam = _outside_camera(scene)
    return cam[0], cam[1], cam[2], cam[3], "outside"


def view_up(up, direction):
    """up made orthogonal to the view direction, normalised (apps/scene_camera.h, view_point): the image's up."""
    d = _unit(direction)
    return _unit(_sub(up, _mul(_dot(up, d), d)))


def camera_rule(poly):
    """The camera for poly as ParaView's view takes it, [position, focal point, view up (orthogonal to the view
    direction), vertical fov in degrees]: see the module's doc (apps/scene_camera.h, view_point)."""
    position, direction, up, vfov, _ = fit_camera(poly)
    lo, hi = bounds(poly)
    return (list(position) + focal_point(lo, hi, position, direction) + view_up(up, direction) +
            [math.degrees(vfov)])
