// radwalk patch SCENE --max-edge L -o OUT.vtp|OUT.obj: validate, split into patches, write them.
#include <cstdio>
#include <filesystem>

#include "apps/options.h"
#include "apps/pipeline.h"
#include "apps/run_metadata.h"
#include "core/timer.h"
#include "io/obj_writer.h"

namespace radwalk::app {

int run_patch(const PatchCommand& command) {
  // The name ends in .vtp or .obj (checked with the command line: apps/output_files.h).
  const std::string ext = std::filesystem::path(command.output).extension().string();
  RunSummary summary("patch", command.scene.argv);
  const PatchSet patches = load_patches(command.scene, summary);
  std::fprintf(report_stream(), "%s: %zu faces -> %zu patches (max edge %g), total area %.6g\n", command.scene.scene.c_str(),
              static_cast<std::size_t>(summary.json()["faces"]), patches.size(), command.scene.max_edge,
              patches.total_area());
  SceneOptions outputs = command.scene;
  if (ext == ".vtp") {
    outputs.vtp = command.output;
  } else {
    Timer timer;
    write_obj(command.output, patches, run_id_of(summary));
    summary.add_timing("write_obj", timer.seconds());
    note("wrote " + command.output);
  }
  write_outputs(outputs, patches, {}, summary);
  return 0;
}

}  // namespace radwalk::app
