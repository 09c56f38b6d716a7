#pragma once
// Atomic file output: a reader never sees a half-written file, a failed or interrupted run never leaves a truncated
// output or replaces a good one, and outputs written together appear together.
//
// A PendingFile writes to a temporary ".radwalk-tmp-HASH-PID-N.EXT" in the target's directory (HASH: 16 hexadecimal
// digits of the target's file name, so the temporary's name fits NAME_MAX whatever the target's length; EXT: the
// target's extension when it is at most 16 bytes) and becomes the target on commit(): the data are flushed to disk (fsync), checked (every byte written, no stream error), and the
// temporary is renamed over the target (atomic on POSIX), then the directory entry is synced. Until then the old
// target, if any, is untouched; a PendingFile destroyed without commit() removes its temporary.
// Targets:
//   - a symbolic link is written through: the file it points to is replaced, the link kept;
//   - an existing target that is not a regular file (a device such as /dev/null, a FIFO, a directory) is refused
//     (InputError), since renaming over it would replace it;
//   - the directory must exist.
// Interrupted runs: SIGINT, SIGTERM and SIGHUP remove every pending temporary, then the signal takes its course
// (the handler that was there before, or the default: the program dies of the signal; an ignored signal stays
// ignored); after a kill -9 the next PendingFile for the same target removes temporaries left by dead processes.
// File-size limit (ulimit -f, RLIMIT_FSIZE): the first PendingFile sets SIGXFSZ to ignored (unless a handler is
// installed), so a write beyond the limit fails instead of killing the process; it is reported as
// "PATH: write failed: file size limit reached (...)", the temporary removed and the old target kept, as on a
// full disk.
// Paths longer than PATH_MAX, or with a component longer than NAME_MAX, are refused ("path too long",
// core/path_length.h).
// Every failure is an InputError naming the target.
// Over MPI (core/distributed.h) only rank 0 writes: on the other ranks the temporary is in the system's temporary
// directory and commit() removes it, after the same checks of the target.
#include <functional>
#include <iosfwd>
#include <memory>
#include <string>
#include <vector>

namespace radwalk {

// Throws InputError "PATH: cannot open for writing (...)" unless `path` can be written: its directory exists and
// is writable, and the path is not an existing non-regular file (a device, FIFO or directory). An empty path is
// allowed (no output). Commands call it for every output before computing anything.
void require_output_directory(const std::string& path);

// The start of the names of the temporaries of `path` (in its directory): ".radwalk-tmp-HASH-", HASH the 16
// hexadecimal digits of the FNV-1a digest of path's file name (core/digest.h).
std::string temporary_prefix(const std::string& path);

// The file a write to `path` lands in: the target of a symbolic link (followed to the end), else `path`.
std::string output_target(const std::string& path);

class PendingFile {
 public:
  // Checks the target (see above) and creates the temporary. Throws InputError.
  explicit PendingFile(const std::string& path);
  ~PendingFile();
  PendingFile(const PendingFile&) = delete;
  PendingFile& operator=(const PendingFile&) = delete;

  const std::string& path() const { return path_; }            // as given
  const std::string& temporary() const { return temporary_; }  // where the writer writes

  // Writes through a stream: write(out) fills the temporary; a stream error is an InputError ("disk full?").
  void write(const std::function<void(std::ostream&)>& write);
  // For writers that take a file name (VTK, OpenEXR): write(temporary()) must fill the temporary; an empty or
  // missing result is an InputError, and so is a temporary that reached the file-size limit (whatever the writer
  // said: it may not notice that it was cut short).
  void write_via_path(const std::function<void(const std::string&)>& write);

  // fsync, rename over the target, sync the directory. Throws InputError (the temporary is then removed).
  void commit();

 private:
  std::string path_, target_, temporary_;
  bool written_ = false, committed_ = false;
  bool discard_ = false;  // over MPI on a rank other than 0: written to a temporary file and removed on commit()
  int slot_ = -1;  // in the signal-cleanup registry
};

// Commits several pending files so that they appear together: all were written completely before (disk-full
// errors happen while writing), and the renames that remain cannot fail for lack of space. In the order given.
void commit_together(const std::vector<PendingFile*>& files);

// Calls write(stream) on a PendingFile for `path` and commits it.
void write_atomically(const std::string& path, const std::function<void(std::ostream&)>& write);

// For writers that take a file name (VTK): write(tmp_path) must create tmp_path; then it replaces `path`.
void write_atomically_via_path(const std::string& path, const std::function<void(const std::string&)>& write);

}  // namespace radwalk
