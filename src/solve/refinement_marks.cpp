#include "solve/refinement_marks.h"

#include <algorithm>
#include <numeric>

#include "core/check.h"

namespace radwalk {
namespace {

// One share's marks: the splittable elements in decreasing x until they hold fraction of sum max(x, 0), or the next
// x is at most floor. Returns the total sum max(x, 0).
double mark_by(const std::vector<double>& x, double fraction, double floor, const std::vector<bool>& splittable,
               std::vector<bool>& marks) {
  const std::size_t N = x.size();
  double total = 0;
  for (const double v : x) total += std::max(v, 0.0);
  std::vector<std::size_t> order(N);
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return x[a] > x[b]; });
  double held = 0;
  for (const std::size_t i : order) {
    if (!(x[i] > 0) || !(x[i] > floor) || held >= fraction * total) break;
    if (!splittable.empty() && !splittable[i]) continue;
    marks[i] = true;
    held += x[i];
  }
  return total;
}

}  // namespace

std::vector<bool> refinement_marks(const std::vector<double>& receiver, const std::vector<double>& shooter,
                                   double fraction, double floor, std::size_t room,
                                   const std::vector<bool>& splittable) {
  const std::size_t N = receiver.size();
  RADWALK_CHECK(shooter.empty() || shooter.size() == N);
  RADWALK_CHECK(splittable.empty() || splittable.size() == N);
  std::vector<bool> marks(N, false);
  const double R = mark_by(receiver, fraction, floor, splittable, marks);
  const double C = shooter.empty() ? 0.0 : mark_by(shooter, fraction, floor, splittable, marks);
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
