#include "fuzz_scratch.h"

#include <unistd.h>

#include <cstdlib>
#include <system_error>

namespace radwalk::fuzz {

const std::filesystem::path& scratch_directory(const std::string& harness) {
  static const std::filesystem::path dir = [&harness] {
    namespace fs = std::filesystem;
    const char* tmpdir = std::getenv("TMPDIR");
    const fs::path base = tmpdir && *tmpdir              ? fs::path(tmpdir)
                          : fs::is_directory("/dev/shm") ? "/dev/shm"
                                                         : "/tmp";
    fs::path d = base / ("radwalk-fuzz-" + harness + "-" + std::to_string(::getpid()));
    fs::create_directories(d);
    std::atexit([] {
      std::error_code ignored;
      fs::remove_all(scratch_directory(""), ignored);
    });
    return d;
  }();
  return dir;
}

}  // namespace radwalk::fuzz
