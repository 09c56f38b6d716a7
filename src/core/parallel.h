#pragma once
// One parallel-for helper and deterministic reductions (docs/ARCHITECTURE.md, convention 6: deterministic parallelism).
//
// Work [0, n) is cut into fixed chunks of `chunk` items that do not depend on the thread count; chunks run in
// parallel (TBB) and per-chunk results are combined in chunk order, so floating-point sums are bit-identical
// for 1 or many threads. Every chunk first polls the cancellation request (core/cancellation.h: throws Cancelled,
// which TBB carries to the calling thread after cancelling the other chunks).
#include <tbb/blocked_range.h>
#include <tbb/global_control.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_pipeline.h>
#include <tbb/partitioner.h>

#include <algorithm>
#include <cstddef>
#include <memory>
#include <type_traits>
#include <utility>
#include <vector>

#include "core/cancellation.h"

namespace radwalk {

// The most threads a caller may ask for (more only costs memory: every TBB thread has its own stack).
constexpr int kMaxThreads = 1024;

// Throws InputError unless 0 <= threads <= kMaxThreads (0: all cores), naming `what` (e.g. "--threads").
void check_thread_count(long long threads, const char* what);

// Limits TBB to `threads` worker threads while alive; threads <= 0 means all cores.
class ThreadLimit {
 public:
  explicit ThreadLimit(int threads) {
    if (threads > 0)
      control_ = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism,
                                                       static_cast<std::size_t>(threads));
  }

 private:
  std::unique_ptr<tbb::global_control> control_;
};

// Number of threads TBB will use now.
int active_threads();

// Calls body(begin, end) for the chunks [k*chunk, min(n, (k+1)*chunk)), in parallel.
template <class Body>
void parallel_chunks(std::size_t n, std::size_t chunk, Body&& body) {
  if (n == 0) return;
  chunk = std::max<std::size_t>(chunk, 1);
  const std::size_t chunks = (n + chunk - 1) / chunk;
  tbb::parallel_for(
      tbb::blocked_range<std::size_t>(0, chunks, 1),
      [&](const tbb::blocked_range<std::size_t>& r) {
        for (std::size_t k = r.begin(); k != r.end(); ++k) {
          throw_if_cancelled();
          body(k * chunk, std::min(n, (k + 1) * chunk));
        }
      },
      tbb::simple_partitioner());
}

// Calls body(i) for every i in [0, n), in parallel chunks.
template <class Body>
void parallel_for(std::size_t n, Body&& body, std::size_t chunk = 64) {
  parallel_chunks(n, chunk, [&](std::size_t b, std::size_t e) {
    for (std::size_t i = b; i < e; ++i) body(i);
  });
}

// Deterministic reduction: map(begin, end) -> T per fixed chunk, then combine(acc, part) in chunk order.
template <class T, class Map, class Combine>
T deterministic_reduce(std::size_t n, std::size_t chunk, T identity, Map&& map, Combine&& combine) {
  chunk = std::max<std::size_t>(chunk, 1);
  const std::size_t chunks = (n + chunk - 1) / chunk;
  std::vector<T> parts(chunks, identity);
  parallel_chunks(n, chunk, [&](std::size_t b, std::size_t e) { parts[b / chunk] = map(b, e); });
  T acc = identity;
  for (auto& p : parts) acc = combine(std::move(acc), p);
  return acc;
}

// Deterministic reduction in bounded memory: part = map(c) for the chunks c = 0 .. chunks-1 in parallel, each
// handed to combine(part) in chunk order, with at most `in_flight` parts alive at once (for parts too large
// to keep one per chunk). A TBB pipeline (serial input, parallel map, serial in-order combine): a thread that
// finishes a chunk takes the next one while earlier chunks still run, so no thread waits at a barrier for the
// slowest chunk of a group.
template <class Map, class Combine>
void ordered_reduce(std::size_t chunks, std::size_t in_flight, Map&& map, Combine&& combine) {
  using Part = std::invoke_result_t<Map&, std::size_t>;
  std::size_t next = 0;
  tbb::parallel_pipeline(std::max<std::size_t>(in_flight, 1),
                         tbb::make_filter<void, std::size_t>(tbb::filter_mode::serial_in_order,
                                                             [&](tbb::flow_control& control) -> std::size_t {
                                                               if (next < chunks) return next++;
                                                               control.stop();
                                                               return chunks;
                                                             }) &
                             tbb::make_filter<std::size_t, Part>(tbb::filter_mode::parallel,
                                                                 [&](std::size_t c) {
                                                                   throw_if_cancelled();
                                                                   return map(c);
                                                                 }) &
                             tbb::make_filter<Part, void>(tbb::filter_mode::serial_in_order,
                                                          [&](Part part) { combine(std::move(part)); }));
}

}  // namespace radwalk
