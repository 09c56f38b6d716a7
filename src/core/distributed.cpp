#include "core/distributed.h"

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <thread>

#ifdef RADWALK_MPI
#define OMPI_SKIP_MPICXX 1  // the C interface only
#define MPICH_SKIP_MPICXX 1
#include <mpi.h>
#endif

namespace radwalk::distributed {

namespace {

int g_rank = 0, g_size = 1;
std::uint64_t g_received = 0;  // bytes_received()

#ifdef RADWALK_MPI
bool g_mpi = false;  // MPI_Init was called by the Session
MPI_Comm g_work = MPI_COMM_NULL;     // the collectives of the computation
MPI_Comm g_control = MPI_COMM_NULL;  // the end-of-run agreement only (Session::finish)
// MPI counts are ints: large buffers go in pieces of at most this many bytes.
constexpr std::size_t kPiece = std::size_t{1} << 30;

// The launchers' environment: Open MPI's mpirun, PMI-1/2 (MPICH, srun --mpi=pmi2), PMIx (srun --mpi=pmix).
bool launched_by_mpi() {
  for (const char* name : {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE", "PMIX_RANK"})
    if (std::getenv(name)) return true;
  return false;
}

int g_saved_stderr = -1;  // the real stderr of a rank > 0 (its fd 2 is a temporary file)

// Copies the last line this rank printed (its error: main prints it last) from its temporary stderr to the real
// stderr, prefixed "rank R: ".
void print_captured() {
  if (g_saved_stderr < 0) return;
  std::fflush(stderr);
  if (::lseek(2, 0, SEEK_SET) < 0) return;
  std::string text;
  char buf[4096];
  for (ssize_t got; (got = ::read(2, buf, sizeof buf)) > 0;) text.append(buf, static_cast<std::size_t>(got));
  while (!text.empty() && text.back() == '\n') text.pop_back();
  const std::size_t start = text.rfind('\n');
  const std::string line = "rank " + std::to_string(g_rank) + ": " +
                           text.substr(start == std::string::npos ? 0 : start + 1) + "\n";
  if (::write(g_saved_stderr, line.data(), line.size()) < 0) return;
}
#endif

}  // namespace

int rank() { return g_rank; }
std::uint64_t bytes_received() { return g_received; }
int size() { return g_size; }

bool built_with_mpi() {
#ifdef RADWALK_MPI
  return true;
#else
  return false;
#endif
}

Range block(std::size_t n, int r, int ranks) {
  const auto R = static_cast<std::size_t>(ranks), k = static_cast<std::size_t>(r);
  const std::size_t base = n / R, extra = n % R;
  const std::size_t lo = base * k + std::min(k, extra);
  return {lo, lo + base + (k < extra ? 1 : 0)};
}

std::vector<Range> all_blocks(std::size_t n, int ranks) {
  std::vector<Range> out;
  for (int r = 0; r < ranks; ++r) out.push_back(block(n, r, ranks));
  return out;
}

std::vector<Range> weighted_blocks(const std::vector<double>& weights, int ranks) {
  const std::size_t n = weights.size();
  double total = 0;
  for (double w : weights) total += w;
  if (!(total > 0)) return all_blocks(n, ranks);  // nothing to weigh: equal blocks
  std::vector<std::size_t> starts(static_cast<std::size_t>(ranks) + 1, n);
  starts[0] = 0;
  double before = 0;  // sum of weights[0 .. i)
  int r = 1;
  for (std::size_t i = 0; i < n && r < ranks; ++i) {
    while (r < ranks && before >= total * r / ranks) starts[static_cast<std::size_t>(r++)] = i;
    before += weights[i];
  }
  std::vector<Range> out;
  for (int k = 0; k < ranks; ++k) out.push_back({starts[static_cast<std::size_t>(k)], starts[static_cast<std::size_t>(k) + 1]});
  return out;
}

#ifdef RADWALK_MPI

void broadcast_bytes(void* data, std::size_t bytes) {
  if (g_size == 1) return;
  auto* p = static_cast<char*>(data);
  if (g_rank != 0) g_received += bytes;
  for (std::size_t at = 0; at < bytes; at += kPiece)
    MPI_Bcast(p + at, static_cast<int>(std::min(kPiece, bytes - at)), MPI_BYTE, 0, g_work);
}

void allgather_in_place(void* data, std::size_t elem_size, const std::vector<Range>& ranges) {
  if (g_size == 1) return;
  RADWALK_CHECK_EQ(ranges.size(), static_cast<std::size_t>(g_size));
  // Elements as one MPI type, so that counts are element counts (far below 2^31 for every caller).
  MPI_Datatype element;
  MPI_Type_contiguous(static_cast<int>(elem_size), MPI_BYTE, &element);
  MPI_Type_commit(&element);
  std::vector<int> counts, displacements;
  for (std::size_t k = 0; k < ranges.size(); ++k)
    if (static_cast<int>(k) != g_rank) g_received += ranges[k].size() * elem_size;
  for (const Range& r : ranges) {
    RADWALK_CHECK(r.end <= std::size_t{0x7fffffff});  // element counts fit an MPI int
    counts.push_back(static_cast<int>(r.size()));
    displacements.push_back(static_cast<int>(r.begin));
  }
  MPI_Allgatherv(MPI_IN_PLACE, 0, MPI_DATATYPE_NULL, data, counts.data(), displacements.data(), element, g_work);
  MPI_Type_free(&element);
}

std::vector<char> allgather_concat_bytes(const void* mine, std::size_t count, std::size_t elem_size) {
  std::vector<unsigned long long> counts(static_cast<std::size_t>(g_size));
  unsigned long long my_count = count;
  MPI_Allgather(&my_count, 1, MPI_UNSIGNED_LONG_LONG, counts.data(), 1, MPI_UNSIGNED_LONG_LONG, g_work);
  std::vector<Range> ranges;
  std::size_t total = 0;
  for (unsigned long long c : counts) {
    ranges.push_back({total, total + static_cast<std::size_t>(c)});
    total += static_cast<std::size_t>(c);
  }
  std::vector<char> out(total * elem_size);
  if (count > 0) std::memcpy(out.data() + ranges[static_cast<std::size_t>(g_rank)].begin * elem_size, mine, count * elem_size);
  allgather_in_place(out.data(), elem_size, ranges);
  return out;
}

void send_to_root(const std::vector<char>& bytes) { send_to_root(bytes.data(), bytes.size()); }

void send_to_root(const void* data, std::size_t bytes) {
  const auto* p = static_cast<const char*>(data);
  unsigned long long n = bytes;
  MPI_Send(&n, 1, MPI_UNSIGNED_LONG_LONG, 0, 1, g_work);
  for (std::size_t at = 0; at < bytes; at += kPiece)
    MPI_Send(p + at, static_cast<int>(std::min(kPiece, bytes - at)), MPI_BYTE, 0, 2, g_work);
}

void receive_into(int r, void* data, std::size_t bytes) {
  unsigned long long n = 0;
  MPI_Recv(&n, 1, MPI_UNSIGNED_LONG_LONG, r, 1, g_work, MPI_STATUS_IGNORE);
  RADWALK_CHECK_EQ(static_cast<std::size_t>(n), bytes);  // the sender sent what the receiver expects
  g_received += bytes;
  auto* p = static_cast<char*>(data);
  for (std::size_t at = 0; at < bytes; at += kPiece)
    MPI_Recv(p + at, static_cast<int>(std::min(kPiece, bytes - at)), MPI_BYTE, r, 2, g_work, MPI_STATUS_IGNORE);
}

std::vector<char> receive_from(int r) {
  unsigned long long n = 0;
  MPI_Recv(&n, 1, MPI_UNSIGNED_LONG_LONG, r, 1, g_work, MPI_STATUS_IGNORE);
  std::vector<char> bytes(static_cast<std::size_t>(n));
  g_received += bytes.size();
  for (std::size_t at = 0; at < bytes.size(); at += kPiece)
    MPI_Recv(bytes.data() + at, static_cast<int>(std::min(kPiece, bytes.size() - at)), MPI_BYTE, r, 2, g_work,
             MPI_STATUS_IGNORE);
  return bytes;
}

double max_over_ranks(double value) {
  if (g_size == 1) return value;
  // NaN wins (a non-finite residual anywhere is non-finite): MPI_MAX would not propagate it.
  double v[2] = {value != value ? 0.0 : value, value != value ? 1.0 : 0.0}, out[2];
  MPI_Allreduce(v, out, 2, MPI_DOUBLE, MPI_MAX, g_work);
  return out[1] > 0 ? std::numeric_limits<double>::quiet_NaN() : out[0];
}

Session::Session(int& argc, char**& argv) {
  if (!launched_by_mpi()) return;
  int provided = 0;
  MPI_Init_thread(&argc, &argv, MPI_THREAD_FUNNELED, &provided);
  g_mpi = true;
  MPI_Comm_dup(MPI_COMM_WORLD, &g_work);
  MPI_Comm_dup(MPI_COMM_WORLD, &g_control);
  MPI_Comm_rank(g_work, &g_rank);
  MPI_Comm_size(g_work, &g_size);
  if (g_rank != 0) {
    // Only rank 0 prints; a rank's own messages are kept for Session::finish.
    std::fflush(stderr);
    // Nor its standard output (the command's summary lines).
    std::fflush(stdout);
    const int null = ::open("/dev/null", O_WRONLY | O_CLOEXEC);
    if (null >= 0) {
      ::dup2(null, 1);
      ::close(null);
    }
    FILE* captured = std::tmpfile();
    if (captured) {
      g_saved_stderr = ::dup(2);
      ::dup2(::fileno(captured), 2);
    }
  }
}

Session::~Session() {
  if (!g_mpi) return;
  MPI_Comm_free(&g_work);
  MPI_Comm_free(&g_control);
  MPI_Finalize();
  g_mpi = false;
}

int Session::finish(int code) {
  if (!g_mpi) return code;
  std::fflush(stderr);
  // [largest code, R - (lowest failing rank)] over all ranks.
  int mine[2] = {code, code != 0 ? g_size - g_rank : 0}, all[2] = {0, 0};
  MPI_Request request;
  MPI_Iallreduce(mine, all, 2, MPI_INT, MPI_MAX, g_control, &request);
  if (code == 0) {
    // The others may still be working (rank 0 writing the outputs): wait as long as they take, without spinning
    // a core that they may share.
    for (int done = 0; !done; std::this_thread::sleep_for(std::chrono::milliseconds(1)))
      MPI_Test(&request, &done, MPI_STATUS_IGNORE);
  } else {
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(kErrorWaitSeconds);
    for (int done = 0;;) {
      MPI_Test(&request, &done, MPI_STATUS_IGNORE);
      if (done) break;
      if (std::chrono::steady_clock::now() > deadline) {
        // The others are stuck in the computation without this rank: say what happened here and end the job.
        // (Rank 0 printed its error already.)
        if (g_rank != 0) print_captured();
        MPI_Abort(MPI_COMM_WORLD, code);
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(5));
    }
  }
  const int failing = all[1] > 0 ? g_size - all[1] : -1;
  if (failing == g_rank && g_rank != 0) print_captured();  // rank 0 succeeded: the lowest failing rank says why
  return all[0];
}

#else  // one process: nothing to exchange

void broadcast_bytes(void*, std::size_t) {}
void allgather_in_place(void*, std::size_t, const std::vector<Range>&) {}
std::vector<char> allgather_concat_bytes(const void* mine, std::size_t count, std::size_t elem_size) {
  const auto* p = static_cast<const char*>(mine);
  return std::vector<char>(p, p + count * elem_size);
}
void send_to_root(const std::vector<char>&) { RADWALK_CHECK(false); }  // one process has no other rank
void send_to_root(const void*, std::size_t) { RADWALK_CHECK(false); }
void receive_into(int, void*, std::size_t) { RADWALK_CHECK(false); }
std::vector<char> receive_from(int) {
  RADWALK_CHECK(false);
  return {};
}
double max_over_ranks(double value) { return value; }
Session::Session(int&, char**&) {}
Session::~Session() {}
int Session::finish(int code) { return code; }

#endif

}  // namespace radwalk::distributed
