#pragma once
// Atomic file output: a reader never sees a half-written file, a failed or interrupted run never leaves a truncated
// output or replaces a good one, and outputs written together appear together.
//
// A PendingFile writes to a temporary ".NAME.radwalk-tmp-PID" in the target's directory and becomes the target on
// commit(): the data are flushed to disk (fsync), checked (every byte written, no stream error), and the
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
  // missing result is an InputError.
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
