// radwalk compare SCENE --estimators LIST --walks-per-patch N --runs R --csv out.csv -o out.vtp: estimator variance
// study.
#include <cmath>
#include <cstdio>
#include <map>

#include "apps/finite_outputs.h"
#include "apps/options.h"
#include "apps/pipeline.h"
#include "core/standard_output.h"
#include "apps/run_metadata.h"
#include "core/parallel.h"
#include "io/csv_writer.h"
#include "solve/problem.h"
#include "solve/solve_radiosity.h"
#include "visibility/embree_visibility.h"
#include "walk/walk_compare.h"

namespace radwalk::app {

int run_compare(const CompareCommand& command) {
  RunSummary summary("compare", command.scene.argv);
  const PatchSet patches = load_patches(command.scene, summary);
  // The options are checked here, once, before any form factor is traced.
  CompareOptions options = command.compare;
  options.walk.seed = command.scene.seed;
  options.progress = true;
  check_compare_options(options, patches.size());
  ThreadLimit limit(command.scene.threads);
  FormFactors ff = obtain_form_factors(command.scene, command.ff, patches, summary);
  const RadiosityProblem problem = make_problem(patches, std::move(ff.F));

  // Reference: the direct solve of the same discrete system (z-scores measure the walks' bias and error bars).
  SolveOptions direct;
  direct.solver = "direct";
  const Solution reference = solve_radiosity(problem, direct);
  summary.add_timing("reference solve", reference.seconds);

  std::unique_ptr<EmbreeVisibility> visibility;
  if (options.walk.kernel == WalkKernel::ray) visibility = std::make_unique<EmbreeVisibility>(patches);
  const CompareResult result = compare_random_walks(problem, &patches, visibility.get(), options, reference.B);
  refuse_overflow(result.rows, patches.max_emission());
  double total = 0;
  for (const auto& s : result.summary) total += s.seconds;
  summary.add_timing("walks", total);

  std::fprintf(report_stream(), "%s", format_compare_summary(result.summary).c_str());

  if (!command.scene.csv.empty()) {
    static const char* kChannel[3] = {"r", "g", "b"};
    std::vector<std::vector<std::string>> rows;
    rows.reserve(result.rows.size());
    for (const CompareRow& r : result.rows)
      rows.push_back({std::to_string(r.patch), std::string(method_name(r.method)), kChannel[r.channel], csv_number(r.mean), csv_number(r.var),
                      csv_number(r.var_se), csv_number(r.var_theory), csv_number(r.z), std::to_string(r.walks), std::to_string(r.steps),
                      csv_number(r.seconds), csv_number(r.efficiency)});
    write_csv_table(command.scene.csv,
                    {"patch", "estimator", "channel", "mean", "var", "var_se", "var_theory", "z", "walks", "steps",
                     "seconds", "efficiency"},
                    rows, run_id_of(summary));
    note("wrote " + output_display_name(command.scene.csv));
  }

  // VTK: per method, fields mean_<m>, var_<m>, var_se_<m>, var_theory_<m>, z_<m> (3 components each), beside B_reference;
  // <m> is the estimator's name with underscores for hyphens (ParaView's Calculator reads '-' as minus), the
  // original names listed in the field data.
  std::vector<CellField> fields = {rgb_field("B_reference", reference.B)};
  const auto n = static_cast<Eigen::Index>(patches.size());
  std::map<std::string, std::array<PatchRgb, 5>> per_method;
  for (const CompareRow& r : result.rows) {
    auto [it, fresh] = per_method.try_emplace(std::string(method_name(r.method)));
    if (fresh)
      for (auto& a : it->second) a = PatchRgb::Constant(n, 3, std::numeric_limits<double>::quiet_NaN());
    it->second[0](r.patch, r.channel) = r.mean;
    it->second[1](r.patch, r.channel) = r.var;
    it->second[2](r.patch, r.channel) = r.var_theory;
    it->second[3](r.patch, r.channel) = r.z;
    it->second[4](r.patch, r.channel) = r.var_se;
  }
  VtpMetadata metadata;
  std::string names, arrays;
  for (const auto& [method, a] : per_method) {
    const std::string m = paraview_name(method);
    fields.push_back(rgb_field("mean_" + m, a[0]));
    fields.push_back(rgb_field("var_" + m, a[1]));
    fields.push_back(rgb_field("var_se_" + m, a[4]));
    fields.push_back(rgb_field("var_theory_" + m, a[2]));
    fields.push_back(rgb_field("z_" + m, a[3]));
    names += (names.empty() ? "" : ",") + method;
    arrays += (arrays.empty() ? "" : ",") + m;
  }
  metadata.set_text("estimators", names);
  metadata.set_text("estimator_array_names", arrays);
  metadata.set_text("kernel", std::string(kernel_name(command.compare.walk.kernel)));
  metadata.set_integer("walks_per_patch", command.compare.walk.walks_per_patch);
  metadata.set_integer("runs", command.compare.runs);
  // The budget and the seeds of the runs (run r uses seed + r), then one object per estimator.
  nlohmann::json seeds = nlohmann::json::array();
  for (int r = 0; r < command.compare.runs; ++r) seeds.push_back(command.scene.seed + static_cast<std::uint64_t>(r));
  summary.json()["compare"] = {{"runs", command.compare.runs},
                               {"walks_per_patch", command.compare.walk.walks_per_patch},
                               {"kernel", std::string(kernel_name(command.compare.walk.kernel))},
                               {"walk_seeds", seeds}};
  const auto number = [](double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(); };
  for (const auto& s : result.summary) {
    auto& j = summary.json()["estimators"][std::string(method_name(s.method))];
    j["runs"] = s.runs;
    j["walks_total"] = s.walks;
    j["walks_per_estimate"] = s.walks_per_estimate;
    j["steps"] = s.steps;
    j["seconds"] = s.seconds;
    j["mean_abs_z"] = number(s.mean_abs_z);
    j["max_abs_z"] = number(s.max_abs_z);
    j["var_over_theory"] = number(s.var_ratio);
    j["spread_over_se"] = number(s.spread_ratio);
    j["mean_var_per_walk"] = number(s.mean_var);
    j["efficiency"] = number(s.efficiency);
  }
  SceneOptions outputs = command.scene;
  outputs.csv.clear();  // the compare CSV is the long-format table written above
  write_outputs(outputs, patches, fields, summary, metadata);
  return 0;
}

}  // namespace radwalk::app
