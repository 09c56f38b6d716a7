#pragma once
// Atomic file output: content goes to "PATH.tmp-XXXX" in the same directory, then rename()s over PATH, so a
// reader never sees a half-written file and a failed run leaves no truncated output.
#include <functional>
#include <iosfwd>
#include <string>

namespace radwalk {

// Throws InputError "PATH: cannot open for writing (no directory D)" unless the directory PATH would be written in
// exists (an empty path is allowed: no output). Commands call it for every output before computing anything.
void require_output_directory(const std::string& path);

// Calls write(stream) on a temporary file next to `path`, flushes, checks the stream, and renames it to `path`.
// Throws InputError naming the path when the file cannot be created or written.
void write_atomically(const std::string& path, const std::function<void(std::ostream&)>& write);

// For writers that take a file name (VTK): write(tmp_path) must create tmp_path; then it is renamed to `path`.
void write_atomically_via_path(const std::string& path, const std::function<void(const std::string&)>& write);

}  // namespace radwalk
