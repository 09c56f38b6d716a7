#include "support/stat_checks.h"

#include <catch2/catch.hpp>
#include <cmath>
#include <limits>

#include "support/artifacts.h"

namespace radwalk::test {

double binomial_se(double p_hat, double n) { return std::sqrt(p_hat * (1 - p_hat) / n); }

ZTable::ZTable(std::string what, double z_crit, ZeroVariance zero)
    : what_(std::move(what)), z_crit_(z_crit), zero_(zero) {}

void ZTable::add(std::string label, double estimate, double se, double expected) {
  rows_.push_back({std::move(label), estimate, se, expected});
}

void ZTable::add_patch(Eigen::Index i, int c, std::string label, double estimate, double se, double expected) {
  rows_.push_back({std::move(label), estimate, se, expected, i, c});
}

bool ZTable::rejects(const Row& r) const {
  if (zero_ == ZeroVariance::exact && r.se == 0)
    return std::abs(r.estimate - r.expected) > 1e-12 * std::abs(r.expected);
  return z_rejects(z_score(r.estimate, r.expected, r.se), z_crit_);
}

std::string ZTable::Report::where() const {
  std::string s;
  for (const std::string& f : files) s += (s.empty() ? "tables in " : ", ") + f;
  return s;
}

ZTable::Report ZTable::evaluate(const PatchSet* patches, bool write) const {
  Report report;
  for (std::size_t k = 0; k < rows_.size(); ++k)
    if (rejects(rows_[k])) report.rejected_rows.push_back(k);
  report.rejected = static_cast<int>(report.rejected_rows.size());
  if (report.rejected == 0 || !write) return report;
  std::vector<std::vector<std::string>> cells;
  for (const Row& r : rows_)
    cells.push_back({r.label, artifact_number(r.estimate), artifact_number(r.se), artifact_number(r.expected),
                     artifact_number(z_score(r.estimate, r.expected, r.se)), artifact_number(z_crit_),
                     rejects(r) ? "1" : "0"});
  report.files.push_back(
      write_artifact_csv(what_, {"entry", "estimate", "se", "expected", "z", "z_critical", "rejected"}, cells));
  if (patches) {
    const auto n = static_cast<Eigen::Index>(patches->size());
    const double nan = std::numeric_limits<double>::quiet_NaN();
    PatchRgb estimate = PatchRgb::Constant(n, 3, nan), se = estimate, expected = estimate, z = estimate;
    for (const Row& r : rows_)
      if (r.patch >= 0 && r.patch < n) {
        estimate(r.patch, r.channel) = r.estimate;
        se(r.patch, r.channel) = r.se;
        expected(r.patch, r.channel) = r.expected;
        z(r.patch, r.channel) = z_score(r.estimate, r.expected, r.se);
      }
    report.files.push_back(write_artifact_patch_z(what_, *patches, estimate, se, expected, z));
  }
  return report;
}

int ZTable::check(const PatchSet* patches) const {
  const Report report = evaluate(patches);
  for (const Row& r : rows_) {
    INFO(what_ << ", " << r.label << ": estimate " << r.estimate << " +- " << r.se << " (se), expected "
               << r.expected << ", z = " << z_score(r.estimate, r.expected, r.se) << ", |z| limit " << z_crit_);
    INFO(report.where());
    CHECK_FALSE(rejects(r));
  }
  return report.rejected;
}

void check_z(const std::string& what, double estimate, double se, double exact, double z_crit) {
  ZTable table(what, z_crit);
  table.add("estimate", estimate, se, exact);
  table.check();
}

int count_rejections(const Solution& s, const PatchRgb& B_ref, double z_crit, const std::string& label,
                     bool report, const PatchSet* patches) {
  ZTable table(label, z_crit, ZeroVariance::exact);
  std::vector<std::pair<Eigen::Index, int>> entries;
  for (Eigen::Index i = 0; i < s.B.rows(); ++i)
    for (int c = 0; c < 3; ++c) {
      if (std::isnan(s.B(i, c))) continue;
      table.add_patch(i, c, "patch " + std::to_string(i) + " channel " + std::to_string(c), s.B(i, c),
                      s.B_se(i, c), B_ref(i, c));
      entries.emplace_back(i, c);
    }
  const ZTable::Report r = table.evaluate(patches, report);
  if (report) {
    for (std::size_t k : r.rejected_rows) {
      const auto [i, c] = entries[k];
      const double diff = s.B(i, c) - B_ref(i, c), se = s.B_se(i, c);
      WARN(label << ": patch " << i << " channel " << c << ": B = " << s.B(i, c) << " +- " << se << ", exact "
                 << B_ref(i, c) << ", z = " << (se > 0 ? diff / se : INFINITY) << ", critical " << z_crit);
    }
    if (r.rejected > 0) WARN(label << ": " << r.rejected << " rejected; " << r.where());
  }
  return r.rejected;
}

void check_solutions_agree(const Solution& a, const Solution& b, double z_crit, const PatchSet* patches) {
  // Both estimates without variance (a patch no sample could light): they must then agree exactly.
  ZTable table(a.method + " vs " + b.method, z_crit, ZeroVariance::exact);
  for (Eigen::Index i = 0; i < a.B.rows(); ++i)
    for (int c = 0; c < 3; ++c)
      table.add_patch(i, c,
                      "patch " + std::to_string(i) + " channel " + std::to_string(c) + " (" + a.method + " " +
                          std::to_string(a.B(i, c)) + " vs " + b.method + " " + std::to_string(b.B(i, c)) + ")",
                      a.B(i, c), std::hypot(a.B_se(i, c), b.B_se(i, c)), b.B(i, c));
  table.check(patches);
}

double check_chi_square(const std::string& what, const std::vector<double>& observed,
                        const std::vector<double>& expected, double alpha) {
  const double p = chi_square_gof_p_value(observed, expected);
  std::string where;
  if (!(p > alpha)) {
    std::vector<std::vector<std::string>> cells;
    for (std::size_t k = 0; k < observed.size(); ++k) {
      const double d = observed[k] - expected[k];
      cells.push_back({std::to_string(k), artifact_number(observed[k]), artifact_number(expected[k]),
                       artifact_number(expected[k] > 0 ? d * d / expected[k] : 0.0)});
    }
    where = "tables in " + write_artifact_csv(what, {"bin", "observed", "expected", "contribution"}, cells);
  }
  INFO(what << ": chi-square p = " << p << ", level " << alpha);
  INFO(where);
  CHECK(p > alpha);
  return p;
}

}  // namespace radwalk::test
