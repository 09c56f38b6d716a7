#include "core/input_file.h"

#include <algorithm>
#include <cerrno>
#include <cstring>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include "core/error.h"
#include "core/path_length.h"

namespace radwalk {

namespace {

// Closes a file descriptor on every path out.
struct FileDescriptor {
  int fd = -1;
  explicit FileDescriptor(int descriptor) : fd(descriptor) {}
  FileDescriptor(FileDescriptor&& other) noexcept : fd(other.fd) { other.fd = -1; }
  FileDescriptor(const FileDescriptor&) = delete;
  FileDescriptor& operator=(const FileDescriptor&) = delete;
  FileDescriptor& operator=(FileDescriptor&&) = delete;
  ~FileDescriptor() {
    if (fd >= 0) ::close(fd);
  }
};

InputObserver g_observer;
InputPieceObserver g_piece_observer;

std::string size_text(std::uint64_t bytes) {
  return bytes >= (std::uint64_t{1} << 30) ? std::to_string(bytes >> 30) + " GiB" : std::to_string(bytes) + " bytes";
}

// Opens path for reading without blocking (a FIFO without a writer would block a plain open) and refuses what is
// not a regular file; returns the descriptor and the size.
FileDescriptor open_regular(const std::string& path, std::uint64_t& size) {
  require_path_length(path);
  FileDescriptor file{::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC)};
  if (file.fd < 0)
    throw InputError(locate(path, 0, -1, std::string("cannot open the file (") + std::strerror(errno) + ")"));
  struct stat st {};
  if (::fstat(file.fd, &st) != 0) throw InputError(locate(path, 0, -1, "cannot read the file's status"));
  if (!S_ISREG(st.st_mode)) {
    const char* kind = S_ISDIR(st.st_mode)                         ? "a directory"
                       : S_ISFIFO(st.st_mode)                      ? "a FIFO (named pipe)"
                       : S_ISCHR(st.st_mode) || S_ISBLK(st.st_mode) ? "a device"
                       : S_ISSOCK(st.st_mode)                      ? "a socket"
                                                                   : "not a regular file";
    throw InputError(locate(path, 0, -1, std::string("is ") + kind + "; radwalk reads input only from regular files"));
  }
  size = static_cast<std::uint64_t>(st.st_size);
  return file;
}

}  // namespace

std::uint64_t input_file_size(const std::string& path) {
  std::uint64_t size = 0;
  open_regular(path, size);
  return size;
}

std::string read_input_file(const std::string& path, std::uint64_t max_bytes) {
  std::uint64_t size = 0;
  const FileDescriptor file = open_regular(path, size);
  if (size > max_bytes)
    throw InputError(locate(path, 0, -1, "is " + size_text(size) + ", more than the " + size_text(max_bytes) +
                                             " radwalk reads"));
  // One byte more than fstat said, to see the end of the file (or that it grew) without a second pass.
  const std::uint64_t limit = max_bytes + 1;
  std::string content;
  content.resize(static_cast<std::size_t>(std::min(limit, size + 1)));
  std::size_t have = 0;
  for (;;) {
    if (have == content.size()) {
      if (have >= limit)
        throw InputError(locate(path, 0, -1, "grew beyond the " + size_text(max_bytes) + " radwalk reads"));
      content.resize(static_cast<std::size_t>(std::min<std::uint64_t>(limit, 2 * content.size() + 4096)));
    }
    const ssize_t got = ::read(file.fd, content.data() + have, content.size() - have);
    if (got < 0) {
      if (errno == EINTR) continue;
      throw InputError(locate(path, 0, -1, std::string("read error (") + std::strerror(errno) + ")"));
    }
    if (got == 0) break;
    have += static_cast<std::size_t>(got);
  }
  content.resize(have);
  if (g_observer) g_observer(path, content);
  return content;
}

void set_input_observer(InputObserver observer) { g_observer = std::move(observer); }

namespace {

std::int64_t mtime_ns(const struct stat& st) {
  return std::int64_t(st.st_mtim.tv_sec) * 1000000000 + std::int64_t(st.st_mtim.tv_nsec);
}

}  // namespace

InputFileReader::InputFileReader(const std::string& path) : path_(path) {
  FileDescriptor file = open_regular(path, size_);
  if (size_ > kMaxInputBytes)
    throw InputError(locate(path, 0, -1, "is " + size_text(size_) + ", more than the " + size_text(kMaxInputBytes) +
                                             " radwalk reads"));
  struct stat st {};
  if (::fstat(file.fd, &st) != 0) throw InputError(locate(path, 0, -1, "cannot read the file's status"));
  mtime_ns_ = mtime_ns(st);
  fd_ = file.fd;
  file.fd = -1;
}

InputFileReader::~InputFileReader() {
  if (fd_ >= 0) ::close(fd_);
}

void InputFileReader::read_at(std::uint64_t offset, void* out, std::size_t n) const {
  auto* p = static_cast<char*>(out);
  std::size_t have = 0;
  while (have < n) {
    const ssize_t got = ::pread(fd_, p + have, n - have, static_cast<off_t>(offset + have));
    if (got < 0) {
      if (errno == EINTR) continue;
      throw InputError(locate(path_, 0, -1, std::string("read error (") + std::strerror(errno) + ")"));
    }
    if (got == 0) throw InputError(locate(path_, 0, -1, "changed while it was read (it is shorter now)"));
    have += static_cast<std::size_t>(got);
  }
  if (g_piece_observer) g_piece_observer(path_, offset, n);
}

void InputFileReader::check_unchanged() const {
  struct stat st {};
  if (::fstat(fd_, &st) != 0) throw InputError(locate(path_, 0, -1, "cannot read the file's status"));
  if (static_cast<std::uint64_t>(st.st_size) != size_ || mtime_ns(st) != mtime_ns_)
    throw InputError(locate(path_, 0, -1, "changed while it was read (its size or modification time differ)"));
}

void set_input_piece_observer(InputPieceObserver observer) { g_piece_observer = std::move(observer); }


}  // namespace radwalk
