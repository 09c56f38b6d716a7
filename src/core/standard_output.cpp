#include "core/standard_output.h"

#include <signal.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <ostream>
#include <streambuf>
#include <vector>

#include "core/atomic_write.h"
#include "core/distributed.h"
#include "core/error.h"

namespace radwalk {
namespace {

// A stream buffer over file descriptor 1: a 64 KiB buffer written with write(2), retried after EINTR and short
// writes; the first failure is kept (errno) and later output discarded, so the caller reports one error.
class DescriptorBuffer : public std::streambuf {
 public:
  explicit DescriptorBuffer(int fd) : fd_(fd), buffer_(1 << 16) { setp(buffer_.data(), buffer_.data() + buffer_.size()); }
  ~DescriptorBuffer() override = default;
  int error() const { return error_; }

  // Writes what is buffered; false after a failure.
  bool drain() {
    const char* p = pbase();
    std::size_t left = static_cast<std::size_t>(pptr() - pbase());
    while (left > 0 && error_ == 0) {
      const ssize_t n = ::write(fd_, p, left);
      if (n < 0) {
        if (errno == EINTR) continue;
        error_ = errno;
      } else {
        p += n;
        left -= static_cast<std::size_t>(n);
      }
    }
    setp(buffer_.data(), buffer_.data() + buffer_.size());
    return error_ == 0;
  }

 protected:
  int_type overflow(int_type c) override {
    if (!drain()) return traits_type::eof();
    if (!traits_type::eq_int_type(c, traits_type::eof())) {
      *pptr() = traits_type::to_char_type(c);
      pbump(1);
    }
    return traits_type::not_eof(c);
  }
  int sync() override { return drain() ? 0 : -1; }

 private:
  int fd_;
  std::vector<char> buffer_;
  int error_ = 0;
};

// A stream that keeps nothing (the ranks other than 0 over MPI).
class NullBuffer : public std::streambuf {
 protected:
  int_type overflow(int_type c) override { return traits_type::not_eof(c); }
};

// SIGPIPE ignored unless someone installed a handler: a closed pipe becomes the write error EPIPE.
void ignore_sigpipe() {
  struct sigaction current {};
  if (::sigaction(SIGPIPE, nullptr, &current) != 0) return;
  if (current.sa_handler != SIG_DFL) return;
  struct sigaction ignore {};
  ignore.sa_handler = SIG_IGN;
  sigemptyset(&ignore.sa_mask);
  ::sigaction(SIGPIPE, &ignore, nullptr);
}

std::string failure(int error) {
  std::string reason = std::strerror(error);
  if (error == EPIPE) reason += ": the reader closed the pipe before the end; what it read is incomplete";
  return "standard output: write failed (" + reason + ")";
}

}  // namespace

bool is_standard_output(const std::string& path) { return path == kStandardOutputName; }

std::string output_display_name(const std::string& path) {
  return is_standard_output(path) ? "standard output" : path;
}

void write_standard_output(const std::function<void(std::ostream&)>& write) {
  if (!distributed::is_root()) {
    NullBuffer discard;
    std::ostream out(&discard);
    write(out);
    return;
  }
  ignore_sigpipe();
  if (std::fflush(stdout) != 0) throw InputError(failure(errno));
  DescriptorBuffer buffer(STDOUT_FILENO);
  std::ostream out(&buffer);
  write(out);
  out.flush();
  if (buffer.error() != 0) throw InputError(failure(buffer.error()));
  if (!out) throw InputError("standard output: write failed (the writer's stream reported an error)");
}

void write_output(const std::string& path, const std::function<void(std::ostream&)>& write) {
  if (is_standard_output(path))
    write_standard_output(write);
  else
    write_atomically(path, write);
}

}  // namespace radwalk
