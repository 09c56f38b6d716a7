// radwalk check SCENE: validate, report repairs and refusals, exit non-zero on refusal.
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
  std::printf("%s: %zu faces (%zu triangles, %zu quads), %zu vertices, %zu materials, %zu emitting faces: %s\n",
              options.scene.c_str(), mesh.face_count(), mesh.face_count() - quads, quads, mesh.vertices.size(),
              mesh.materials.size(), emitters,
              mesh.warnings.empty() ? "clean" : (std::to_string(mesh.warnings.size()) + " warnings").c_str());
  summary.json()["emitting_faces"] = emitters;
  summary.json()["clean"] = mesh.warnings.empty();
  if (!options.json.empty()) summary.write(options.json);
  return 0;
}

}  // namespace radwalk::app
