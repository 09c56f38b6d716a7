#pragma once
// Progress of a long stage on stderr, for every stage that can take more than a few seconds (form factors, walks,
// solves, path tracing, reading F). Silenced by Progress::set_enabled(false) (--quiet).
//
// One report reads
//     radwalk: form factors 42% (1234/2938), 12 s elapsed, about 16 s left
// and the last one
//     radwalk: form factors done in 23 s
// How often, by where stderr goes (ProgressOutput::standard()):
//  - a terminal: one line redrawn in place ('\r') every 0.25 s from the first second on;
//  - anything else (a file, a pipe, a CI log): plain lines, one every 5 s (RADWALK_PROGRESS_INTERVAL=S sets S
//    seconds), the first after one interval.
// Either way a stage that ends before its first report prints nothing, not even the "done" line, unless it took
// longer than that first interval (a stage whose only work item is long). The stages of a run share their silence
// (ProgressSilence): a stage's first report is due one first interval after the last line any of them printed (or
// after the first stage's start), not after its own start, so that a run of stages each too short to report alone
// still prints a line every few seconds (a target step on a 139,808-patch city block: form factors 4 s, a solve
// 1 s, an error propagation 5 s; 12 s without a line before). Reports are made by advance() (and finish()), in
// whichever thread gets there first: nothing is printed while no work item completes.
#include <atomic>
#include <cstddef>
#include <functional>
#include <limits>
#include <memory>
#include <mutex>
#include <string>

namespace radwalk {

// When the stages sharing it last printed a line (seconds of their clock; NaN until the first stage starts, whose
// start is then taken).
struct ProgressSilence {
  std::atomic<double> last_line{std::numeric_limits<double>::quiet_NaN()};
};

// Where and how often a Progress reports.
struct ProgressOutput {
  bool enabled = true;
  bool in_place = false;  // redraw one terminal line ('\r') instead of printing lines
  double first_s = 5;     // no report before this many seconds
  double every_s = 5;     // then at most one report per this many seconds
  std::function<double()> clock;                  // seconds from a fixed origin; empty: a steady clock
  std::function<void(const std::string&)> write;  // receives the text to print; empty: stderr
  // Shared by the stages of a run (standard(): the process's own, on the steady clock); null: each stage's first
  // report first_s after its own start.
  std::shared_ptr<ProgressSilence> silence;

  // What Progress(label, total) uses: disabled after set_enabled(false); in place when stderr is a terminal;
  // otherwise lines every 5 s, or every RADWALK_PROGRESS_INTERVAL seconds when that variable holds a number > 0;
  // the process's silence shared by every stage.
  static ProgressOutput standard();
  // Plain lines every `interval` seconds, the first after one interval, given to `write` and timed by `clock`
  // (empty: stderr, a steady clock), whatever stderr is: for callers that collect the reports (and tests).
  static ProgressOutput lines(double interval, std::function<double()> clock = {},
                              std::function<void(const std::string&)> write = {});
};

class Progress {
 public:
  // `label` names the stage ("form factors"), `total` the number of work items.
  Progress(std::string label, std::size_t total);
  Progress(std::string label, std::size_t total, ProgressOutput output);
  ~Progress();  // finish(), or, while an exception unwinds the stage, only the end of a line drawn in place
  Progress(const Progress&) = delete;
  Progress& operator=(const Progress&) = delete;

  // `done_items` more items are complete; reports when a report is due. Thread-safe.
  void advance(std::size_t done_items);
  // Replaces the total, for stages whose length is an estimate that improves as they run (iterative solvers);
  // kUnknownTotal while there is none: the reports then read "LABEL: DONE so far, T elapsed".
  void set_total(std::size_t total);
  static constexpr std::size_t kUnknownTotal = std::numeric_limits<std::size_t>::max();
  // The "done" line, if anything was reported or the stage took longer than the first interval; once.
  void finish();

  // Global switch (--quiet): Progress objects made afterwards by Progress(label, total) report nothing.
  static void set_enabled(bool enabled);

  // "LABEL P% (DONE/TOTAL), T elapsed, about R left" (no estimate before the first item is done); "LABEL: DONE so
  // far, T elapsed" when the total is kUnknownTotal.
  static std::string format(const std::string& label, std::size_t done, std::size_t total, double elapsed);
  // A duration for people: "3.2 s", "42 s", "3 min 05 s", "2 h 07 min".
  static std::string format_duration(double seconds);

 private:
  double now() const;
  void report(const std::string& text, bool last);

  std::string label_;
  std::atomic<std::size_t> total_;
  std::atomic<std::size_t> done_{0};
  ProgressOutput output_;
  double start_ = 0;
  std::atomic<double> next_report_{0};
  std::mutex mutex_;
  std::size_t drawn_length_ = 0;  // in place: length of the line on screen
  int uncaught_ = 0;  // std::uncaught_exceptions() at construction
  bool reported_ = false;
  bool finished_ = false;
};

}  // namespace radwalk
