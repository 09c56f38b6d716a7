#include "core/atomic_write.h"
#include "core/distributed.h"

#include <array>
#include <atomic>
#include <cerrno>
#include <csignal>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <mutex>
#include <string_view>

#include <fcntl.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <unistd.h>

#include "core/digest.h"
#include "core/error.h"
#include "core/path_length.h"

namespace radwalk {
namespace fs = std::filesystem;
namespace {

// ---- Temporaries removed on SIGINT, SIGTERM, SIGHUP -------------------------------------------------------------
// A fixed table of heap-allocated path strings: the handler only loads pointers and calls unlink (both
// async-signal-safe); registering and unregistering swap pointers atomically.
constexpr int kSlots = 256;
std::array<std::atomic<char*>, kSlots> g_pending{};
struct sigaction g_previous[3];
constexpr int kSignals[3] = {SIGINT, SIGTERM, SIGHUP};

extern "C" void remove_pending_and_die(int sig) {
  for (auto& slot : g_pending)
    if (char* p = slot.load()) ::unlink(p);
  // Die of the same signal, as the default action would (so the exit status tells the shell what happened).
  for (int k = 0; k < 3; ++k)
    if (kSignals[k] == sig) ::sigaction(sig, &g_previous[k], nullptr);
  ::raise(sig);
}

// Puts remove_pending_and_die in front of whatever handles each signal now (checked at every registration, so a
// handler installed later by someone else, or a forked child's reset, does not silently drop ours).
void install_handlers() {
  static std::mutex mutex;
  const std::lock_guard lock(mutex);
  for (int k = 0; k < 3; ++k) {
    struct sigaction current {};
    ::sigaction(kSignals[k], nullptr, &current);
    const bool ours = !(current.sa_flags & SA_SIGINFO) && current.sa_handler == remove_pending_and_die;
    // An ignored signal (nohup) stays ignored; an earlier handler runs after ours (it is restored and the signal
    // raised again).
    const bool ignored = !(current.sa_flags & SA_SIGINFO) && current.sa_handler == SIG_IGN;
    if (ours || ignored) continue;
    g_previous[k] = current;
    struct sigaction action {};
    action.sa_handler = remove_pending_and_die;
    sigemptyset(&action.sa_mask);
    ::sigaction(kSignals[k], &action, nullptr);
  }
}

int register_pending(const std::string& path) {
  install_handlers();
  char* copy = ::strdup(path.c_str());
  if (!copy) throw std::bad_alloc();
  for (int s = 0; s < kSlots; ++s) {
    char* expected = nullptr;
    if (g_pending[static_cast<std::size_t>(s)].compare_exchange_strong(expected, copy)) return s;
  }
  std::free(copy);
  return -1;  // table full: this temporary is still removed on every ordinary path, only not on a signal
}

void unregister_pending(int slot) {
  if (slot < 0) return;
  std::free(g_pending[static_cast<std::size_t>(slot)].exchange(nullptr));
}

// ---- Names ------------------------------------------------------------------------------------------------------

std::atomic<unsigned> g_counter{0};

bool process_is_dead(long pid) { return pid > 0 && ::kill(static_cast<pid_t>(pid), 0) != 0 && errno == ESRCH; }

// An extension kept at the end of a temporary's name (for writers that choose their format by it) when it is
// this short; a longer one is left out, so that the name stays within NAME_MAX.
constexpr std::size_t kMaxKeptExtension = 16;

// Removes temporaries of `target` left by processes that no longer exist (a kill -9, a power cut): this module's
// ".radwalk-tmp-HASH-PID-N" and the names earlier radwalk versions used, ".NAME.radwalk-tmp-PID-N",
// "NAME.tmp-PID" and ".tmp-PID-NAME".
void remove_stale_temporaries(const fs::path& target) {
  const std::string name = target.filename().string();
  const fs::path dir = target.parent_path().empty() ? fs::path(".") : target.parent_path();
  const std::string ours = temporary_prefix(target.string()), older = "." + name + ".radwalk-tmp-",
                    old_suffix = name + ".tmp-";
  std::error_code ec;
  for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
    const std::string entry = it->path().filename().string();
    long pid = 0;
    if (entry.rfind(ours, 0) == 0) pid = std::atol(entry.c_str() + ours.size());
    else if (entry.rfind(older, 0) == 0) pid = std::atol(entry.c_str() + older.size());
    else if (entry.rfind(old_suffix, 0) == 0) pid = std::atol(entry.c_str() + old_suffix.size());
    else if (entry.rfind(".tmp-", 0) == 0 && entry.size() > name.size() + 5 &&
             entry[entry.size() - name.size() - 1] == '-' &&
             std::string_view(entry).substr(entry.size() - name.size()) == name)
      pid = std::atol(entry.c_str() + 5);
    if (process_is_dead(pid)) fs::remove(it->path(), ec);
  }
}

// ---- The file-size limit (ulimit -f, RLIMIT_FSIZE) ---------------------------------------------------------------
// By default a write beyond the limit kills the process with SIGXFSZ, leaving the temporary behind. Ignored, the
// write fails with EFBIG instead, and the failure is reported like a full disk.

// Checked at every PendingFile, as the signal handlers above: a disposition reset since (a forked child's) is set
// again.
void ignore_file_size_signal() {
  static std::mutex mutex;
  const std::lock_guard lock(mutex);
  struct sigaction current {};
  ::sigaction(SIGXFSZ, nullptr, &current);
  // A handler someone installed stays (the write still fails with EFBIG once it returns).
  if ((current.sa_flags & SA_SIGINFO) || current.sa_handler != SIG_DFL) return;
  struct sigaction ignore {};
  ignore.sa_handler = SIG_IGN;
  sigemptyset(&ignore.sa_mask);
  ::sigaction(SIGXFSZ, &ignore, nullptr);
}

// The soft file-size limit in bytes, 0 when there is none.
std::uintmax_t file_size_limit() {
  struct rlimit limit {};
  if (::getrlimit(RLIMIT_FSIZE, &limit) != 0 || limit.rlim_cur == RLIM_INFINITY) return 0;
  return static_cast<std::uintmax_t>(limit.rlim_cur);
}

// True when `file` has reached the file-size limit (a write to it failed, or a writer stopped, at the limit), or
// the write's error was EFBIG.
bool at_file_size_limit(const std::string& file, int error) {
  if (error == EFBIG) return true;
  const std::uintmax_t limit = file_size_limit();
  std::error_code ec;
  const std::uintmax_t size = fs::file_size(file, ec);
  return limit > 0 && !ec && size >= limit;
}

// "PATH: write failed: file size limit reached (ulimit -f: N bytes)".
std::string file_size_limit_message(const std::string& path) {
  const std::uintmax_t limit = file_size_limit();
  return path + ": write failed: file size limit reached (ulimit -f" +
         (limit > 0 ? ": " + std::to_string(limit) + " bytes" : std::string()) + ")";
}

const char* kind_of(const struct stat& st) {
  return S_ISDIR(st.st_mode)                           ? "a directory"
         : S_ISFIFO(st.st_mode)                        ? "a FIFO (named pipe)"
         : S_ISCHR(st.st_mode) || S_ISBLK(st.st_mode)  ? "a device"
         : S_ISSOCK(st.st_mode)                        ? "a socket"
                                                       : "not a regular file";
}

void sync_path(const std::string& path, int flags) {
  const int fd = ::open(path.c_str(), flags | O_CLOEXEC);
  if (fd < 0) return;
  const int rc = ::fsync(fd);
  const int err = errno;
  ::close(fd);
  if (rc != 0 && err != EINVAL && err != EROFS)
    throw InputError(path + ": cannot write output: " + std::strerror(err));
}

}  // namespace

std::string temporary_prefix(const std::string& path) {
  Digest d;
  d.add(fs::path(path).filename().string());
  return ".radwalk-tmp-" + d.hex() + "-";
}

std::string output_target(const std::string& path) {
  fs::path p(path);
  std::error_code ec;
  for (int depth = 0; depth < 40 && fs::is_symlink(fs::symlink_status(p, ec)); ++depth) {
    const fs::path link = fs::read_symlink(p, ec);
    if (ec) break;
    p = link.is_absolute() ? link : p.parent_path() / link;
  }
  return p.string();
}

void require_output_directory(const std::string& path) {
  if (path.empty()) return;
  require_path_length(path);
  const fs::path target(output_target(path));
  const fs::path dir = target.parent_path().empty() ? fs::path(".") : target.parent_path();
  std::error_code ec;
  if (!fs::is_directory(dir, ec))
    throw InputError(path + ": cannot open for writing (no directory " + dir.string() + ")");
  if (::access(dir.c_str(), W_OK | X_OK) != 0)
    throw InputError(path + ": cannot open for writing (directory " + dir.string() + " is not writable)");
  struct stat st {};
  if (::stat(target.c_str(), &st) == 0 && !S_ISREG(st.st_mode))
    throw InputError(path + ": cannot write output: it is " + kind_of(st) +
                     "; radwalk writes outputs only to regular files");
}

PendingFile::PendingFile(const std::string& path) : path_(path), target_(output_target(path)) {
  require_output_directory(path);
  require_path_length(target_);  // a symbolic link may point to a longer path
  ignore_file_size_signal();
  const fs::path t(target_);
  // Over MPI only rank 0 writes: the other ranks write into a temporary of their own that commit() removes
  // (core/distributed.h), so every rank runs the same code and fails alike. They leave the target's directory alone
  // (on another node rank 0's process id looks dead).
  discard_ = !distributed::is_root();
  if (!discard_) remove_stale_temporaries(t);
  // A name of bounded length whatever the target's (a target name of 255 bytes has a temporary too): the hash
  // of the target's name, the process and a counter; a short extension stays last, for writers that look at it.
  std::string name = temporary_prefix(target_);
  name += std::to_string(::getpid());
  name += '-';
  name += std::to_string(g_counter++);
  const std::string extension = t.extension().string();
  if (extension.size() <= kMaxKeptExtension) name += extension;
  temporary_ = ((discard_ ? fs::temp_directory_path() : t.parent_path()) / name).string();
  // Registered before it exists: a signal between creating and registering would leave it behind (found by the
  // CLI test that kills radwalk as soon as the temporary appears). Unlinking a name not yet created is harmless.
  slot_ = register_pending(temporary_);
  const int fd = ::open(temporary_.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
  if (fd < 0) {
    const int error = errno;
    unregister_pending(slot_);
    slot_ = -1;
    throw InputError(path + ": cannot open for writing (" + std::strerror(error) + ")");
  }
  ::close(fd);
}

PendingFile::~PendingFile() {
  if (!committed_) ::unlink(temporary_.c_str());
  unregister_pending(slot_);
}

void PendingFile::write(const std::function<void(std::ostream&)>& write) {
  std::streamoff bytes = 0;
  {
    std::ofstream out(temporary_, std::ios::binary | std::ios::trunc);
    if (!out) throw InputError(path_ + ": cannot open for writing");
    errno = 0;
    try {
      write(out);  // a writer may check its stream and throw its own "disk full?"
    } catch (...) {
      if (at_file_size_limit(temporary_, errno)) throw InputError(file_size_limit_message(path_));
      throw;
    }
    out.flush();
    int error = errno;
    bytes = out ? static_cast<std::streamoff>(out.tellp()) : -1;
    out.close();
    if (!out || bytes < 0) {
      if (error == 0) error = errno;
      if (at_file_size_limit(temporary_, error)) throw InputError(file_size_limit_message(path_));
      throw InputError(path_ + ": write failed (disk full?)");
    }
  }
  std::error_code ec;
  if (fs::file_size(temporary_, ec) != static_cast<std::uintmax_t>(bytes) || ec)
    throw InputError(path_ + ": write failed: the file on disk is shorter than what was written (disk full?)");
  written_ = true;
}

void PendingFile::write_via_path(const std::function<void(const std::string&)>& write) {
  // A writer that stops at the file-size limit may or may not say so: a file that reached the limit is taken as
  // cut short (a file of exactly the limit is refused too; it cannot be told apart).
  try {
    write(temporary_);
  } catch (...) {
    if (at_file_size_limit(temporary_, 0)) throw InputError(file_size_limit_message(path_));
    throw;
  }
  if (at_file_size_limit(temporary_, 0)) throw InputError(file_size_limit_message(path_));
  std::error_code ec;
  const auto size = fs::file_size(temporary_, ec);
  if (ec || size == 0) throw InputError(path_ + ": write failed: nothing was written (disk full?)");
  written_ = true;
}

void PendingFile::commit() {
  if (!written_) throw InternalError(path_ + ": commit before write");
  if (discard_) {  // a rank other than 0 (see the constructor)
    ::unlink(temporary_.c_str());
    committed_ = true;
    return;
  }
  sync_path(temporary_, O_RDONLY);
  std::error_code ec;
  fs::rename(temporary_, target_, ec);
  if (ec) throw InputError(path_ + ": cannot write output: rename failed (" + ec.message() + ")");
  committed_ = true;
  const fs::path dir = fs::path(target_).parent_path();
  sync_path(dir.empty() ? "." : dir.string(), O_RDONLY | O_DIRECTORY);
}

void commit_together(const std::vector<PendingFile*>& files) {
  for (PendingFile* f : files) f->commit();
}

void write_atomically(const std::string& path, const std::function<void(std::ostream&)>& write) {
  PendingFile file(path);
  file.write(write);
  file.commit();
}

void write_atomically_via_path(const std::string& path, const std::function<void(const std::string&)>& write) {
  PendingFile file(path);
  file.write_via_path(write);
  file.commit();
}

}  // namespace radwalk
