#include "interruptible.h"

#include <condition_variable>
#include <exception>
#include <mutex>
#include <thread>

#include "core/cancellation.h"

namespace radwalk::python {

void run_interruptible(const std::function<void()>& work) {
  std::mutex mutex;
  std::condition_variable finished;
  bool done = false;
  std::exception_ptr error;
  std::thread worker([&] {
    try {
      work();
    } catch (...) {
      error = std::current_exception();
    }
    {
      std::lock_guard lock(mutex);
      done = true;
    }
    finished.notify_all();
  });
  // Steps: wait for the worker a poll interval at a time without the GIL; between waits run the signal handlers.
  std::optional<py::error_already_set> raised;
  try {
    for (;;) {
      {
        py::gil_scoped_release release;
        std::unique_lock lock(mutex);
        if (finished.wait_for(lock, kSignalPollInterval, [&] { return done; })) break;
      }
      if (PyErr_CheckSignals() != 0) {
        raised.emplace();  // fetches the handler's exception (KeyboardInterrupt for SIGINT's default handler)
        request_cancellation();
        break;
      }
    }
  } catch (...) {
    request_cancellation();  // never leave a joinable worker behind
    raised.reset();
    {
      py::gil_scoped_release release;
      worker.join();
    }
    clear_cancellation();
    throw;
  }
  {
    py::gil_scoped_release release;
    worker.join();
  }
  if (raised) {
    clear_cancellation();
    throw std::move(*raised);
  }
  // The module's translators map work's exceptions (Cancelled, when another thread's Ctrl-C stopped this
  // computation too, to KeyboardInterrupt).
  if (error) std::rethrow_exception(error);
}

}  // namespace radwalk::python
