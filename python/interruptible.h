#pragma once
// Ctrl-C during a long computation of the module: the computation runs on a worker thread while the calling
// thread, with the GIL released, wakes every kSignalPollInterval to take the GIL and run Python's signal handlers
// (PyErr_CheckSignals). When a handler raises (SIGINT's default handler raises KeyboardInterrupt), the
// computation is asked to stop (core/cancellation.h), the worker is joined, and the handler's exception is
// raised in place of a result. Python runs signal handlers only in the main thread, so a call made from another
// thread is not interrupted by Ctrl-C itself; it stops with KeyboardInterrupt only when a main-thread call's
// Ctrl-C cancels the computations in flight (the request is process-wide).
//
// The time from the signal to the exception: at most one poll interval to notice it, plus the time the
// computation takes to reach its next poll (one chunk of work: core/cancellation.h lists the polls).
#include <pybind11/pybind11.h>

#include <chrono>
#include <functional>
#include <optional>
#include <type_traits>
#include <utility>

namespace radwalk::python {

namespace py = pybind11;

constexpr std::chrono::milliseconds kSignalPollInterval{50};

// Runs work() on a worker thread (it must not touch Python objects: it runs without the GIL) as described above.
// Called with the GIL held. work's exceptions are rethrown here (the module's translators map them); Cancelled
// becomes KeyboardInterrupt; a signal handler's exception is raised as py::error_already_set.
void run_interruptible(const std::function<void()>& work);

// run_interruptible for a function returning a value: returns it.
template <class Work>
auto interruptible(Work&& work) {
  using R = std::invoke_result_t<Work&>;
  if constexpr (std::is_void_v<R>) {
    run_interruptible(work);
  } else {
    std::optional<R> result;
    run_interruptible([&] { result.emplace(work()); });
    return std::move(*result);
  }
}

}  // namespace radwalk::python
