// radwalk check SCENE: validate, report every repair, warning, note and refusal (grouped by kind: the pipeline's
// load_validated_mesh), exit 2 on refusal once the whole scene was checked. --json lists every finding, also on
// refusal.
#include <cstdio>

#include "apps/options.h"
#include "apps/pipeline.h"

namespace radwalk::app {

int run_check(const SceneOptions& options) {
  RunSummary summary("check", options.argv);
  const Mesh mesh = load_validated_mesh(options, summary);
  std::size_t quads = 0, emitters = 0;
  for (std::size_t f = 0; f < mesh.face_count(); ++f) {
    quads += mesh.is_quad(f);
    emitters += (mesh.materials[mesh.face_material[f]].Ke > 0).any();
  }
  // "clean", or the count of each severity found ("3 repairs, 2 warnings, 1 note"): printed with --quiet too.
  std::string found;
  for (const Severity s : {Severity::repair, Severity::warning, Severity::note}) {
    long n = 0;
    for (const Finding& f : mesh.findings) n += f.severity == s;
    if (n > 0) found += (found.empty() ? "" : ", ") + std::to_string(n) + " " + severity_name(s) + (n == 1 ? "" : "s");
  }
  // Clean: nothing repaired and nothing to worry about (notes are harmless: T-junctions, open shells).
  bool clean = true;
  for (const Finding& f : mesh.findings) clean = clean && f.severity == Severity::note;
  const std::string verdict = clean ? (found.empty() ? "clean" : "clean (" + found + ")") : found;
  std::fprintf(report_stream(), "%s: %zu faces (%zu triangles, %zu quads), %zu vertices, %zu materials, %zu emitting faces: %s\n",
              options.scene.c_str(), mesh.face_count(), mesh.face_count() - quads, quads, mesh.vertices.size(),
              mesh.materials.size(), emitters, verdict.c_str());
  const LengthUnit unit = length_unit(options);
  std::fprintf(report_stream(), "lengths in %s, radiosity B in %s\n", unit.length().c_str(), unit.radiosity().c_str());
  summary.json()["emitting_faces"] = emitters;
  summary.json()["clean"] = clean;
  summary.json()["refused"] = false;
  if (!options.json.empty()) summary.write(options.json);
  return 0;
}

}  // namespace radwalk::app
