#pragma once
// Wall-clock stopwatch.
#include <chrono>

namespace radwalk {

class Timer {
 public:
  Timer() : start_(std::chrono::steady_clock::now()) {}
  // Seconds since construction or the last reset().
  double seconds() const {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  }
  void reset() { start_ = std::chrono::steady_clock::now(); }

 private:
  std::chrono::steady_clock::time_point start_;
};

// Peak resident set size of this process so far, in bytes (from getrusage), 0 if unknown.
long peak_memory_bytes();

}  // namespace radwalk
