#pragma once
// Jacobi sweeps for a block of right-hand sides: X = Z + H X, H = diag(rho) F, where column 3k + c of Z and X
// belongs to channel c (k = 0, 1, ...: probes, or a single signed right-hand side). Each sweep computes
//   X_new(i, :) = Z(i, :) + rho_i (sum_j F_ij X(j, :)),
// until the largest change is at most `tolerance` times the largest entry. Converges when the spectral radius of
// H is below 1 (every physical scene: rho < 1 and rows of F summing to at most 1).
// Over MPI with F row-distributed (p.row_blocks) each process sweeps the rows it holds and the new rows are shared
// (collective), so every process ends with the same X bit for bit, whatever the number of processes.
#include "core/types.h"
#include "solve/problem.h"

namespace radwalk {

// Row-major so that one patch's columns (all probes and channels) are contiguous for the gather.
using RowBlock = Eigen::Array<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

struct BlockSolution {
  RowBlock X;
  long sweeps = 0;
};

// Z: N x 3K. Throws InputError naming `what` if the sweeps do not converge within 10,000 (spectral radius of H
// near or above 1).
BlockSolution solve_block_jacobi(const RadiosityProblem& p, const RowBlock& Z, double tolerance, const char* what);

}  // namespace radwalk
