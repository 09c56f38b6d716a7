#pragma once
// Input files, read once: the one place where radwalk opens a file given by the user for reading.
//
// Only regular files are read: a FIFO, a device, a socket or a directory is refused before a byte is read (so
// nothing blocks on a pipe without a writer, or reads /dev/zero until memory runs out), and so is a file larger
// than the caller's bound, and a path too long to open (core/path_length.h). Every refusal is one InputError
// naming the file.
#include <cstdint>
#include <functional>
#include <string>

namespace radwalk {

// The largest input file radwalk reads (16 GiB): a bound on what one read may allocate.
inline constexpr std::uint64_t kMaxInputBytes = std::uint64_t{16} << 30;

// The whole content of a regular file of at most max_bytes (the file is read once, also if it grows meanwhile).
std::string read_input_file(const std::string& path, std::uint64_t max_bytes = kMaxInputBytes);

// The size in bytes of a regular file, for readers that stream it (they bound their allocations by it); refuses
// what read_input_file refuses.
std::uint64_t input_file_size(const std::string& path);

// Called with the path and the bytes of every file read_input_file returns, as it returns them (the run id of
// apps/run_metadata.h hashes the bytes that were parsed, not a second read); an empty function (the default) for
// none. Not synchronised: set it before reading, from the thread that reads.
using InputObserver = std::function<void(const std::string& path, const std::string& bytes)>;
void set_input_observer(InputObserver observer);

}  // namespace radwalk
