#pragma once
// Hypothesis-test helpers for the random-walk tests (docs/ARCHITECTURE.md, convention 7: Monte Carlo tests are
// hypothesis tests).
#include <catch2/catch.hpp>
#include <cmath>
#include <string>

#include "core/solution.h"

namespace radwalk::test {

// Two-sided z-test of every estimated (patch, channel) of `s` against B_ref with the estimated standard error:
// returns the number rejected at critical value z_crit and reports each rejection with its operands. An entry
// with zero standard error must equal B_ref up to rounding (1e-12 relative).
inline int count_rejections(const Solution& s, const PatchRgb& B_ref, double z_crit, const std::string& label,
                            bool report = true) {
  int rejected = 0;
  for (Eigen::Index i = 0; i < s.B.rows(); ++i)
    for (int c = 0; c < 3; ++c) {
      if (std::isnan(s.B(i, c))) continue;
      const double diff = s.B(i, c) - B_ref(i, c);
      const double se = s.B_se(i, c);
      const bool reject = se > 0 ? std::abs(diff / se) > z_crit : std::abs(diff) > 1e-12 * std::abs(B_ref(i, c));
      if (reject) {
        ++rejected;
        if (report)
          WARN(label << ": patch " << i << " channel " << c << ": B = " << s.B(i, c) << " +- " << se
                              << ", exact " << B_ref(i, c) << ", z = " << (se > 0 ? diff / se : INFINITY)
                              << ", critical " << z_crit);
      }
    }
  return rejected;
}

}  // namespace radwalk::test
