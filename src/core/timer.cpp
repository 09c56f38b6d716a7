#include "core/timer.h"

#include <sys/resource.h>

namespace radwalk {

long peak_memory_bytes() {
  rusage usage{};
  if (getrusage(RUSAGE_SELF, &usage) != 0) return 0;
  return usage.ru_maxrss * 1024L;  // Linux reports kilobytes
}

}  // namespace radwalk
