#include "walk/stochastic_jacobi.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <span>
#include <utility>
#include <vector>

#include "core/check.h"
#include "core/parallel.h"
#include "core/rng.h"
#include "walk/matrix_kernel.h"
#include "walk/ray_kernel.h"
#include "walk/stratified_emission.h"

namespace radwalk {
namespace {

constexpr double kStopFraction = 1e-6;  // iterate until the unshot power is at most this fraction of Phi_0
constexpr int kMaxIterations = 200;
constexpr long kMinRays = 16;

double unshot_power(const PatchRgb& S, const Eigen::VectorXd& area) {
  double phi = 0;
  for (Eigen::Index j = 0; j < S.rows(); ++j) phi += area(j) * S.row(j).abs().sum();
  return phi;
}

// One iteration: S_next from n rays shot from S by stratified emission (the top of stochastic_jacobi.h).
template <TransitionKernel K>
PatchRgb shoot_once(const K& kernel, const RadiosityProblem& problem, const PatchRgb& S, long n, std::uint64_t seed,
                    std::uint64_t b, WalkCounters& counters) {
  const auto N = static_cast<Eigen::Index>(problem.size());
  const StratifiedEmission emission(S, problem.area, n, seed, b, StreamDomain::jacobi_shift);
  PatchRgb next = PatchRgb::Zero(N, 3);
  if (!(emission.power() > 0)) return next;
  const KernelTables& t = kernel.tables();
  // At most 64 chunks of at least 4096 rays, each with its own N x 3 sums, merged in chunk order.
  const long chunk = std::max<long>(4096, (n + 63) / 64);
  const auto chunks = static_cast<std::size_t>((n + chunk - 1) / chunk);
  std::vector<PatchRgb> parts(chunks);
  std::vector<WalkCounters> part_counters(chunks);
  parallel_for(
      chunks,
      [&](std::size_t c) {
        PatchRgb& part = parts[c];
        part.setZero(N, 3);
        const long begin = static_cast<long>(c) * chunk, end = std::min(n, begin + chunk);
        constexpr std::size_t L = K::kLanes;
        std::array<SampleRequest, L> requests;
        std::array<PatchIndex, L> out;
        std::array<std::array<float, 4>, L> u;
        std::array<Rng, L> rngs;
        std::array<std::size_t, L> from;
        for (long w0 = begin; w0 < end; w0 += static_cast<long>(L)) {
          const std::size_t m = static_cast<std::size_t>(std::min<long>(static_cast<long>(L), end - w0));
          for (std::size_t q = 0; q < m; ++q) {
            const long w = w0 + static_cast<long>(q);
            from[q] = emission.patch_of(w);
            u[q] = emission.first_uniforms(w, from[q]);
            rngs[q] = stream(seed, StreamDomain::jacobi_shift, (std::uint64_t{1} << 46) + static_cast<std::uint64_t>(w), b);
            requests[q] = SampleRequest{from[q], &rngs[q], u[q].data()};
          }
          kernel.sample(std::span<const SampleRequest>(requests.data(), m), std::span<PatchIndex>(out.data(), m),
                        part_counters[c]);
          for (std::size_t q = 0; q < m; ++q) {
            if (out[q] < 0) continue;
            const auto h = static_cast<std::size_t>(out[q]);
            const auto row = static_cast<Eigen::Index>(h);
            part.row(row) += (t.rho[h] * emission.weight(from[q]) * (t.n[from[q]] / problem.area(row))).transpose();
          }
        }
      },
      1);
  for (std::size_t c = 0; c < chunks; ++c) {
    next += parts[c];
    counters += part_counters[c];
  }
  return next / static_cast<double>(n);
}

}  // namespace

template <TransitionKernel K>
JacobiResult run_stochastic_jacobi(const K& kernel, const RadiosityProblem& problem, const WalkOptions& options,
                                   const ReplicateDirectLight& direct) {
  const auto N = static_cast<Eigen::Index>(problem.size());
  const int R = options.replicates;
  RADWALK_CHECK(R >= 2);
  double rho_bar = 0, total_area = 0;
  for (Eigen::Index j = 0; j < N; ++j) {
    rho_bar += problem.area(j) * problem.rho.row(j).mean();
    total_area += problem.area(j);
  }
  rho_bar = total_area > 0 ? std::clamp(rho_bar / total_area, 0.0, 0.99) : 0.0;
  JacobiResult result;
  std::vector<PatchRgb> Bs(static_cast<std::size_t>(R));
  for (int r = 0; r < R; ++r) {
    ReplicateStart start = replicate_start(problem.E, r, direct, result.counters);
    PatchRgb& B = Bs[static_cast<std::size_t>(r)];
    B = std::move(start.base);
    PatchRgb S = std::move(start.source);
    const double phi0 = unshot_power(S, problem.area);
    if (!(phi0 > 0)) continue;
    const double rays_per_power = static_cast<double>(replicate_particles(options, r)) * (1 - rho_bar) / phi0;
    for (int k = 0; k < kMaxIterations; ++k) {
      const double phi = unshot_power(S, problem.area);
      if (!(phi > kStopFraction * phi0)) break;
      const long n = std::max(kMinRays, std::lround(rays_per_power * phi));
      const std::uint64_t b = static_cast<std::uint64_t>(r) << 32 | static_cast<std::uint64_t>(k);
      S = shoot_once(kernel, problem, S, n, options.seed, b, result.counters);
      B += S;
      ++result.iterations;
    }
  }
  result.estimate = replicate_estimate(Bs, options.particles);
  return result;
}

template JacobiResult run_stochastic_jacobi<MatrixKernel>(const MatrixKernel&, const RadiosityProblem&,
                                                          const WalkOptions&, const ReplicateDirectLight&);
template JacobiResult run_stochastic_jacobi<RayKernel>(const RayKernel&, const RadiosityProblem&,
                                                       const WalkOptions&, const ReplicateDirectLight&);

}  // namespace radwalk
