#pragma once
// Runs the radwalk program for end-to-end tests: run("solve scene.obj ...") returns its exit code and its merged
// stdout + stderr. RADWALK_BINARY and RADWALK_SOURCE_DIR are compile definitions of the test targets.
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <catch2/catch.hpp>
#include <cstdio>
#include <filesystem>
#include <string>

struct Run {
  int exit_code;
  std::string out;  // stdout and stderr, merged
};

inline Run run(const std::string& args) {
  const std::string cmd = std::string(RADWALK_BINARY) + " --quiet " + args + " 2>&1";
  Run r{-1, {}};
  FILE* pipe = popen(cmd.c_str(), "r");
  REQUIRE(pipe != nullptr);
  std::array<char, 4096> buf{};
  while (std::fgets(buf.data(), buf.size(), pipe)) r.out += buf.data();
  const int status = pclose(pipe);
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return r;
}

// Peak resident memory (KiB) of one radwalk run, which must succeed (wait4's rusage of the child).
inline double peak_kib(const std::string& args) {
  const std::string cmd = std::string(RADWALK_BINARY) + " -q " + args + " > /dev/null 2>&1";
  const pid_t pid = fork();
  REQUIRE(pid >= 0);
  if (pid == 0) {
    execl("/bin/sh", "sh", "-c", cmd.c_str(), static_cast<char*>(nullptr));
    _exit(127);
  }
  int status = 0;
  struct rusage usage {};
  REQUIRE(wait4(pid, &status, 0, &usage) == pid);
  REQUIRE(WIFEXITED(status));
  REQUIRE(WEXITSTATUS(status) == 0);
  return static_cast<double>(usage.ru_maxrss);
}

// Path of a file in the source tree, e.g. source("meshes/cube.obj").
// A scratch folder for one test file, one per process: test runs of other checkouts on the same machine must not
// share it.
inline std::filesystem::path scratch_dir(const std::string& name) {
  const auto dir = std::filesystem::temp_directory_path() / ("radwalk_" + name + "_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  return dir;
}

inline std::string source(const std::string& rel) { return std::string(RADWALK_SOURCE_DIR) + "/" + rel; }
