#pragma once
// Cooperative cancellation of long computations (the Python module's Ctrl-C): one process-wide request flag that
// the long loops poll where they hand out work, so that a request stops the computation in flight within about one
// work item.
//
// Where it is polled: before every chunk of parallel_chunks, deterministic_reduce and ordered_reduce
// (core/parallel.h), every 1024 walks of a chunk of random walks (walk/walk_lockstep.h), and in Progress::advance (core/progress.h: every form-factor row block, iterative-solver
// sweep, LU factorisation, Matrix Market read). So the form factors, the walks, the path tracer and the iterative
// solvers stop within one chunk; a single long step with no chunk inside (one dense LU, one dense variance) runs
// to its end first.
//
// A cancelled computation throws Cancelled out of the parallel loop (TBB cancels the other chunks and rethrows it
// in the calling thread); no result is returned and nothing is half-written (writers are not cancelled). The flag
// stays set until clear_cancellation(): whoever requested it clears it once its computation has stopped. The CLI
// never requests it (its signals are handled by core/atomic_write.h).
#include <stdexcept>

namespace radwalk {

// Thrown by throw_if_cancelled() when a cancellation was requested. Not an input, numerical or internal error.
class Cancelled : public std::runtime_error {
 public:
  Cancelled() : std::runtime_error("cancelled") {}
};

// Asks every computation in flight in this process to stop at its next poll. Async-signal-safe (a lock-free
// atomic store).
void request_cancellation();
// Withdraws the request (computations started afterwards run to their end).
void clear_cancellation();
// Whether a cancellation is requested now.
bool cancellation_requested();
// Throws Cancelled when a cancellation is requested; otherwise costs one relaxed atomic load.
void throw_if_cancelled();

}  // namespace radwalk
