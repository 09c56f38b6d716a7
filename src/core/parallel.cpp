#include "core/parallel.h"

#include <tbb/info.h>
#include <tbb/task_arena.h>

namespace radwalk {

int active_threads() {
  return static_cast<int>(tbb::global_control::active_value(tbb::global_control::max_allowed_parallelism));
}

}  // namespace radwalk
