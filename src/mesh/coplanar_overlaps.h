#pragma once
// Faces that lie in one plane and overlap: two surfaces in the same place (a face modelled twice, a decal on a
// wall, a lid left on its box), which render on top of each other and which the radiosity counts twice. Faces
// that only share an edge or a corner do not overlap.
//
// find_coplanar_overlaps returns pairs facing either way; validation reports those facing the same way (back to
// back they are a contact: patch/contact.h).
//
// Coplanar means within rounding: every corner q of one face is at a distance from the plane of each triangle
// (a, b, c) of the other (a quad is its fan (0,1,2), (0,2,3)) no larger than the rounding of the distance
// |((b-a) x (c-a)) . (q-a)| / |(b-a) x (c-a)|: 8 u times the determinant's permanent over |(b-a) x (c-a)| (u the
// unit roundoff, Shewchuk's orient3d bound) plus 4 u max|coordinate| (the inputs' own rounding to binary).
// The overlap area is the sum of the triangles' intersections (convex clipping in the first face's plane); it
// counts as positive above 64 u (P_f + P_g) D, the clipping's rounding: perimeters P_f, P_g, D the diameter of
// the two faces' bounding box (a shared edge gives a sliver of width a few u D).
//
// Cost: candidate pairs come from a hierarchical grid (level l has cells of size h 2^l, h the median face extent;
// each face is in the at most 8 cells of the level where its bounding box fits a cell, sorted by cell): the faces
// of one cell are paired with each other, and each face looks up the cells its box covers on the coarser levels in
// use. A mesh whose faces are of similar sizes costs O(F log F) (the sort) and O(F) pair tests, never a test of
// every pair; each pair test rejects neighbours that only touch by a separating side before any exact test.
#include <cstdint>
#include <vector>

#include "mesh/mesh.h"

namespace radwalk {

struct CoplanarOverlap {
  std::int32_t face_a = -1, face_b = -1;  // mesh faces, face_a < face_b
  double area = 0;                        // the area they share
  bool same_side = true;                  // their normals point the same way (false: back to back)
};

// Every pair of coplanar faces that overlap with positive area, ordered by face_a then face_b. Faces with
// skip[f] (if given) are left out. Precondition: every face index is in range and every coordinate finite.
// When `pair_tests` is given, the number of candidate pairs tested is added to it (the cost stated above).
std::vector<CoplanarOverlap> find_coplanar_overlaps(const Mesh& mesh, const std::vector<bool>* skip = nullptr,
                                                    std::size_t* pair_tests = nullptr);

}  // namespace radwalk
