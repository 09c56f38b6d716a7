#pragma once
// Radiosity problems with exact form factors, shared by the solver, walk and failure-mode tests (built in code:
// no mesh, no ray tracing).
//
// The unit cube, one patch per face, faces numbered so that face i is opposite face i ^ 1 (order x=0, x=1, y=0,
// y=1, z=0, z=1 where a geometry is attached, as in box_scenes.h and the walk tests' cube_patches). Its exact
// form factors are the closed forms of view_factors.h for unit squares (Howell's catalogue):
//   opposite faces  F = 0.199824896  (C-11, parallel directly opposed rectangles, X = Y = 1)
//   adjacent faces  F = 0.200043776  (C-14, perpendicular rectangles with a common edge, W = H = 1)
// and a row sums to F_opp + 4 F_adj = 1 (to 1e-9). The stored F is float (SparseF), like every F of radwalk.
#include <Eigen/Sparse>
#include <vector>

#include "solve/problem.h"

namespace radwalk::test {

inline constexpr double kOpposite = 0.199824896;
inline constexpr double kAdjacent = 0.200043776;

inline const std::vector<int> kCubeFaces = {0, 1, 2, 3, 4, 5};

// F of the closed unit cube restricted to `faces` (a face left out is an opening: rows then sum below 1), every
// entry multiplied by `scale` before it is rounded to float.
inline SparseF unit_cube_F(const std::vector<int>& faces = kCubeFaces, double scale = 1) {
  const auto n = static_cast<int>(faces.size());
  std::vector<Eigen::Triplet<float, std::int32_t>> t;
  for (int a = 0; a < n; ++a)
    for (int b = 0; b < n; ++b)
      if (faces[a] != faces[b])
        t.emplace_back(a, b, static_cast<float>(scale * ((faces[a] ^ 1) == faces[b] ? kOpposite : kAdjacent)));
  SparseF F(n, n);
  F.setFromTriplets(t.begin(), t.end());
  return F;
}

// A problem over unit_cube_F(faces, scale) with the given reflectances and emissions (one row per face kept) and
// unit areas.
inline RadiosityProblem cube_problem(const PatchRgb& rho, const PatchRgb& E, const std::vector<int>& faces = kCubeFaces,
                                     double scale = 1) {
  RadiosityProblem p;
  p.F = unit_cube_F(faces, scale);
  p.rho = rho;
  p.E = E;
  p.area = Eigen::VectorXd::Ones(static_cast<Eigen::Index>(faces.size()));
  return p;
}

}  // namespace radwalk::test
