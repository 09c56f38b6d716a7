#include "solve/closed_cavities.h"

#include <algorithm>
#include <numeric>

#include "core/check.h"

namespace radwalk {
namespace {

// Union-find with path halving; the root of a set is its smallest index (so sets come out in order of their
// first patch without a sort).
struct DisjointSets {
  std::vector<std::size_t> parent;
  explicit DisjointSets(std::size_t n) : parent(n) {
    std::iota(parent.begin(), parent.end(), std::size_t(0));
  }
  std::size_t find(std::size_t i) {
    while (parent[i] != i) i = parent[i] = parent[parent[i]];
    return i;
  }
  void join(std::size_t a, std::size_t b) {
    a = find(a), b = find(b);
    if (a != b) parent[std::max(a, b)] = std::min(a, b);
  }
};

}  // namespace

std::vector<ClosedCavity> closed_cavities(const SparseF& F, const NetRadiationInput& input,
                                          double leak_threshold) {
  const std::size_t n = input.area.size();
  RADWALK_CHECK_EQ(input.surface.size(), n);
  RADWALK_CHECK_EQ(static_cast<std::size_t>(F.rows()), n);
  RADWALK_CHECK_EQ(static_cast<std::size_t>(F.cols()), n);
  const auto known_flux = [&](std::size_t i) { return !input.surface[i].temperature_given; };

  // The connected components of the known-flux patches through non-zero entries in either direction.
  DisjointSets sets(n);
  for (std::size_t i = 0; i < n; ++i) {
    if (!known_flux(i)) continue;
    for (SparseF::InnerIterator it(F, Eigen::Index(i)); it; ++it) {
      const auto j = std::size_t(it.col());
      if (it.value() != 0 && known_flux(j)) sets.join(i, j);
    }
  }

  // Per component (indexed by its root): area, `out` (1 - sum_{j in C} F_ij holds what goes to the sky, into
  // backs and to other patches: a traced row's entries, s_i and b_i are fractions of its rays; for an
  // analytic or read F s_i = 1 - the row sum), `in` and the given heat.
  std::vector<double> area(n, 0.0), incoming(n, 0.0), out(n, 0.0), given(n, 0.0);
  for (std::size_t i = 0; i < n; ++i) {
    const double A = input.area[i];
    if (!known_flux(i)) {
      // A known-temperature row sending into a component: its part of `in`.
      for (SparseF::InnerIterator it(F, Eigen::Index(i)); it; ++it) {
        const auto j = std::size_t(it.col());
        if (known_flux(j)) incoming[sets.find(j)] += A * double(it.value());
      }
      continue;
    }
    const std::size_t c = sets.find(i);
    double within = 0;
    for (SparseF::InnerIterator it(F, Eigen::Index(i)); it; ++it)
      if (known_flux(std::size_t(it.col()))) within += double(it.value());  // same component by construction
    area[c] += A;
    out[c] += A * std::max(0.0, 1.0 - within);
    given[c] += A * input.surface[i].heat_flux;
  }

  std::vector<ClosedCavity> cavities;
  std::vector<std::size_t> index_of(n, n);
  for (std::size_t i = 0; i < n; ++i) {
    if (!known_flux(i)) continue;
    const std::size_t c = sets.find(i);
    if (index_of[c] == n) {
      if (!(area[c] > 0)) continue;
      const double leak = std::max(out[c], incoming[c]) / area[c];
      if (!(leak < leak_threshold)) continue;
      index_of[c] = cavities.size();
      ClosedCavity cavity;
      cavity.area = area[c];
      cavity.leak = leak;
      cavity.given_Q = given[c];
      cavities.push_back(cavity);
    }
    cavities[index_of[c]].patches.push_back(i);
  }
  return cavities;
}

}  // namespace radwalk
