#include "core/progress.h"

#include <unistd.h>

#include <cstdio>

namespace radwalk {
namespace {
std::atomic<bool> g_enabled{true};
}

void Progress::set_enabled(bool enabled) { g_enabled = enabled; }

Progress::Progress(std::string label, std::size_t total)
    : label_(std::move(label)), total_(total), active_(g_enabled && ::isatty(STDERR_FILENO)) {}

Progress::~Progress() { finish(); }

void Progress::advance(std::size_t done_items) {
  const std::size_t done = done_ += done_items;
  if (!active_) return;
  const double now = timer_.seconds();
  if (now - last_draw_.load() < 0.25) return;
  std::unique_lock lock(mutex_, std::try_to_lock);
  if (!lock.owns_lock()) return;
  last_draw_ = now;
  draw(done);
}

void Progress::draw(std::size_t done) {
  const double t = timer_.seconds();
  const double frac = total_ ? double(done) / double(total_) : 1.0;
  const double eta = frac > 0 ? t * (1 - frac) / frac : 0;
  std::fprintf(stderr, "\r%s: %5.1f%% (%.1f s, about %.0f s left)   ", label_.c_str(), 100 * frac, t, eta);
  std::fflush(stderr);
}

void Progress::finish() {
  if (!active_ || finished_) return;
  finished_ = true;
  std::fprintf(stderr, "\r%s: done in %.2f s%40s\n", label_.c_str(), timer_.seconds(), "");
}

}  // namespace radwalk
