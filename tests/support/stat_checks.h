#pragma once
// The hypothesis checks of the Monte Carlo tests, one convention for all (docs/ARCHITECTURE.md, "Tests"):
//
//   z-test:  z = (estimate - expected) / se, two-sided; H0 is kept iff |z| <= z_crit, with z_crit =
//            z_critical(sidak(alpha, m)) for a family of m checks at family-wise level alpha (statistics.h). A
//            z that is not a number (se = 0 and no difference) rejects, unless the family says that an entry
//            without variance must match exactly (ZeroVariance::exact, the deterministic estimators of the walk
//            tests: |estimate - expected| <= 1e-12 |expected|). A two-sample test uses expected = the other
//            estimate and se = sqrt(se_a^2 + se_b^2); a binomial fraction p_hat of n trials se = sqrt(p_hat
//            (1 - p_hat) / n).
//   chi-square: Pearson's goodness of fit of counts (statistics.h); H0 is kept iff p > alpha.
//
// A check that rejects writes the tables it compared and names the files in its failure message (artifacts.h).
#include <string>
#include <vector>

#include "core/solution.h"
#include "core/types.h"
#include "patch/patch_set.h"
#include "support/statistics.h"

namespace radwalk::test {

inline double z_score(double estimate, double expected, double se) { return (estimate - expected) / se; }
inline bool z_rejects(double z, double z_crit) { return !(std::abs(z) <= z_crit); }
double binomial_se(double p_hat, double n);

enum class ZeroVariance { reject, exact };

// A family of z-tests at one critical value, collected row by row and judged together.
class ZTable {
 public:
  ZTable(std::string what, double z_crit, ZeroVariance zero = ZeroVariance::reject);

  void add(std::string label, double estimate, double se, double expected);
  // An entry (patch i, channel c) of a per-patch estimate: also a cell of the .vtp of z.
  void add_patch(Eigen::Index i, int c, std::string label, double estimate, double se, double expected);

  struct Report {
    int rejected = 0;
    std::vector<std::size_t> rejected_rows;  // in the order of add()
    std::vector<std::string> files;  // written when rejected > 0 and writing was asked for
    std::string where() const;       // "tables in FILE, FILE" (empty when no file)
  };
  // Judges every row; when one rejects and `write`, writes the table as CSV and, for per-patch rows with
  // `patches`, a .vtp of z per patch and channel.
  Report evaluate(const PatchSet* patches = nullptr, bool write = true) const;
  // evaluate(), then one CHECK per row (|z| <= z_crit) that names the row and, on failure, the files.
  int check(const PatchSet* patches = nullptr) const;

 private:
  struct Row {
    std::string label;
    double estimate, se, expected;
    Eigen::Index patch = -1;
    int channel = -1;
  };
  bool rejects(const Row& r) const;
  std::string what_;
  double z_crit_;
  ZeroVariance zero_;
  std::vector<Row> rows_;
};

// One z-test, a family of one row: CHECKs |estimate - exact| / se <= z_crit, names the operands.
void check_z(const std::string& what, double estimate, double se, double exact, double z_crit);

// Every estimated (patch, channel) of `s` against B_ref (NaN estimates, patches left out, are skipped; an entry
// with zero standard error must match exactly): returns the number rejected; with `report`, WARNs each rejection
// with its operands and, on a rejection, writes the tables (the .vtp when `patches` are given) and WARNs where.
int count_rejections(const Solution& s, const PatchRgb& B_ref, double z_crit, const std::string& label,
                     bool report = true, const PatchSet* patches = nullptr);

// Two-sample z-tests: every patch and channel of two independent estimates agree; CHECKs each.
void check_solutions_agree(const Solution& a, const Solution& b, double z_crit, const PatchSet* patches = nullptr);

// Chi-square goodness of fit of observed against expected counts: CHECKs p > alpha; on rejection writes the
// table (bin, observed, expected, (o - e)^2 / e) and names it. Returns p.
double check_chi_square(const std::string& what, const std::vector<double>& observed,
                        const std::vector<double>& expected, double alpha);

}  // namespace radwalk::test
