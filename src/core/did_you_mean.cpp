#include "core/did_you_mean.h"

#include <algorithm>
#include <cctype>

namespace radwalk {

std::size_t edit_distance(const std::string& a, const std::string& b) {
  auto lower = [](char c) { return static_cast<char>(std::tolower(static_cast<unsigned char>(c))); };
  const std::size_t n = a.size(), m = b.size();
  // d[i][j]: distance between the first i characters of a and the first j of b (three rows kept).
  std::vector<std::size_t> before(m + 1), previous(m + 1), current(m + 1);
  for (std::size_t j = 0; j <= m; ++j) previous[j] = j;
  for (std::size_t i = 1; i <= n; ++i) {
    current[0] = i;
    for (std::size_t j = 1; j <= m; ++j) {
      const bool same = lower(a[i - 1]) == lower(b[j - 1]);
      current[j] = std::min({previous[j] + 1, current[j - 1] + 1, previous[j - 1] + (same ? 0 : 1)});
      if (i > 1 && j > 1 && lower(a[i - 1]) == lower(b[j - 2]) && lower(a[i - 2]) == lower(b[j - 1]))
        current[j] = std::min(current[j], before[j - 2] + 1);
    }
    std::swap(before, previous);
    std::swap(previous, current);
  }
  return previous[m];
}

std::string nearest_choice(const std::string& given, const std::vector<std::string>& choices) {
  if (given.empty()) return "";
  const std::size_t allowed = std::max<std::size_t>(1, given.size() / 3);
  std::string best;
  std::size_t best_distance = allowed + 1;
  for (const std::string& c : choices) {
    const std::size_t d = edit_distance(given, c);
    if (d < best_distance) {
      best = c;
      best_distance = d;
    }
  }
  if (!best.empty()) return best;
  // A unique prefix ("gauss" for "gauss-seidel").
  std::string prefixed;
  for (const std::string& c : choices)
    if (c.size() > given.size() && edit_distance(given, c.substr(0, given.size())) == 0) {
      if (!prefixed.empty()) return "";
      prefixed = c;
    }
  return prefixed;
}

std::string did_you_mean(const std::string& given, const std::vector<std::string>& choices) {
  const std::string nearest = nearest_choice(given, choices);
  return nearest.empty() ? std::string() : " (did you mean '" + nearest + "'?)";
}

}  // namespace radwalk
