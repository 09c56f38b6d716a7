#pragma once
// PatchSet: the flat, structure-of-arrays description of the patches every algorithm works on.
//
// A patch is a planar triangle or convex quad with constant reflectance rho (per channel) and constant emitted
// radiosity E = pi * Ke (W/m^2 in the mesh's length unit). With no subdivision, patch i is input face i.
// The normal is the unit normal given by the corner order (counter-clockwise seen from the front).
//
// Sides (docs/two-sided.md): a patch of a one-sided face is seen from its front only; the
// back of a one-sided face absorbs what reaches it and emits nothing (a "back hit"). A two-sided face is two
// patches at the same place, its front (Side::front) and its back (Side::back: the corners in reverse order, so
// the normal is reversed), each with its own B; each of the two is seen from its own front only, so a ray that
// reaches a two-sided face hits the patch of the side it arrives on (visibility/visibility.h).
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "core/types.h"
#include "mesh/material.h"

namespace radwalk {

struct Mesh;

// Which side of its input face a patch covers.
enum class Side : std::uint8_t {
  one_sided = 0,  // the front of a one-sided face (the back absorbs)
  front = 1,      // the front of a two-sided face
  back = 2,       // the back of a two-sided face: the reversed copy of a front patch
};

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
  // Empty when every patch is one-sided (the default); otherwise one entry per patch. Invariant: the patches of
  // Side::front and of Side::back of a face each tile the same surface (add_back_sides makes them so and
  // split_patches keeps it), so a ray reaching a two-sided face from either side finds a patch of that side.
  std::vector<Side> side;
  // Names for the outputs (CSV columns object, group, material; the .vtp's name tables): the group of input face
  // f (the value of `face`) is input_face_group[f], an index into group_object and group_name (the object and
  // group names as the file spells them, "" for none), -1 outside any. Filled by make_patches from the Mesh (OBJ
  // o/g, STL solids, glTF nodes and meshes); empty for scenes built without names.
  std::vector<std::int32_t> input_face_group;
  std::vector<std::string> group_object, group_name;

  std::size_t size() const { return area.size(); }
  bool is_quad(std::size_t i) const { return corners[i][3] >= 0; }
  int corner_count(std::size_t i) const { return is_quad(i) ? 4 : 3; }
  const Vec3& corner(std::size_t i, int k) const { return points[corners[i][k]]; }
  Side side_of(std::size_t i) const { return side.empty() ? Side::one_sided : side[i]; }
  // True for both patches of a two-sided face: a ray arriving at its back passes (the other side's patch takes it).
  bool two_sided(std::size_t i) const { return side_of(i) != Side::one_sided; }
  bool is_back(std::size_t i) const { return side_of(i) == Side::back; }
  // The object, group and material names of patch i ("" where none is known).
  const std::string& object_of(std::size_t i) const;
  const std::string& group_of(std::size_t i) const;
  const std::string& material_of(std::size_t i) const;
  double total_area() const;
  // Largest extent of the bounding box of all points (for scale-aware epsilons).
  double scene_extent() const;
  // Largest emitted radiosity E of any patch and channel (0 for none): the scale of the estimators' moments
  // (core/moments.h moment_scale) and of the overflow messages.
  double max_emission() const;
};

// Fills input_face_group, group_object and group_name from the mesh's groups (Mesh::face_group of each face's
// input face, Mesh::source_face), so the outputs can name each patch's object and group.
void set_group_names(const Mesh& mesh, PatchSet& patches);

// rho = Kd and E = pi Ke (Ke is emitted radiance) of every patch's material.
void set_radiometry_from_materials(PatchSet& patches);

// Makes the faces of two-sided materials (Material::two_sided, or every material when all_materials, the
// --two-sided option) two-sided: each patch i of such a face (Side::one_sided) becomes Side::front and gets a back
// patch, appended after all existing patches in the order of i, with the corners in reverse order (c0, c3, c2, c1)
// for a quad, (c0, c2, c1) for a triangle (so the same diagonal c0-c2 splits it) on the same points, the reversed
// normal and the same face, material, rho and E (Ke applies to both sides of a two-sided emitter). Dielectric
// materials are left one-sided: a dielectric is an interface whose two sides are its two media (pathtrace/bsdf.h).
// Patch indices below the old size are unchanged. Returns the number of back patches added; with none, the
// PatchSet is unchanged (side stays empty). Calling it again on the result adds nothing.
std::size_t add_back_sides(PatchSet& patches, bool all_materials = false);

// Recomputes centroid, normal and area of every patch from its corners.
void compute_patch_geometry(PatchSet& patches);

// A uniform point on patch i (pdf = 1 / area), from u in [0, 1)^2. A quad is two triangles (0,1,2), (0,2,3)
// chosen in proportion to their areas. Loops over many points of one patch: PatchPointSampler
// (patch_point_sampler.h), which gives the same points.
Vec3 sample_patch_point(const PatchSet& patches, std::size_t i, double u1, double u2);

}  // namespace radwalk
