// Atomic writes: the target appears complete or not at all.
#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <csignal>
#include <functional>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include "core/atomic_write.h"
#include "core/error.h"

using namespace radwalk;

TEST_CASE("write_atomically writes the content and leaves no temporary file", "[io]") {
  const auto dir = std::filesystem::temp_directory_path() / "radwalk_atomic_test";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  const std::string path = (dir / "out.txt").string();
  write_atomically(path, [](std::ostream& out) { out << "hello\n"; });
  std::ifstream in(path);
  std::stringstream ss;
  ss << in.rdbuf();
  CHECK(ss.str() == "hello\n");
  CHECK(std::distance(std::filesystem::directory_iterator(dir), {}) == 1);

  // A writer that throws leaves the old file untouched and no temporary behind.
  CHECK_THROWS(write_atomically(path, [](std::ostream& out) {
    out << "partial";
    throw InputError("boom");
  }));
  std::ifstream again(path);
  std::stringstream ss2;
  ss2 << again.rdbuf();
  CHECK(ss2.str() == "hello\n");
  CHECK(std::distance(std::filesystem::directory_iterator(dir), {}) == 1);
  std::filesystem::remove_all(dir);
}

TEST_CASE("write_atomically names the path when the directory does not exist", "[io]") {
  try {
    write_atomically("/nonexistent-dir/x.csv", [](std::ostream&) {});
    FAIL("no exception");
  } catch (const InputError& e) {
    CHECK(std::string(e.what()).find("/nonexistent-dir/x.csv") != std::string::npos);
  }
}

namespace {

namespace fs = std::filesystem;

fs::path fresh_dir(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / ("radwalk_atomic_" + name + "_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

std::size_t entries(const fs::path& dir) {
  return static_cast<std::size_t>(std::distance(fs::directory_iterator(dir), fs::directory_iterator()));
}

// A process id that is not running: a child that has exited and been reaped.
pid_t dead_pid() {
  const pid_t child = ::fork();
  if (child == 0) ::_exit(0);
  int status = 0;
  ::waitpid(child, &status, 0);
  return child;
}

}  // namespace

TEST_CASE("outputs are written through symbolic links, devices, FIFOs and directories are refused", "[io][fault]") {
  // D2: --csv /dev/null (as root) replaced /dev/null with a regular file; a symlink was replaced by a file.
  const fs::path dir = fresh_dir("targets");
  write_atomically((dir / "real.csv").string(), [](std::ostream& o) { o << "old\n"; });
  fs::create_symlink("real.csv", dir / "link.csv");
  write_atomically((dir / "link.csv").string(), [](std::ostream& o) { o << "new\n"; });
  CHECK(fs::is_symlink(fs::symlink_status(dir / "link.csv")));
  CHECK(slurp(dir / "real.csv") == "new\n");
  CHECK(entries(dir) == 2);

  struct stat before {};
  REQUIRE(::stat("/dev/null", &before) == 0);
  CHECK_THROWS_WITH(write_atomically("/dev/null", [](std::ostream& o) { o << "x"; }),
                    Catch::Contains("/dev/null") && Catch::Contains("a device"));
  CHECK_THROWS_WITH(require_output_directory("/dev/null"), Catch::Contains("a device"));
  struct stat after {};
  REQUIRE(::stat("/dev/null", &after) == 0);
  CHECK(S_ISCHR(after.st_mode));
  const fs::path fifo = dir / "pipe.csv";
  REQUIRE(::mkfifo(fifo.c_str(), 0600) == 0);
  CHECK_THROWS_WITH(write_atomically(fifo.string(), [](std::ostream& o) { o << "x"; }), Catch::Contains("FIFO"));
  CHECK(fs::is_fifo(fifo));
  fs::create_directories(dir / "folder.csv");
  CHECK_THROWS_WITH(require_output_directory((dir / "folder.csv").string()), Catch::Contains("a directory"));
}

TEST_CASE("files committed together appear together, an abandoned one leaves the old file", "[io][fault]") {
  const fs::path dir = fresh_dir("together");
  write_atomically((dir / "a.obj").string(), [](std::ostream& o) { o << "old obj\n"; });
  write_atomically((dir / "a.mtl").string(), [](std::ostream& o) { o << "old mtl\n"; });
  {
    PendingFile mtl((dir / "a.mtl").string()), obj((dir / "a.obj").string());
    mtl.write([](std::ostream& o) { o << "new mtl\n"; });
    // The second write fails (as on a full disk): neither file may change.
    CHECK_THROWS(obj.write([](std::ostream& o) {
      o << "partial";
      throw InputError("disk full");
    }));
  }
  CHECK(slurp(dir / "a.obj") == "old obj\n");
  CHECK(slurp(dir / "a.mtl") == "old mtl\n");
  CHECK(entries(dir) == 2);
  {
    PendingFile mtl((dir / "a.mtl").string()), obj((dir / "a.obj").string());
    mtl.write([](std::ostream& o) { o << "new mtl\n"; });
    obj.write([](std::ostream& o) { o << "new obj\n"; });
    commit_together({&mtl, &obj});
  }
  CHECK(slurp(dir / "a.obj") == "new obj\n");
  CHECK(slurp(dir / "a.mtl") == "new mtl\n");
  CHECK(entries(dir) == 2);
}

TEST_CASE("SIGTERM removes pending temporaries, temporaries of dead processes are cleaned up", "[io][fault]") {
  // P2: kill -9 / SIGTERM / SIGHUP left .tmp-PID-* files (up to 16 MB each, accumulating).
  const fs::path dir = fresh_dir("signals");
  for (int sig : {SIGTERM, SIGHUP, SIGINT}) {
    INFO("signal " << sig);
    const pid_t child = ::fork();
    if (child == 0) {
      // A plain program: default dispositions (not the test framework's handlers).
      for (int s : {SIGTERM, SIGHUP, SIGINT}) std::signal(s, SIG_DFL);
      PendingFile f((dir / "out.vtp").string());
      f.write([](std::ostream& o) { o << std::string(1 << 20, 'x'); });
      ::raise(sig);
      ::_exit(0);  // not reached
    }
    int status = 0;
    ::waitpid(child, &status, 0);
    CHECK(WIFSIGNALED(status));
    CHECK(WTERMSIG(status) == sig);
    CHECK(entries(dir) == 0);
  }
  // What a kill -9 leaves: temporaries of a process that is gone, in this module's and earlier versions' names.
  const std::string pid = std::to_string(dead_pid());
  const std::string prefix = temporary_prefix((dir / "out.vtp").string());
  for (const std::string& name : {prefix + pid + "-0.vtp", ".out.vtp.radwalk-tmp-" + pid + "-0.vtp",
                                  "out.vtp.tmp-" + pid, ".tmp-" + pid + "-out.vtp"})
    std::ofstream(dir / name) << "stale";
  std::ofstream(dir / (prefix + std::to_string(::getpid()) + "-99.vtp")) << "ours, alive";
  std::ofstream(dir / (temporary_prefix((dir / "other.vtp").string()) + pid + "-0.vtp")) << "another target's";
  write_atomically((dir / "out.vtp").string(), [](std::ostream& o) { o << "fresh\n"; });
  CHECK(slurp(dir / "out.vtp") == "fresh\n");
  CHECK(entries(dir) == 3);  // the output, the live process's temporary and another target's
  fs::remove_all(dir);
}

TEST_CASE("a full disk fails the write and keeps the old file", "[io][fault]") {
  // A real full disk: a 256 KiB tmpfs (needs mount permission; skipped with a message where it is missing).
  const fs::path mnt = fresh_dir("fulldisk");
  if (::system(("mount -t tmpfs -o size=256k tmpfs " + mnt.string() + " 2>/dev/null").c_str()) != 0) {
    WARN("skipped: cannot mount a tmpfs here (needs root and mount permission)");
    return;
  }
  const std::string out = (mnt / "out.csv").string();
  write_atomically(out, [](std::ostream& o) { o << "old\n"; });
  CHECK_THROWS_WITH(write_atomically(out, [](std::ostream& o) { o << std::string(1 << 20, 'x'); }),
                    Catch::Contains("out.csv") && Catch::Contains("disk full"));
  CHECK(slurp(out) == "old\n");
  CHECK(entries(mnt) == 1);
  ::system(("umount " + mnt.string()).c_str());
}

TEST_CASE("target names of up to 255 bytes have temporaries that fit NAME_MAX", "[io]") {
  const fs::path dir = fresh_dir("long_names");
  // 255 bytes with a short extension, 255 bytes that are all extension, and the longest temporary name possible.
  for (const std::string& name : {std::string(251, 'a') + ".vtp", "." + std::string(254, 'b'), "c." + std::string(253, 'd')}) {
    INFO(name.size());
    const std::string path = (dir / name).string();
    {
      PendingFile file(path);
      CHECK(fs::path(file.temporary()).filename().string().size() <= 255);
      CHECK(fs::path(file.temporary()).filename().string().rfind(temporary_prefix(path), 0) == 0);
    }
    write_atomically(path, [](std::ostream& o) { o << "long\n"; });
    CHECK(slurp(path) == "long\n");
  }
  CHECK(fs::path(PendingFile((dir / "x.vtp").string()).temporary()).extension() == ".vtp");
  CHECK(entries(dir) == 3);
  fs::remove_all(dir);
}

TEST_CASE("a file-size limit (RLIMIT_FSIZE) fails the write, keeps the old file and leaves no temporary",
          "[io][fault]") {
  const fs::path dir = fresh_dir("fsize");
  const std::string out = (dir / "out.csv").string();
  write_atomically(out, [](std::ostream& o) { o << "old\n"; });
  // In a child process (the limit and SIGXFSZ are per process), as a plain program: SIGXFSZ at its default
  // (kill). Exit code 0: every check held; otherwise the number of the first that failed.
  const pid_t child = ::fork();
  if (child == 0) {
    std::signal(SIGXFSZ, SIG_DFL);
    const rlimit limit{64 * 1024, 64 * 1024};
    if (::setrlimit(RLIMIT_FSIZE, &limit) != 0) ::_exit(10);
    const auto refused = [&](const std::function<void()>& write) {
      try {
        write();
      } catch (const InputError& e) {
        const std::string what = e.what();
        return what.find(out + ": write failed: file size limit reached") != std::string::npos;
      }
      return false;
    };
    // A stream writer, and a writer that takes a file name and does not check what it wrote.
    if (!refused([&] { write_atomically(out, [](std::ostream& o) { o << std::string(1 << 20, 'x'); }); })) ::_exit(1);
    if (slurp(out) != "old\n" || entries(dir) != 1) ::_exit(2);
    if (!refused([&] {
          write_atomically_via_path(out, [](const std::string& tmp) { std::ofstream(tmp) << std::string(1 << 20, 'y'); });
        }))
      ::_exit(3);
    if (slurp(out) != "old\n" || entries(dir) != 1) ::_exit(4);
    // Below the limit a write succeeds.
    write_atomically(out, [](std::ostream& o) { o << "new\n"; });
    ::_exit(slurp(out) == "new\n" && entries(dir) == 1 ? 0 : 5);
  }
  int status = 0;
  REQUIRE(::waitpid(child, &status, 0) == child);
  INFO("killed by signal " << (WIFSIGNALED(status) ? WTERMSIG(status) : 0));
  REQUIRE(WIFEXITED(status));
  CHECK(WEXITSTATUS(status) == 0);
  CHECK(slurp(out) == "new\n");
  CHECK(entries(dir) == 1);
  fs::remove_all(dir);
}
