#include "core/progress.h"

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <exception>

#include "core/cancellation.h"

namespace radwalk {
namespace {

std::atomic<bool> g_enabled{true};

double steady_seconds() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

void write_stderr(const std::string& text) {
  std::fputs(text.c_str(), stderr);
  std::fflush(stderr);
}

}  // namespace

ProgressOutput ProgressOutput::lines(double interval, std::function<double()> clock,
                                     std::function<void(const std::string&)> write) {
  ProgressOutput o;
  o.first_s = o.every_s = interval;
  o.clock = std::move(clock);
  o.write = std::move(write);
  return o;
}

ProgressOutput ProgressOutput::standard() {
  double interval = 5;
  if (const char* s = std::getenv("RADWALK_PROGRESS_INTERVAL")) {
    char* end = nullptr;
    const double v = std::strtod(s, &end);
    if (end != s && *end == '\0' && std::isfinite(v) && v > 0) interval = v;
  }
  ProgressOutput o = lines(interval);
  static const std::shared_ptr<ProgressSilence> process_silence = std::make_shared<ProgressSilence>();
  o.silence = process_silence;
  o.enabled = g_enabled;
  o.in_place = ::isatty(STDERR_FILENO) != 0;
  if (o.in_place) {
    o.first_s = 1;
    o.every_s = 0.25;
  }
  return o;
}

void Progress::set_enabled(bool enabled) { g_enabled = enabled; }

Progress::Progress(std::string label, std::size_t total)
    : Progress(std::move(label), total, ProgressOutput::standard()) {}

Progress::Progress(std::string label, std::size_t total, ProgressOutput output)
    : label_(std::move(label)), total_(total), output_(std::move(output)) {
  if (!output_.clock) output_.clock = steady_seconds;
  if (!output_.write) output_.write = write_stderr;
  start_ = output_.clock();
  next_report_ = start_ + output_.first_s;
  if (output_.silence) {  // one first interval after the last line of any stage sharing the silence
    double last = std::numeric_limits<double>::quiet_NaN();
    output_.silence->last_line.compare_exchange_strong(last, start_);  // the first stage: its own start
    last = output_.silence->last_line.load();
    next_report_ = std::min(start_ + output_.first_s, std::max(last + output_.first_s, start_));
  }
  uncaught_ = std::uncaught_exceptions();
}

Progress::~Progress() {
  if (std::uncaught_exceptions() <= uncaught_) {
    finish();
    return;
  }
  // The stage failed: no "done" line; the error message that follows starts on a line of its own.
  if (!output_.enabled) return;
  std::lock_guard lock(mutex_);
  if (!finished_ && reported_ && output_.in_place) output_.write("\n");
  finished_ = true;
}

double Progress::now() const { return output_.clock(); }

std::string Progress::format_duration(double seconds) {
  char buf[64];
  if (!(seconds >= 0)) seconds = 0;
  if (seconds < 9.95) {
    std::snprintf(buf, sizeof buf, "%.1f s", seconds);
  } else if (seconds < 119.5) {
    std::snprintf(buf, sizeof buf, "%.0f s", seconds);
  } else if (seconds < 7200) {
    const long s = std::lround(seconds);
    std::snprintf(buf, sizeof buf, "%ld min %02ld s", s / 60, s % 60);
  } else {
    const long m = std::lround(seconds / 60);
    std::snprintf(buf, sizeof buf, "%ld h %02ld min", m / 60, m % 60);
  }
  return buf;
}

std::string Progress::format(const std::string& label, std::size_t done, std::size_t total, double elapsed) {
  if (total == kUnknownTotal)
    return label + ": " + std::to_string(done) + " so far, " + format_duration(elapsed) + " elapsed";
  const double fraction = total > 0 ? std::min(1.0, double(done) / double(total)) : 1.0;
  const int percent = static_cast<int>(std::floor(100 * fraction));
  std::string text = label + " " + std::to_string(percent) + "% (" + std::to_string(done) + "/" +
                     std::to_string(total) + "), " + format_duration(elapsed) + " elapsed";
  if (done > 0 && done < total)
    text += ", about " + format_duration(elapsed * double(total - done) / double(done)) + " left";
  return text;
}

void Progress::report(const std::string& text, bool last) {
  // Called with mutex_ held.
  const std::string line = "radwalk: " + text;
  if (output_.in_place) {
    std::string shown = "\r" + line;
    if (line.size() < drawn_length_) shown.append(drawn_length_ - line.size(), ' ');
    drawn_length_ = std::max(drawn_length_, line.size());  // what the screen shows after the padding
    output_.write(last ? shown + "\n" : shown);
  } else {
    output_.write(line + "\n");
  }
  reported_ = true;
  if (output_.silence) output_.silence->last_line = now();
}

void Progress::advance(std::size_t done_items) {
  throw_if_cancelled();  // every long stage reports here (core/cancellation.h)
  const std::size_t done = done_ += done_items;
  if (!output_.enabled) return;
  const double t = now();
  if (t < next_report_.load()) return;
  std::unique_lock lock(mutex_, std::try_to_lock);
  if (!lock.owns_lock() || finished_ || t < next_report_.load()) return;
  next_report_ = t + output_.every_s;
  report(format(label_, done, total_, t - start_), false);
}

void Progress::set_total(std::size_t total) { total_ = total; }

void Progress::finish() {
  if (!output_.enabled) return;
  std::lock_guard lock(mutex_);
  if (finished_) return;
  finished_ = true;
  const double elapsed = now() - start_;
  if (reported_ || elapsed >= output_.first_s) report(label_ + " done in " + format_duration(elapsed), true);
}

}  // namespace radwalk
