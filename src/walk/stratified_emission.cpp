#include "walk/stratified_emission.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "core/check.h"
#include "core/error.h"
#include "core/rng.h"

namespace radwalk {

StratifiedEmission::StratifiedEmission(const PatchRgb& S, const Eigen::VectorXd& area, long n, std::uint64_t seed,
                                       std::uint64_t replicate, StreamDomain domain)
    : n_(n) {
  RADWALK_CHECK(n >= 1);
  const auto N = static_cast<std::size_t>(S.rows());
  if (static_cast<std::size_t>(area.size()) != N)
    throw InputError("stratified emission: " + std::to_string(N) + " source rows but " +
                     std::to_string(area.size()) + " areas");
  std::vector<double> phi(N, 0.0);
  for (std::size_t j = 0; j < N; ++j) {
    const auto row = static_cast<Eigen::Index>(j);
    if (!S.row(row).isFinite().all() || area(row) < 0)
      throw InputError("stratified emission: patch " + std::to_string(j) + " has a non-finite source or a negative area");
    phi[j] = area(row) * S.row(row).abs().sum();
    power_ += phi[j];
  }
  first_.assign(N + 1, 0);
  W0_.assign(N, Rgb::Zero());
  shift_.resize(N);
  if (!(power_ > 0)) return;
  const double U = stream(seed, domain, std::uint64_t{1} << 47, replicate).uniform();
  double cdf = 0;
  for (std::size_t j = 0; j < N; ++j) {
    first_[j] = std::clamp(static_cast<long>(std::ceil(static_cast<double>(n) * cdf - U)), 0L, n);
    cdf += phi[j] / power_;
    if (phi[j] > 0) {
      const double pi = phi[j] / power_;
      W0_[j] = area(static_cast<Eigen::Index>(j)) * S.row(static_cast<Eigen::Index>(j)).transpose() / pi;
      Rng rng = stream(seed, domain, j, replicate);
      for (auto& w : shift_[j].word) w = rng.next_u32();
    }
  }
  first_[N] = n;
  // Rounding of the running CDF must not let a particle land on a patch without power: the last patch with
  // power takes everything up to n.
  for (std::size_t j = N; j-- > 0;) {
    if (phi[j] > 0) break;
    first_[j] = n;
  }
}

std::size_t StratifiedEmission::patch_of(long w) const {
  const auto it = std::upper_bound(first_.begin(), first_.end(), w);
  return static_cast<std::size_t>(it - first_.begin() - 1);
}

std::array<float, 4> StratifiedEmission::first_uniforms(long w, std::size_t j) const {
  return sobol_point(static_cast<std::uint32_t>(w - first_[j]), shift_[j]);
}

}  // namespace radwalk
