#pragma once
// Running mean and second central moment per channel (Welford), mergeable (Chan et al. 1979): partial moments of
// fixed chunks merged in chunk order give bit-identical results for any thread count, and no cancellation when
// the variance is tiny (zero-variance estimators stay at exactly 0 when every score is equal).
//   add x:    n += 1, d = x - mean, mean += d / n, M2 += d (x - mean)
//   merge b:  d = mean_b - mean_a, mean = mean_a + d n_b / n, M2 = M2_a + M2_b + d^2 n_a n_b / n
// Per-sample variance M2 / (n - 1); standard error of the mean sqrt(var / n).
#include "core/types.h"

namespace radwalk {

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

// The per-chunk accumulator of hot loops: sums of d = x - K and d^2 with the shift K = the chunk's first sample
// (shifted-data algorithm: no division per sample, no cancellation when K is a typical value; all-equal samples
// give M2 = 0 exactly). moments() converts to Moments: mean = K + S1 / n, M2 = S2 - S1^2 / n.
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

}  // namespace radwalk
