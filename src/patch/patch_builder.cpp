#include "patch/patch_builder.h"

namespace radwalk {

int PatchBuilder::add_material(const Material& m) {
  set_.materials.push_back(m);
  return static_cast<int>(set_.materials.size()) - 1;
}

int PatchBuilder::add_material(const std::string& name, const Rgb& rho, const Rgb& Le) {
  Material m;
  m.name = name;
  m.Kd = rho;
  m.Ke = Le;
  return add_material(m);
}

PatchIndex PatchBuilder::add_triangle(const Vec3& a, const Vec3& b, const Vec3& c, int material) {
  const auto base = static_cast<std::int32_t>(set_.points.size());
  set_.points.insert(set_.points.end(), {a, b, c});
  set_.corners.push_back({base, base + 1, base + 2, -1});
  set_.material.push_back(material);
  set_.face.push_back(static_cast<std::int32_t>(set_.face.size()));
  return static_cast<PatchIndex>(set_.corners.size() - 1);
}

PatchIndex PatchBuilder::add_quad(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d, int material) {
  const auto base = static_cast<std::int32_t>(set_.points.size());
  set_.points.insert(set_.points.end(), {a, b, c, d});
  set_.corners.push_back({base, base + 1, base + 2, base + 3});
  set_.material.push_back(material);
  set_.face.push_back(static_cast<std::int32_t>(set_.face.size()));
  return static_cast<PatchIndex>(set_.corners.size() - 1);
}

PatchSet PatchBuilder::build() const {
  PatchSet s = set_;
  set_radiometry_from_materials(s);
  compute_patch_geometry(s);
  return s;
}

}  // namespace radwalk
