// SparseF (sparse_f.h): moving a form-factor matrix hands over its arrays (no copy of the non-zeros), through
// every path F takes in the program: a return into an existing FormFactors, make_problem, a RadiosityProblem.
// Eigen 3.4's own SparseMatrix copies on each of these (it has no move operations).
#include <catch2/catch.hpp>

#include <utility>
#include <vector>

#include "formfactor/form_factors.h"
#include "formfactor/sparse_f.h"
#include "solve/problem.h"

using namespace radwalk;

namespace {

SparseF small_matrix() {
  std::vector<Eigen::Triplet<float, std::int32_t>> t{{0, 1, 0.5f}, {1, 0, 0.25f}, {1, 2, 0.125f}, {2, 2, 1.0f}};
  SparseF F(3, 3);
  F.setFromTriplets(t.begin(), t.end());
  return F;
}

}  // namespace

TEST_CASE("SparseF: move construction and assignment hand over the arrays", "[formfactor][sparse_f]") {
  SparseF F = small_matrix();
  const float* values = F.valuePtr();
  const std::int32_t* columns = F.innerIndexPtr();
  SparseF G(std::move(F));
  CHECK(G.valuePtr() == values);
  CHECK(G.innerIndexPtr() == columns);
  CHECK(G.nonZeros() == 4);
  CHECK(F.rows() == 0);
  CHECK(F.nonZeros() == 0);

  SparseF H = small_matrix();
  H = std::move(G);
  CHECK(H.valuePtr() == values);
  CHECK(H.coeff(1, 2) == 0.125f);
  CHECK(G.nonZeros() == 0);
}

TEST_CASE("SparseF: copies and expressions still evaluate as Eigen's", "[formfactor][sparse_f]") {
  const SparseF F = small_matrix();
  const SparseF copy = F;
  CHECK(copy.valuePtr() != F.valuePtr());
  CHECK(copy.coeff(0, 1) == 0.5f);
  const SparseF T = F.transpose();
  CHECK(T.coeff(1, 0) == 0.5f);
  CHECK(T.coeff(2, 1) == 0.125f);
  SparseF A;
  A = F.transpose();
  CHECK(A.coeff(0, 1) == 0.25f);
}

TEST_CASE("SparseF: the program's paths move F without copying it", "[formfactor][sparse_f]") {
  FormFactors ff;
  FormFactors result;
  result.F = small_matrix();
  const float* values = result.F.valuePtr();
  ff = std::move(result);  // as obtain_form_factors assigns estimate_form_factors' result
  CHECK(ff.F.valuePtr() == values);

  PatchSet patches;
  for (int i = 0; i < 3; ++i) {
    patches.rho.push_back(Rgb::Constant(0.5));
    patches.E.push_back(Rgb::Zero());
    patches.area.push_back(1.0);
  }
  RadiosityProblem p = make_problem(patches, std::move(ff.F));
  CHECK(p.F.valuePtr() == values);
  RadiosityProblem q = std::move(p);
  CHECK(q.F.valuePtr() == values);
}
