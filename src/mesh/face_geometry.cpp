#include "mesh/face_geometry.h"

#include <algorithm>
#include <cmath>

namespace radwalk {

namespace {
const Vec3& corner(const Mesh& mesh, std::size_t f, int k) {
  return mesh.vertices[static_cast<std::size_t>(mesh.faces[f][static_cast<std::size_t>(k)])];
}
}  // namespace

double face_area(const Mesh& mesh, std::size_t f) {
  const Vec3& a = corner(mesh, f, 0);
  const Vec3& b = corner(mesh, f, 1);
  const Vec3& c = corner(mesh, f, 2);
  double area = 0.5 * (b - a).cross(c - a).norm();
  if (mesh.is_quad(f)) area += 0.5 * (c - a).cross(corner(mesh, f, 3) - a).norm();
  return area;
}

Vec3 face_vector_area(const Mesh& mesh, std::size_t f) {
  const int n = mesh.corner_count(f);
  // Relative to corner 0, for accuracy far from the origin.
  const Vec3& o = corner(mesh, f, 0);
  Vec3 s = Vec3::Zero();
  for (int k = 1; k + 1 < n; ++k) s += (corner(mesh, f, k) - o).cross(corner(mesh, f, k + 1) - o);
  return 0.5 * s;
}

double quad_nonplanarity(const Mesh& mesh, std::size_t f) {
  if (!mesh.is_quad(f)) return 0.0;
  const Vec3 va = face_vector_area(mesh, f);
  const double len = va.norm();
  const double diagonal = std::max((corner(mesh, f, 2) - corner(mesh, f, 0)).norm(),
                                   (corner(mesh, f, 3) - corner(mesh, f, 1)).norm());
  if (len == 0 || diagonal == 0) return 0.0;  // degenerate: reported by the area check
  const Vec3 n = va / len;
  Vec3 mean = Vec3::Zero();
  for (int k = 0; k < 4; ++k) mean += corner(mesh, f, k);
  mean /= 4.0;
  double deviation = 0;
  for (int k = 0; k < 4; ++k) deviation = std::max(deviation, std::abs((corner(mesh, f, k) - mean).dot(n)));
  // The width across the longer diagonal, 2 |vector area| / diagonal: the longer diagonal itself for a
  // square, much less for a thin quad, whose fold across its short direction the diagonal alone would hide.
  const double width = 2 * len / diagonal;
  return deviation / width;
}

double quad_min_turn_sine(const Mesh& mesh, std::size_t f) {
  if (!mesh.is_quad(f)) return 1.0;
  const Vec3 va = face_vector_area(mesh, f);
  const double len = va.norm();
  if (len == 0) return 0.0;
  const Vec3 n = va / len;
  double smallest = 1.0;
  for (int k = 0; k < 4; ++k) {
    const Vec3 in = corner(mesh, f, k) - corner(mesh, f, (k + 3) % 4);
    const Vec3 out = corner(mesh, f, (k + 1) % 4) - corner(mesh, f, k);
    const double denom = in.norm() * out.norm();
    if (denom == 0) continue;  // repeated corner: reported elsewhere
    smallest = std::min(smallest, in.cross(out).dot(n) / denom);
  }
  return smallest;
}

double quad_area_ambiguity(const Mesh& mesh, std::size_t f) {
  if (!mesh.is_quad(f)) return 0;
  const Vec3 &p0 = corner(mesh, f, 0), &p1 = corner(mesh, f, 1), &p2 = corner(mesh, f, 2), &p3 = corner(mesh, f, 3);
  const double a02 = 0.5 * ((p1 - p0).cross(p2 - p0).norm() + (p2 - p0).cross(p3 - p0).norm());
  const double a13 = 0.5 * ((p1 - p0).cross(p3 - p0).norm() + (p2 - p1).cross(p3 - p1).norm());
  const double larger = std::max(a02, a13);
  return larger > 0 ? std::max(0.0, larger - face_vector_area(mesh, f).norm()) / larger : 0;
}

}  // namespace radwalk
