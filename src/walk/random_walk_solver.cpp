#include "walk/random_walk_solver.h"

#include <algorithm>
#include <memory>
#include <cmath>
#include <limits>
#include <optional>
#include <array>
#include <sstream>
#include <string>
#include <tuple>
#include <vector>

#include <tbb/enumerable_thread_specific.h>

#include "core/check.h"
#include "core/distributed.h"
#include "core/error.h"
#include "core/moments.h"
#include "core/parallel.h"
#include "core/progress.h"
#include "core/timer.h"
#include "solve/convergence.h"
#include "solve/spectral_radius.h"
#include "walk/matrix_kernel.h"
#include "walk/ray_kernel.h"
#include "walk/walk_estimators.h"
#include "walk/walk_lockstep.h"
#include "walk/walk_variance.h"
#include "walk/control_variate.h"
#include "walk/direct_light.h"
#include "walk/replicates.h"
#include "walk/stochastic_jacobi.h"
#include "walk/stratified_emission.h"

namespace radwalk {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// Gathering work layout, a function of (m target patches, walks per patch) only.
//   segments  each target patch's walks cut into `per_patch` segments of `chunk` walks (the last one shorter),
//             at least 64 walks each, max(1, 512 / m) segments per patch aimed at (so one per patch from 512
//             target patches up): a segment's moments are the sums of its walks' scores in walk order, and a
//             patch's moments merge its segments in order, so the segments fix the result's bits;
//   tasks     `per_task` consecutive segments (in the order patch, segment) traced together, about
//             total / 512 walks, at least kTaskWalks and at most kMaxTaskWalks (unless one segment has more;
//             a task's scores are stored until its segments are summed): their walks share the lockstep
//             lanes, so that the ray packets stay full when a patch has only a few walks (at 10^6 patches and 3
//             walks each, one task per patch ran packets of 3 rays and paid a task per 3 walks). How segments
//             are grouped into tasks changes no value: each walk draws only from its own stream.
struct GatherLayout {
  long chunk = 0;             // walks per segment
  std::size_t per_patch = 0;  // segments per target patch
  std::size_t per_task = 0;   // segments per task
};
constexpr long kTaskWalks = 1024, kMaxTaskWalks = 65536;
GatherLayout gather_layout(std::size_t m, long walks) {
  const long per_patch_target = std::max<long>(1, 512 / static_cast<long>(std::max<std::size_t>(m, 1)));
  const long chunk = std::max<long>(64, (walks + per_patch_target - 1) / per_patch_target);
  const auto per_patch = static_cast<std::size_t>((walks + chunk - 1) / chunk);
  // Walks per segment, on average (>= 1), and per task.
  const long segment_walks = std::max<long>(1, walks / static_cast<long>(per_patch));
  const long total = static_cast<long>(m) * walks;
  const long task_walks = std::clamp<long>((total + 511) / 512, kTaskWalks, kMaxTaskWalks);
  return {chunk, per_patch, static_cast<std::size_t>(std::max<long>(1, task_walks / segment_walks))};
}

// Shooting chunk size: at least 1024 particles, about 256 chunks in all.
long shoot_chunk(long particles) { return std::max<long>(1024, (particles + 255) / 256); }

struct RunResult {
  PatchRgb B, var, se;
  WalkCounters counters;
};

// One segment of a gathering task: walks [begin, end) of target patch `patch`, walk w on the stream
// (seed, gather_walk, patch, w).
struct GatherSegment {
  std::size_t patch = 0;
  long begin = 0, end = 0;
  std::size_t first = 0;  // the task's number of its walk `begin`
};

// The walks of consecutive segments, K::kLanes of them in lockstep (walk_lockstep.h) whatever segment they come
// from; out[s] = the moments of segment s, its walks' scores added in walk order once all have finished, so they
// depend neither on the lane count nor on the other segments of the task.
template <class Estimator, TransitionKernel K>
void gather_walks(const K& kernel, const typename Estimator::Tables& tables,
                  const std::vector<GatherSegment>& segments, std::uint64_t seed, Moments* out,
                  WalkCounters& counters) {
  using Walk = typename Estimator::template Walk<K>;
  if (segments.empty()) return;
  const GatherSegment& last = segments.back();
  const std::size_t count = last.first + static_cast<std::size_t>(last.end - last.begin);
  // Walk w of the task: the segment holding it (a cursor: run_lockstep asks for the walks in order).
  std::size_t at = 0;
  auto segment_of = [&](std::size_t w) -> const GatherSegment& {
    while (at > 0 && w < segments[at].first) --at;
    while (at + 1 < segments.size() && w >= segments[at + 1].first) ++at;
    return segments[at];
  };
  auto make = [&](std::size_t w) {
    const GatherSegment& s = segment_of(w);
    const RngFamily streams(seed, StreamDomain::gather_walk, s.patch);  // walk b of the patch: stream b
    return Walk(kernel, tables, s.patch, streams.stream(static_cast<std::uint64_t>(s.begin) + (w - s.first)));
  };
  auto step = [](Walk& walk, std::size_t, PatchIndex j) { walk.advance(j); };
  std::vector<Rgb> X(count, Rgb::Zero());
  run_lockstep(kernel, count, K::kLanes, make, step, [&](std::size_t w, const Walk& walk) { X[w] = walk.score(); },
               counters);
  for (std::size_t s = 0; s < segments.size(); ++s) {
    ShiftedSums sums;
    const std::size_t b = segments[s].first, e = b + static_cast<std::size_t>(segments[s].end - segments[s].begin);
    for (std::size_t w = b; w < e; ++w) sums.add(X[w]);
    out[s] = sums.moments();
  }
}

// Gathering: every target patch gets `walks` walks, cut into the segments of gather_layout, traced in tasks of
// consecutive segments; each patch's moments merge its segments' in segment order.
template <class Estimator, TransitionKernel K>
RunResult run_gather(const K& kernel, const std::vector<std::size_t>& targets, long walks, std::uint64_t seed,
                     Progress* progress) {
  const typename Estimator::Tables tables(kernel.tables());
  const std::size_t m = targets.size();
  const GatherLayout layout = gather_layout(m, walks);
  const std::size_t per_patch = layout.per_patch, per_task = layout.per_task;
  const std::size_t segments = m * per_patch, tasks = (segments + per_task - 1) / per_task;
  std::vector<Moments> parts(segments);
  std::vector<WalkCounters> task_counters(tasks);
  // Over MPI each rank runs a block of the tasks (their walks have their own streams), then all share the
  // segments' moments (the rank's segments are those of its tasks: consecutive) and the tasks' counters.
  const std::vector<distributed::Range> blocks = distributed::all_blocks(tasks);
  std::vector<distributed::Range> segment_blocks;
  for (const distributed::Range& b : blocks)
    segment_blocks.push_back({std::min(segments, b.begin * per_task), std::min(segments, b.end * per_task)});
  const distributed::Range mine = blocks[static_cast<std::size_t>(distributed::rank())];
  parallel_for(
      mine.size(),
      [&](std::size_t local) {
        const std::size_t task = mine.begin + local;
        const std::size_t first = task * per_task, last = std::min(segments, first + per_task);
        std::vector<GatherSegment> work;
        work.reserve(last - first);
        std::size_t walks_before = 0;
        for (std::size_t c = first; c < last; ++c) {
          GatherSegment s;
          s.patch = targets[c / per_patch];
          s.begin = static_cast<long>(c % per_patch) * layout.chunk;
          s.end = std::min(walks, s.begin + layout.chunk);
          s.first = walks_before;
          walks_before += static_cast<std::size_t>(s.end - s.begin);
          work.push_back(s);
        }
        gather_walks<Estimator>(kernel, tables, work, seed, parts.data() + first, task_counters[task]);
        if (progress) progress->advance(last - first);
      },
      1);
  distributed::share_blocks(parts, segment_blocks);
  distributed::share_blocks(task_counters, blocks);
  // Merge per patch in segment order.
  const auto N = static_cast<Eigen::Index>(kernel.size());
  RunResult r;
  r.B.setConstant(N, 3, kNaN);
  r.var.setConstant(N, 3, kNaN);
  r.se.setConstant(N, 3, kNaN);
  for (const WalkCounters& c : task_counters) r.counters += c;
  for (std::size_t t = 0; t < m; ++t) {
    Moments mom;
    for (std::size_t c = 0; c < per_patch; ++c) mom.merge(parts[t * per_patch + c]);
    const auto row = static_cast<Eigen::Index>(targets[t]);
    r.B.row(row) = mom.mean.transpose();
    r.var.row(row) = mom.variance().transpose();
    r.se.row(row) = mom.standard_error().transpose();
  }
  return r;
}

// One chunk's sums of the per-particle scores Y_j and Y_j^2 (radiosity units) over the patches j its particles
// scored on, by increasing j: a part of O(work) size, not O(N), in a plain layout (vectors of PODs) that can be
// sent between processes. Its value depends only on the chunk's particles.
struct ShootEntry {
  std::uint64_t patch;
  double sum[3], sum2[3];
};
struct ShootPart {
  std::vector<ShootEntry> entries;  // patch increasing, each patch once
  WalkCounters counters;
};

// A ShootPart as bytes and back, for the distributed ordered reduce (core/distributed.h): every rank's parts are
// combined on rank 0 in chunk order. The part is sparse already (the rows its particles scored on), so the bytes
// grow with the scores of the chunk, not with N.
void save_shoot_part(const ShootPart& part, distributed::ByteWriter& out) {
  out.put(static_cast<std::uint64_t>(part.entries.size()));
  out.put_bytes(part.entries.data(), part.entries.size() * sizeof(ShootEntry));
  out.put(part.counters);
}
ShootPart load_shoot_part(distributed::ByteReader& in, std::uint64_t N) {
  ShootPart part;
  part.entries.resize(in.get<std::uint64_t>());
  in.get_bytes(part.entries.data(), part.entries.size() * sizeof(ShootEntry));
  for (const ShootEntry& e : part.entries) RADWALK_CHECK(e.patch < N);  // a row of the sender's part
  part.counters = in.get<WalkCounters>();
  return part;
}

// Adds a part's sums into the N x 3 totals: row j += the entry of j (its sum divided by `divisor`) (rows without an entry are unchanged,
// which is what adding a dense part's zero rows did, bit for bit).
void add_part(const ShootPart& part, PatchRgb& sum, PatchRgb* sum2, double divisor = 1.0) {
  for (const ShootEntry& e : part.entries) {
    const auto row = static_cast<Eigen::Index>(e.patch);
    for (Eigen::Index c = 0; c < 3; ++c) {
      sum(row, c) += e.sum[c] / divisor;  // x / 1 = x exactly
      if (sum2) (*sum2)(row, c) += e.sum2[c];
    }
  }
}

// One score of a particle in a lockstep batch, recorded to be summed in particle order.
struct ShootScore {
  std::uint32_t particle, j;  // particle - begin, patch
  Rgb power;
};
// A patch and a power or a per-particle score Y_j.
struct PatchValue {
  std::uint32_t patch;
  Rgb value;
};
// Per-thread buffers of shoot_particles, reused by every chunk the thread runs (no fresh pages per chunk); all
// O(work of one chunk), none O(N).
struct ShootScratch {
  std::vector<ShootScore> scores, sorted;  // the lockstep path's scores, as recorded and by particle
  std::vector<std::size_t> first;          // counting-sort offsets
  std::vector<PatchValue> touched;         // one particle's power per patch, in first-touch order
  std::vector<PatchValue> Y, Y_sorted;     // the chunk's Y_j, particle by particle, then by patch; sort scratch
};
using ShootScratches = tbb::enumerable_thread_specific<ShootScratch>;

// `sorted` = the scores sorted by particle (0 .. count-1), each particle's in their recorded order (a counting
// sort; `first` is its work array).
void sort_by_particle(const std::vector<ShootScore>& scores, std::size_t count, std::vector<ShootScore>& sorted,
                      std::vector<std::size_t>& first) {
  first.assign(count + 1, 0);
  for (const ShootScore& s : scores) ++first[s.particle + 1];
  for (std::size_t w = 0; w < count; ++w) first[w + 1] += first[w];
  sorted.resize(scores.size());
  for (const ShootScore& s : scores) sorted[first[s.particle]++] = s;
}

// Sorts `values` by patch, stably (equal patches keep their order: particle order), by LSD radix passes of 8
// bits, as many as patch indices below patch_count need (2 up to 65536 patches); `buffer` is the passes' scratch.
// O(values) per pass with no allocation once the per-thread buffers have grown, where std::stable_sort
// allocated a buffer per chunk and cost a quarter of the shooting time at a few hundred patches.
void sort_by_patch(std::vector<PatchValue>& values, std::vector<PatchValue>& buffer, std::size_t patch_count) {
  buffer.resize(values.size());
  const std::size_t largest = patch_count > 0 ? patch_count - 1 : 0;
  for (unsigned shift = 0; shift < 32 && (largest >> shift) != 0; shift += 8) {
    std::array<std::size_t, 257> first{};
    for (const PatchValue& v : values) ++first[((v.patch >> shift) & 0xffu) + 1];
    for (std::size_t b = 0; b < 256; ++b) first[b + 1] += first[b];
    for (const PatchValue& v : values) buffer[first[(v.patch >> shift) & 0xffu]++] = v;
    values.swap(buffer);
  }
}

// Particles [begin, end), K::kLanes of them in lockstep. With one lane each particle's scores are summed per
// patch as it finishes; with more, they are recorded, put in particle order (each particle's in its own step
// order) and then summed the same way, so the sums do not depend on the lane count. Each finished particle
// appends its Y_j (its power per patch over A_j) to the chunk's list; the list is then sorted by patch, stably, so
// that each patch's Y_j are summed in particle order, the order a dense per-patch accumulator would add them in
// (the same bits). Work and memory O(steps of the chunk) (plus a sort), whatever N.
// make(w) returns particle w (0 .. count-1) of the chunk, born.
template <class Estimator, TransitionKernel K, class Make>
ShootPart shoot_particles(const K& kernel, const Eigen::VectorXd& area, std::size_t count, ShootScratch& s,
                          Make&& make) {
  using Particle = typename Estimator::template Particle<K>;
  ShootPart part;
  s.Y.clear();
  // One particle's power per patch, summed in scoring order (a particle scores on few patches: a linear search).
  auto accumulate = [&](std::size_t j, const Rgb& power) {
    const auto patch = static_cast<std::uint32_t>(j);
    for (PatchValue& t : s.touched)
      if (t.patch == patch) {
        t.value += power;
        return;
      }
    s.touched.push_back({patch, power});
  };
  auto flush = [&] {
    for (const PatchValue& t : s.touched) s.Y.push_back({t.patch, Rgb(t.value / area(static_cast<Eigen::Index>(t.patch)))});
    s.touched.clear();
  };
  if constexpr (K::kLanes == 1) {
    // One lane: particles run to the end in order, each flushed at once.
    run_singly(
        kernel, count, make, [&](Particle& particle, std::size_t, PatchIndex j) { particle.advance(j, accumulate); },
        [&](std::size_t, const Particle&) { flush(); }, part.counters);
  } else {
    // Lanes: scores recorded with their particle, then taken particle by particle in order.
    std::vector<ShootScore>& scores = s.scores;
    scores.clear();
    run_lockstep(
        kernel, count, K::kLanes, make,
        [&](Particle& particle, std::size_t w, PatchIndex j) {
          particle.advance(j, [&](std::size_t jj, const Rgb& power) {
            scores.push_back({static_cast<std::uint32_t>(w), static_cast<std::uint32_t>(jj), power});
          });
        },
        [](std::size_t, const Particle&) {}, part.counters);
    sort_by_particle(scores, count, s.sorted, s.first);
    const std::vector<ShootScore>& sorted = s.sorted;
    for (std::size_t k = 0; k < sorted.size(); flush())
      for (const std::uint32_t w = sorted[k].particle; k < sorted.size() && sorted[k].particle == w; ++k)
        accumulate(sorted[k].j, sorted[k].power);
  }
  // The chunk's sums per patch, by increasing patch: each patch's Y_j in particle order (a stable sort).
  sort_by_patch(s.Y, s.Y_sorted, kernel.size());
  part.entries.reserve(s.Y.size());  // at most one entry per Y
  for (std::size_t k = 0; k < s.Y.size();) {
    const std::uint32_t j = s.Y[k].patch;
    Rgb sum = Rgb::Zero(), sum2 = Rgb::Zero();
    for (; k < s.Y.size() && s.Y[k].patch == j; ++k) {
      const Rgb& Y = s.Y[k].value;
      sum += Y;
      sum2 += Y * Y;
    }
    ShootEntry e;
    e.patch = j;
    for (int c = 0; c < 3; ++c) {
      e.sum[c] = sum[c];
      e.sum2[c] = sum2[c];
    }
    part.entries.push_back(e);
  }
  return part;
}

// Shooting: `particles` particles in fixed chunks, run in parallel, merged in chunk order (ordered_reduce).
template <class Estimator, TransitionKernel K>
RunResult run_shoot(const K& kernel, const RadiosityProblem& problem, long particles, std::uint64_t seed,
                    Progress* progress) {
  const auto N = static_cast<Eigen::Index>(kernel.size());
  const ShootSource source = make_shoot_source(problem.E, problem.area);
  const typename Estimator::Tables tables(kernel.tables());
  RunResult r;
  PatchRgb sum = PatchRgb::Zero(N, 3), sum2 = PatchRgb::Zero(N, 3);
  if (source.power > 0) {
    const long chunk = shoot_chunk(particles);
    const auto chunks = static_cast<std::size_t>((particles + chunk - 1) / chunk);
    // Parts and per-thread buffers are O(chunk work), never O(N). Over MPI: ranks take blocks of chunks, rank 0
    // combines all in chunk order (core/distributed.h); solve() broadcasts the result.
    ShootScratches scratches;
    distributed::distributed_ordered_reduce(
        chunks, 2 * static_cast<std::size_t>(std::max(1, active_threads())),
        [&](std::size_t c) {
          const long begin = static_cast<long>(c) * chunk;
          const long end = std::min(particles, begin + chunk);
          const RngFamily streams(seed, StreamDomain::shoot_particle, 0);  // particle w: stream w
          auto make = [&](std::size_t w) {
            return typename Estimator::template Particle<K>(kernel, tables, source,
                                                            streams.stream(static_cast<std::uint64_t>(begin) + w));
          };
          ShootPart part = shoot_particles<Estimator>(kernel, problem.area, static_cast<std::size_t>(end - begin),
                                                      scratches.local(), make);
          if (progress) progress->advance(1);
          return part;
        },
        [&](const ShootPart& part) {
          add_part(part, sum, &sum2);
          r.counters += part.counters;
        },
        save_shoot_part, [N](distributed::ByteReader& in) { return load_shoot_part(in, static_cast<std::uint64_t>(N)); });
  }
  // B = E + mean Y; per-particle variance from the power sums (clamped at 0 against rounding).
  const double n = static_cast<double>(particles);
  PatchRgb mean;
  std::tie(mean, r.var) = mean_and_variance(sum, sum2, n);
  r.B = problem.E + mean;
  r.se = (r.var / n).sqrt();
  return r;
}

// Sobol shooting (WalkSampler::sobol): R replicates (replicates.h), each an independent estimate
//   B_r = E [+ D_r] + (1 / n_r) sum_w Y_w,
// with the particles of stratified_emission.h shot from S = E (or from S = D_r, the direct light, when
// `direct` is given: they then carry the indirect light only); particle w of replicate r draws after its first
// ray from stream (seed, sobol_particle, r, w). B, B_se and var from the replicates (replicate_estimate).
template <class Estimator, TransitionKernel K>
RunResult run_shoot_sobol(const K& kernel, const RadiosityProblem& problem, const WalkOptions& options,
                          const ReplicateDirectLight& direct, Progress* progress) {
  const auto N = static_cast<Eigen::Index>(kernel.size());
  const typename Estimator::Tables tables(kernel.tables());
  const int R = options.replicates;
  RunResult r;
  // Per replicate: its base (E or E + D_r), its emission and its chunks; then all chunks of all replicates in one
  // parallel pass (fixed order: replicate, then chunk), each replicate's sums merged in chunk order.
  std::vector<PatchRgb> Bs(static_cast<std::size_t>(R));
  std::vector<StratifiedEmission> emissions;
  struct Chunk {
    int rep;
    long begin, end;
  };
  std::vector<Chunk> chunks;
  for (int rep = 0; rep < R; ++rep) {
    const long n = replicate_particles(options, rep);
    ReplicateStart start = replicate_start(problem.E, rep, direct, r.counters);
    Bs[static_cast<std::size_t>(rep)] = std::move(start.base);
    emissions.emplace_back(start.source, problem.area, n, options.seed, static_cast<std::uint64_t>(rep));
    const long chunk = shoot_chunk(n);
    for (long begin = 0; begin < n; begin += chunk)
      if (emissions.back().power() > 0) chunks.push_back({rep, begin, std::min(n, begin + chunk)});
      else if (progress) progress->advance(1);
  }
  ShootScratches scratches;
  distributed::distributed_ordered_reduce(  // over MPI: as in run_shoot
      chunks.size(), 2 * static_cast<std::size_t>(std::max(1, active_threads())),
      [&](std::size_t c) {
        const Chunk& ch = chunks[c];
        const StratifiedEmission& emission = emissions[static_cast<std::size_t>(ch.rep)];
        const RngFamily streams(options.seed, StreamDomain::sobol_particle, static_cast<std::uint64_t>(ch.rep));
        auto make = [&](std::size_t w) {
          const long particle = ch.begin + static_cast<long>(w);
          const std::size_t j = emission.patch_of(particle);
          return typename Estimator::template Particle<K>(kernel, tables, j, emission.weight(j),
                                                          streams.stream(static_cast<std::uint64_t>(particle)),
                                                          emission.first_uniforms(particle, j));
        };
        ShootPart part = shoot_particles<Estimator>(kernel, problem.area, static_cast<std::size_t>(ch.end - ch.begin),
                                                    scratches.local(), make);
        if (progress) progress->advance(1);
        return part;
      },
      [&, c = std::size_t{0}](const ShootPart& part) mutable {
        const int rep = chunks[c++].rep;
        add_part(part, Bs[static_cast<std::size_t>(rep)], nullptr,
                 static_cast<double>(replicate_particles(options, rep)));
        r.counters += part.counters;
      },
      save_shoot_part, [N](distributed::ByteReader& in) { return load_shoot_part(in, static_cast<std::uint64_t>(N)); });
  ReplicateEstimate estimate = replicate_estimate(Bs, options.particles);
  r.B = std::move(estimate.B);
  r.se = std::move(estimate.se);
  r.var = std::move(estimate.var);
  return r;
}

// Over MPI: rank 0 holds the combined result (distributed_ordered_reduce); every rank gets it.
void share_run_result(RunResult& r) {
  if (distributed::size() == 1) return;
  for (PatchRgb* a : {&r.B, &r.var, &r.se}) {
    std::uint64_t rows = static_cast<std::uint64_t>(a->rows());
    distributed::broadcast_bytes(&rows, sizeof rows);
    a->resize(static_cast<Eigen::Index>(rows), 3);
    distributed::broadcast_bytes(a->data(), sizeof(double) * static_cast<std::size_t>(a->size()));
  }
  distributed::broadcast_bytes(&r.counters, sizeof r.counters);
}

// The one dispatch from the method to its estimator (walk_estimators.h).
template <TransitionKernel K>
RunResult run(const K& kernel, const RadiosityProblem& problem, const WalkOptions& options, Progress* progress,
              const ReplicateDirectLight& direct) {
  if (options.sampler == WalkSampler::jacobi) {
    JacobiResult j = run_stochastic_jacobi(kernel, problem, options, direct);
    if (progress) progress->advance(static_cast<std::size_t>(options.replicates));
    RunResult r;
    r.B = std::move(j.estimate.B);
    r.se = std::move(j.estimate.se);
    r.var = std::move(j.estimate.var);
    r.counters = j.counters;
    return r;
  }
  return with_estimator(options.method, [&](auto method) {
    using Method = decltype(method);
    using Estimator = typename Method::Estimator;
    if constexpr (Method::kDirection == WalkDirection::gather) {
      std::vector<std::size_t> targets;
      if (options.patches.empty())
        for (std::size_t i = 0; i < problem.size(); ++i) targets.push_back(i);
      else
        for (int i : options.patches) targets.push_back(static_cast<std::size_t>(i));
      return run_gather<Estimator>(kernel, targets, options.walks_per_patch, options.seed, progress);
    } else if (options.sampler == WalkSampler::sobol) {
      return run_shoot_sobol<Estimator>(kernel, problem, options, direct, progress);
    } else {
      return run_shoot<Estimator>(kernel, problem, options.particles, options.seed, progress);
    }
  });
}

// Shooting: of the non-emitting patches that reflect (rho > 0 in some channel), how many got no score at all
// (B = E in every channel), and how many there are.
struct Reach {
  std::size_t unreached = 0, reflecting = 0;
};
Reach shooting_reach(const RadiosityProblem& problem, const PatchRgb& B) {
  Reach r;
  for (Eigen::Index k = 0; k < B.rows(); ++k) {
    if (problem.E.row(k).maxCoeff() > 0 || !(problem.rho.row(k).maxCoeff() > 0)) continue;
    ++r.reflecting;
    r.unreached += (B.row(k) == problem.E.row(k)).all();
  }
  return r;
}

// The exact variance (walk_variance.h) of the walks of B' from the shifted source E of the control variate
// (control_variate.h), which is B's. The dense algebra reads E from a problem, so this (at most
// kMaxTheoryPatches patches, beside its O(N^2) dense matrices) is the one place the problem is copied.
PatchRgb shifted_theoretical_variance(const RadiosityProblem& problem, const PatchRgb& E, const WalkOptions& options) {
  RadiosityProblem shifted = problem;
  shifted.E = E;
  return theoretical_variance(shifted, options, dense_radiosity(shifted));
}

Solution solve_unscaled(const RadiosityProblem& problem, const PatchSet* patches, const Visibility* visibility,
                        const WalkOptions& options, Progress* progress) {
  const std::size_t N = problem.size();
  check_walk_options(options, N);
  const bool gather = is_gathering(options.method);
  RADWALK_CHECK_EQ(static_cast<std::size_t>(problem.rho.rows()), N);  // the problem's arrays agree in size
  RADWALK_CHECK_EQ(static_cast<std::size_t>(problem.E.rows()), N);
  const bool F_stored = problem.F.rows() == static_cast<Eigen::Index>(N) && problem.F.cols() == problem.F.rows();
  // What each kernel needs from its caller (a caller's bug otherwise, not the user's).
  if (options.kernel == WalkKernel::matrix) RADWALK_CHECK(F_stored);  // the matrix kernel walks over an N x N F
  if (options.kernel == WalkKernel::ray) {
    RADWALK_CHECK(patches != nullptr && visibility != nullptr);  // the ray kernel traces the patches
    RADWALK_CHECK_EQ(patches->size(), N);
  }

  std::vector<double> p = survival_probabilities(problem.rho, options.survival);
  check_survival_probabilities(p, problem.rho, options.survival.rule);

  Solution sol;
  sol.method = std::string(method_name(options.method));

  if (F_stored) {
    const WalkConvergence convergence = check_walks_converge(problem, sol.method);
    sol.info["spectral_radius"] = convergence.radius.estimate;
    if (!convergence.refusal.empty()) {
      sol.status = SolveStatus::diverged;
      sol.message = convergence.refusal;
      return sol;
    }
  }

  // The constant control variate (control_variate.h): the walks estimate B' = B - c from the shifted source E',
  // which the kernel takes in place of problem.E (gathering only, check_walk_options: the shooting samplers read
  // their source from problem.E).
  ControlVariate cv;
  if (options.control_variate) {
    if (!F_stored)
      throw InputError("random walk: --control-variate needs the row sums of F, so F stored (--kernel matrix)");
    cv = constant_control_variate(problem);
    for (int c = 0; c < 3; ++c) sol.info[std::string("control_variate_") + "rgb"[c]] = cv.c(c);
  }
  const PatchRgb& source = options.control_variate ? cv.E_shifted : problem.E;

  std::optional<Progress> own_progress;
  if (!progress && options.progress)
    progress = &own_progress.emplace("random walks (" + sol.method + ")", walk_work_items(options, N));
  const Timer timer;
  RunResult r;
  // The direct light of the Sobol sampler: exact from F (matrix kernel) or by shadow rays (ray kernel).
  const long shadow_rays = direct_shadow_rays(options, N);
  ReplicateDirectLight direct;
  if (options.direct_light && options.kernel == WalkKernel::matrix)
    direct = [&](std::uint64_t, WalkCounters&) { return exact_direct_light(problem); };
  else if (options.direct_light)
    direct = [&](std::uint64_t rep, WalkCounters& counters) {
      DirectLight d = options.direct_sampled
                          ? estimate_direct_light(problem, *patches, *visibility, shadow_rays / options.replicates,
                                                  options.seed, rep)
                          : estimate_visible_direct_light(problem, *patches, *visibility,
                                                          shadow_rays / options.replicates, options.seed, rep);
      counters.steps += d.rays;
      return std::move(d.D);
    };
  if (options.kernel == WalkKernel::matrix) {
    const MatrixKernel kernel(problem, source, std::move(p), direction_of(options.method));
    r = run(kernel, problem, options, progress, direct);
  } else {
    const RayKernel kernel(problem, source, *patches, *visibility, std::move(p));
    r = run(kernel, problem, options, progress, direct);
  }
  if (options.control_variate) r.B.rowwise() += cv.c.transpose();  // B = c + B'; B' 's variance is B's
  share_run_result(r);  // over MPI: rank 0's result on every rank
  sol.seconds = timer.seconds();
  if (own_progress) own_progress->finish();
  sol.B = std::move(r.B);
  sol.var = std::move(r.var);
  sol.B_se = std::move(r.se);
  sol.walks = total_walks(options, N);
  sol.steps = r.counters.steps;
  sol.info["escapes"] = static_cast<double>(r.counters.escapes);
  sol.info["back_hits"] = static_cast<double>(r.counters.back_hits);
  if (gather)
    sol.info["walks_per_patch"] = static_cast<double>(options.walks_per_patch);
  else
    sol.info["particles"] = static_cast<double>(options.particles);
  if (options.sampler != WalkSampler::random) sol.info["replicates"] = options.replicates;
  if (options.direct_light && options.kernel == WalkKernel::ray)
    sol.info["shadow_rays_per_patch"] = static_cast<double>(shadow_rays / options.replicates * options.replicates);
  double power = 0;
  for (Eigen::Index i = 0; i < problem.area.size(); ++i) power += problem.area(i) * problem.E.row(i).sum();
  sol.info["emitted_power"] = power;

  // Finite-variance check, and the exact variance where asked for.
  std::ostringstream msg;
  msg << sol.method << " (" << kernel_name(options.kernel) << " kernel, survival "
      << survival_name(options.survival.rule) << "): "
      << (gather ? options.walks_per_patch : options.particles) << (gather ? " walks per patch" : " particles");
  if (options.sampler != WalkSampler::random)
    msg << ", " << sampler_name(options.sampler) << " sampler, " << options.replicates << " replicates"
        << (options.direct_light ? ", direct light apart" : "");
  if (!gather) {
    const Reach reach = shooting_reach(problem, sol.B);
    sol.info["unreached_patches"] = static_cast<double>(reach.unreached);
    sol.info["reflecting_patches"] = static_cast<double>(reach.reflecting);
    if (too_few_particles(sol))
      msg << "; WARNING: " << reach.unreached << " of the " << reach.reflecting
          << " non-emitting reflecting patches got no particle's score, so their B = 0 only says that too few "
             "particles were shot (use more particles)";
  }
  if (F_stored) {
    const VarianceCheck check = check_finite_variance(problem, options);
    sol.info["variance_radius"] = check.radius;
    if (!check.finite())
      msg << "; WARNING: spectral radius of K = H^2/P is " << check.radius
          << " >= 1, so the per-walk variance is infinite and the error bars are meaningless"
          << " (choose a survival probability closer to rho, e.g. --survival analog)";
  } else {
    sol.info["variance_radius"] = kNaN;
  }
  if (options.theory) {
    if (options.kernel != WalkKernel::matrix)
      msg << "; no exact variance for the ray kernel (its F is not stored)";
    else if (N > kMaxTheoryPatches)
      msg << "; exact variance skipped (" << N << " patches > " << kMaxTheoryPatches << ")";
    else if (options.control_variate)
      sol.var_theory = shifted_theoretical_variance(problem, cv.E_shifted, options);
    else
      sol.var_theory = theoretical_variance(problem, options, dense_radiosity(problem));
  }
  sol.message = msg.str();
  sol.status = SolveStatus::converged;
  return sol;
}

// Scale before squaring (core/moments.h): with an emission far from 1 (beyond 2^200 or below 2^-200) the walks run
// on a copy of the problem with E / s, s = moment_scale(max E) a power of two, and B, B_se, the control variate and
// the emitted power are multiplied back by s, var and var_theory by s^2. Every estimator is linear in E and draws
// its random numbers from ratios of E, so the result is s times that of E / s bit for bit, and it is infinite only
// where the quantity itself does not fit a double (a per-walk variance above 1.8e308). Otherwise (the common case)
// the problem is used as it is.
Solution solve(const RadiosityProblem& problem, const PatchSet* patches, const Visibility* visibility,
               const WalkOptions& options, Progress* progress) {
  const double s = moment_scale(problem.max_emission());
  if (s == 1) return solve_unscaled(problem, patches, visibility, options, progress);
  RadiosityProblem scaled = problem;
  scaled.E /= s;
  Solution sol = solve_unscaled(scaled, patches, visibility, options, progress);
  sol.B *= s;
  sol.B_se *= s;
  sol.var *= s * s;
  sol.var_theory *= s * s;
  for (auto& [key, value] : sol.info)
    if (key == "emitted_power" || key.rfind("control_variate_", 0) == 0) value *= s;
  return sol;
}

}  // namespace

WalkConvergence check_walks_converge(const RadiosityProblem& problem, const std::string& method) {
  WalkConvergence c;
  c.radius = estimate_spectral_radius(problem);
  const SpectralRadius& radius = c.radius;
  if (radius.lower >= 1.0 - kRadiusOneTolerance || radius.estimate >= 1.0 - kRadiusOneTolerance) {
    std::ostringstream why;
    why << method << " refused: the spectral radius of diag(rho) F is " << radius.estimate << " (channel "
        << radius.channel << ", max rho " << radius.max_rho << ", max row sum of F " << radius.max_row_sum
        << ") >= 1, so B = E + diag(rho) F B has no finite solution for the walks to estimate; check that "
           "reflectances are below 1 and that rows of F sum to at most 1";
    c.refusal = why.str();
  }
  return c;
}

long direct_shadow_rays(const WalkOptions& options, std::size_t patch_count) {
  if (!options.direct_light) return 0;
  const long R = options.replicates;
  if (options.shadow_rays > 0) return std::max(R, options.shadow_rays);
  return std::max(16 * R, options.particles / (2 * static_cast<long>(std::max<std::size_t>(patch_count, 1))));
}

std::size_t walk_work_items(const WalkOptions& options, std::size_t patch_count) {
  if (is_gathering(options.method)) {
    const std::size_t m = options.patches.empty() ? patch_count : options.patches.size();
    return m * gather_layout(m, options.walks_per_patch).per_patch;
  }
  if (options.sampler == WalkSampler::jacobi) return static_cast<std::size_t>(options.replicates);
  if (options.sampler == WalkSampler::sobol) {
    std::size_t items = 0;
    for (int r = 0; r < options.replicates; ++r) {
      const long n = replicate_particles(options, r), chunk = shoot_chunk(n);
      items += static_cast<std::size_t>((n + chunk - 1) / chunk);
    }
    return items;
  }
  const long chunk = shoot_chunk(options.particles);
  return static_cast<std::size_t>((options.particles + chunk - 1) / chunk);
}

bool too_few_particles(const Solution& solution) {
  const auto unreached = solution.info.find("unreached_patches"), reflecting = solution.info.find("reflecting_patches");
  return unreached != solution.info.end() && reflecting != solution.info.end() &&
         2 * unreached->second > reflecting->second;
}

Solution solve_random_walk(const RadiosityProblem& problem, const PatchSet* patches, const Visibility* visibility,
                           const WalkOptions& options) {
  return solve(problem, patches, visibility, options, nullptr);
}

Solution solve_random_walk(const RadiosityProblem& problem, const PatchSet* patches, const Visibility* visibility,
                           const WalkOptions& options, Progress& progress) {
  return solve(problem, patches, visibility, options, &progress);
}

}  // namespace radwalk
