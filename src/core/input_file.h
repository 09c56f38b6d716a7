#pragma once
// Input files, read once: the one place where radwalk opens a file given by the user for reading.
//
// Only regular files are read: a FIFO, a device, a socket or a directory is refused before a byte is read (so
// nothing blocks on a pipe without a writer, or reads /dev/zero until memory runs out), and so is a file larger
// than the caller's bound, and a path too long to open (core/path_length.h). Every refusal is one InputError
// naming the file.
#include <cstddef>
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

// An input file read in pieces at given offsets, for binary readers that copy straight into their destination (so
// memory stays that of the destination, and a file shrunk while it is read gives an error: a memory-mapped file
// would kill the process with SIGBUS instead). Opening refuses what read_input_file refuses (not a regular file,
// more than kMaxInputBytes). Every error is one InputError naming the file.
class InputFileReader {
 public:
  explicit InputFileReader(const std::string& path);
  ~InputFileReader();
  InputFileReader(const InputFileReader&) = delete;
  InputFileReader& operator=(const InputFileReader&) = delete;

  const std::string& path() const { return path_; }
  // The size when the file was opened.
  std::uint64_t size() const { return size_; }
  // Exactly n bytes at `offset` into `out`; offset + n must not exceed size() (callers check the layout first).
  // A read that ends early means the file shrank: InputError "FILE: changed while it was read".
  void read_at(std::uint64_t offset, void* out, std::size_t n) const;
  // InputError "FILE: changed while it was read" when the file's size or modification time now differ from when
  // it was opened (a reader calls it after its last read; a file rewritten in place to the same size is caught
  // here, and by the format's own checksums where it has some).
  void check_unchanged() const;

 private:
  std::string path_;
  int fd_ = -1;
  std::uint64_t size_ = 0;
  std::int64_t mtime_ns_ = 0;
};

// A test seam: called after every InputFileReader::read_at with the path, offset and byte count (tests change the
// file there, deterministically, between two reads). An empty function (the default) for none; not synchronised.
using InputPieceObserver = std::function<void(const std::string& path, std::uint64_t offset, std::size_t n)>;
void set_input_piece_observer(InputPieceObserver observer);

}  // namespace radwalk
