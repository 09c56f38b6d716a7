#include "core/atomic_write.h"

#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>

#include "core/error.h"

namespace radwalk {
namespace {

std::string temporary_name(const std::string& path) {
  return path + ".tmp-" + std::to_string(::getpid());
}

void publish(const std::string& tmp, const std::string& path) {
  std::error_code ec;
  std::filesystem::rename(tmp, path, ec);
  if (ec) {
    std::filesystem::remove(tmp, ec);
    throw InputError(path + ": cannot write output: rename failed");
  }
}

}  // namespace

void require_output_directory(const std::string& path) {
  if (path.empty()) return;
  const std::filesystem::path parent = std::filesystem::path(path).parent_path();
  const std::filesystem::path dir = parent.empty() ? std::filesystem::path(".") : parent;
  std::error_code ec;
  if (!std::filesystem::is_directory(dir, ec))
    throw InputError(path + ": cannot open for writing (no directory " + dir.string() + ")");
}

void write_atomically(const std::string& path, const std::function<void(std::ostream&)>& write) {
  require_output_directory(path);
  const std::string tmp = temporary_name(path);
  {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    if (!out) throw InputError(path + ": cannot open for writing");
    try {
      write(out);
    } catch (...) {
      out.close();
      std::remove(tmp.c_str());
      throw;
    }
    out.flush();
    if (!out) {
      out.close();
      std::remove(tmp.c_str());
      throw InputError(path + ": write failed (disk full?)");
    }
  }
  publish(tmp, path);
}

void write_atomically_via_path(const std::string& path,
                               const std::function<void(const std::string&)>& write) {
  // Keep the extension last: some writers (VTK) care about it.
  const std::filesystem::path p(path);
  require_output_directory(path);  // in one line, before the writer (VTK logs its own failures at length)
  const std::string tmp =
      (p.parent_path() / (".tmp-" + std::to_string(::getpid()) + "-" + p.filename().string())).string();
  try {
    write(tmp);
  } catch (...) {
    std::remove(tmp.c_str());
    throw;
  }
  if (!std::filesystem::exists(tmp)) throw InputError(path + ": cannot write output");
  publish(tmp, path);
}

}  // namespace radwalk
