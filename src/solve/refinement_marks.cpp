#include "solve/refinement_marks.h"

#include <algorithm>
#include <limits>
#include <numeric>

#include "core/check.h"

namespace radwalk {
namespace {

double positive_sum(const std::vector<double>& x) {
  double total = 0;
  for (const double v : x) total += std::max(v, 0.0);
  return total;
}

}  // namespace

std::size_t mark_largest(const std::vector<double>& x, double fraction, double floor,
                         const std::vector<bool>& splittable, std::size_t room, std::vector<bool>& marks) {
  const std::size_t N = x.size();
  RADWALK_CHECK_EQ(marks.size(), N);
  RADWALK_CHECK(splittable.empty() || splittable.size() == N);
  const double total = positive_sum(x);
  std::vector<std::size_t> order(N);
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return x[a] > x[b]; });
  double held = 0;
  std::size_t marked = 0;
  for (const std::size_t i : order) {
    if (!(x[i] > 0) || !(x[i] > floor) || held >= fraction * total) break;
    if (!marks[i]) {
      if (marked >= room) break;
      if (!splittable.empty() && !splittable[i]) continue;
      marks[i] = true;
      ++marked;
    }
    held += x[i];
  }
  return marked;
}

std::vector<bool> refinement_marks(const std::vector<double>& receiver, const std::vector<double>& shooter,
                                   double fraction, double floor, std::size_t room,
                                   const std::vector<bool>& splittable) {
  const std::size_t N = receiver.size();
  RADWALK_CHECK(shooter.empty() || shooter.size() == N);
  RADWALK_CHECK(splittable.empty() || splittable.size() == N);
  std::vector<bool> marks(N, false);
  const std::size_t all = std::numeric_limits<std::size_t>::max();  // the room is applied below, to the union
  mark_largest(receiver, fraction, floor, splittable, all, marks);
  if (!shooter.empty()) mark_largest(shooter, fraction, floor, splittable, all, marks);
  const double R = positive_sum(receiver), C = shooter.empty() ? 0.0 : positive_sum(shooter);
  const auto count = static_cast<std::size_t>(std::count(marks.begin(), marks.end(), true));
  if (count <= room) return marks;
  // Over the budget: the largest of the two normalised shares first.
  std::vector<double> score(N, 0.0);
  std::vector<std::size_t> marked;
  for (std::size_t i = 0; i < N; ++i) {
    if (!marks[i]) continue;
    marked.push_back(i);
    if (R > 0) score[i] = std::max(score[i], receiver[i] / R);
    if (C > 0) score[i] = std::max(score[i], shooter[i] / C);
  }
  std::stable_sort(marked.begin(), marked.end(), [&](std::size_t a, std::size_t b) { return score[a] > score[b]; });
  std::vector<bool> kept(N, false);
  for (std::size_t q = 0; q < room; ++q) kept[marked[q]] = true;
  return kept;
}

}  // namespace radwalk
