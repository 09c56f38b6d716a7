#include "apps/exchange_sensitivities.h"

#include <cmath>
#include <cstdio>
#include <map>

#include "apps/pipeline.h"
#include "core/error.h"
#include "core/timer.h"
#include "io/csv_writer.h"
#include "solve/net_radiation_sensitivity.h"

namespace radwalk::app {

void report_sensitivities(const std::string& spec, const std::string& csv, const std::string& group_by,
                          const NetRadiationInput& input, const SparseF& F, const NetRadiationResult& r,
                          const std::vector<std::int32_t>& group, const std::vector<std::string>& names,
                          bool traced, RunSummary& summary) {
  const int groups = int(names.size());
  std::map<std::string, int> index;
  for (int G = 0; G < groups; ++G) index.emplace(names[std::size_t(G)], G);
  std::vector<int> responses;
  if (spec == "all") {
    for (int G = 0; G < groups; ++G) responses.push_back(G);
  } else {
    std::size_t start = 0;
    while (start <= spec.size()) {
      const std::size_t end = std::min(spec.find(',', start), spec.size());
      const std::string name = spec.substr(start, end - start);
      const auto it = index.find(name);
      if (it == index.end()) {
        std::string known;
        for (int G = 0; G < groups && G < 8; ++G) known += (G ? ", '" : "'") + names[std::size_t(G)] + "'";
        throw InputError("--sensitivities: '" + name + "' names no " + group_by + " of the scene (--group-by " +
                         group_by + "; " + std::to_string(groups) + " of them: " + known +
                         (groups > 8 ? ", ..." : "") + "); give comma-separated names or 'all'");
      }
      responses.push_back(it->second);
      start = end + 1;
    }
  }
  Timer timer;
  const NetRadiationSensitivity s = net_radiation_sensitivity(input, F, r, group, groups, responses);
  summary.add_timing("sensitivities", timer.seconds());
  const std::string error_note = traced ? "the traced form factors' noise is not propagated into them"
                                        : "deterministic given F (no statistical error)";
  auto& j = summary.json()["exchange"]["sensitivities"];
  j["method"] = "adjoint of the net-radiation system, one BiCGSTAB solve per response group "
                "(docs/theory/net_radiation.md, Sensitivities)";
  j["errors"] = error_note;
  j["units"] = {{"dQ_deps", "W"}, {"dQ_dT", "W/K"}};
  nlohmann::json table = nlohmann::json::array();
  std::vector<std::vector<std::string>> rows;
  for (std::size_t k = 0; k < responses.size(); ++k) {
    const std::string& to = names[std::size_t(responses[k])];
    for (int H = 0; H < groups; ++H) {
      const double de = s.dQ_deps(Eigen::Index(k), H), dT = s.dQ_dT(Eigen::Index(k), H);
      table.push_back({{"group_from", names[std::size_t(H)]}, {"group_to", to}, {"dQ_deps", de}, {"dQ_dT", dT}});
      rows.push_back({csv_text(names[std::size_t(H)]), csv_text(to), csv_number(de), csv_number(dT)});
    }
    j["adjoint"].push_back({{"group", to}, {"iterations", s.iterations[k]}, {"relative_residual", s.residual[k]}});
    // The report: the parameter groups Q_G is most sensitive to.
    int worst_e = 0, worst_T = 0;
    for (int H = 1; H < groups; ++H) {
      if (std::abs(s.dQ_deps(Eigen::Index(k), H)) > std::abs(s.dQ_deps(Eigen::Index(k), worst_e))) worst_e = H;
      if (std::abs(s.dQ_dT(Eigen::Index(k), H)) > std::abs(s.dQ_dT(Eigen::Index(k), worst_T))) worst_T = H;
    }
    std::fprintf(report_stream(),
                 "  sensitivity of Q(%s %s): largest dQ/deps %.6g W (of %s), largest dQ/dT %.6g W/K (of %s); "
                 "adjoint residual %.2g (%s)\n",
                 group_by.c_str(), to.c_str(), s.dQ_deps(Eigen::Index(k), worst_e),
                 names[std::size_t(worst_e)].c_str(), s.dQ_dT(Eigen::Index(k), worst_T),
                 names[std::size_t(worst_T)].c_str(), s.residual[k], error_note.c_str());
  }
  j["table"] = table;
  if (!csv.empty()) {
    write_csv_table(csv, {"group_from", "group_to", "dQ_deps_W", "dQ_dT_W_per_K"}, rows, run_id_of(summary));
    note("wrote " + csv);
  }
}

}  // namespace radwalk::app
