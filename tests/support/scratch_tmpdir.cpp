// Every test process gets a scratch folder of its own and leaves the temporary directory as it found it.
//
// Contract: before the first test case runs, a fresh folder "radwalk-test-<program>-XXXXXX" is made in the
// temporary directory the process was given ($TMPDIR, else /tmp) and TMPDIR is pointed at it, so that
// std::filesystem::temp_directory_path(), mkstemp and every child process (the radwalk CLI, mpirun, Python) put
// their files there. When the run ends with no failed assertion the folder is removed with all it holds; when a
// test failed it is kept and named on stderr ("radwalk test: kept scratch folder PATH"), as the statistical tests
// keep their artifacts. A process killed before the end (a timeout, a crash) keeps its folder too: that is a
// failure, and the folder is what one wants to look at.
//
// Linked into every Catch2 test program (cmake/RadwalkWarnings.cmake, radwalk_add_test) as an object file, so that
// the listener's registration is not dropped by the linker.
#define CATCH_CONFIG_EXTERNAL_INTERFACES
#include <catch2/catch.hpp>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <system_error>
#include <vector>

namespace {

// The folder the process was given for temporary files, as std::filesystem::temp_directory_path() reads it.
std::filesystem::path given_temporary_directory() {
  std::error_code ec;
  std::filesystem::path dir = std::filesystem::temp_directory_path(ec);
  return ec ? std::filesystem::path("/tmp") : dir;
}

// The running program's file name ("radwalk_io_tests"), for a folder name that says whose it is.
std::string program_name() {
  std::error_code ec;
  const std::filesystem::path self = std::filesystem::read_symlink("/proc/self/exe", ec);
  return ec ? std::string("tests") : self.filename().string();
}

class ScratchTmpdir : public Catch::TestEventListenerBase {
 public:
  using TestEventListenerBase::TestEventListenerBase;

  void testRunStarting(const Catch::TestRunInfo& info) override {
    TestEventListenerBase::testRunStarting(info);
    std::string pattern = (given_temporary_directory() / ("radwalk-test-" + program_name() + "-XXXXXX")).string();
    std::vector<char> name(pattern.begin(), pattern.end());
    name.push_back('\0');
    if (!::mkdtemp(name.data())) {
      std::perror("radwalk test: cannot make a scratch folder; temporary files go to the given directory");
      return;
    }
    scratch_ = name.data();
    ::setenv("TMPDIR", scratch_.c_str(), 1);
  }

  void testRunEnded(const Catch::TestRunStats& stats) override {
    TestEventListenerBase::testRunEnded(stats);
    if (scratch_.empty()) return;
    if (stats.totals.assertions.failed == 0 && stats.totals.testCases.failed == 0) {
      std::error_code ec;
      std::filesystem::remove_all(scratch_, ec);
      if (ec) std::fprintf(stderr, "radwalk test: cannot remove scratch folder %s: %s\n", scratch_.c_str(),
                           ec.message().c_str());
    } else {
      std::fprintf(stderr, "radwalk test: kept scratch folder %s\n", scratch_.c_str());
    }
  }

 private:
  std::string scratch_;
};

}  // namespace

CATCH_REGISTER_LISTENER(ScratchTmpdir)
