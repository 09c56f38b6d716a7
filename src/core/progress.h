#pragma once
// Progress on long runs: a single updating line on stderr, only when stderr is a terminal.
#include <atomic>
#include <cstddef>
#include <mutex>
#include <string>

#include "core/timer.h"

namespace radwalk {

class Progress {
 public:
  // `label` names the step ("form factors"), `total` the number of work items.
  Progress(std::string label, std::size_t total);
  ~Progress();
  // Thread-safe; redraws at most a few times a second.
  void advance(std::size_t done_items);
  void finish();

  // Global switch (e.g. --quiet); progress is also off when stderr is not a terminal.
  static void set_enabled(bool enabled);

 private:
  void draw(std::size_t done);
  std::string label_;
  std::size_t total_;
  std::atomic<std::size_t> done_{0};
  std::atomic<double> last_draw_{0};
  std::mutex mutex_;
  Timer timer_;
  bool active_;
  bool finished_ = false;
};

}  // namespace radwalk
