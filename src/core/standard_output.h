#pragma once
// "-" as an output's name: the output goes to standard output (the Unix convention for pipelines:
// `radwalk solve scene.obj --csv - | python3 plot.py`).
//
// Standard output is a stream, not a file: it is written as it goes, not atomically (a reader of a pipe sees the
// rows as they come; there is no temporary to rename). What is kept is that a failed write never passes silently:
//   - every write is checked; a failure (EPIPE: the reader closed the pipe before the end, as `| head` does;
//     ENOSPC: a full disk or /dev/full; EIO, EFBIG, ...) throws InputError "standard output: write failed (...)",
//     which the program prints as one line on stderr with exit code 2;
//   - SIGPIPE: before the first write the signal is set to ignored (unless a handler is installed), so a closed pipe
//     is the write error EPIPE above instead of a silent death by the signal; what the reader received before it
//     closed the pipe is a prefix of the output, and the exit code says it is incomplete.
// Over MPI (core/distributed.h) only rank 0 writes; the other ranks call `write` on a stream that discards.
#include <functional>
#include <iosfwd>
#include <string>

namespace radwalk {

// The name that means standard output.
inline constexpr const char* kStandardOutputName = "-";

// True when `path` is "-".
bool is_standard_output(const std::string& path);

// "standard output" for "-", else the path: for messages ("wrote ...").
std::string output_display_name(const std::string& path);

// write(stream) writes to standard output, unbuffered by C stdio (whatever stdio held is flushed first); throws
// InputError "standard output: write failed (REASON)" on the first failed write (see above). A writer's own stream
// error (badbit) is reported the same way.
void write_standard_output(const std::function<void(std::ostream&)>& write);

// To standard output when `path` is "-" (write_standard_output), else to the file, atomically
// (core/atomic_write.h, write_atomically).
void write_output(const std::string& path, const std::function<void(std::ostream&)>& write);

}  // namespace radwalk
