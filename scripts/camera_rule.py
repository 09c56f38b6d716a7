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
cells) shadow rays, cast in batches with numpy against the triangles of the bounding boxes they cross.
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


CLUSTER = 32           # fan triangles per box of the ray culling (consecutive in Morton order), boxes per top box


def _fan_triangles(poly):
    """(points, a, b, c, owner) of the cells' fan triangles (corner 0, k, k + 1) as index arrays, or None when the
    cells are not all polygons (then the cells are read one by one)."""
    from vtkmodules.util.numpy_support import vtk_to_numpy
    polys = poly.GetPolys()
    n = poly.GetNumberOfCells()
    if n == 0 or polys is None or polys.GetNumberOfCells() != n or poly.GetPoints() is None:
        return None
    points = vtk_to_numpy(poly.GetPoints().GetData()).astype(float).reshape(-1, 3)
    offsets = vtk_to_numpy(polys.GetOffsetsArray()).astype(np.int64)
    conn = vtk_to_numpy(polys.GetConnectivityArray()).astype(np.int64)
    counts = np.diff(offsets)
    per = np.maximum(counts - 2, 0)
    owner = np.repeat(np.arange(n), per)
    first = np.repeat(np.cumsum(per) - per, per)
    k = np.arange(owner.size) - first + 1
    start = offsets[:-1][owner]
    return points, conn[start], conn[start + k], conn[start + k + 1], owner


def _crosses(o, d, lo, hi, L):
    """Whether rays o + t d, 0 <= t <= L, cross the boxes [lo, hi] (slab test, broadcast over leading axes; a zero
    direction component crosses iff its origin lies within the slab)."""
    with np.errstate(divide="ignore", invalid="ignore"):
        inv = 1.0 / d
        t0 = (lo - o) * inv
        t1 = (hi - o) * inv
    flat = d == 0
    inside = (lo <= o) & (o <= hi)
    near = np.where(flat, np.where(inside, -np.inf, np.inf), np.minimum(t0, t1))
    far = np.where(flat, np.where(inside, np.inf, -np.inf), np.maximum(t0, t1))
    return np.maximum(near.max(axis=-1), 0.0) <= np.minimum(far.min(axis=-1), L)


class _Scene:
    """The cells of a radwalk .vtp as the rule needs them: normals, emission, areas, centroids, a ray caster."""

    def __init__(self, poly):
        self.poly = poly
        n = poly.GetNumberOfCells()
        self.n = n
        self.lo, self.hi = bounds(poly)
        cd = poly.GetCellData()
        normals, E, area = cd.GetArray("normal"), cd.GetArray("E"), cd.GetArray("area")
        fan = _fan_triangles(poly)
        if fan is not None:
            from vtkmodules.util.numpy_support import vtk_to_numpy
            points, ia, ib, ic, owner = fan
            pa, pb, pc = points[ia], points[ib], points[ic]
            # Area centroid by a fan from the first corner (the display polygon's T-junction points lie on its
            # edges, so this is the patch's centroid), summed triangle by triangle in the fan's order with the
            # operations of the scalar code, so that it is the same to the last bit.
            cr = np.cross(pb - pa, pc - pa)
            ta = 0.5 * np.sqrt(((0.0 + cr[:, 0] * cr[:, 0]) + cr[:, 1] * cr[:, 1]) + cr[:, 2] * cr[:, 2])
            part = (ta / 3.0)[:, None] * ((pa + pb) + pc)
            total = np.zeros(n)
            csum = np.zeros((n, 3))
            first = np.ones(owner.size, dtype=bool)
            first[1:] = owner[1:] != owner[:-1]
            rank = np.arange(owner.size) - np.maximum.accumulate(np.where(first, np.arange(owner.size), 0))
            for k in range(int(rank.max()) + 1 if rank.size else 0):
                sel = rank == k
                csum[owner[sel]] = csum[owner[sel]] + part[sel]
                total[owner[sel]] = total[owner[sel]] + ta[sel]
            conn0 = vtk_to_numpy(poly.GetPolys().GetConnectivityArray()).astype(np.int64)
            corner0 = points[conn0[vtk_to_numpy(poly.GetPolys().GetOffsetsArray()).astype(np.int64)[:-1]]]
            with np.errstate(invalid="ignore", divide="ignore"):
                centroid = np.where((total > 0)[:, None], (1.0 / total)[:, None] * csum, corner0)
            self.centroid = centroid
            if normals is not None:
                self.normal = vtk_to_numpy(normals).astype(float).reshape(-1, 3)
            else:
                self.normal = np.array([self._cell_normal(i) for i in range(n)], dtype=float).reshape(-1, 3)
            e = vtk_to_numpy(E).astype(float).reshape(-1, 3) if E is not None else np.zeros((n, 3))
            self.emits = list((e > 0).any(axis=1))
            self.E_sum = list(e.sum(axis=1))
            self.area = list(vtk_to_numpy(area).astype(float)) if area is not None else list(total)
            tri_a, tri_b, tri_c, tri_cell = pa, pb, pc, owner
        else:
            self.normal, self.emits, self.area, self.centroid, self.E_sum = [], [], [], [], []
            a, b, c, cells = [], [], [], []
            for i in range(n):
                cell = poly.GetCell(i)
                pts = [cell.GetPoints().GetPoint(k) for k in range(cell.GetNumberOfPoints())]
                self.normal.append(list(normals.GetTuple3(i)) if normals is not None else self._cell_normal(i))
                e = E.GetTuple3(i) if E is not None else (0.0, 0.0, 0.0)
                self.emits.append(any(x > 0 for x in e))
                self.E_sum.append(sum(e))
                total, cc = 0.0, [0.0, 0.0, 0.0]
                for k in range(1, len(pts) - 1):
                    ar = 0.5 * _norm(_cross(_sub(pts[k], pts[0]), _sub(pts[k + 1], pts[0])))
                    cc = _add(cc, _mul(ar / 3.0, _add(_add(pts[0], pts[k]), pts[k + 1])))
                    total += ar
                    a.append(pts[0]), b.append(pts[k]), c.append(pts[k + 1]), cells.append(i)
                self.centroid.append(_mul(1.0 / total, cc) if total > 0 else list(pts[0]))
                self.area.append(area.GetValue(i) if area is not None else total)
            self.normal = np.array(self.normal, dtype=float).reshape(-1, 3)
            self.centroid = np.array(self.centroid, dtype=float).reshape(-1, 3)
            tri_a = np.array(a, dtype=float).reshape(-1, 3)
            tri_b = np.array(b, dtype=float).reshape(-1, 3)
            tri_c = np.array(c, dtype=float).reshape(-1, 3)
            tri_cell = np.array(cells, dtype=int)
        self.far = 4.0 * _norm(_sub(self.hi, self.lo)) + 1e-12
        # The cells as fan triangles, each with its cell, cast against with numpy (Moller-Trumbore, double). VTK's
        # locators were not used: on the same .vtp, ParaView's vtkModifiedBSPTree missed 52 of a closed cube's 512
        # centre probes and Debian's vtkStaticCellLocator 6 of a furnished room's. A ray is tested only against
        # the triangles of the clusters (CLUSTER consecutive triangles in Morton order of their centroids) whose
        # bounding box, widened by 1e-9 of the scene, it crosses: the same hits as testing every triangle.
        m = len(tri_cell)
        if m:
            mid = (tri_a + tri_b + tri_c) / 3.0
            span = np.maximum(np.asarray(self.hi, dtype=float) - np.asarray(self.lo, dtype=float), 1e-300)
            cell = np.clip(((mid - np.asarray(self.lo, dtype=float)) / span * 1023).astype(np.int64), 0, 1023)
            code = np.zeros(m, dtype=np.int64)
            for bit in range(10):
                for axis in range(3):
                    code |= ((cell[:, axis] >> bit) & 1) << (3 * bit + axis)
            order = np.argsort(code, kind="stable")
        else:
            order = np.zeros(0, dtype=int)
        self.tri_index = order                      # the original triangle index (ties go to the lower one)
        self.tri_a = tri_a[order]
        self.tri_e1 = tri_b[order] - self.tri_a
        self.tri_e2 = tri_c[order] - self.tri_a
        self.tri_cell = np.asarray(tri_cell, dtype=int)[order]
        self.tri_normal = self.normal[self.tri_cell] if m else np.zeros((0, 3))
        k = (m + CLUSTER - 1) // CLUSTER
        pad = CLUSTER * k - m
        corners = np.stack([self.tri_a, self.tri_a + self.tri_e1, self.tri_a + self.tri_e2], axis=1)
        if pad:
            corners = np.concatenate([corners, np.repeat(corners[-1:], pad, axis=0)])
        corners = corners.reshape(k, 3 * CLUSTER, 3)
        widen = 1e-9 * self.far
        self.box_lo = corners.min(axis=1) - widen
        self.box_hi = corners.max(axis=1) + widen
        # A second level: CLUSTER consecutive boxes under one box.
        kt = (k + CLUSTER - 1) // CLUSTER
        lo_, hi_ = self.box_lo, self.box_hi
        if kt * CLUSTER > k:
            lo_ = np.concatenate([lo_, np.repeat(lo_[-1:], kt * CLUSTER - k, axis=0)])
            hi_ = np.concatenate([hi_, np.repeat(hi_[-1:], kt * CLUSTER - k, axis=0)])
        self.top_lo = lo_.reshape(kt, CLUSTER, 3).min(axis=1)
        self.top_hi = hi_.reshape(kt, CLUSTER, 3).max(axis=1)

    def _cell_normal(self, i):
        nn = [0.0, 0.0, 0.0]
        vtkPolygon.ComputeNormal(self.poly.GetCell(i).GetPoints(), nn)
        return nn

    def intersect_many(self, origins, directions, tmax=None):
        """The first hits of rays (origins, directions: (R, 3)) within (0, tmax] (tmax: (R,) or None for the
        scene's far distance): arrays t (inf for none), cell (-1 for none), front (bool), as intersect gives them
        ray by ray."""
        O = np.asarray(origins, dtype=float).reshape(-1, 3)
        D = np.asarray(directions, dtype=float).reshape(-1, 3)
        R = len(O)
        length = np.full(R, self.far) if tmax is None else np.asarray(tmax, dtype=float).reshape(R)
        best_t = np.full(R, np.inf)
        best_key = np.full(R, np.inf)
        best_tri = np.full(R, -1, dtype=np.int64)
        if len(self.tri_cell) == 0 or R == 0:
            return best_t, np.full(R, -1, dtype=int), np.zeros(R, dtype=bool)
        eps = 1e-12 * self.far
        K = len(self.box_lo)
        chunk = max(1, min(2048, int(4e6 // max(len(self.top_lo), 1))))
        for r0 in range(0, R, chunk):
            o, d, L = O[r0:r0 + chunk], D[r0:r0 + chunk], length[r0:r0 + chunk]
            # The rays against the top boxes, then against the boxes under each top box they cross.
            ray, top = np.nonzero(_crosses(o[:, None, :], d[:, None, :], self.top_lo[None], self.top_hi[None],
                                           L[:, None]))
            if ray.size == 0:
                continue
            box = top[:, None] * CLUSTER + np.arange(CLUSTER)[None, :]
            valid = box < K
            box = np.minimum(box, K - 1)
            hit_box = valid & _crosses(o[ray][:, None, :], d[ray][:, None, :], self.box_lo[box], self.box_hi[box],
                                       L[ray][:, None])
            sel = np.nonzero(hit_box)
            ray, box = ray[sel[0]], box[sel]
            if ray.size == 0:
                continue
            tri = (box[:, None] * CLUSTER + np.arange(CLUSTER)[None, :]).ravel()
            ray = np.repeat(ray, CLUSTER)
            keep = tri < len(self.tri_cell)
            tri, ray = tri[keep], ray[keep]
            dd, e1, e2 = d[ray], self.tri_e1[tri], self.tri_e2[tri]
            p = np.cross(dd, e2)
            det = np.einsum("ij,ij->i", e1, p)
            ok = np.abs(det) > 1e-300
            inv_det = np.where(ok, 1.0 / np.where(ok, det, 1.0), 0.0)
            s_ = o[ray] - self.tri_a[tri]
            u = np.einsum("ij,ij->i", s_, p) * inv_det
            q = np.cross(s_, e1)
            v = np.einsum("ij,ij->i", q, dd) * inv_det
            t = np.einsum("ij,ij->i", e2, q) * inv_det
            hit = ok & (u >= 0) & (v >= 0) & (u + v <= 1) & (t > eps) & (t <= L[ray])
            if not hit.any():
                continue
            ray, tri, t = ray[hit], tri[hit], t[hit]
            # Coincident cells (the front and back patch of a two-sided face) are hit at the same t: the side facing
            # the ray is the one it meets, as Embree reports it.
            back = np.einsum("ij,ij->i", self.tri_normal[tri], d[ray]) >= 0
            key = t * (1 + 1e-9 * back)
            original = self.tri_index[tri]
            order = np.lexsort((original, key, ray))
            ray, key, t, tri = ray[order], key[order], t[order], tri[order]
            first = np.ones(ray.size, dtype=bool)
            first[1:] = ray[1:] != ray[:-1]
            rr = ray[first] + r0
            better = (key[first] < best_key[rr]) | (
                (key[first] == best_key[rr]) & (self.tri_index[tri[first]] < self.tri_index[np.maximum(best_tri[rr], 0)]))
            rr = rr[better]
            best_key[rr] = key[first][better]
            best_t[rr] = t[first][better]
            best_tri[rr] = tri[first][better]
        found = best_tri >= 0
        cell = np.where(found, self.tri_cell[np.maximum(best_tri, 0)], -1)
        front = found & (np.einsum("ij,ij->i", self.normal[np.maximum(cell, 0)], D) < 0)
        return best_t, cell, front

    def intersect(self, origin, direction, tmax=None):
        """(distance, cell, front) of the first hit of the ray within (0, tmax], or None (Moller-Trumbore)."""
        t, c, f = self.intersect_many([origin], [direction], None if tmax is None else [tmax])
        if c[0] < 0:
            return None
        return float(t[0]), int(c[0]), bool(f[0])


def _enclosed(scene, p):
    dirs = [probe_direction(k) for k in range(PROBES)]
    t, c, f = scene.intersect_many(np.repeat([p], PROBES, axis=0), dirs)
    if not (c >= 0).all() or not f.all():
        return None
    return [(float(t[k]), int(c[k]), True) for k in range(PROBES)]


def _direct_irradiance(scene, i, x, emitters, eps):
    """Unoccluded irradiance at x on cell i from the emitting cells' centroids (shadow rays cast together)."""
    rays = []
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
        rays.append((_add(x, _mul(eps, scene.normal[i])), w, r * (1 - 1e-6),
                     scene.E_sum[j] * scene.area[j] * ci * cj / (math.pi * r2)))
    if not rays:
        return 0.0
    _, c, _ = scene.intersect_many([r[0] for r in rays], [r[1] for r in rays], [r[2] for r in rays])
    total = 0.0
    for k, r in enumerate(rays):
        if c[k] < 0:
            total += r[3]
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
        cells, dirs = [], []
        for n in range(0, len(objects), stride):
            i = objects[n]
            d = _sub(scene.centroid[i], q)
            z = _dot(d, f)
            if not z > 0 or abs(_dot(d, r)) > z * tan_half or abs(_dot(d, u)) > z * tan_half:
                continue
            cells.append(i)
            dirs.append(_unit(d))
        score = 0
        if cells:
            _, hit, front = scene.intersect_many(np.repeat([q], len(cells), axis=0), dirs)
            score = int(np.count_nonzero(front & (hit == np.asarray(cells))))
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
        rays = []
        for y in range(n):
            for x in range(n):
                sx = (2.0 * (x + 0.5) / n - 1.0) * half
                sy = (1.0 - 2.0 * (y + 0.5) / n) * half
                rays.append(_unit(_add(_add(forward, _mul(sx, right)), _mul(sy, true_up))))
        _, c, front = scene.intersect_many(np.repeat([position], len(rays), axis=0), rays)
        seen = 0.0
        for k in range(len(rays)):
            if front[k]:
                seen += 2 if scene.emits[c[k]] else 1
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
