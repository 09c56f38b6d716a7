#include "mesh/orient_shells.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <queue>

#include "core/error.h"
#include "mesh/edge_table.h"
#include "mesh/face_geometry.h"

namespace radwalk {

namespace {

Vec3 corner(const Mesh& mesh, std::size_t f, int k) {
  return mesh.vertices[static_cast<std::size_t>(mesh.faces[f][static_cast<std::size_t>(k)])];
}

// Whether ray o + t d (t > 0) crosses triangle (a, b, c) (Moeller-Trumbore; edge hits count by the half-open rule
// of the barycentric tests, a ray direction that is no face's plane direction makes them measure-zero).
bool crosses(const Vec3& o, const Vec3& d, const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 e1 = b - a, e2 = c - a, p = d.cross(e2);
  const double det = e1.dot(p);
  if (det == 0) return false;
  const Vec3 s = o - a;
  const double u = s.dot(p) / det;
  if (u < 0 || u >= 1) return false;
  const Vec3 q = s.cross(e1);
  const double v = d.dot(q) / det;
  if (v < 0 || u + v >= 1) return false;
  return e2.dot(q) / det > 0;
}

}  // namespace

const char* orient_mode_name(OrientMode mode) {
  switch (mode) {
    case OrientMode::none: return "none";
    case OrientMode::consistent: return "consistent";
    case OrientMode::outward: return "outward";
  }
  return "?";
}

OrientMode parse_orient_mode(const std::string& name) {
  if (name == "none") return OrientMode::none;
  if (name == "consistent") return OrientMode::consistent;
  if (name == "outward") return OrientMode::outward;
  throw InputError("--orient: '" + name + "' is not one of none, consistent, outward");
}

OrientationResult orient_shells(Mesh& mesh, OrientMode mode) {
  OrientationResult out;
  const std::size_t n = mesh.face_count();
  if (n == 0) return out;
  const EdgeTable t = build_edge_table(mesh);

  // Shells: faces joined through manifold edges, walked breadth-first; flip[f] = whether f must turn to agree.
  std::vector<std::int32_t> shell(n, -1);
  std::vector<char> flip(n, 0);
  std::vector<std::vector<std::size_t>> members;
  std::vector<char> orientable;
  for (std::size_t start = 0; start < n; ++start) {
    if (shell[start] >= 0) continue;
    const auto id = static_cast<std::int32_t>(members.size());
    members.emplace_back();
    orientable.push_back(1);
    std::queue<std::size_t> queue;
    queue.push(start);
    shell[start] = id;
    while (!queue.empty()) {
      const std::size_t f = queue.front();
      queue.pop();
      members.back().push_back(f);
      for (int k = 0; k < mesh.corner_count(f); ++k) {
        const std::int32_t e = t.face_edge[f][static_cast<std::size_t>(k)];
        if (e < 0 || t.use_count(static_cast<std::size_t>(e)) != 2) continue;
        const EdgeUse* u = t.uses_begin(static_cast<std::size_t>(e));
        const EdgeUse& mine = static_cast<std::size_t>(u[0].face) == f && u[0].side == k ? u[0] : u[1];
        const EdgeUse& other = &mine == &u[0] ? u[1] : u[0];
        const auto g = static_cast<std::size_t>(other.face);
        if (g == f) continue;
        // Agree: opposite directions once both flips are applied.
        const char want = static_cast<char>(flip[f] ^ (mine.forward == other.forward ? 1 : 0));
        if (shell[g] < 0) {
          shell[g] = id;
          flip[g] = want;
          queue.push(g);
        } else if (flip[g] != want) {
          orientable.back() = 0;
        }
      }
    }
  }
  out.shells = members.size();

  // Per shell: closed?, areas flipped either way, signed volume, bounding box.
  const std::size_t m = members.size();
  std::vector<char> closed(m, 1), emitters_only(m, 1);
  std::vector<double> area_walk(m, 0), area_total(m, 0), volume(m, 0);
  std::vector<std::size_t> boundary(m, 0);
  std::vector<Vec3> lo(m, Vec3::Constant(std::numeric_limits<double>::infinity())), hi(m, -lo[0]);
  for (std::size_t e = 0; e < t.edge_count(); ++e) {
    const std::int32_t uses = t.use_count(e);
    if (uses == 2) continue;
    for (const EdgeUse* u = t.uses_begin(e); u != t.uses_end(e); ++u) {
      const auto s = static_cast<std::size_t>(shell[static_cast<std::size_t>(u->face)]);
      closed[s] = 0;
      boundary[s] += uses == 1;
    }
  }
  for (std::size_t s = 0; s < m; ++s) {
    Vec3 c = Vec3::Zero();
    std::size_t corners = 0;
    for (std::size_t f : members[s])
      for (int k = 0; k < mesh.corner_count(f); ++k) {
        const Vec3 p = corner(mesh, f, k);
        c += p;
        ++corners;
        lo[s] = lo[s].cwiseMin(p);
        hi[s] = hi[s].cwiseMax(p);
      }
    c /= static_cast<double>(std::max<std::size_t>(corners, 1));
    for (std::size_t f : members[s]) {
      const double a = face_area(mesh, f);
      area_total[s] += a;
      if (flip[f]) area_walk[s] += a;
      const std::int32_t material = mesh.face_material[f];
      if (material < 0 || !(mesh.materials[static_cast<std::size_t>(material)].Ke > 0).any()) emitters_only[s] = 0;
      double v = 0;
      for (int k = 1; k + 1 < mesh.corner_count(f); ++k)
        v += (corner(mesh, f, 0) - c).dot((corner(mesh, f, k) - c).cross(corner(mesh, f, k + 1) - c));
      volume[s] += (flip[f] ? -v : v) / 6;
    }
  }

  // The room: a closed shell whose box holds every other shell's, with a point of another shell inside it (or the
  // only shell).
  std::vector<char> room(m, 0);
  {
    Vec3 all_lo = lo[0], all_hi = hi[0];
    for (std::size_t s = 1; s < m; ++s) {
      all_lo = all_lo.cwiseMin(lo[s]);
      all_hi = all_hi.cwiseMax(hi[s]);
    }
    const double tol = 1e-9 * (all_hi - all_lo).norm();
    for (std::size_t s = 0; s < m; ++s) {
      if (!closed[s] || !orientable[s]) continue;
      if ((lo[s].array() > all_lo.array() + tol).any() || (hi[s].array() < all_hi.array() - tol).any()) continue;
      if (m == 1) {
        room[s] = 1;
        continue;
      }
      // A point of the largest other shell: the centroid of its first face.
      std::size_t other = s == 0 ? 1 : 0;
      for (std::size_t r = 0; r < m; ++r)
        if (r != s && area_total[r] > area_total[other]) other = r;
      const std::size_t f0 = members[other][0];
      Vec3 p = Vec3::Zero();
      for (int k = 0; k < mesh.corner_count(f0); ++k) p += corner(mesh, f0, k);
      p /= mesh.corner_count(f0);
      const Vec3 d = Vec3(0.5773502691896258, 0.5773502691896258 + 1.234e-4, 0.5773502691896258 - 2.71e-5).normalized();
      std::size_t crossings = 0;
      for (std::size_t f : members[s])
        for (int k = 1; k + 1 < mesh.corner_count(f); ++k)
          crossings += crosses(p, d, corner(mesh, f, 0), corner(mesh, f, k), corner(mesh, f, k + 1));
      room[s] = crossings % 2 == 1;
    }
  }

  // Decide each shell's orientation and flip.
  for (std::size_t s = 0; s < m; ++s) {
    out.closed_shells += closed[s];
    out.enclosing_shells += room[s];
    if (mode == OrientMode::outward) out.rooms += room[s];
    if (!orientable[s]) {
      ++out.non_orientable;
      out.non_orientable_faces.push_back(members[s][0]);
    }
    if (!closed[s] && !emitters_only[s]) {
      out.open_shells.push_back({*std::min_element(members[s].begin(), members[s].end()), members[s].size(),
                                 boundary[s], area_total[s]});
      out.open_shell_faces.insert(out.open_shell_faces.end(), members[s].begin(), members[s].end());
    }
    if (mode == OrientMode::none) continue;
    // reverse: take the walk's opposite (every face with flip 0 turns instead).
    bool reverse = area_walk[s] > area_total[s] - area_walk[s];  // the one that flips less area
    if (mode == OrientMode::outward && closed[s] && orientable[s] && volume[s] != 0)
      reverse = room[s] ? volume[s] > 0 : volume[s] < 0;
    for (std::size_t f : members[s]) {
      if ((flip[f] != 0) == reverse) continue;
      auto& c = mesh.faces[f];
      if (c[3] >= 0) std::swap(c[1], c[3]);
      else std::swap(c[1], c[2]);
      out.flipped.push_back(f);
      out.flipped_area += face_area(mesh, f);
    }
  }
  std::sort(out.flipped.begin(), out.flipped.end());
  std::sort(out.open_shell_faces.begin(), out.open_shell_faces.end());
  out.flipped_faces = out.flipped.size();
  return out;
}

}  // namespace radwalk
