#pragma once
// View factors between groups of patches (objects, groups, materials) from the patch form factors:
//   A_G = sum_{i in G} A_i,     F_GH = (1 / A_G) sum_{i in G} A_i sum_{j in H} F_ij,
// the fraction of the diffuse power leaving G uniformly (constant radiosity over G) that arrives at H. Where the
// patch F is reciprocal (A_i F_ij = A_j F_ji) so is the group F: A_G F_GH = sum_{i in G, j in H} A_i F_ij =
// A_H F_HG; and sum_H F_GH = (1 / A_G) sum_{i in G} A_i (row sum of i), which is 1 in a closed scene. With a traced
// (non-reciprocal) F the two sides of the reciprocity differ by the noise; the table reports both.
// Also, per group, the area-weighted sky view factor and the fraction that reaches the backs of one-sided faces.
#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "formfactor/sparse_f.h"

namespace radwalk {

struct GroupViewFactors {
  std::vector<double> area;   // A_G per group
  Eigen::MatrixXd F;          // F_GH, groups x groups
  std::vector<double> sky;    // (1 / A_G) sum_{i in G} A_i s_i
  std::vector<double> back;   // (1 / A_G) sum_{i in G} A_i b_i
};

// group[i] in [0, groups) for every patch i; F holds every row; sky and back per patch (empty: 0).
GroupViewFactors group_view_factors(const SparseF& F, const std::vector<double>& area,
                                    const std::vector<std::int32_t>& group, int groups,
                                    const std::vector<double>& sky = {}, const std::vector<double>& back = {});

// The largest relative reciprocity defect |A_G F_GH - A_H F_HG| / max(A_G F_GH, A_H F_HG) over the pairs with a
// non-zero exchange area (0 when there are none).
double group_reciprocity_defect(const GroupViewFactors& g);

}  // namespace radwalk
