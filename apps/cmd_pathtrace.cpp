// radwalk pathtrace SCENE --spp N [--csv] [-o] [--image out.png|exr]: the continuous reference.
#include "apps/options.h"
#include "apps/pipeline.h"
#include "core/error.h"

namespace radwalk::app {

int run_pathtrace(const PathtraceCommand&) {
  throw InputError("pathtrace: not available yet in this build");
}

}  // namespace radwalk::app
