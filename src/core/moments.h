#pragma once
// Sample mean and variance: every accumulator of radwalk (solvers, path tracer, tests) in one place. For samples
// x_1..x_n the estimates are
//   mean = (1/n) sum x,   var = sum (x - mean)^2 / (n - 1)  (unbiased, per sample),   se = sqrt(var / n)
// (the standard error of the mean), computed four ways, each exact to its own rounding and kept bit for bit:
//
//   mean_and_variance(S1, S2, m)  from power sums S1 = sum x, S2 = sum x^2 of m >= 2 samples, element by element
//                                 for Eigen arrays (Rgb, PatchRgb) or doubles:
//                                 mean = S1 / m, var = max(0, (S2 - m mean^2) / (m - 1));
//                                 the clamp at 0 absorbs rounding when every sample is (nearly) equal.
//   PowerSums                     a scalar running n, S1, S2 with the same formula (tests' estimates).
//   Moments                       running mean and second central moment M2 per channel (Welford), mergeable
//                                 (Chan et al. 1979): partial moments of fixed chunks merged in chunk order give
//                                 bit-identical results for any thread count, and no cancellation when the
//                                 variance is tiny (a zero-variance estimator stays at exactly 0):
//                                   add x:    n += 1, d = x - mean, mean += d / n, M2 += d (x - mean)
//                                   merge b:  d = mean_b - mean_a, mean = mean_a + d n_b / n,
//                                             M2 = M2_a + M2_b + d^2 n_a n_b / n
//                                 var = M2 / (n - 1).
//   ShiftedSums                   the per-chunk accumulator of hot loops: sums of d = x - K and d^2 with the shift K
//                                 = the chunk's first sample (shifted-data algorithm: no division per sample, no
//                                 cancellation when K is a typical value; all-equal samples give M2 = 0 exactly);
//                                 moments() converts: mean = K + S1 / n, M2 = max(0, S2 - S1^2 / n).
//   CentralMoments4               n, mean and the central sums M2, M3, M4 (M_k = sum (x - mean)^k) per channel, for
//                                 the variance of the variance: of(x, count) from a block of stored samples by two
//                                 passes (no cancellation), merge(b) combines blocks (Pebay 2008, with
//                                 d = mean_b - mean_a, n = n_a + n_b):
//                                   M2 = M2_a + M2_b + d^2 n_a n_b / n
//                                   M3 = M3_a + M3_b + d^3 n_a n_b (n_a - n_b) / n^2 + 3 d (n_a M2_b - n_b M2_a) / n
//                                   M4 = M4_a + M4_b + d^4 n_a n_b (n_a^2 - n_a n_b + n_b^2) / n^3
//                                        + 6 d^2 (n_a^2 M2_b + n_b^2 M2_a) / n^2 + 4 d (n_a M3_b - n_b M3_a) / n;
//                                 blocks merged in a fixed order give the same bits for any thread count.
//                                 vov() = M4 / M2^2 - 1 / n: MCNP's VOV, the estimated relative variance of the
//                                 estimated variance of the mean (0 where M2 = 0); a confidence interval from the
//                                 sample variance is trusted only where it is below kVovReliable = 0.1 (MCNP's
//                                 statistical checks, X-5 Monte Carlo Team 2003, vol. I ch. 2 sec. VI).
//   sample_moments(x)             two passes over stored samples: mean, var and the fourth central moment
//                                 mu4 = (1/n) sum (x - mean)^4 (for the variance z-test of the tests).
//
// Scale before squaring: samples as large as 1e300 (emission is legal up to pi 1e300) have squares beyond the
// largest double, tiny ones squares below the smallest. moment_scale(largest) gives a power of two s near the
// largest magnitude expected; an accumulator then takes x / s and the results are multiplied back:
// mean = s mean(x / s), se = s se(x / s), var = s^2 var(x / s), which is infinite only when the variance itself
// does not fit a double. Dividing and multiplying by a power of two is exact (away from subnormals), so the
// results are those of the unscaled samples bit for bit wherever those did not overflow.
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <utility>
#include <vector>

#include "core/types.h"

namespace radwalk {

namespace detail {
inline double clamp_at_zero(double v) { return std::max(v, 0.0); }
template <class Array>
Array clamp_at_zero(const Array& v) {
  return v.max(0.0);
}
}  // namespace detail

template <class T>
std::pair<T, T> mean_and_variance(const T& sum, const T& sum2, double m) {
  T mean = sum / m;
  T var = detail::clamp_at_zero(T((sum2 - m * mean * mean) / (m - 1.0)));
  return {std::move(mean), std::move(var)};
}

struct PowerSums {
  double n = 0, sum = 0, sum2 = 0;

  void add(double x) {
    n += 1;
    sum += x;
    sum2 += x * x;
  }
  double mean() const { return sum / n; }
  double variance() const { return mean_and_variance(sum, sum2, n).second; }
  double standard_error() const { return std::sqrt(variance() / n); }
};

struct Moments {
  long n = 0;
  Rgb mean = Rgb::Zero();
  Rgb M2 = Rgb::Zero();

  void add(const Rgb& x) {
    ++n;
    const Rgb d = x - mean;
    mean += d / static_cast<double>(n);
    M2 += d * (x - mean);
  }
  void merge(const Moments& b) {
    if (b.n == 0) return;
    if (n == 0) {
      *this = b;
      return;
    }
    const double na = static_cast<double>(n), nb = static_cast<double>(b.n), nn = na + nb;
    const Rgb d = b.mean - mean;
    mean += d * (nb / nn);
    M2 += b.M2 + d * d * (na * nb / nn);
    n += b.n;
  }
  Rgb variance() const { return n > 1 ? Rgb(M2 / static_cast<double>(n - 1)) : Rgb::Zero(); }
  Rgb standard_error() const { return n > 0 ? Rgb((variance() / static_cast<double>(n)).sqrt()) : Rgb::Zero(); }
};

struct ShiftedSums {
  long n = 0;
  Rgb K = Rgb::Zero(), S1 = Rgb::Zero(), S2 = Rgb::Zero();

  void add(const Rgb& x) {
    if (n == 0) K = x;
    const Rgb d = x - K;
    S1 += d;
    S2 += d * d;
    ++n;
  }
  Moments moments() const {
    Moments m;
    m.n = n;
    if (n == 0) return m;
    const double nn = static_cast<double>(n);
    m.mean = K + S1 / nn;
    m.M2 = (S2 - S1 * S1 / nn).max(0.0);
    return m;
  }
};

// 1 when `largest` is within [2^-200, 2^200] (squares of samples up to 2^200 times 2^63 samples fit a double:
// nothing to gain, and the common case is left untouched), else the power of two 2^(e - 1) with largest = f 2^e,
// f in [0.5, 1), so that largest / s is in [1, 2) (and s is finite up to the largest double); 1 for 0, a
// negative or a non-finite `largest`.
inline double moment_scale(double largest) {
  if (!(largest > 0) || !std::isfinite(largest)) return 1;
  if (largest >= std::ldexp(1.0, -200) && largest <= std::ldexp(1.0, 200)) return 1;
  int exponent = 0;
  std::frexp(largest, &exponent);
  return std::ldexp(1.0, exponent - 1);
}

inline constexpr double kVovReliable = 0.1;

struct CentralMoments4 {
  long n = 0;
  Rgb mean = Rgb::Zero(), M2 = Rgb::Zero(), M3 = Rgb::Zero(), M4 = Rgb::Zero();

  static CentralMoments4 of(const Rgb* x, std::size_t count) {
    CentralMoments4 m;
    if (count == 0) return m;
    m.n = static_cast<long>(count);
    for (std::size_t i = 0; i < count; ++i) m.mean += x[i];
    m.mean /= static_cast<double>(count);
    for (std::size_t i = 0; i < count; ++i) {
      const Rgb d = x[i] - m.mean, d2 = d * d;
      m.M2 += d2;
      m.M3 += d2 * d;
      m.M4 += d2 * d2;
    }
    return m;
  }
  void merge(const CentralMoments4& b) {
    if (b.n == 0) return;
    if (n == 0) {
      *this = b;
      return;
    }
    const double na = static_cast<double>(n), nb = static_cast<double>(b.n), nn = na + nb;
    const Rgb d = b.mean - mean, d2 = d * d;
    M4 += b.M4 + d2 * d2 * (na * nb * (na * na - na * nb + nb * nb) / (nn * nn * nn)) +
          6.0 * d2 * (na * na * b.M2 + nb * nb * M2) / (nn * nn) + 4.0 * d * (na * b.M3 - nb * M3) / nn;
    M3 += b.M3 + d2 * d * (na * nb * (na - nb) / (nn * nn)) + 3.0 * d * (na * b.M2 - nb * M2) / nn;
    M2 += b.M2 + d2 * (na * nb / nn);
    mean += d * (nb / nn);
    n += b.n;
  }
  // Divided by M2 twice (not by M2^2) so that tiny samples do not underflow the square.
  Rgb vov() const {
    Rgb v = Rgb::Zero();
    for (int c = 0; c < 3; ++c)
      if (M2[c] > 0) v[c] = std::max(0.0, M4[c] / M2[c] / M2[c] - 1.0 / static_cast<double>(n));
    return v;
  }
};

struct SampleMoments {
  double mean = 0, var = 0, mu4 = 0;
  std::size_t n = 0;
};

inline SampleMoments sample_moments(const std::vector<double>& x) {
  SampleMoments m;
  m.n = x.size();
  for (double v : x) m.mean += v;
  m.mean /= static_cast<double>(m.n);
  double s2 = 0, s4 = 0;
  for (double v : x) {
    const double d = v - m.mean;
    s2 += d * d;
    s4 += d * d * d * d;
  }
  m.var = s2 / static_cast<double>(m.n - 1);
  m.mu4 = s4 / static_cast<double>(m.n);
  return m;
}

}  // namespace radwalk
