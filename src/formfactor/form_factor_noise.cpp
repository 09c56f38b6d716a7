#include "formfactor/form_factor_noise.h"

#include <vector>

#include "core/check.h"
#include "core/distributed.h"
#include "core/parallel.h"

namespace radwalk {

bool has_noise_model(const FormFactors& ff) { return !ff.rays.empty(); }

GatherVariance gather_variance(const SparseF& F, const FormFactors& ff, const PatchRgb& B, const RowBlocks& blocks) {
  const Eigen::Index N = F.rows();
  RADWALK_CHECK_EQ(B.rows(), N);
  RADWALK_CHECK(has_noise_model(ff));
  RADWALK_CHECK_EQ(static_cast<Eigen::Index>(ff.rays.size()), N);
  std::vector<char> replaced(static_cast<std::size_t>(N), 0);
  for (std::int32_t e : ff.emitter_columns) replaced[static_cast<std::size_t>(e)] = 1;
  const bool emitters = ff.emitter_variance.rows() == N;
  GatherVariance out;
  out.rays = PatchRgb::Zero(N, 3);
  out.emitter = PatchRgb::Zero(N, 3);
  const distributed::Range mine = own_rows(blocks, static_cast<std::size_t>(N));
  parallel_for(mine.size(), [&](std::size_t k) {
    const std::size_t i = mine.begin + k;
    const auto row = static_cast<Eigen::Index>(i);
    RowGather g;
    for (SparseF::InnerIterator it(F, row); it; ++it)
      if (!replaced[static_cast<std::size_t>(it.col())]) g.add_ray_entry(it.value(), B.row(it.col()).transpose());
    if (emitters)
      for (SparseF::InnerIterator it(ff.emitter_variance, row); it; ++it)
        g.add_emitter_entry(0.0, it.value(), B.row(it.col()).transpose());
    out.rays.row(row) = g.ray_variance(ff.rays[i]).transpose();
    out.emitter.row(row) = g.emitter_variance().transpose();
  });
  if (!blocks.empty()) {  // over MPI: every process gets every row's parts
    distributed::allgather_in_place(out.rays.data(), 3 * sizeof(double), blocks);
    distributed::allgather_in_place(out.emitter.data(), 3 * sizeof(double), blocks);
  }
  return out;
}

}  // namespace radwalk
