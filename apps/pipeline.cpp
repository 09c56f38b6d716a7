#include "apps/pipeline.h"

#include <algorithm>
#include <cstdint>
#include "apps/rank_agreement.h"
#include "apps/run_metadata.h"
#include "apps/scene_camera.h"
#include "io/paraview_state.h"

#include <cstdio>
#include <exception>
#include <filesystem>
#if defined(__GLIBC__)
#include <malloc.h>  // malloc_trim
#endif
#include <fstream>
#include <map>

#include "apps/closure_option.h"
#include "core/digest.h"
#include "core/distributed.h"
#include "core/error.h"
#include "core/format_number.h"
#include "core/input_file.h"
#include "core/parallel.h"
#include "core/path_length.h"
#include "core/standard_output.h"
#include "core/timer.h"
#include "formfactor/analytic_form_factors.h"
#include "formfactor/emitter_form_factors.h"
#include "formfactor/form_factor_diagnostics.h"
#include "formfactor/form_factor_file.h"
#include "formfactor/form_factor_rows.h"
#include "formfactor/matrix_market.h"
#include "formfactor/reciprocity.h"
#include "io/csv_writer.h"
#include "io/vtp_writer.h"
#include "mesh/length_unit.h"
#include "mesh/material_override.h"
#include "mesh/prepare_mesh.h"
#include "mesh/read_scene.h"
#include "mesh/t_junctions.h"
#include "mesh/validate.h"
#include "patch/contact.h"
#include "patch/patch_scene.h"
#include "patch/patching.h"
#include "visibility/embree_visibility.h"

namespace radwalk::app {

namespace {
bool g_quiet = false;
long g_silenced = 0;
std::FILE* g_report = stdout;
}  // namespace

void warn(RunSummary& summary, const std::string& message) {
  std::fprintf(stderr, "radwalk: warning: %s\n", message.c_str());
  summary.add_warning(message);
}

// A warning about the scene (a finding): not printed with --quiet, only counted.
void warn_scene(RunSummary& summary, const std::string& message) {
  if (g_quiet)
    ++g_silenced;
  else
    std::fprintf(stderr, "radwalk: warning: %s\n", message.c_str());
  summary.add_warning(message);
}

long silenced_warnings() { return g_silenced; }

void set_quiet(bool quiet) { g_quiet = quiet; }

void note(const std::string& message) {
  if (!g_quiet) std::fprintf(stderr, "radwalk: %s\n", message.c_str());
}

std::FILE* report_stream() { return g_report; }

void report_to_stderr_if_stdout_written(const SceneOptions& options) {
  if (is_standard_output(options.csv) || is_standard_output(options.json)) g_report = stderr;
}

namespace {

// What the form-factor stage needs to know about the scene last validated (load_validated_mesh): where each
// input face is (object, group, material) and whether the faces form a closed shell (mesh/t_junctions.h).
struct SceneFacts {
  std::vector<std::string> face_context;  // per input face: " (object 'o', group 'g', material 'm')" or ""
  bool closed_shell = false;
};
SceneFacts g_scene;

// " (object ..., material ...)" of input face f, "" when unknown.
std::string face_context(std::int32_t face) {
  return face >= 0 && static_cast<std::size_t>(face) < g_scene.face_context.size()
             ? g_scene.face_context[static_cast<std::size_t>(face)]
             : std::string();
}

nlohmann::json findings_json(const std::vector<Finding>& findings) {
  nlohmann::json list = nlohmann::json::array();
  for (const Finding& f : findings)
    list.push_back({{"kind", f.kind},
                    {"severity", severity_name(f.severity)},
                    {"file", f.file},
                    {"line", f.line},
                    {"face", f.face},
                    {"object", f.object},
                    {"group", f.group},
                    {"material", f.material},
                    {"message", f.message}});
  return list;
}

// The scene's findings into the summary: the list, and the count of each severity.
void record_findings(const std::vector<Finding>& findings, RunSummary& summary) {
  summary.json()["findings"] = findings_json(findings);
  nlohmann::json counts = {{"error", 0}, {"repair", 0}, {"warning", 0}, {"note", 0}};
  for (const Finding& f : findings) counts[severity_name(f.severity)] = counts[severity_name(f.severity)].get<long>() + 1;
  summary.json()["finding_counts"] = counts;
}

void record_overrides(const SceneOptions& options, const std::vector<MaterialOverride>& overrides,
                      RunSummary& summary) {
  nlohmann::json list = nlohmann::json::array();
  for (const MaterialOverride& o : overrides)
    list.push_back({{"material", o.material}, {"property", o.property}, {"value", {o.value[0], o.value[1], o.value[2]}}});
  summary.json()["material_overrides"] = list;
  summary.json()["rho_scale"] = options.rho_scale;
}

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

// load_validated_mesh on this rank alone, noting in `inputs` every file read and its digest as it is read.
Mesh read_validated_mesh(const SceneOptions& options, RunSummary& summary, RankInputs& inputs) {
  for (const std::string& w : options.warnings) summary.add_warning(w);
  summary.json()["scene"] = options.scene;
  summary.json()["strict"] = options.strict;
  summary.json()["orient"] = options.orient;
  summary.json()["open_shells"] = options.open_shells;
  const LengthUnit unit = length_unit(options);
  summary.json()["units"] = {{"file_unit", options.unit.empty() ? nlohmann::json() : nlohmann::json(options.unit)},
                             {"scale", options.scale},
                             {"length", unit.length()},
                             {"radiosity", unit.radiosity()}};
  std::vector<MaterialOverride> overrides;
  for (const std::string& text : options.set_material) overrides.push_back(parse_material_override(text));
  record_overrides(options, overrides, summary);
  // Every file the readers read (the scene, its material libraries), as they read them: --json may be written on
  // a refusal only if it is none of them (it may be refused for naming one, directly or through a link).
  std::vector<NamedFile> inputs_read;
  const auto json_writable = [&] {
    return !options.json.empty() && check_distinct_files(output_files_of("--json", options.json), inputs_read).empty();
  };
  // A refusal is written to --json too, with every finding (a reading error that stops the reader is one), unless
  // --json itself is refused.
  auto refuse = [&](const std::vector<Finding>& findings, const std::string& message) {
    record_findings(findings, summary);
    summary.json()["refused"] = true;
    summary.json()["error"] = message;
    if (json_writable()) summary.write(options.json);
  };
  require_path_length(options.scene);
  std::error_code missing;
  if (!std::filesystem::exists(options.scene, missing)) {
    const std::string message = options.scene + ": no such file";
    Finding f;
    f.kind = "no such file";
    f.severity = Severity::error;
    f.file = options.scene;
    f.message = "no such file";
    refuse({f}, message);
    throw InputError(message);
  }
  Timer timer;
  ReadOptions read;
  read.strict = options.strict;
  Mesh mesh;
  try {
    // The run id hashes the bytes the readers parse, as they read them (core/input_file.h), then the
    // --form-factors file.
    Digest input_bytes;
    struct ObserverScope {
      ~ObserverScope() { set_input_observer({}); }
    } scope;
    set_input_observer([&input_bytes, &inputs_read, &inputs](const std::string& path, const std::string& bytes) {
      input_bytes.add(bytes);
      inputs_read.push_back({"an input read", path});
      if (distributed::size() > 1) {  // only the ranks of an MPI run compare their files (agree_on_inputs)
        Digest file;
        file.add(bytes);
        inputs.files.push_back({path, file.value()});
      }
    });
    mesh = read_scene(options.scene, read);
    set_input_observer({});
    if (!options.form_factors_input.empty()) {
      const std::uint64_t digest = file_bytes_digest(options.form_factors_input);
      input_bytes.add(digest);
      inputs.files.push_back({options.form_factors_input, digest});
    }
    summary.json()["run_id"] = run_id(options, input_bytes);
    std::vector<NamedFile> libraries;
    for (const Material& m : mesh.materials)
      if (!m.file.empty()) libraries.push_back({"the scene's material library", m.file});
    const std::string clash = check_distinct_files(options.outputs, libraries);
    if (!clash.empty()) throw InputError(clash);
    MeshPreparation preparation;
    preparation.scale = options.scale;
    preparation.overrides = overrides;
    preparation.rho_scale = options.rho_scale;
    preparation.tolerances.strict = options.strict;
    preparation.tolerances.orient = parse_orient_mode(options.orient);
    preparation.tolerances.orient_given = options.orient_given;
    preparation.tolerances.open_shells = parse_open_shell_sides(options.open_shells);
    prepare_mesh(mesh, preparation);
  } catch (const MeshRefused& e) {
    // Every finding, grouped by kind: the warnings (unless --quiet), then the errors, then one summary line.
    const std::vector<Finding>& all = e.findings();
    for (const std::string& w : validation_lines(all, 10)) warn_scene(summary, w);
    for (const std::string& n : validation_notes(all, 10)) note("note: " + n);
    // One error is its own one-line refusal; several are listed, then counted in one line.
    const std::vector<std::string> errors = grouped_lines(all, {Severity::error}, 10);
    std::string message = e.what();
    if (errors.size() > 1) {
      for (const std::string& line : errors) std::fprintf(stderr, "radwalk: error: %s\n", line.c_str());
      message = options.scene + ": refused: " + count_by_kind(all, Severity::error) +
                (options.strict ? " (--strict)" : "") + "; every finding is listed above" +
                (json_writable() ? " and in " + output_display_name(options.json) : "");
    }
    refuse(all, message);
    throw InputError(message);
  } catch (const InputError& e) {
    Finding f;
    f.kind = "reading error";
    f.severity = Severity::error;
    f.file = options.scene;
    f.message = e.what();
    refuse({f}, e.what());
    throw;
  }
  g_scene = SceneFacts{};
  for (std::size_t f = 0; f < mesh.face_count(); ++f) {
    const auto source = static_cast<std::size_t>(mesh.source_face(f));
    if (g_scene.face_context.size() <= source) g_scene.face_context.resize(source + 1);
    g_scene.face_context[source] = mesh.context(f);
  }
  g_scene.closed_shell = is_closed_shell(mesh);
  summary.json()["closed_shell"] = g_scene.closed_shell;
  summary.add_timing("load", timer.seconds());
  for (const std::string& w : mesh.warnings) warn_scene(summary, w);
  for (const std::string& n : validation_notes(mesh.findings, 10)) note("note: " + n);
  record_findings(mesh.findings, summary);
  summary.json()["seed"] = options.seed;
  summary.json()["threads"] = options.threads;
  summary.json()["faces"] = mesh.face_count();
  summary.json()["materials"] = mesh.materials.size();
  return mesh;
}

}  // namespace

LengthUnit length_unit(const SceneOptions& options) { return checked_length_unit(options.unit, options.scale); }

Mesh load_validated_mesh(const SceneOptions& options, RunSummary& summary) {
  // Every rank reads and validates its own copy of the inputs, then the ranks compare what they read
  // (apps/rank_agreement.h), also when a rank refused them: a rank that lacks a file or read other bytes is named
  // by every rank at once instead of leaving the others in the next collective or mixing two scenes.
  RankInputs inputs;
  Mesh mesh;
  std::exception_ptr refused;
  try {
    mesh = read_validated_mesh(options, summary, inputs);
  } catch (const InputError& e) {
    inputs.refusal = e.what();
    refused = std::current_exception();
  }
  agree_on_inputs(inputs);
  if (refused) std::rethrow_exception(refused);
  return mesh;
}

// Objects standing on faces (patch/contact.h), as patch_scene found them: noted, and whether the supporting faces
// were cut along the footprints (with --contact-cut when the faces are split).
void note_contacts(const SceneOptions& options, const PatchedScene& scene, RunSummary& summary) {
  const std::vector<Contact>& contacts = scene.contacts;
  summary.json()["contacts"] = contacts.size();
  summary.json()["contact_cut"] = scene.cut;
  summary.json()["contact_faces_cut"] = scene.contact_faces_cut;
  if (contacts.empty()) return;
  for (std::size_t c = 0; c < contacts.size() && c < 10; ++c)
    note("contact: " + scene.contact_lines[c]);
  if (contacts.size() > 10) note("contact: " + std::to_string(contacts.size() - 10) + " more");
  const bool splitting = options.max_edge > 0 || options.max_area > 0 || options.splits_later;
  note(std::to_string(contacts.size()) + (contacts.size() == 1 ? " object stands" : " objects stand") +
       " on faces of the scene: " +
       (scene.cut ? "the supporting faces are cut along the footprints (" + std::to_string(scene.contact_faces_cut) +
                        " faces cut), so no patch mixes the lit floor with the part hidden underneath"
        : splitting ? std::string("not cut (--no-contact-cut), so a patch may average the lit floor with the "
                                  "part hidden underneath")
                    : std::string("not cut, since the input faces are kept as patches (they are cut along the "
                                  "footprints when --max-edge or --max-area splits them)")));
}

PatchSet load_patches(const SceneOptions& options, RunSummary& summary) {
  Mesh mesh;
  return load_patches(options, summary, mesh);
}

PatchSet load_patches(const SceneOptions& options, RunSummary& summary, Mesh& mesh,
                      std::vector<ContactRegion>* regions) {
  ScenePatchingOptions patching;
  patching.split.max_edge = options.max_edge;
  patching.split.max_area = options.max_area;
  patching.contact_cut = options.contact_cut;
  patching.splits_later = options.splits_later;
  patching.two_sided = options.two_sided;
  PatchedScene scene = patch_scene(load_validated_mesh(options, summary), patching);
  note_contacts(options, scene, summary);
  summary.add_timing("contacts", scene.contacts_seconds);
  summary.add_timing("patch", scene.patch_seconds);
  const PatchSet& patches = scene.patches;
  summary.json()["max_edge"] = options.max_edge;
  summary.json()["max_area"] = options.max_area;
  summary.json()["patches"] = patches.size();
  if (options.two_sided) summary.json()["two_sided"] = true;
  if (scene.back_patches > 0) summary.json()["back_patches"] = scene.back_patches;
  summary.json()["total_area"] = patches.total_area();
  const PatchAreaDistribution areas = patch_area_distribution(patches);
  summary.json()["patch_area"] = {{"count", areas.count}, {"min", areas.min}, {"median", areas.median},
                                  {"max", areas.max}};
  char line[160];
  std::snprintf(line, sizeof line, "%zu patches from %zu faces, patch area min %.4g, median %.4g, max %.4g",
                areas.count, scene.mesh.face_count(), areas.min, areas.median, areas.max);
  const std::string unit = length_unit(options).length();
  note(std::string(line) + " (" + (unit.find(' ') != std::string::npos ? "(" + unit + ")" : unit) + "^2)");
  mesh = std::move(scene.mesh);
  if (regions) *regions = std::move(scene.contact_regions);
  return std::move(scene.patches);
}

namespace {

// Rays that escaped a closed scene went through a gap (a crack between faces that do not share their edges, a
// face missing from the room) or started inside a closed object: a warning naming the patches and the groups
// (object, group, material) they come from, most first; escaped_by_group in the JSON.
// "16.7 %".
std::string percent(double fraction) {
  return format_number(100 * fraction, 3) + " %";
}

void warn_escaped_rays(const FormFactors& ff, const PatchSet& patches, std::uint64_t escaped, std::uint64_t rays,
                       std::uint64_t back, RunSummary& summary) {
  std::map<std::string, std::uint64_t> by_group;
  std::size_t worst = 0, sources = 0;
  for (std::size_t i = 0; i < patches.size(); ++i) {
    if (ff.escaped[i] == 0) continue;
    ++sources;
    std::string where = face_context(patches.face[i]);
    by_group[where.empty() ? "(no object, group or material)" : where.substr(2, where.size() - 3)] += ff.escaped[i];
    if (ff.escaped[i] > ff.escaped[worst]) worst = i;
  }
  std::vector<std::pair<std::string, std::uint64_t>> groups(by_group.begin(), by_group.end());
  std::stable_sort(groups.begin(), groups.end(), [](const auto& a, const auto& b) { return a.second > b.second; });
  nlohmann::json list = nlohmann::json::array();
  std::string named;
  for (std::size_t k = 0; k < groups.size(); ++k) {
    list.push_back({{"where", groups[k].first}, {"escaped", groups[k].second}});
    if (k < 3) named += (k ? "; " : "") + groups[k].first + ": " + std::to_string(groups[k].second);
  }
  // Of them, the rays from patches lying on a plane of the bounding box and facing out of it: an object's bottom
  // on the room's floor, a back against its wall. No light reaches such a patch, so their escape loses none.
  Vec3 lo = patches.points.empty() ? Vec3::Zero() : patches.points[0], hi = lo;
  for (const Vec3& q : patches.points) {
    lo = lo.cwiseMin(q);
    hi = hi.cwiseMax(q);
  }
  const double tol = 1e-9 * (hi - lo).norm();
  std::uint64_t hidden = 0;
  for (std::size_t i = 0; i < patches.size(); ++i) {
    bool out = false;
    for (int a = 0; a < 3; ++a)
      out = out || (std::abs(patches.centroid[i][a] - lo[a]) <= tol && patches.normal[i][a] < -0.999) ||
            (std::abs(patches.centroid[i][a] - hi[a]) <= tol && patches.normal[i][a] > 0.999);
    if (out) hidden += ff.escaped[i];
  }
  summary.json()["escaped_by_group"] = list;
  summary.json()["patches_with_escaped_rays"] = sources;
  summary.json()["escaped_from_hidden_faces"] = hidden;
  // Faces facing out of the room are harmless only when the light stays in: with many back hits the room itself
  // may face out (inside out), and the light is lost into the backs of its walls.
  const bool backs = back > rays / 100;
  const std::string harmless =
      backs && hidden > 0
          ? " " + std::to_string(hidden) + " of them left faces lying on the room's floor or walls and facing out of "
            "it; that is harmless only if no light reaches them, but " + std::to_string(back) + " rays (" +
            percent(double(back) / double(std::max<std::uint64_t>(rays, 1))) +
            ") hit the backs of faces: the room may be inside out (its faces pointing outwards) and the light lost "
            "into their backs (--orient outward turns it; see power_balance)."
      : hidden == escaped ? " All of them left faces lying on the room's floor or walls and facing out of it (an "
                          "object's bottom on the floor, a back against a wall), which no light reaches: harmless."
      : hidden > 0 ? " " + std::to_string(hidden) + " of them left faces lying on the room's floor or walls and "
                     "facing out of it (an object's bottom on the floor, a back against a wall), which no light "
                     "reaches: harmless."
                   : std::string();
  warn(summary, std::to_string(escaped) + " of " + std::to_string(rays) + " rays (" +
                    percent(double(escaped) / double(std::max<std::uint64_t>(rays, 1))) +
                    ") escaped although the scene's faces form a closed shell: they left " +
                    std::to_string(sources) + " patch(es) through a gap, from a face oriented outwards or from "
                    "inside a closed object, and their light is lost. Most from patch " + std::to_string(worst) + " (input face " +
                    std::to_string(patches.face[worst]) + face_context(patches.face[worst]) + "); by group: " +
                    named + (groups.size() > 3 ? "; ..." : "") + " (escaped_by_group in --json, the escaped field)." +
                    harmless);
}

}  // namespace

namespace {

// The cosine-ray and analytic options of the command line.
FormFactorOptions ray_options(const SceneOptions& scene, const FormFactorCliOptions& options) {
  FormFactorOptions o;
  o.rays_per_patch = options.rays;
  o.rays_per_area = options.rays_per_area;
  o.min_rays = options.min_rays;
  o.seed = scene.seed;
  o.sobol = options.sobol_rays;
  return o;
}

AnalyticFormFactorOptions analytic_options(const SceneOptions& scene, const FormFactorCliOptions& options) {
  AnalyticFormFactorOptions a;
  a.seed = scene.seed;
  a.max_visibility_samples = options.visibility_samples;
  a.cutoff = options.analytic_cutoff;
  a.cutoff_rays = options.analytic_cutoff_rays;
  return a;
}

}  // namespace

FormFactors trace_form_factors(const SceneOptions& scene, const FormFactorCliOptions& options, const PatchSet& patches) {
  ThreadLimit limit(scene.threads);
  const EmbreeVisibility visibility(patches);
  FormFactors ff;
  if (options.analytic) {
    ff = analytic_form_factors(patches, visibility, analytic_options(scene, options)).form_factors;
  } else {
    ff = estimate_form_factors_with_emitters(patches, visibility, ray_options(scene, options), options.emitter_samples);
  }
  if (options.reciprocity) enforce_reciprocity(ff.F, patches.area);
  return ff;
}

FormFactors obtain_form_factors(const SceneOptions& scene, const FormFactorCliOptions& options,
                                const PatchSet& patches, RunSummary& summary, RowsHeld held) {
  FormFactors ff;
  Timer timer;
  // Over MPI with RowsHeld::own_rows each rank keeps only its block of rows (formfactor/form_factor_rows.h).
  const bool own_rows = held == RowsHeld::own_rows;
  if (!options.form_factors.empty()) {
    // .npz (read in pieces) or .mtx; a refusal that one rank finds in its own rows is every rank's.
    distributed::agree_on_input_error([&] {
      ff.F = read_form_factors(options.form_factors, patches.size(), own_rows ? &ff.row_blocks : nullptr);
    });
    summary.add_timing("read_form_factors", timer.seconds());
    summary.json()["form_factors_file"] = options.form_factors;
    // Rows above 1 beyond rounding (another program's integration error, up to the readers' 1e-3): normalised on
    // request, otherwise named in a warning (each rank checks the rows it holds).
    if (options.normalise_rows) {
      const std::size_t divided = normalise_rows(ff.F);
      summary.json()["rows_normalised"] = divided;
      if (divided > 0) note("form factors: " + std::to_string(divided) + " rows summing above 1 divided by their sums");
    } else {
      const RowsAboveOne above = rows_above_one(ff.F, kRoundingRowSum);
      if (above.count > 0)
        warn(summary, std::to_string(above.count) + " rows of " + options.form_factors +
                          " sum above 1 + 1e-6 (more than rounding), the largest row " + std::to_string(above.worst) +
                          " (0-based) at " + std::to_string(above.worst_sum) +
                          "; used as read (--normalise-rows divides them by their sums)");
    }
  } else if (options.analytic) {
    // Every rank computes the whole F (formfactor/analytic_form_factors.h); row_blocks stay empty.
    ThreadLimit limit(scene.threads);
    const EmbreeVisibility visibility(patches);
    summary.add_timing("embree_scene", timer.seconds());
    timer.reset();
    AnalyticFormFactors a = analytic_form_factors(patches, visibility, analytic_options(scene, options));
    const double seconds = timer.seconds();
    summary.add_timing("form_factors", seconds);
    double worst_se = 0;
    std::size_t worst = 0;
    for (std::size_t i = 0; i < a.form_factors.row_std_error.size(); ++i)
      if (a.form_factors.row_std_error[i] > worst_se) worst_se = a.form_factors.row_std_error[i], worst = i;
    nlohmann::json& j = summary.json()["analytic"];
    j["pairs"] = a.pairs;
    j["clear_pairs"] = a.clear_pairs;
    j["hidden_pairs"] = a.hidden_pairs;
    j["sampled_pairs"] = a.sampled_pairs;
    j["visibility_rays"] = a.visibility_rays;
    j["rows_scaled"] = a.rows_scaled;
    j["largest_row_std_error"] = worst_se;
    // The cut-off's dropped pairs, never silent: per row an upper bound on their sum and its one-point estimate.
    std::size_t worst_cut = 0;
    double cut_total = 0;
    for (std::size_t i = 0; i < a.cutoff_bound.size(); ++i) {
      if (a.cutoff_bound[i] > a.cutoff_bound[worst_cut]) worst_cut = i;
      cut_total += patches.area[i] * a.cutoff_estimate[i];
    }
    j["cutoff"] = a.cutoff;
    j["dropped_pairs"] = a.dropped_pairs;
    j["largest_cutoff_bound"] = a.cutoff_bound.empty() ? 0.0 : a.cutoff_bound[worst_cut];
    j["largest_cutoff_bound_patch"] = worst_cut;
    j["largest_cutoff_estimate"] =
        a.cutoff_estimate.empty() ? 0.0 : *std::max_element(a.cutoff_estimate.begin(), a.cutoff_estimate.end());
    j["cutoff_estimate_area_weighted"] = patches.total_area() > 0 ? cut_total / patches.total_area() : 0.0;
    j["cutoff_rays"] = a.cutoff_rays;
    j["completed_pairs"] = a.completed_pairs;
    if (a.cutoff > 0)
      note("form factors (analytic): cut-off " + std::to_string(a.cutoff) + ": " + std::to_string(a.dropped_pairs) +
           " pairs dropped; a row's dropped sum is at most " + std::to_string(j["largest_cutoff_bound"].get<double>()) +
           " (patch " + std::to_string(worst_cut) + "), estimated at " +
           std::to_string(j["cutoff_estimate_area_weighted"].get<double>()) + " on average over the area" +
           (a.cutoff_rays > 0 ? "; " + std::to_string(a.completed_pairs) + " of them estimated by " +
                                    std::to_string(a.cutoff_rays) + " cosine rays"
                              : std::string()));
    note("form factors (analytic): " + std::to_string(a.pairs) + " facing pairs (" + std::to_string(a.clear_pairs) +
         " proven clear, " + std::to_string(a.hidden_pairs) + " proven hidden, " + std::to_string(a.sampled_pairs) +
         " sampled with " + std::to_string(a.visibility_rays) + " rays) in " + std::to_string(seconds) +
         " s; largest row standard error " + std::to_string(worst_se) + " (patch " + std::to_string(worst) + ")");
    if (a.rows_scaled > 0)
      warn(summary, std::to_string(a.rows_scaled) + " form-factor rows summed above 1 (by at most " +
                        std::to_string(a.largest_row_excess) +
                        ") from visibility estimates and were scaled down to 1, keeping reciprocity");
    ff = std::move(a.form_factors);
  } else {
    const FormFactorOptions o = ray_options(scene, options);
    ThreadLimit limit(scene.threads);
    const EmbreeVisibility visibility(patches);
    summary.add_timing("embree_scene", timer.seconds());
    timer.reset();
    const EmitterSampleChoice emitter = choose_emitter_samples(patches, o, options.emitter_samples);
    ff = own_rows ? estimate_form_factor_rows(patches, visibility, o) : estimate_form_factors(patches, visibility, o);
    summary.json()["emitter_samples"] = emitter.samples;
    summary.json()["emitter_samples_choice"] = emitter.reason;
    if (emitter.samples > 0) {
      EmitterFormFactors ef = replace_emitter_columns(std::move(ff), patches, visibility, emitter.samples);
      long shadow_rays = 0;  // over the ranks' rows (each traced its own)
      for (long r : distributed::allgather_concat(std::vector<long>{ef.shadow_rays})) shadow_rays += r;
      summary.json()["emitter_columns"] = ef.emitter_columns;
      summary.json()["emitter_shadow_rays"] = shadow_rays;
      note("form factors: " + std::to_string(ef.emitter_columns) + " emitter columns from " +
           std::to_string(shadow_rays) + " shadow rays (" + std::to_string(emitter.samples) + " a patch, " +
           emitter.reason + ")");
      ff = std::move(ef.form_factors);
    } else if (options.emitter_samples == kAutoEmitterSamples) {
      note("form factors: no emitter columns (" + emitter.reason + ")");
    }
    const double seconds = timer.seconds();
    summary.add_timing("form_factors", seconds);
    std::uint64_t rays = 0, escaped = 0, back = 0;
    for (std::size_t i = 0; i < patches.size(); ++i) {
      rays += ff.rays[i];
      escaped += ff.escaped[i];
      back += ff.back_hits[i];
    }
    const double traced = double(std::max<std::uint64_t>(rays, 1));
    summary.json()["rays_total"] = rays;
    if (options.rays_per_area <= 0) summary.json()["rays_per_patch"] = options.rays;
    summary.json()["rays_per_second"] = double(rays) / std::max(seconds, 1e-9);
    summary.json()["escaped_fraction"] = double(escaped) / traced;
    summary.json()["back_hit_fraction"] = double(back) / traced;
    note("form factors: " + std::to_string(rays) + " rays in " + std::to_string(seconds) + " s, " +
         std::to_string(total_nonzeros(ff.F, ff.row_blocks)) + " non-zeros");
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
                        std::to_string(patches.face[worst]) + face_context(patches.face[worst]) +
                        "); see the back_hits field");
    }
    if (escaped > 0 && g_scene.closed_shell) warn_escaped_rays(ff, patches, escaped, rays, back, summary);
  }
  summary.json()["form_factor_nonzeros"] = total_nonzeros(ff.F, ff.row_blocks);
  if (options.reciprocity) {
    // Averaging A_i F_ij with A_j F_ji needs the other rows: over MPI the whole F is gathered, then each rank
    // keeps its rows again.
    const RowBlocks blocks = ff.row_blocks;
    gather_whole_rows(ff.F, ff.row_blocks);
    const ReciprocityChange change = enforce_reciprocity(ff.F, patches.area);
    if (holds_own_rows_only(blocks)) {
      ff.F = keep_rows(ff.F, blocks[static_cast<std::size_t>(distributed::rank())]);
      ff.row_blocks = blocks;
    }
    summary.json()["reciprocity_max_relative_change"] = change.max_relative_change;
    summary.json()["reciprocity_mean_relative_change"] = change.mean_relative_change;
    summary.json()["reciprocity_rows_rescaled"] = change.rows_rescaled;
    note("reciprocity enforced: entries changed by " + std::to_string(100 * change.mean_relative_change) +
         " % on average, at most " + std::to_string(100 * change.max_relative_change) + " %; " +
         std::to_string(change.rows_rescaled) + " rows rescaled to keep row sums <= 1");
  }
  if (options.enforce_closure) {
    // The adjustment couples all rows: over MPI the whole F is gathered, then each rank keeps its rows again.
    const RowBlocks blocks = ff.row_blocks;
    gather_whole_rows(ff.F, ff.row_blocks);
    apply_closure(ff, patches, summary, options.form_factors.empty() ? "the form factors" : options.form_factors);
    if (holds_own_rows_only(blocks)) {
      ff.F = keep_rows(ff.F, blocks[static_cast<std::size_t>(distributed::rank())]);
      ff.row_blocks = blocks;
    }
  }
  if (distributed::size() > 1)  // what each rank holds (docs/json-schema.md)
    summary.json()["mpi"]["form_factor_nonzeros_by_rank"] = nonzeros_by_rank(ff.F);
  return ff;
}

std::vector<CellField> form_factor_fields(const FormFactors& ff, const PatchSet& patches, const SparseF* gathered) {
  // The reciprocity error needs F_ji: with a row-distributed F rank 0 gathers the whole F (unless the caller
  // already did), computes the diagnostics alone and sends them to the other ranks (O(N) each).
  SparseF storage;
  const SparseF& F = gathered ? *gathered : gather_rows_to_root(ff.F, ff.row_blocks, storage);
  const bool rows_only = holds_own_rows_only(ff.row_blocks);
  FormFactorDiagnostics d;
  if (!rows_only || distributed::is_root()) d = diagnose_form_factors(F, patches.area, ff.rays, ff.back_hits);
  if (rows_only)
    for (std::vector<double>* v : {&d.row_sum, &d.back_hit_fraction, &d.reciprocity_error, &d.row_std_error})
      distributed::broadcast(*v);
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
  if (!ff.closure_max_change.empty()) {  // --enforce-closure: how much each row was adjusted
    fields.push_back(scalar_field("closure_max_change", ff.closure_max_change));
    fields.push_back(scalar_field("closure_rms_change", ff.closure_rms_change));
  }
  if (!ff.row_std_error.empty())  // the analytic route: each row sum's standard error from its visibility estimates
    fields.push_back(scalar_field("row_std_error", ff.row_std_error));
  return fields;
}

void write_outputs(const SceneOptions& options, const PatchSet& patches, const std::vector<CellField>& fields,
                   RunSummary& summary, const VtpMetadata& metadata) {
  Timer timer;
  if (!options.vtp.empty()) {
    // Memory (docs/scaling.md, "Ten million patches"): what the solve freed goes back to the system first; the
    // display mesh is built before the patch description is allocated (its edge table is the writer's peak); the
    // command's fields go by pointer, not copied (at 10^7 patches a copy of B, B_se and B_var is 0.7 GB); the
    // description is freed once the file is written.
#if defined(__GLIBC__)
    malloc_trim(0);
#endif
    const DisplayMesh mesh = make_display_mesh(patches);
#if defined(__GLIBC__)
    malloc_trim(0);  // the display mesh's build leaves millions of small freed blocks
#endif
    const std::vector<CellField> description = patch_fields(patches);
    std::vector<const CellField*> all;
    for (const CellField& f : description) all.push_back(&f);
    for (const CellField& f : fields) all.push_back(&f);
    VtpMetadata m = run_metadata(options, summary);
    m.merge(metadata);
    write_vtp_fields(options.vtp, patches, all, m, &mesh);
    note("wrote " + options.vtp);
    if (!options.paraview_state.empty()) {
      StateColouring colouring;
      for (const CellField& f : fields)
        if (f.name == "B" && f.components == 3) colouring = radiosity_colouring(patches, f.values);
        else if (f.name == "q" && f.components == 1) colouring = heat_flux_colouring(f.values);  // exchange
      const ViewPoint view = view_point(scene_camera(options.scene, patches), patches);  // pathtrace's camera
      write_paraview_state(options.paraview_state, options.vtp, view, colouring, run_id_of(summary));
      note("wrote " + options.paraview_state + " (ParaView state: File > Load State)");
    }
  }
  if (!options.csv.empty()) {
    write_patch_csv(options.csv, patches, fields, run_id_of(summary));
    note("wrote " + output_display_name(options.csv));
  }
  summary.add_timing("write", timer.seconds());
  if (distributed::size() > 1) {  // over MPI only (docs/json-schema.md): rank 0's traffic, gathers of the whole F
    nlohmann::json& mpi = summary.json()["mpi"];
    mpi["ranks"] = distributed::size();
    mpi["rank0_bytes_received"] = distributed::bytes_received();
    mpi["whole_form_factor_gathers"] = whole_row_gathers();
  }
  if (!options.json.empty()) {
    summary.write(options.json);
    note("wrote " + output_display_name(options.json));
  }
}

}  // namespace radwalk::app
