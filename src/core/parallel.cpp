#include "core/parallel.h"

#include <tbb/info.h>
#include <tbb/task_arena.h>

#include <string>

#include "core/error.h"

namespace radwalk {

void check_thread_count(long long threads, const char* what) {
  if (threads < 0 || threads > kMaxThreads)
    throw InputError(std::string(what) + " " + std::to_string(threads) + ": expected a whole number from 0 (all cores) to " +
                     std::to_string(kMaxThreads));
}

int active_threads() {
  return static_cast<int>(tbb::global_control::active_value(tbb::global_control::max_allowed_parallelism));
}

}  // namespace radwalk
