#include "patch/refine_criterion.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "core/check.h"
#include "core/error.h"

namespace radwalk {

std::vector<double> radiosity_jumps(const PatchSet& patches, const PatchRgb& B,
                                    const std::vector<std::pair<PatchIndex, PatchIndex>>& neighbours,
                                    const JumpOptions& options) {
  const std::size_t n = patches.size();
  const double floor_fraction = options.floor_fraction, noise_z = options.noise_z;
  const PatchRgb& H_se = options.H_se;
  const std::vector<double>& visible = options.visible;
  if (!visible.empty()) RADWALK_CHECK_EQ(visible.size(), n);
  for (double v : visible)
    if (!(v >= 0 && v <= 1)) throw InputError("radiosity_jumps: visible fraction " + std::to_string(v) + " not in [0, 1]");
  const auto ignored = [&](std::size_t i) { return !visible.empty() && visible[i] == 0; };
  const auto visible_part = [&](std::size_t i) { return visible.empty() || visible[i] == 0 ? 1.0 : visible[i]; };
  RADWALK_CHECK_EQ(std::size_t(B.rows()), n);
  if (H_se.size() != 0) RADWALK_CHECK_EQ(std::size_t(H_se.rows()), n);
  if (!(noise_z >= 0) || !std::isfinite(noise_z))
    throw InputError("radiosity_jumps: noise z must be finite and >= 0, got " + std::to_string(noise_z));
  if (!(floor_fraction >= 0) || !std::isfinite(floor_fraction))
    throw InputError("radiosity_jumps: floor fraction must be finite and >= 0, got " + std::to_string(floor_fraction));

  // H = max(0, B - E) / rho where rho > 0, and the floor from the area-weighted mean of rho H = B - E.
  PatchRgb H = PatchRgb::Zero(Eigen::Index(n), 3);
  Rgb weighted = Rgb::Zero(), area = Rgb::Zero();
  for (std::size_t i = 0; i < n; ++i)
    for (int c = 0; c < 3; ++c) {
      const double rho = patches.rho[i](c);
      if (!(rho > 0)) continue;
      const double h = std::max(0.0, B(Eigen::Index(i), c) - patches.E[i](c)) / rho / visible_part(i);
      H(Eigen::Index(i), c) = h;
      weighted(c) += patches.area[i] * rho * h;
      area(c) += patches.area[i];
    }
  Rgb floor = Rgb::Zero();
  for (int c = 0; c < 3; ++c) floor(c) = area(c) > 0 ? floor_fraction * weighted(c) / area(c) : 0.0;

  std::vector<double> jump(n, 0.0);
  std::vector<bool> judged(n, false);
  for (const auto& [a, b] : neighbours) {
    RADWALK_CHECK_LT(std::size_t(a), n);  // a negative index wraps around to a large one
    RADWALK_CHECK_LT(std::size_t(b), n);
    const auto i = std::size_t(a), j = std::size_t(b);
    judged[i] = judged[j] = true;
    if (ignored(i) || ignored(j)) continue;
    double d = 0;
    for (int c = 0; c < 3; ++c) {
      if (!(patches.rho[i](c) > 0) || !(patches.rho[j](c) > 0)) continue;
      const double hi = H(Eigen::Index(i), c), hj = H(Eigen::Index(j), c);
      if (hi == hj) continue;
      if (H_se.size() != 0) {
        const double si = H_se(Eigen::Index(i), c) / visible_part(i), sj = H_se(Eigen::Index(j), c) / visible_part(j);
        if (std::abs(hi - hj) <= noise_z * std::sqrt(si * si + sj * sj)) continue;
      }
      const double rho = std::max(patches.rho[i](c), patches.rho[j](c));
      d = std::max(d, rho * std::abs(hi - hj) / std::max({rho * hi, rho * hj, floor(c)}));
    }
    jump[i] = std::max(jump[i], d);
    jump[j] = std::max(jump[j], d);
  }
  for (std::size_t i = 0; i < n; ++i)
    if (!judged[i] && !ignored(i)) jump[i] = 1.0;
  return jump;
}

std::vector<bool> mark_jumps(const std::vector<double>& jump, double tol) {
  std::vector<bool> marked(jump.size());
  for (std::size_t i = 0; i < jump.size(); ++i) marked[i] = jump[i] > tol;
  return marked;
}

}  // namespace radwalk
