#include "apps/pipeline.h"

#include <algorithm>
#include <cstdint>
#include "apps/run_metadata.h"
#include "apps/scene_camera.h"
#include "io/paraview_state.h"

#include <cstdio>
#include <filesystem>
#include <fstream>

#include "core/digest.h"
#include "core/error.h"
#include "core/input_file.h"
#include "core/timer.h"
#include "core/parallel.h"
#include "formfactor/form_factor_diagnostics.h"
#include "formfactor/matrix_market.h"
#include "formfactor/reciprocity.h"
#include "io/csv_writer.h"
#include "visibility/embree_visibility.h"
#include "io/vtp_writer.h"
#include "mesh/read_scene.h"
#include "patch/patching.h"

namespace radwalk::app {

void warn(RunSummary& summary, const std::string& message) {
  std::fprintf(stderr, "radwalk: warning: %s\n", message.c_str());
  summary.add_warning(message);
}

namespace {
bool g_quiet = false;
}

void set_quiet(bool quiet) { g_quiet = quiet; }

void note(const std::string& message) {
  if (!g_quiet) std::fprintf(stderr, "radwalk: %s\n", message.c_str());
}

namespace {

// The digest of a file's bytes, read in blocks (a form-factor file may be large); refuses what read_input_file
// refuses (a FIFO, a device).
std::uint64_t file_bytes_digest(const std::string& path) {
  input_file_size(path);
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path + ": cannot open the file");
  Digest d;
  std::vector<char> block(std::size_t{1} << 20);
  while (in) {
    in.read(block.data(), static_cast<std::streamsize>(block.size()));
    d.add(std::string_view(block.data(), static_cast<std::size_t>(in.gcount())));
  }
  if (in.bad()) throw InputError(path + ": read error");
  return d.value();
}

}  // namespace

Mesh load_validated_mesh(const SceneOptions& options, RunSummary& summary) {
  for (const std::string& w : options.warnings) summary.add_warning(w);
  if (!std::filesystem::exists(options.scene)) throw InputError(options.scene + ": no such file");
  Timer timer;
  ReadOptions read;
  read.strict = options.strict;
  // The run id hashes the bytes the readers parse, as they read them (core/input_file.h), then the
  // --form-factors file.
  Digest input_bytes;
  struct ObserverScope {
    ~ObserverScope() { set_input_observer({}); }
  } scope;
  set_input_observer([&input_bytes](const std::string&, const std::string& bytes) { input_bytes.add(bytes); });
  Mesh mesh = load_scene(options.scene, read);
  set_input_observer({});
  if (!options.form_factors_input.empty()) input_bytes.add(file_bytes_digest(options.form_factors_input));
  summary.json()["run_id"] = run_id(options, input_bytes);
  summary.add_timing("load", timer.seconds());
  std::vector<NamedFile> libraries;
  for (const Material& m : mesh.materials)
    if (!m.file.empty()) libraries.push_back({"the scene's material library", m.file});
  const std::string clash = check_distinct_files(options.outputs, libraries);
  if (!clash.empty()) throw InputError(clash);
  for (const std::string& w : mesh.warnings) warn(summary, w);
  summary.json()["scene"] = options.scene;
  summary.json()["seed"] = options.seed;
  summary.json()["threads"] = options.threads;
  summary.json()["strict"] = options.strict;
  summary.json()["faces"] = mesh.face_count();
  summary.json()["materials"] = mesh.materials.size();
  return mesh;
}

PatchSet load_patches(const SceneOptions& options, RunSummary& summary) {
  const Mesh mesh = load_validated_mesh(options, summary);
  Timer timer;
  PatchSet patches = make_patches(mesh, options.max_edge);
  summary.add_timing("patch", timer.seconds());
  summary.json()["max_edge"] = options.max_edge;
  summary.json()["patches"] = patches.size();
  summary.json()["total_area"] = patches.total_area();
  return patches;
}

FormFactors obtain_form_factors(const SceneOptions& scene, const FormFactorCliOptions& options,
                                const PatchSet& patches, RunSummary& summary) {
  FormFactors ff;
  Timer timer;
  if (!options.form_factors.empty()) {
    ff.F = read_matrix_market(options.form_factors, patches.size());
    summary.add_timing("read_form_factors", timer.seconds());
    summary.json()["form_factors_file"] = options.form_factors;
  } else {
    FormFactorOptions o;
    o.rays_per_patch = options.rays;
    o.rays_per_area = options.rays_per_area;
    o.min_rays = options.min_rays;
    o.seed = scene.seed;
    ThreadLimit limit(scene.threads);
    const EmbreeVisibility visibility(patches);
    summary.add_timing("embree_scene", timer.seconds());
    timer.reset();
    ff = estimate_form_factors(patches, visibility, o);
    const double seconds = timer.seconds();
    summary.add_timing("form_factors", seconds);
    std::uint64_t rays = 0, escaped = 0, back = 0;
    for (std::size_t i = 0; i < patches.size(); ++i) {
      rays += ff.rays[i];
      escaped += ff.escaped[i];
      back += ff.back_hits[i];
    }
    const double traced = double(std::max<std::uint64_t>(rays, 1));
    summary.json()["rays"] = rays;
    summary.json()["rays_per_second"] = double(rays) / std::max(seconds, 1e-9);
    summary.json()["escaped_fraction"] = double(escaped) / traced;
    summary.json()["back_hit_fraction"] = double(back) / traced;
    note("form factors: " + std::to_string(rays) + " rays in " + std::to_string(seconds) + " s, " +
         std::to_string(ff.F.nonZeros()) + " non-zeros");
    if (back > 0) {
      std::size_t worst = 0, patches_hit = 0, enclosed = 0;
      for (std::size_t i = 0; i < patches.size(); ++i) {
        patches_hit += ff.back_hits[i] > 0;
        enclosed += ff.back_hits[i] == ff.rays[i];
        if (ff.back_hits[i] > ff.back_hits[worst]) worst = i;
      }
      summary.json()["patches_with_back_hits"] = patches_hit;
      summary.json()["enclosed_patches"] = enclosed;
      warn(summary, std::to_string(patches_hit) + " patches sent rays into the back of a patch (" +
                        std::to_string(enclosed) + " of them entirely: they lie inside a closed object, e.g. " +
                        "floor under a block, and receive no light); elsewhere back hits mean a face is " +
                        "oriented the wrong way. Most from patch " + std::to_string(worst) + " (input face " +
                        std::to_string(patches.face[worst]) + "); see the back_hits field");
    }
  }
  summary.json()["form_factor_nonzeros"] = ff.F.nonZeros();
  if (options.reciprocity) {
    const ReciprocityChange change = enforce_reciprocity(ff.F, patches.area);
    summary.json()["reciprocity_max_relative_change"] = change.max_relative_change;
    summary.json()["reciprocity_mean_relative_change"] = change.mean_relative_change;
    summary.json()["reciprocity_rows_rescaled"] = change.rows_rescaled;
    note("reciprocity enforced: entries changed by " + std::to_string(100 * change.mean_relative_change) +
         " % on average, at most " + std::to_string(100 * change.max_relative_change) + " %; " +
         std::to_string(change.rows_rescaled) + " rows rescaled to keep row sums <= 1");
  }
  return ff;
}

std::vector<CellField> form_factor_fields(const FormFactors& ff, const PatchSet& patches) {
  const FormFactorDiagnostics d = diagnose_form_factors(ff.F, patches.area, ff.rays, ff.back_hits);
  std::vector<CellField> fields = {scalar_field("row_sum", d.row_sum),
                                   scalar_field("reciprocity_error", d.reciprocity_error)};
  if (!ff.rays.empty()) {
    std::vector<double> rays(ff.rays.begin(), ff.rays.end()), escaped(ff.escaped.begin(), ff.escaped.end()),
        back(ff.back_hits.begin(), ff.back_hits.end());
    fields.push_back(scalar_field("rays", rays, FieldKind::count));
    fields.push_back(scalar_field("escaped", escaped, FieldKind::count));
    fields.push_back(scalar_field("back_hits", back, FieldKind::count));
    fields.push_back(scalar_field("row_std_error", d.row_std_error));
  }
  return fields;
}

void write_outputs(const SceneOptions& options, const PatchSet& patches, const std::vector<CellField>& fields,
                   RunSummary& summary, const VtpMetadata& metadata) {
  Timer timer;
  if (!options.vtp.empty()) {
    std::vector<CellField> all = patch_fields(patches);
    all.insert(all.end(), fields.begin(), fields.end());
    VtpMetadata m = run_metadata(options, summary);
    m.merge(metadata);
    write_vtp(options.vtp, patches, all, m);
    note("wrote " + options.vtp);
    if (!options.paraview_state.empty()) {
      const Camera camera = scene_camera(options.scene, patches);
      const ViewPoint view{camera.position, camera_focal_point(camera, patches), camera.up,
                           camera.vfov * 180.0 / kPi};
      write_paraview_state(options.paraview_state, options.vtp, view, run_id_of(summary));
      note("wrote " + options.paraview_state + " (ParaView state: File > Load State)");
    }
  }
  if (!options.csv.empty()) {
    write_patch_csv(options.csv, patches, fields, run_id_of(summary));
    note("wrote " + options.csv);
  }
  summary.add_timing("write", timer.seconds());
  if (!options.json.empty()) {
    summary.write(options.json);
    note("wrote " + options.json);
  }
}

}  // namespace radwalk::app
