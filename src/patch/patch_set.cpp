#include "patch/patch_set.h"

#include "mesh/mesh.h"

#include "patch/patch_point_sampler.h"

#include <algorithm>


namespace radwalk {

namespace {
const std::string kNoName;
}  // namespace

const std::string& PatchSet::object_of(std::size_t i) const {
  const auto f = static_cast<std::size_t>(face[i]);
  if (f >= input_face_group.size() || input_face_group[f] < 0) return kNoName;
  return group_object[static_cast<std::size_t>(input_face_group[f])];
}

const std::string& PatchSet::group_of(std::size_t i) const {
  const auto f = static_cast<std::size_t>(face[i]);
  if (f >= input_face_group.size() || input_face_group[f] < 0) return kNoName;
  return group_name[static_cast<std::size_t>(input_face_group[f])];
}

const std::string& PatchSet::material_of(std::size_t i) const {
  const std::int32_t m = material[i];
  if (m < 0 || static_cast<std::size_t>(m) >= materials.size()) return kNoName;
  return materials[static_cast<std::size_t>(m)].name;
}

void set_group_names(const Mesh& mesh, PatchSet& patches) {
  patches.group_object = mesh.group_object;
  patches.group_name = mesh.group_name;
  patches.input_face_group.clear();
  for (std::size_t f = 0; f < mesh.face_count() && f < mesh.face_group.size(); ++f) {
    const long input = mesh.source_face(f);
    if (input < 0) continue;
    if (static_cast<std::size_t>(input) >= patches.input_face_group.size())
      patches.input_face_group.resize(static_cast<std::size_t>(input) + 1, -1);
    const std::int32_t g = mesh.face_group[f];
    patches.input_face_group[static_cast<std::size_t>(input)] =
        g >= 0 && static_cast<std::size_t>(g) < mesh.group_name.size() ? g : -1;
  }
}

double PatchSet::total_area() const {
  double s = 0;
  for (double a : area) s += a;
  return s;
}

double PatchSet::scene_extent() const {
  if (points.empty()) return 0;
  Vec3 lo = points[0], hi = points[0];
  for (const auto& p : points) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  return (hi - lo).maxCoeff();
}

double PatchSet::max_emission() const {
  double largest = 0;
  for (const Rgb& e : E) largest = std::max(largest, e.maxCoeff());
  return largest;
}

void compute_patch_geometry(PatchSet& patches) {
  const std::size_t n = patches.corners.size();
  patches.centroid.resize(n);
  patches.normal.resize(n);
  patches.area.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    const Vec3& a = patches.corner(i, 0);
    const Vec3& b = patches.corner(i, 1);
    const Vec3& c = patches.corner(i, 2);
    // Triangle fan (0,1,2), (0,2,3): area-weighted centroid and the vector area of the polygon.
    Vec3 cross1 = (b - a).cross(c - a);
    double a1 = 0.5 * cross1.norm();
    Vec3 centroid = a1 * (a + b + c) / 3.0;
    Vec3 vector_area = 0.5 * cross1;
    double total = a1;
    if (patches.is_quad(i)) {
      const Vec3& d = patches.corner(i, 3);
      Vec3 cross2 = (c - a).cross(d - a);
      double a2 = 0.5 * cross2.norm();
      centroid += a2 * (a + c + d) / 3.0;
      vector_area += 0.5 * cross2;
      total += a2;
    }
    patches.area[i] = total;
    patches.centroid[i] = total > 0 ? Vec3(centroid / total) : a;
    const double len = vector_area.norm();
    patches.normal[i] = len > 0 ? Vec3(vector_area / len) : Vec3(0, 0, 1);
  }
}

void set_radiometry_from_materials(PatchSet& patches) {
  patches.rho.resize(patches.corners.size());
  patches.E.resize(patches.corners.size());
  for (std::size_t i = 0; i < patches.corners.size(); ++i) {
    const Material& m = patches.materials[static_cast<std::size_t>(patches.material[i])];
    patches.rho[i] = m.Kd;
    patches.E[i] = kPi * m.Ke;
  }
}

std::size_t add_back_sides(PatchSet& patches, bool all_materials) {
  const std::size_t n = patches.size();
  const auto wanted = [&](std::size_t i) {
    if (patches.side_of(i) != Side::one_sided) return false;  // already two-sided
    const Material& m = patches.materials[static_cast<std::size_t>(patches.material[i])];
    return m.kind != BsdfKind::dielectric && (all_materials || m.two_sided);
  };
  std::size_t added = 0;
  for (std::size_t i = 0; i < n; ++i) added += wanted(i);
  if (added == 0) return 0;
  if (patches.side.empty()) patches.side.assign(n, Side::one_sided);
  patches.corners.reserve(n + added);
  for (std::size_t i = 0; i < n; ++i) {
    if (!wanted(i)) continue;
    patches.side[i] = Side::front;
    const auto c = patches.corners[i];
    patches.corners.push_back(patches.is_quad(i) ? std::array<std::int32_t, 4>{c[0], c[3], c[2], c[1]}
                                                 : std::array<std::int32_t, 4>{c[0], c[2], c[1], -1});
    patches.rho.push_back(patches.rho[i]);
    patches.E.push_back(patches.E[i]);
    patches.face.push_back(patches.face[i]);
    patches.material.push_back(patches.material[i]);
    patches.side.push_back(Side::back);
  }
  compute_patch_geometry(patches);
  return added;
}

Vec3 sample_patch_point(const PatchSet& patches, std::size_t i, double u1, double u2) {
  return PatchPointSampler(patches, i).point(u1, u2);
}

}  // namespace radwalk
