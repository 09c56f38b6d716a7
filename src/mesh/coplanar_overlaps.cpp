#include "mesh/coplanar_overlaps.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "mesh/face_geometry.h"

namespace radwalk {

namespace {

using Vec2 = Eigen::Vector2d;
constexpr double kU = std::numeric_limits<double>::epsilon() / 2;  // unit roundoff

const Vec3& corner(const Mesh& mesh, std::size_t f, int k) {
  return mesh.vertices[static_cast<std::size_t>(mesh.faces[f][static_cast<std::size_t>(k)])];
}

// The face's triangles: (0,1,2), and (0,2,3) for a quad.
int triangle_count(const Mesh& mesh, std::size_t f) { return mesh.is_quad(f) ? 2 : 1; }
std::array<Vec3, 3> triangle(const Mesh& mesh, std::size_t f, int t) {
  return t == 0 ? std::array<Vec3, 3>{corner(mesh, f, 0), corner(mesh, f, 1), corner(mesh, f, 2)}
                : std::array<Vec3, 3>{corner(mesh, f, 0), corner(mesh, f, 2), corner(mesh, f, 3)};
}

// q lies in the plane of (a, b, c) within the rounding of its distance from it (coplanar_overlaps.h).
bool in_plane(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& q) {
  const Vec3 ad = a - q, bd = b - q, cd = c - q;
  const double det = ad.dot(bd.cross(cd));
  const double permanent = std::abs(ad.x()) * (std::abs(bd.y() * cd.z()) + std::abs(bd.z() * cd.y())) +
                           std::abs(ad.y()) * (std::abs(bd.z() * cd.x()) + std::abs(bd.x() * cd.z())) +
                           std::abs(ad.z()) * (std::abs(bd.x() * cd.y()) + std::abs(bd.y() * cd.x()));
  const double cross = (b - a).cross(c - a).norm();
  if (!(cross > 0)) return false;
  const double M = std::max({a.cwiseAbs().maxCoeff(), b.cwiseAbs().maxCoeff(), c.cwiseAbs().maxCoeff(),
                             q.cwiseAbs().maxCoeff()});
  const double input = 4 * kU * M * (1 + (q - a).norm() * ((b - a).norm() + (c - a).norm()) / cross);
  return std::abs(det) / cross <= 8 * kU * permanent / cross + input;
}

double polygon_area(const std::vector<Vec2>& p) {
  double s = 0;
  for (std::size_t k = 0; k < p.size(); ++k) {
    const Vec2 &a = p[k], &b = p[(k + 1) % p.size()];
    s += a.x() * b.y() - a.y() * b.x();
  }
  return 0.5 * s;
}

// Area of the intersection of two triangles in the plane (Sutherland-Hodgman: s clipped by each side of t).
double intersection_area(std::array<Vec2, 3> s, std::array<Vec2, 3> t) {
  auto cross = [](const Vec2& a, const Vec2& b, const Vec2& p) {
    return (b.x() - a.x()) * (p.y() - a.y()) - (b.y() - a.y()) * (p.x() - a.x());
  };
  if (cross(t[0], t[1], t[2]) < 0) std::swap(t[1], t[2]);  // counter-clockwise
  std::vector<Vec2> poly(s.begin(), s.end()), next;
  for (int e = 0; e < 3 && !poly.empty(); ++e) {
    const Vec2 &a = t[static_cast<std::size_t>(e)], &b = t[static_cast<std::size_t>((e + 1) % 3)];
    next.clear();
    for (std::size_t k = 0; k < poly.size(); ++k) {
      const Vec2 &p = poly[k], &q = poly[(k + 1) % poly.size()];
      const double dp = cross(a, b, p), dq = cross(a, b, q);
      if (dp >= 0) next.push_back(p);
      if ((dp >= 0) != (dq >= 0)) next.push_back(p + (dp / (dp - dq)) * (q - p));
    }
    poly.swap(next);
  }
  return poly.size() < 3 ? 0.0 : std::abs(polygon_area(poly));
}

}  // namespace

std::vector<CoplanarOverlap> find_coplanar_overlaps(const Mesh& mesh, const std::vector<bool>* skip,
                                                    std::size_t* pair_tests) {
  const std::size_t F = mesh.face_count();
  std::vector<CoplanarOverlap> found;
  if (F < 2) return found;

  // Boxes, unit normals, extents; h = the median extent.
  std::vector<Vec3> lo(F), hi(F), normal(F);
  std::vector<double> extent(F);
  Vec3 origin = Vec3::Constant(std::numeric_limits<double>::infinity());
  for (std::size_t f = 0; f < F; ++f) {
    lo[f] = hi[f] = corner(mesh, f, 0);
    for (int k = 1; k < mesh.corner_count(f); ++k) {
      lo[f] = lo[f].cwiseMin(corner(mesh, f, k));
      hi[f] = hi[f].cwiseMax(corner(mesh, f, k));
    }
    extent[f] = (hi[f] - lo[f]).maxCoeff();
    origin = origin.cwiseMin(lo[f]);
    const Vec3 va = face_vector_area(mesh, f);
    normal[f] = va.norm() > 0 ? Vec3(va / va.norm()) : Vec3::Zero();
  }
  std::vector<double> sorted = extent;
  std::nth_element(sorted.begin(), sorted.begin() + static_cast<std::ptrdiff_t>(F / 2), sorted.end());
  double h = sorted[F / 2];
  if (!(h > 0)) h = *std::max_element(extent.begin(), extent.end());
  if (!(h > 0) || !std::isfinite(h)) return found;

  // Levels: face f is on the lowest level l with extent <= h 2^l, in the cells (at most 2 per axis) its box covers.
  std::vector<std::int8_t> level(F);
  std::vector<char> level_used(64, 0);
  for (std::size_t f = 0; f < F; ++f) {
    int l = 0;
    while (l < 62 && std::ldexp(h, l) < extent[f]) ++l;
    level[f] = static_cast<std::int8_t>(l);
    level_used[static_cast<std::size_t>(l)] = 1;
  }
  // Cell coordinates, clamped to 32 bits (a clamped cell is only a larger one: more candidates, none lost).
  auto cells = [&](std::size_t f, int l) {
    const double size = std::ldexp(h, l);
    std::array<std::int32_t, 6> c{};
    auto index = [](double x) {
      return static_cast<std::int32_t>(std::clamp(std::floor(x), -2147483648.0, 2147483647.0));
    };
    for (int a = 0; a < 3; ++a) {
      c[static_cast<std::size_t>(2 * a)] = index((lo[f][a] - origin[a]) / size);
      c[static_cast<std::size_t>(2 * a + 1)] = index((hi[f][a] - origin[a]) / size);
    }
    return c;  // x0, x1, y0, y1, z0, z1
  };
  // One entry per (cell, face), sorted by cell: (level, x, y, z), so a cell's faces are consecutive and cells are
  // visited in space order (the faces' data then stays in cache for meshes whose face order follows space).
  struct Entry {
    std::array<std::int32_t, 4> cell;  // level, x, y, z
    std::int32_t face;
  };
  // Cell order and equality, written out (std::array's call memcmp).
  auto before = [](const std::array<std::int32_t, 4>& x, const std::array<std::int32_t, 4>& y) {
    if (x[0] != y[0]) return x[0] < y[0];
    if (x[1] != y[1]) return x[1] < y[1];
    if (x[2] != y[2]) return x[2] < y[2];
    return x[3] < y[3];
  };
  auto same = [](const std::array<std::int32_t, 4>& x, const std::array<std::int32_t, 4>& y) {
    return x[0] == y[0] && x[1] == y[1] && x[2] == y[2] && x[3] == y[3];
  };
  std::vector<Entry> entries;
  entries.reserve(4 * F);
  for (std::size_t f = 0; f < F; ++f) {
    if (skip && (*skip)[f]) continue;
    if (normal[f] == Vec3::Zero()) continue;
    const int l = level[f];
    const auto c = cells(f, l);
    for (std::int64_t x = c[0]; x <= c[1]; ++x)
      for (std::int64_t y = c[2]; y <= c[3]; ++y)
        for (std::int64_t z = c[4]; z <= c[5]; ++z)
          entries.push_back({{l, static_cast<std::int32_t>(x), static_cast<std::int32_t>(y), static_cast<std::int32_t>(z)},
                             static_cast<std::int32_t>(f)});
  }
  std::sort(entries.begin(), entries.end(),
            [&](const Entry& x, const Entry& y) { return same(x.cell, y.cell) ? x.face < y.face : before(x.cell, y.cell); });
  int levels = 0;
  for (const char used : level_used) levels += used;
  // The first entry of a cell (entries.size() if none): a binary search.
  auto first_entry = [&](const std::array<std::int32_t, 4>& cell) -> std::size_t {
    const auto it = std::lower_bound(entries.begin(), entries.end(), cell,
                                     [&](const Entry& e, const std::array<std::int32_t, 4>& c) { return before(e.cell, c); });
    return it != entries.end() && same(it->cell, cell) ? static_cast<std::size_t>(it - entries.begin()) : entries.size();
  };

  // The pair test: boxes touch, normals (anti)parallel, every corner in the other's planes, positive overlap.
  std::size_t tests = 0;
  auto test = [&](std::size_t f, std::size_t g) {
    ++tests;
    for (int a = 0; a < 3; ++a)
      if (lo[f][a] > hi[g][a] || lo[g][a] > hi[f][a]) return;
    const double cosine = normal[f].dot(normal[g]);
    if (std::abs(cosine) < 1 - 1e-3) return;  // a loose filter: the plane test below decides
    // In f's plane: a side of either face along which they are apart, or only touch (neighbours sharing an edge),
    // within the rounding 64 u D of the projected coordinates, separates them (a quick rejection, sound for any
    // corners: the triangles lie in the hull of their face's corners).
    const Vec3 e1 = normal[f].unitOrthogonal(), e2 = normal[f].cross(e1), o = corner(mesh, f, 0);
    const double D = (hi[f].cwiseMax(hi[g]) - lo[f].cwiseMin(lo[g])).norm();
    std::array<Vec2, 4> pf, pg;
    const int nf = mesh.corner_count(f), ng = mesh.corner_count(g);
    for (int k = 0; k < nf; ++k)
      pf[static_cast<std::size_t>(k)] = Vec2((corner(mesh, f, k) - o).dot(e1), (corner(mesh, f, k) - o).dot(e2));
    for (int k = 0; k < ng; ++k)
      pg[static_cast<std::size_t>(k)] = Vec2((corner(mesh, g, k) - o).dot(e1), (corner(mesh, g, k) - o).dot(e2));
    for (const auto& [poly, m] : {std::pair<const std::array<Vec2, 4>*, int>{&pf, nf}, {&pg, ng}})
      for (int k = 0; k < m; ++k) {
        const Vec2 edge = (*poly)[static_cast<std::size_t>((k + 1) % m)] - (*poly)[static_cast<std::size_t>(k)];
        const double length = edge.norm();
        if (!(length > 0)) continue;
        const Vec2 axis(-edge.y() / length, edge.x() / length);
        double f0 = std::numeric_limits<double>::infinity(), f1 = -f0, g0 = f0, g1 = -f0;
        for (int j = 0; j < nf; ++j) {
          const double x = axis.dot(pf[static_cast<std::size_t>(j)]);
          f0 = std::min(f0, x);
          f1 = std::max(f1, x);
        }
        for (int j = 0; j < ng; ++j) {
          const double x = axis.dot(pg[static_cast<std::size_t>(j)]);
          g0 = std::min(g0, x);
          g1 = std::max(g1, x);
        }
        if (f0 >= g1 - 64 * kU * D || g0 >= f1 - 64 * kU * D) return;
      }
    for (const auto& [x, y] : {std::pair<std::size_t, std::size_t>{f, g}, {g, f}})
      for (int t = 0; t < triangle_count(mesh, x); ++t) {
        const auto tri = triangle(mesh, x, t);
        for (int k = 0; k < mesh.corner_count(y); ++k)
          if (!in_plane(tri[0], tri[1], tri[2], corner(mesh, y, k))) return;
      }
    auto flat = [&](const std::array<Vec3, 3>& tri) {
      std::array<Vec2, 3> p;
      for (std::size_t k = 0; k < 3; ++k) p[k] = Vec2((tri[k] - o).dot(e1), (tri[k] - o).dot(e2));
      return p;
    };
    double area = 0;
    for (int s = 0; s < triangle_count(mesh, f); ++s)
      for (int t = 0; t < triangle_count(mesh, g); ++t)
        area += intersection_area(flat(triangle(mesh, f, s)), flat(triangle(mesh, g, t)));
    auto perimeter = [&](std::size_t x) {
      double p = 0;
      for (int k = 0; k < mesh.corner_count(x); ++k)
        p += (corner(mesh, x, (k + 1) % mesh.corner_count(x)) - corner(mesh, x, k)).norm();
      return p;
    };
    if (!(area > 64 * kU * (perimeter(f) + perimeter(g)) * D)) return;
    found.push_back({static_cast<std::int32_t>(std::min(f, g)), static_cast<std::int32_t>(std::max(f, g)), area,
                     cosine > 0});
  };

  // Pairs on one level: within each cell's entries, each pair in the first cell both boxes cover.
  for (std::size_t begin = 0, end = 0; begin < entries.size(); begin = end) {
    end = begin + 1;
    while (end < entries.size() && same(entries[end].cell, entries[begin].cell)) ++end;
    const auto& cell = entries[begin].cell;
    for (std::size_t i = begin; i < end; ++i)
      for (std::size_t j = i + 1; j < end; ++j) {
        const auto f = static_cast<std::size_t>(entries[i].face), g = static_cast<std::size_t>(entries[j].face);
        const auto cf = cells(f, cell[0]), cg = cells(g, cell[0]);
        if (std::max(cf[0], cg[0]) != cell[1] || std::max(cf[2], cg[2]) != cell[2] || std::max(cf[4], cg[4]) != cell[3])
          continue;
        test(f, g);
      }
  }
  // Pairs across levels: each face looks up the cells its box covers on every coarser level in use.
  for (std::size_t f = 0; f < F && levels > 1; ++f) {
    if (skip && (*skip)[f]) continue;
    if (normal[f] == Vec3::Zero()) continue;
    for (int l = level[f] + 1; l < 64; ++l) {
      if (!level_used[static_cast<std::size_t>(l)]) continue;
      const auto c = cells(f, l);
      for (std::int64_t x = c[0]; x <= c[1]; ++x)
        for (std::int64_t y = c[2]; y <= c[3]; ++y)
          for (std::int64_t z = c[4]; z <= c[5]; ++z) {
            const std::array<std::int32_t, 4> cell = {l, static_cast<std::int32_t>(x), static_cast<std::int32_t>(y),
                                                      static_cast<std::int32_t>(z)};
            for (std::size_t e = first_entry(cell); e < entries.size() && same(entries[e].cell, cell); ++e) {
              const auto g = static_cast<std::size_t>(entries[e].face);
              const auto cg = cells(g, l);
              // Each pair once: in the first cell both boxes cover.
              if (std::max(c[0], cg[0]) != x || std::max(c[2], cg[2]) != y || std::max(c[4], cg[4]) != z) continue;
              test(f, g);
            }
          }
    }
  }
  if (pair_tests) *pair_tests += tests;
  std::sort(found.begin(), found.end(), [](const CoplanarOverlap& a, const CoplanarOverlap& b) {
    return a.face_a != b.face_a ? a.face_a < b.face_a : a.face_b < b.face_b;
  });
  return found;
}

}  // namespace radwalk
