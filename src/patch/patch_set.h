#pragma once
// PatchSet: the flat, structure-of-arrays description of the patches every algorithm works on.
//
// A patch is a planar triangle or convex quad with constant reflectance rho (per channel) and constant emitted
// radiosity E = pi * Ke (W/m^2 in the mesh's length unit). With no subdivision, patch i is input face i.
// The normal is the unit normal given by the corner order (counter-clockwise seen from the front).
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "core/types.h"
#include "mesh/material.h"

namespace radwalk {

struct PatchSet {
  std::string source;                                 // scene file
  std::vector<Vec3> points;                           // shared corner points (conforming: no T-junctions)
  std::vector<std::array<std::int32_t, 4>> corners;  // indices into points; [3] == -1 for a triangle
  std::vector<Vec3> centroid;                         // area centroid
  std::vector<Vec3> normal;                           // unit normal
  std::vector<double> area;
  std::vector<Rgb> rho;                               // diffuse reflectance
  std::vector<Rgb> E;                                 // emitted radiosity (exitance) = pi * Ke
  std::vector<std::int32_t> face;                     // input face this patch came from
  std::vector<std::int32_t> material;                 // index into materials
  std::vector<Material> materials;

  std::size_t size() const { return area.size(); }
  bool is_quad(std::size_t i) const { return corners[i][3] >= 0; }
  int corner_count(std::size_t i) const { return is_quad(i) ? 4 : 3; }
  const Vec3& corner(std::size_t i, int k) const { return points[corners[i][k]]; }
  double total_area() const;
  // Largest extent of the bounding box of all points (for scale-aware epsilons).
  double scene_extent() const;
};

// rho = Kd and E = pi Ke (Ke is emitted radiance) of every patch's material.
void set_radiometry_from_materials(PatchSet& patches);

// Recomputes centroid, normal and area of every patch from its corners.
void compute_patch_geometry(PatchSet& patches);

// A uniform point on patch i (pdf = 1 / area), from u in [0, 1)^2. A quad is two triangles (0,1,2), (0,2,3)
// chosen in proportion to their areas. Loops over many points of one patch: PatchPointSampler
// (patch_point_sampler.h), which gives the same points.
Vec3 sample_patch_point(const PatchSet& patches, std::size_t i, double u1, double u2);

}  // namespace radwalk
