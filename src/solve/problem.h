#pragma once
// The discrete radiosity system, per channel c:  B_c = E_c + diag(rho_c) F B_c,
// i.e. (I - H_c) B_c = E_c with H_c = diag(rho_c) F. F is N x N row-major (row i: where power leaving patch i
// lands, rows sum to 1 in a closed scene, less in an open one); rho in [0, 1); E = emitted radiosity, W/m^2.
#include <Eigen/Core>

#include "core/types.h"
#include "formfactor/form_factor_rows.h"
#include "formfactor/sparse_f.h"
#include "patch/patch_set.h"

namespace radwalk {

struct RadiosityProblem {
  SparseF F;             // N x N form factors (over MPI possibly only this rank's rows: row_blocks)
  // Over MPI: the rank blocks of F's rows when F holds only this rank's rows (formfactor/form_factor_rows.h);
  // empty when every rank holds every row. Jacobi, Gauss-Seidel, the residual and the spectral radius work on the
  // own rows and exchange vectors; the other solvers gather the whole F (whole_problem).
  RowBlocks row_blocks;
  PatchRgb rho;          // N x 3 reflectance
  PatchRgb E;            // N x 3 emitted radiosity
  Eigen::VectorXd area;  // N patch areas
  std::size_t size() const { return static_cast<std::size_t>(area.size()); }
  // Largest emitted radiosity of any patch and channel (0 for none): the scale of the walks' moments.
  double max_emission() const { return E.size() > 0 ? E.maxCoeff() : 0.0; }
};

// Takes rho, E and area from the patches and F as given (with its row blocks, when row-distributed); F must be
// N x N (RADWALK_CHECK: InternalError).
RadiosityProblem make_problem(const PatchSet& patches, SparseF F, RowBlocks row_blocks = {});

// Collective when p's F is row-distributed: a copy of p whose F holds every row on every rank
// (gather_whole_rows), for the stages that need the whole F (the direct solve, Southwell).
RadiosityProblem whole_problem(const RadiosityProblem& p);

// Throws InputError naming the first defect: a value that is not finite, rho < 0, E < 0, F_ij < 0 or area <= 0.
// Sizes that disagree (F N x N, rho and E N x 3, area N) are InternalError (RADWALK_CHECK). Reflectances >= 1 and rows of F summing above 1 are
// accepted here: the solvers report what they do to the spectral radius (SolveStatus, message).
void check_problem(const RadiosityProblem& p);

}  // namespace radwalk
