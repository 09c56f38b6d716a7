#include "walk/transition_kernel.h"

namespace radwalk {

KernelTables make_kernel_tables(const PatchRgb& rho, const PatchRgb& E, std::vector<double> p, std::vector<double> n,
                                std::vector<double> s) {
  const auto N = static_cast<std::size_t>(rho.rows());
  KernelTables t;
  t.p = std::move(p);
  t.n = std::move(n);
  t.s = std::move(s);
  t.E.resize(N);
  t.rho.resize(N);
  for (std::size_t k = 0; k < N; ++k) {
    const auto r = static_cast<Eigen::Index>(k);
    t.E[k] = E.row(r).transpose();
    t.rho[k] = rho.row(r).transpose();
  }
  return t;
}

}  // namespace radwalk
