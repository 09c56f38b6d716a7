// Deterministic reductions give bit-identical sums for 1 and 2 threads.
#include <catch2/catch.hpp>

#include "core/parallel.h"
#include "core/rng.h"

using namespace radwalk;

static double noisy_sum() {
  return deterministic_reduce(
      100000, 97, 0.0,
      [](std::size_t b, std::size_t e) {
        double s = 0;
        for (std::size_t i = b; i < e; ++i) s += stream(1, StreamDomain::test, i).uniform() * 1e-3 + 1e6 * (i % 3);
        return s;
      },
      [](double a, double b) { return a + b; });
}

TEST_CASE("deterministic_reduce is independent of the thread count", "[parallel]") {
  double one, two;
  {
    ThreadLimit limit(1);
    one = noisy_sum();
  }
  {
    ThreadLimit limit(2);
    two = noisy_sum();
  }
  CHECK(one == two);  // bit-identical, not approximately equal
}

TEST_CASE("parallel_for visits every index once", "[parallel]") {
  std::vector<int> seen(1001, 0);
  parallel_for(seen.size(), [&](std::size_t i) { seen[i] += 1; }, 10);
  for (int s : seen) CHECK(s == 1);
}
