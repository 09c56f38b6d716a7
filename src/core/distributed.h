#pragma once
// The processes of one run (MPI), behind a small interface that is the only user of mpi.h (distributed.cpp).
//
// A run is one process unless radwalk was built with MPI (CMake option RADWALK_MPI) *and* launched by an MPI
// launcher (mpirun, mpiexec, srun), recognised by its environment (OMPI_COMM_WORLD_SIZE, PMI_SIZE, PMIX_RANK):
// a plain `radwalk ...` or the Python module never initialises MPI and behaves as before. Every rank runs the
// whole program on the same inputs; the stages that cost (form factors, walks, path tracing, sweeps) give each
// rank a contiguous block of their fixed work items and put the results together in item order, so the result is
// bit-identical to one process (docs/ARCHITECTURE.md, convention 6, over processes). What is not distributed is
// computed by every rank alike. Only rank 0 writes files (core/atomic_write.h) and prints (docs/scaling.md,
// "Over MPI").
//
// Every function here is collective over all ranks (each rank calls it, in the same order) unless it says
// otherwise, and is called from the main thread only (MPI_THREAD_FUNNELED). With one process they are no-ops or
// copies.
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <string>
#include <type_traits>
#include <vector>

#include "core/check.h"
#include "core/error.h"
#include "core/parallel.h"

namespace radwalk::distributed {

// This process's rank in [0, size()), and the number of processes (1 without MPI or without a launcher).
int rank();
int size();
inline bool is_root() { return rank() == 0; }
// True when this build can run over MPI (RADWALK_MPI).
bool built_with_mpi();

// A contiguous range [begin, end) of work items.
struct Range {
  std::size_t begin = 0, end = 0;
  std::size_t size() const { return end - begin; }
};

// Block partition of [0, n) over `ranks` ranks: consecutive blocks whose sizes differ by at most one (the first
// n mod ranks take one more). Not collective; block(n, r) is for this run's size().
Range block(std::size_t n, int r, int ranks);
inline Range block(std::size_t n, int r) { return block(n, r, size()); }
inline Range my_block(std::size_t n) { return block(n, rank()); }
// Contiguous blocks of [0, weights.size()) with about equal total weight each (e.g. rays per row): block r begins
// at the first item whose preceding weights sum to at least W r / ranks (W the total; equal blocks when W is 0), so
// each block's weight is within the largest single weight of W / ranks. Not collective.
std::vector<Range> weighted_blocks(const std::vector<double>& weights, int ranks);
inline std::vector<Range> weighted_blocks(const std::vector<double>& weights) { return weighted_blocks(weights, size()); }

// Raw collectives on bytes (count elements of elem_size bytes each; fewer than 2^31 elements per rank, any size).
// Broadcast `bytes` bytes at data from rank 0 to every rank.
void broadcast_bytes(void* data, std::size_t bytes);
// In place: rank r has filled elements [ranges[r].begin, ranges[r].end) of data; afterwards every rank has all.
void allgather_in_place(void* data, std::size_t elem_size, const std::vector<Range>& ranges);
// Every rank's `mine` (count elements) concatenated in rank order, on every rank (allgatherv).
std::vector<char> allgather_concat_bytes(const void* mine, std::size_t count, std::size_t elem_size);
// Point to point with rank 0 (not collective): a rank r > 0 sends, rank 0 receives from r (messages from one
// rank arrive in the order sent).
void send_to_root(const std::vector<char>& bytes);
void send_to_root(const void* data, std::size_t bytes);
std::vector<char> receive_from(int r);
// Receives the next message of rank r into data, which has room for exactly `bytes` bytes (RADWALK_CHECK: the
// message is that long), with no copy in between.
void receive_into(int r, void* data, std::size_t bytes);
// The largest value over all ranks.
double max_over_ranks(double value);
// The bytes this rank has received from other ranks so far (every collective and message above; not collective).
std::uint64_t bytes_received();

// Typed forms.
template <class T>
void broadcast(std::vector<T>& v) {
  static_assert(std::is_trivially_copyable_v<T>);
  if (size() == 1) return;
  std::uint64_t n = v.size();
  broadcast_bytes(&n, sizeof n);
  v.resize(n);
  broadcast_bytes(v.data(), n * sizeof(T));
}
// Every rank filled items[ranges[r]] for its own r; afterwards every rank holds all of them.
template <class T>
void share_blocks(std::vector<T>& items, const std::vector<Range>& ranges) {
  if (size() == 1) return;
  allgather_in_place(items.data(), sizeof(T), ranges);
}
// Concatenation of every rank's `mine` in rank order, on every rank.
template <class T>
std::vector<T> allgather_concat(const std::vector<T>& mine) {
  if (size() == 1) return mine;
  const std::vector<char> bytes = allgather_concat_bytes(mine.data(), mine.size(), sizeof(T));
  std::vector<T> out(bytes.size() / sizeof(T));
  if (!bytes.empty()) std::memcpy(static_cast<void*>(out.data()), bytes.data(), bytes.size());
  return out;
}
// Runs f() on every rank; when it threw an InputError on any rank, every rank throws the InputError of the lowest
// such rank (with the same one-line message), so that a refusal that one rank alone finds (a bad entry in its own
// rows of a file) ends the job at once with that line from rank 0 instead of leaving the others in the next
// collective. Other exceptions propagate as they are (Session::finish). With one process it is f().
template <class F>
void agree_on_input_error(F&& f) {
  if (size() == 1) {
    f();
    return;
  }
  std::string mine;
  try {
    f();
  } catch (const InputError& e) {
    mine = e.what();
    if (mine.empty()) mine = "input error";
  }
  const std::vector<std::uint64_t> lengths = allgather_concat(std::vector<std::uint64_t>{mine.size()});
  std::size_t first = 0;
  while (first < lengths.size() && lengths[first] == 0) ++first;
  if (first == lengths.size()) return;  // no rank refused
  // The ranks before `first` sent nothing, so its message opens the concatenation.
  const std::vector<char> all = allgather_concat(std::vector<char>(mine.begin(), mine.end()));
  throw InputError(std::string(all.data(), static_cast<std::size_t>(lengths[first])));
}

// The blocks of every rank for n items (block(n, r) for r = 0 .. R-1). Not collective.
std::vector<Range> all_blocks(std::size_t n, int ranks);
inline std::vector<Range> all_blocks(std::size_t n) { return all_blocks(n, size()); }

// Serialisation of work items' results into bytes (plain values and arrays of doubles), for the ordered reduce.
class ByteWriter {
 public:
  explicit ByteWriter(std::vector<char>& out) : out_(out) {}
  template <class T>
  void put(const T& value) {
    static_assert(std::is_trivially_copyable_v<T>);
    put_bytes(&value, sizeof value);
  }
  void put_bytes(const void* data, std::size_t bytes) {
    const auto* p = static_cast<const char*>(data);
    out_.insert(out_.end(), p, p + bytes);
  }

 private:
  std::vector<char>& out_;
};
class ByteReader {
 public:
  explicit ByteReader(const std::vector<char>& in) : at_(in.data()), end_(in.data() + in.size()) {}
  template <class T>
  T get() {
    T value;
    get_bytes(&value, sizeof value);
    return value;
  }
  void get_bytes(void* data, std::size_t bytes) {
    RADWALK_CHECK(static_cast<std::size_t>(end_ - at_) >= bytes);  // the sender wrote what the reader reads
    std::memcpy(data, at_, bytes);
    at_ += bytes;
  }
  bool done() const { return at_ == end_; }

 private:
  const char* at_;
  const char* end_;
};

// The distributed form of ordered_reduce (core/parallel.h): chunks [0, chunks) are cut into one contiguous block
// per rank; each rank maps its block (ordered_reduce, at most in_flight parts alive); rank 0 combines its own parts
// as they come, then receives every other rank's parts (serialised by save(part, writer) in chunk order, read back
// by load(reader)) and combines them, rank by rank: combine sees every chunk's part in chunk order, exactly as with
// one process, so a floating-point result is bit-identical by construction. combine runs on rank 0 only; the
// caller broadcasts what the other ranks need. With one process it is ordered_reduce.
// Memory: a rank r > 0 keeps its serialised parts until rank 0 takes them (the size of its parts).
template <class Map, class Combine, class Save, class Load>
void distributed_ordered_reduce(std::size_t chunks, std::size_t in_flight, Map&& map, Combine&& combine,
                                Save&& save, Load&& load) {
  if (size() == 1) {
    ordered_reduce(chunks, in_flight, map, combine);
    return;
  }
  const Range mine = my_block(chunks);
  auto local = [&](std::size_t c) { return map(mine.begin + c); };
  if (is_root()) {
    ordered_reduce(mine.size(), in_flight, local, combine);
    for (int r = 1; r < size(); ++r) {
      const Range theirs = block(chunks, r);
      const std::vector<char> bytes = receive_from(r);
      ByteReader in(bytes);
      for (std::size_t c = theirs.begin; c < theirs.end; ++c) combine(load(in));
      RADWALK_CHECK(in.done());  // every part sent was combined
    }
  } else {
    std::vector<char> bytes;
    ByteWriter out(bytes);
    using Part = std::invoke_result_t<decltype(local)&, std::size_t>;
    ordered_reduce(mine.size(), in_flight, local, [&](Part part) { save(part, out); });
    send_to_root(bytes);
  }
}

// The processes of a run: MPI_Init when launched by an MPI launcher (in an MPI build), nothing otherwise. On ranks
// other than 0, stdout goes to /dev/null and stderr to a private temporary file (only rank 0 prints progress,
// notes, warnings, errors and the summary lines; a rank's last line is kept for finish).
// One per program, made first in main.
class Session {
 public:
  Session(int& argc, char**& argv);
  ~Session();
  Session(const Session&) = delete;
  Session& operator=(const Session&) = delete;

  // The end of the run with this rank's exit code; returns the exit code of the whole job. Every rank's code
  // is combined (the largest wins) on a communicator of its own, so a rank that fails while the others are inside
  // a collective never makes them wait for ever: a failing rank that is not joined by all the others within
  // kErrorWaitSeconds prints its error line (rank 0 has already; rank r > 0 as "rank r: radwalk: error: ...") and
  // aborts the job with its code (MPI_Abort). When
  // every rank failed, rank 0 has printed its one-line error, the others print nothing, and all exit with the code.
  int finish(int code);

  static constexpr double kErrorWaitSeconds = 10;
};

}  // namespace radwalk::distributed
