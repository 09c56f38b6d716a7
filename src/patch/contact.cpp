#include "patch/contact.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>

#include "core/error.h"
#include "mesh/edge_table.h"
#include "mesh/face_geometry.h"

namespace radwalk {

namespace {

using Polygon = std::vector<Vec3>;

// Coplanar: normals within about 4.5e-5 rad (1 - cos < 1e-9).
constexpr double kCoplanarDot = 1 - 1e-9;

const Vec3& corner(const Mesh& m, std::size_t f, int k) {
  return m.vertices[static_cast<std::size_t>(m.faces[f][static_cast<std::size_t>(k)])];
}

Polygon face_polygon(const Mesh& m, std::size_t f) {
  Polygon p;
  for (int k = 0; k < m.corner_count(f); ++k) p.push_back(corner(m, f, k));
  return p;
}

// Vector area of a polygon (Newell): its norm is the area, its direction the normal of the corner order.
Vec3 vector_area(const Polygon& p) {
  Vec3 a = Vec3::Zero();
  for (std::size_t k = 0; k + 2 < p.size(); ++k) a += 0.5 * (p[k + 1] - p[0]).cross(p[k + 2] - p[0]);
  return a;
}

bool lexicographic_less(const Vec3& a, const Vec3& b) {
  return a.x() != b.x() ? a.x() < b.x() : a.y() != b.y() ? a.y() < b.y() : a.z() < b.z();
}

// The parts of convex polygon p where (x - a) . m >= 0 (inside) and <= 0 (outside). Corners within tol of the line
// count as on it. A crossing point is computed from the edge's end points in lexicographic order, so the same edge
// gives the same point whichever face it belongs to.
void clip(const Polygon& p, const Vec3& a, const Vec3& m, double tol, Polygon& inside, Polygon& outside) {
  inside.clear();
  outside.clear();
  const std::size_t n = p.size();
  std::vector<double> s(n);
  for (std::size_t k = 0; k < n; ++k) {
    s[k] = (p[k] - a).dot(m);
    if (std::abs(s[k]) <= tol) s[k] = 0;
  }
  for (std::size_t k = 0; k < n; ++k) {
    const std::size_t l = (k + 1) % n;
    if (s[k] >= 0) inside.push_back(p[k]);
    if (s[k] <= 0) outside.push_back(p[k]);
    if ((s[k] > 0 && s[l] < 0) || (s[k] < 0 && s[l] > 0)) {
      const bool forward = lexicographic_less(p[k], p[l]);
      const Vec3& u = forward ? p[k] : p[l];
      const Vec3& v = forward ? p[l] : p[k];
      const double su = forward ? s[k] : s[l], sv = forward ? s[l] : s[k];
      const Vec3 x = u + (su / (su - sv)) * (v - u);
      inside.push_back(x);
      outside.push_back(x);
    }
  }
}

// Drops corners within tol of the previous one and corners where the polygon goes straight on.
Polygon simplified(const Polygon& p, double tol) {
  Polygon q;
  for (const Vec3& v : p)
    if (q.empty() || (v - q.back()).norm() > tol) q.push_back(v);
  while (q.size() > 1 && (q.front() - q.back()).norm() <= tol) q.pop_back();
  bool changed = true;
  while (changed && q.size() >= 3) {
    changed = false;
    for (std::size_t k = 0; k < q.size(); ++k) {
      const Vec3& a = q[(k + q.size() - 1) % q.size()];
      const Vec3& b = q[k];
      const Vec3& c = q[(k + 1) % q.size()];
      const Vec3 e1 = b - a, e2 = c - b;
      if (e1.cross(e2).norm() <= 1e-12 * e1.norm() * e2.norm() + tol * tol) {
        q.erase(q.begin() + static_cast<std::ptrdiff_t>(k));
        changed = true;
        break;
      }
    }
  }
  return q;
}

// Unit inward normal of edge a -> b of a polygon counter-clockwise about n (the polygon lies to its left).
Vec3 inward(const Vec3& n, const Vec3& a, const Vec3& b) { return n.cross(b - a).normalized(); }

// S n K for convex S and K (K counter-clockwise about n).
Polygon intersection(const Polygon& S, const Polygon& K, const Vec3& n, double tol) {
  Polygon current = S, in, out;
  for (std::size_t k = 0; k < K.size() && current.size() >= 3; ++k) {
    clip(current, K[k], inward(n, K[k], K[(k + 1) % K.size()]), tol, in, out);
    current = in;
  }
  return current.size() >= 3 ? current : Polygon{};
}

// Arm k of a pinwheel of convex P about convex K (counter-clockwise about n): the part of P outside the line of
// K's edge k and inside the line of its neighbouring edge j (j = k - 1 for the forward pinwheel, k + 1 for the
// backward one),
//   R_k = P n {x : (x - K_k) . m_k < 0} n {x : (x - K_j) . m_j >= 0}     (m_i: edge i's inward normal).
// The arms of one pinwheel and P n K tile P: seen from a point x outside convex K, the edges whose lines x lies
// outside of form one run of consecutive edges, and x is in the arm of the run's first edge only (forward) or of
// its last edge only (backward). Each arm is P cut by two half-planes, so convex; each footprint edge's line is
// continued beyond one of its two corners only, to P's boundary, instead of as a chord across the whole of P in
// both directions, which cut the pieces beside K again into wedges and slivers.
Polygon pinwheel_arm(const Polygon& P, const Polygon& K, std::size_t k, bool forward, const Vec3& n, double tol) {
  const std::size_t j = forward ? (k + K.size() - 1) % K.size() : (k + 1) % K.size();
  Polygon in, out, arm;
  clip(P, K[j], inward(n, K[j], K[(j + 1) % K.size()]), tol, in, out);
  in = simplified(in, tol);
  if (in.size() < 3) return {};
  clip(in, K[k], inward(n, K[k], K[(k + 1) % K.size()]), tol, out, arm);
  return simplified(arm, tol);
}

// The smallest corner angle of polygon p (radians): the shape measure of a piece (pi / 3 for an equilateral
// triangle, pi / 2 for a rectangle, near 0 for a sliver).
double smallest_angle(const Polygon& p) {
  double smallest = kPi;
  for (std::size_t k = 0; k < p.size(); ++k) {
    const Vec3 u = p[(k + p.size() - 1) % p.size()] - p[k], v = p[(k + 1) % p.size()] - p[k];
    smallest = std::min(smallest, std::atan2(u.cross(v).norm(), u.dot(v)));
  }
  return smallest;
}

// Convex polygon p as mesh faces: a fan of quads from corner s (s, s+1, s+2, s+3), (s, s+3, s+4, s+5), ... and one
// triangle if the corner count is odd. Of the fans from each corner, the one whose smallest face angle is largest
// (the first such corner on ties), so that a pentagon or hexagon is not split along a diagonal that leaves a sliver.
std::vector<Polygon> fan_faces(const Polygon& p) {
  std::vector<Polygon> best;
  double best_angle = -1;
  const std::size_t m = p.size();
  for (std::size_t s = 0; s < (m > 4 ? m : 1); ++s) {
    std::vector<Polygon> faces;
    auto at = [&](std::size_t k) { return p[(s + k) % m]; };
    std::size_t k = 1;
    for (; k + 2 < m; k += 2) faces.push_back({at(0), at(k), at(k + 1), at(k + 2)});
    if (k + 1 < m) faces.push_back({at(0), at(k), at(k + 1)});
    double angle = kPi;
    for (const Polygon& f : faces) angle = std::min(angle, smallest_angle(f));
    if (angle > best_angle) {
      best_angle = angle;
      best = std::move(faces);
    }
  }
  return best;
}

// The smallest face angle of the pieces as they will be written (fan_faces).
double worst_angle(const std::vector<Polygon>& pieces) {
  double angle = kPi;
  for (const Polygon& piece : pieces)
    for (const Polygon& f : fan_faces(piece)) angle = std::min(angle, smallest_angle(f));
  return angle;
}

// Whether segment a-b crosses the interior of convex polygon P (counter-clockwise about n): the part of the segment
// inside P is longer than tol and P has area more than min_area on both sides of the segment's line. The two sides
// (clip's inside and outside of the line, normal n x (b - a)) are left in `in` and `out` when it does.
bool crosses(const Polygon& P, const Vec3& n, const Vec3& a, const Vec3& b, double tol, double min_area, Polygon& in,
             Polygon& out) {
  double t0 = 0, t1 = 1;
  const Vec3 d = b - a;
  for (std::size_t k = 0; k < P.size() && t0 <= t1; ++k) {
    const Vec3 m = inward(n, P[k], P[(k + 1) % P.size()]);
    const double s0 = (a - P[k]).dot(m), ds = d.dot(m);  // (a + t d - P_k) . m >= 0
    if (std::abs(ds) < 1e-300) {
      if (s0 < -tol) return false;
    } else if (ds > 0) {
      t0 = std::max(t0, -s0 / ds);
    } else {
      t1 = std::min(t1, -s0 / ds);
    }
  }
  if ((t1 - t0) * d.norm() <= tol) return false;
  clip(P, a, n.cross(d).normalized(), tol, in, out);
  return vector_area(in).norm() > min_area && vector_area(out).norm() > min_area;
}

bool is_convex(const Polygon& K, const Vec3& n) {
  for (std::size_t k = 0; k < K.size(); ++k) {
    const Vec3& a = K[k];
    const Vec3& b = K[(k + 1) % K.size()];
    const Vec3& c = K[(k + 2) % K.size()];
    if ((b - a).cross(c - b).dot(n) < -1e-12 * (b - a).norm() * (c - b).norm()) return false;
  }
  return true;
}

// Union-find over faces.
struct Sets {
  std::vector<std::int32_t> parent;
  explicit Sets(std::size_t n) : parent(n) { std::iota(parent.begin(), parent.end(), 0); }
  std::int32_t find(std::int32_t i) {
    while (parent[static_cast<std::size_t>(i)] != i)
      i = parent[static_cast<std::size_t>(i)] = parent[static_cast<std::size_t>(parent[static_cast<std::size_t>(i)])];
    return i;
  }
  void unite(std::int32_t a, std::int32_t b) {
    a = find(a);
    b = find(b);
    if (a != b) parent[static_cast<std::size_t>(std::max(a, b))] = std::min(a, b);
  }
};

double scene_extent(const Mesh& m) {
  if (m.vertices.empty()) return 0;
  Vec3 lo = m.vertices[0], hi = m.vertices[0];
  for (const Vec3& v : m.vertices) {
    lo = lo.cwiseMin(v);
    hi = hi.cwiseMax(v);
  }
  return (hi - lo).maxCoeff();
}

}  // namespace

std::vector<Contact> find_contacts(const Mesh& mesh) {
  std::vector<Contact> contacts;
  const std::size_t n_faces = mesh.face_count();
  if (n_faces == 0) return contacts;
  const double tol = kContactTolerance * scene_extent(mesh);
  const EdgeTable table = build_edge_table(mesh);
  std::vector<Vec3> normal(n_faces);
  for (std::size_t f = 0; f < n_faces; ++f) normal[f] = face_vector_area(mesh, f).normalized();
  auto distance = [&](std::size_t f, const Vec3& p) { return normal[f].dot(p - corner(mesh, f, 0)); };
  auto coplanar_with = [&](std::size_t f, std::size_t g) {  // g's corners on f's plane
    for (int k = 0; k < mesh.corner_count(g); ++k)
      if (std::abs(distance(f, corner(mesh, g, k))) > tol) return false;
    return true;
  };

  // Support surfaces: coplanar, same-facing faces joined through shared edges.
  Sets surfaces(n_faces);
  for (std::size_t e = 0; e < table.edge_count(); ++e)
    for (const EdgeUse* u = table.uses_begin(e); u != table.uses_end(e); ++u)
      for (const EdgeUse* w = u + 1; w != table.uses_end(e); ++w) {
        const auto f = static_cast<std::size_t>(u->face), g = static_cast<std::size_t>(w->face);
        if (normal[f].dot(normal[g]) >= kCoplanarDot && coplanar_with(f, g) && coplanar_with(g, f))
          surfaces.unite(u->face, w->face);
      }
  std::map<std::int32_t, std::vector<std::int32_t>> members;
  for (std::size_t f = 0; f < n_faces; ++f) members[surfaces.find(static_cast<std::int32_t>(f))].push_back(
      static_cast<std::int32_t>(f));

  auto position = [&](std::int32_t w) -> const Vec3& {
    return mesh.vertices[static_cast<std::size_t>(table.welded_source[static_cast<std::size_t>(w)])];
  };
  std::vector<std::int32_t> surface_of(n_faces);
  for (const auto& [root, faces] : members)
    for (const std::int32_t f : faces) surface_of[static_cast<std::size_t>(f)] = root;

  // Welded vertex -> edges and faces using it; a uniform grid of the welded vertices (cells of 1/128 of the
  // extent), so each surface only looks at the vertices near its bounding box.
  const std::size_t n_welded = table.welded_source.size();
  std::vector<std::vector<std::int32_t>> vertex_edges(n_welded), vertex_faces(n_welded);
  for (std::size_t e = 0; e < table.edge_count(); ++e)
    for (const std::int32_t v : table.edges[e]) vertex_edges[static_cast<std::size_t>(v)].push_back(static_cast<std::int32_t>(e));
  for (std::size_t f = 0; f < n_faces; ++f)
    for (int k = 0; k < mesh.corner_count(f); ++k) {
      auto& list = vertex_faces[static_cast<std::size_t>(table.weld[static_cast<std::size_t>(mesh.faces[f][static_cast<std::size_t>(k)])])];
      if (list.empty() || list.back() != static_cast<std::int32_t>(f)) list.push_back(static_cast<std::int32_t>(f));
    }
  Vec3 scene_lo = position(0), scene_hi = position(0);
  for (std::size_t w = 0; w < n_welded; ++w) {
    scene_lo = scene_lo.cwiseMin(position(static_cast<std::int32_t>(w)));
    scene_hi = scene_hi.cwiseMax(position(static_cast<std::int32_t>(w)));
  }
  const double cell = std::max((scene_hi - scene_lo).maxCoeff() / 128.0, std::max(tol, 1e-300));
  auto cell_of = [&](double x, double origin) {
    return static_cast<std::int64_t>(std::floor(std::min((x - origin) / cell, 1e6)));
  };
  std::map<std::array<std::int64_t, 3>, std::vector<std::int32_t>> grid;
  for (std::size_t w = 0; w < n_welded; ++w) {
    const Vec3& p = position(static_cast<std::int32_t>(w));
    grid[{cell_of(p.x(), scene_lo.x()), cell_of(p.y(), scene_lo.y()), cell_of(p.z(), scene_lo.z())}].push_back(
        static_cast<std::int32_t>(w));
  }

  for (const auto& [root, faces] : members) {
    const auto s0 = static_cast<std::size_t>(faces.front());
    const Vec3 n = normal[s0];
    Vec3 lo = corner(mesh, s0, 0), hi = lo;
    for (const std::int32_t f : faces)
      for (int k = 0; k < mesh.corner_count(static_cast<std::size_t>(f)); ++k) {
        lo = lo.cwiseMin(corner(mesh, static_cast<std::size_t>(f), k));
        hi = hi.cwiseMax(corner(mesh, static_cast<std::size_t>(f), k));
      }
    lo.array() -= tol;
    hi.array() += tol;
    auto on_surface = [&](const Vec3& p) {
      return std::abs(distance(s0, p)) <= tol && (p.array() >= lo.array()).all() && (p.array() <= hi.array()).all();
    };
    // The welded vertices on the surface's plane within its bounding box, from the grid cells the box overlaps.
    std::vector<std::int32_t> near;
    {
      const std::int64_t x0 = cell_of(lo.x(), scene_lo.x()), x1 = cell_of(hi.x(), scene_lo.x());
      const std::int64_t y0 = cell_of(lo.y(), scene_lo.y()), y1 = cell_of(hi.y(), scene_lo.y());
      const std::int64_t z0 = cell_of(lo.z(), scene_lo.z()), z1 = cell_of(hi.z(), scene_lo.z());
      if ((x1 - x0 + 1) * (y1 - y0 + 1) * (z1 - z0 + 1) > static_cast<std::int64_t>(grid.size())) {
        for (const auto& [key, list] : grid)
          for (const std::int32_t w : list)
            if (on_surface(position(w))) near.push_back(w);
      } else {
        for (std::int64_t x = x0; x <= x1; ++x)
          for (std::int64_t y = y0; y <= y1; ++y)
            for (std::int64_t z = z0; z <= z1; ++z) {
              const auto it = grid.find({x, y, z});
              if (it == grid.end()) continue;
              for (const std::int32_t w : it->second)
                if (on_surface(position(w))) near.push_back(w);
            }
      }
      std::sort(near.begin(), near.end());
    }
    auto is_near = [&](std::int32_t w) { return std::binary_search(near.begin(), near.end(), w); };
    std::vector<std::int32_t> candidate_edges, candidate_faces;
    for (const std::int32_t w : near) {
      for (const std::int32_t e : vertex_edges[static_cast<std::size_t>(w)]) {
        const auto& ends = table.edges[static_cast<std::size_t>(e)];
        if (is_near(ends[0] == w ? ends[1] : ends[0])) candidate_edges.push_back(e);
      }
      for (const std::int32_t f : vertex_faces[static_cast<std::size_t>(w)]) candidate_faces.push_back(f);
    }
    std::sort(candidate_edges.begin(), candidate_edges.end());
    candidate_edges.erase(std::unique(candidate_edges.begin(), candidate_edges.end()), candidate_edges.end());
    std::sort(candidate_faces.begin(), candidate_faces.end());
    candidate_faces.erase(std::unique(candidate_faces.begin(), candidate_faces.end()), candidate_faces.end());
    // Contact edges: (edge, rising face), adjacency by welded vertex.
    std::map<std::int32_t, std::vector<std::pair<std::int32_t, std::int32_t>>> at;  // vertex -> (edge, face)
    for (const std::int32_t edge : candidate_edges) {
      const auto e = static_cast<std::size_t>(edge);
      bool own = false;
      std::int32_t rising = -1;
      for (const EdgeUse* u = table.uses_begin(e); u != table.uses_end(e); ++u) {
        const auto F = static_cast<std::size_t>(u->face);
        if (surface_of[F] == root) own = true;
        if (surface_of[F] == root || rising >= 0) continue;
        double lowest = 0, highest = 0;
        for (int k = 0; k < mesh.corner_count(F); ++k) {
          const double d = distance(s0, corner(mesh, F, k));
          lowest = std::min(lowest, d);
          highest = std::max(highest, d);
        }
        if (lowest >= -tol && highest > tol) rising = u->face;
      }
      if (own || rising < 0) continue;
      for (const std::int32_t v : table.edges[e]) at[v].push_back({static_cast<std::int32_t>(e), rising});
    }
    // Closed loops of contact edges.
    std::map<std::int32_t, bool> visited;
    std::vector<std::int32_t> loop_edges;  // edges of every closed loop, kept as a footprint or not
    std::vector<std::vector<std::int32_t>> loop_vertices;
    for (const auto& entry : at) {
      const std::int32_t start = entry.first;
      if (visited[start]) continue;
      // Walk the component; a loop has degree 2 everywhere.
      std::vector<std::int32_t> order, edges, risers;
      bool loop = true;
      std::int32_t v = start, came = -1;
      while (true) {
        visited[v] = true;
        const auto& l = at[v];
        if (l.size() != 2) loop = false;
        order.push_back(v);
        const auto next = l[0].first != came ? l[0] : (l.size() > 1 ? l[1] : l[0]);
        if (next.first == came) { loop = false; break; }
        edges.push_back(next.first);
        risers.push_back(next.second);
        const auto& ends = table.edges[static_cast<std::size_t>(next.first)];
        const std::int32_t w = ends[0] == v ? ends[1] : ends[0];
        came = next.first;
        if (w == start) break;
        if (visited[w]) { loop = false; break; }
        v = w;
      }
      if (!loop || order.size() < 3) continue;
      loop_edges.insert(loop_edges.end(), edges.begin(), edges.end());
      Contact c;
      for (const std::int32_t w : order) c.footprint.push_back(position(w));
      // Counter-clockwise about the support's normal.
      if (vector_area(c.footprint).dot(n) < 0) {
        std::reverse(c.footprint.begin(), c.footprint.end());
        std::reverse(order.begin(), order.end());
        std::reverse(risers.begin(), risers.end());
        std::rotate(risers.begin(), risers.begin() + 1, risers.end());  // riser k: edge order[k] -> order[k + 1]
      }
      // A solid standing on the surface faces away from its footprint; walls around a floor face into it.
      int outward = 0;
      for (std::size_t k = 0; k < order.size(); ++k) {
        const Vec3 m = inward(n, c.footprint[k], c.footprint[(k + 1) % order.size()]);
        outward += normal[static_cast<std::size_t>(risers[k])].dot(m) < 0 ? 1 : -1;
      }
      if (outward <= 0) continue;
      c.footprint = simplified(c.footprint, tol);
      if (c.footprint.size() < 3) continue;
      c.area = vector_area(c.footprint).norm();
      c.convex = is_convex(c.footprint, n);
      c.standing = risers;
      std::sort(c.standing.begin(), c.standing.end());
      c.standing.erase(std::unique(c.standing.begin(), c.standing.end()), c.standing.end());
      loop_vertices.push_back(order);
      contacts.push_back(c);
    }
    // Faces lying on the surface back to back, not already the inside of a loop.
    const std::size_t first_of_surface = contacts.size() - loop_vertices.size();
    for (const std::int32_t face : candidate_faces) {
      const auto g = static_cast<std::size_t>(face);
      if (normal[g].dot(n) > -kCoplanarDot) continue;
      bool on = true;
      for (int k = 0; k < mesh.corner_count(g) && on; ++k) on = on_surface(corner(mesh, g, k));
      if (!on) continue;
      bool known = false;
      for (const auto& loop : loop_vertices) {
        bool all = true;
        for (int k = 0; k < mesh.corner_count(g) && all; ++k)
          all = std::find(loop.begin(), loop.end(),
                          table.weld[static_cast<std::size_t>(mesh.faces[g][static_cast<std::size_t>(k)])]) != loop.end();
        known |= all;
      }
      if (known) continue;
      Contact c;
      c.footprint = face_polygon(mesh, g);
      std::reverse(c.footprint.begin(), c.footprint.end());
      c.footprint = simplified(c.footprint, tol);
      if (c.footprint.size() < 3) continue;
      c.area = vector_area(c.footprint).norm();
      c.convex = is_convex(c.footprint, n);
      c.standing = {static_cast<std::int32_t>(g)};
      c.lying = true;
      contacts.push_back(c);
    }
    // Contact lines: contact edges in no closed loop (a board's edge touching a shelf's side, a thin sheet
    // standing on the floor). Each is cut along, through the faces whose interior it crosses.
    std::sort(loop_edges.begin(), loop_edges.end());
    const std::size_t first_line = contacts.size();
    std::map<std::int32_t, std::int32_t> line_rising;  // edge -> its rising face, in edge order
    for (const auto& [v, list] : at)
      for (const auto& [edge, rising] : list)
        if (!std::binary_search(loop_edges.begin(), loop_edges.end(), edge)) line_rising.emplace(edge, rising);
    for (const auto& [edge, rising] : line_rising) {
      const auto& ends = table.edges[static_cast<std::size_t>(edge)];
      Contact c;
      c.footprint = {position(ends[0]), position(ends[1])};
      c.standing = {rising};
      c.line = true;
      const Vec3 seg_lo = c.footprint[0].cwiseMin(c.footprint[1]).array() - tol;
      const Vec3 seg_hi = c.footprint[0].cwiseMax(c.footprint[1]).array() + tol;
      for (const std::int32_t f : faces) {
        const Polygon S = face_polygon(mesh, static_cast<std::size_t>(f));
        Vec3 face_lo = S[0], face_hi = S[0];
        for (const Vec3& q : S) face_lo = face_lo.cwiseMin(q), face_hi = face_hi.cwiseMax(q);
        if ((face_hi.array() < seg_lo.array()).any() || (face_lo.array() > seg_hi.array()).any()) continue;
        const Vec3 area = vector_area(S);
        Polygon in, out;
        if (crosses(S, area.normalized(), c.footprint[0], c.footprint[1], tol, 1e-9 * area.norm(), in, out))
          c.supports.push_back(f);
      }
      contacts.push_back(c);
    }
    // A face is cut along at most kMaxContactLinesPerFace lines: the others are reported, not cut.
    std::map<std::int32_t, int> lines_on;
    for (std::size_t c = first_line; c < contacts.size(); ++c)
      for (const std::int32_t f : contacts[c].supports)
        if (++lines_on[f] > kMaxContactLinesPerFace) contacts[c].convex = false;
    // The surface's faces each footprint overlaps.
    for (std::size_t c = first_of_surface; c < first_line; ++c)
      for (const std::int32_t f : faces) {
        const Polygon S = face_polygon(mesh, static_cast<std::size_t>(f));
        const double a = vector_area(S).norm();
        if (vector_area(intersection(S, contacts[c].footprint, n, tol)).norm() > 1e-9 * a)
          contacts[c].supports.push_back(f);
      }
    contacts.erase(std::remove_if(contacts.begin() + static_cast<std::ptrdiff_t>(first_of_surface), contacts.end(),
                                  [](const Contact& c) { return c.supports.empty(); }),
                   contacts.end());
  }
  return contacts;
}

Mesh cut_along_contacts(const Mesh& mesh, const std::vector<Contact>& contacts, std::size_t* cut_faces) {
  const double tol = kContactTolerance * scene_extent(mesh);
  // The footprints on each face.
  std::map<std::int32_t, std::vector<const Contact*>> on_face;
  for (const Contact& c : contacts)
    if (c.convex)
      for (const std::int32_t f : c.supports) on_face[f].push_back(&c);

  Mesh out = mesh;
  out.faces.clear();
  out.face_material.clear();
  out.face_line.clear();
  out.face_source.clear();
  out.face_group.clear();
  // New vertices shared between pieces: one vertex for all the positions within `weld` of each other (the pieces
  // of neighbouring faces compute the same corner in different orders, a few units in the last place apart; two
  // vertices there would make a cell with coincident corners, which no reader can triangulate), found in a grid
  // of cells of that size (the 27 cells around a position).
  const double weld = 1e-9 * scene_extent(mesh);
  std::map<std::array<std::int64_t, 3>, std::vector<std::int32_t>> added;
  const auto index = [&](double x) {  // clamped: a zero extent (one point) makes every quotient infinite
    const double q = weld > 0 ? std::floor(x / weld) : 0.0;
    return static_cast<std::int64_t>(std::clamp(std::isfinite(q) ? q : 0.0, -4e18, 4e18));
  };
  const auto cell = [&](const Vec3& p) { return std::array<std::int64_t, 3>{index(p.x()), index(p.y()), index(p.z())}; };
  auto vertex = [&](const Vec3& p, std::size_t f) {
    for (int k = 0; k < mesh.corner_count(f); ++k)
      if ((corner(mesh, f, k) - p).norm() <= weld) return mesh.faces[f][static_cast<std::size_t>(k)];
    const std::array<std::int64_t, 3> c = cell(p);
    for (std::int64_t dx = -1; dx <= 1; ++dx)
      for (std::int64_t dy = -1; dy <= 1; ++dy)
        for (std::int64_t dz = -1; dz <= 1; ++dz) {
          const auto it = added.find({c[0] + dx, c[1] + dy, c[2] + dz});
          if (it == added.end()) continue;
          for (const std::int32_t v : it->second)
            if ((out.vertices[static_cast<std::size_t>(v)] - p).norm() <= weld) return v;
        }
    const auto v = static_cast<std::int32_t>(out.vertices.size());
    out.vertices.push_back(p);
    added[c].push_back(v);
    return v;
  };
  auto copy_face = [&](std::size_t f, const std::array<std::int32_t, 4>& corners) {
    out.faces.push_back(corners);
    out.face_material.push_back(f < mesh.face_material.size() ? mesh.face_material[f] : -1);
    if (f < mesh.face_line.size()) out.face_line.push_back(mesh.face_line[f]);
    out.face_source.push_back(static_cast<std::int32_t>(mesh.source_face(f)));
    if (f < mesh.face_group.size()) out.face_group.push_back(mesh.face_group[f]);
  };
  std::size_t cut = 0;
  for (std::size_t f = 0; f < mesh.face_count(); ++f) {
    const auto it = on_face.find(static_cast<std::int32_t>(f));
    if (it == on_face.end()) {
      copy_face(f, mesh.faces[f]);
      continue;
    }
    const Polygon S = face_polygon(mesh, f);
    const Vec3 n = vector_area(S).normalized();
    const double min_area = 1e-9 * vector_area(S).norm();
    // Pieces: (polygon, under a footprint).
    std::vector<std::pair<Polygon, bool>> pieces = {{S, false}};
    for (const Contact* c : it->second) {
      std::vector<std::pair<Polygon, bool>> next;
      if (c->line) {  // each piece the segment crosses is cut in two along the segment's line
        const Vec3 &a = c->footprint[0], &b = c->footprint[1];
        for (auto& [piece, covered] : pieces) {
          Polygon in, out_part;
          if (!crosses(piece, n, a, b, tol, min_area, in, out_part)) {
            next.emplace_back(piece, covered);
            continue;
          }
          next.emplace_back(simplified(in, tol), covered);
          next.emplace_back(simplified(out_part, tol), covered);
        }
        pieces = next;
        continue;
      }
      for (auto& [piece, covered] : pieces) {
        // A piece under another footprint, or beside this one, stays as it is.
        if (covered || vector_area(intersection(piece, c->footprint, n, tol)).norm() <= min_area) {
          next.emplace_back(piece, covered);
          continue;
        }
        const Polygon& K = c->footprint;
        const Polygon under = simplified(intersection(piece, K, n, tol), tol);
        if (under.size() >= 3 && vector_area(under).norm() > min_area) next.emplace_back(under, true);
        // The pinwheel (forward or backward) whose arms have the better worst angle.
        std::vector<Polygon> arms[2];
        for (const bool forward : {true, false})
          for (std::size_t k = 0; k < K.size(); ++k) {
            Polygon arm = pinwheel_arm(piece, K, k, forward, n, tol);
            if (arm.size() >= 3 && vector_area(arm).norm() > min_area) arms[forward ? 0 : 1].push_back(std::move(arm));
          }
        for (Polygon& arm : arms[worst_angle(arms[1]) > worst_angle(arms[0]) ? 1 : 0])
          next.emplace_back(std::move(arm), false);
      }
      pieces = next;
    }
    if (pieces.size() <= 1) {
      copy_face(f, mesh.faces[f]);
      continue;
    }
    ++cut;
    // Covered pieces first, then the rest; each convex piece as a fan of quads (+ one triangle).
    std::stable_partition(pieces.begin(), pieces.end(), [](const auto& p) { return p.second; });
    for (const auto& [piece, covered] : pieces) {
      (void)covered;
      for (const Polygon& q : fan_faces(piece))
        copy_face(f, {vertex(q[0], f), vertex(q[1], f), vertex(q[2], f), q.size() == 4 ? vertex(q[3], f) : -1});
    }
  }
  if (cut_faces) *cut_faces = cut;
  return out;
}

std::string describe_contact(const Mesh& mesh, const Contact& c) {
  auto list = [&](const std::vector<std::int32_t>& faces) {
    std::string s = faces.size() == 1 ? "face " : "faces ";
    for (std::size_t k = 0; k < faces.size() && k < 6; ++k)
      s += (k ? ", " : "") + std::to_string(mesh.source_face(static_cast<std::size_t>(faces[k])));
    if (faces.size() > 6) s += " and " + std::to_string(faces.size() - 6) + " more";
    return s + (faces.empty() ? "" : mesh.context(static_cast<std::size_t>(faces.front())));
  };
  if (c.line)
    return list(c.standing) + " touches " + list(c.supports) + " along a line of length " +
           number_text((c.footprint[1] - c.footprint[0]).norm()) +
           (c.convex ? "" : " (more than " + std::to_string(kMaxContactLinesPerFace) + " lines on a face: not cut)");
  return list(c.standing) + (c.lying ? " lies back to back on " : " stand on ") + list(c.supports) +
         ": footprint of " + std::to_string(c.footprint.size()) + " corners, area " + number_text(c.area) +
         (c.convex ? "" : " (not convex: not cut)");
}

}  // namespace radwalk
