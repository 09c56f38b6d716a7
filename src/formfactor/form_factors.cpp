#include "formfactor/form_factors.h"

#include <algorithm>
#include <cstring>
#include <cmath>
#include <limits>
#include <numeric>
#include <string>

#include "core/check.h"
#include "core/distributed.h"
#include "core/error.h"
#include "core/morton.h"
#include "core/parallel.h"
#include "core/progress.h"
#include "core/rng.h"
#include "core/sampling.h"
#include "core/sobol.h"
#include "formfactor/form_factor_rows.h"
#include "patch/patch_point_sampler.h"
#include "visibility/ray_offset.h"

namespace radwalk {
namespace {

constexpr std::size_t kBlockRays = std::size_t(1) << 24;  // row entries (min(rays, N) per row) per assembly block
constexpr std::size_t kBatch = 64;                        // rays per Visibility::intersect batch
constexpr double kBelowOne = 0x1.fffffffffffffp-1;
constexpr std::uint32_t kMaxStrataSide = 1024;  // at most 2^20 stratified rays per patch; the rest are uniform

void check_options(const FormFactorOptions& o) {
  const auto bad = [](const std::string& what) { return InputError(locate("form factor options", 0, -1, what)); };
  if (o.rays_per_patch < 1 || o.rays_per_patch > long(std::numeric_limits<std::uint32_t>::max()))
    throw bad("rays_per_patch must be in [1, 2^32-1], got " + std::to_string(o.rays_per_patch));
  if (!std::isfinite(o.rays_per_area) || o.rays_per_area < 0)
    throw bad("rays_per_area must be finite and >= 0, got " + std::to_string(o.rays_per_area));
  if (o.min_rays < 1 || o.min_rays > long(std::numeric_limits<std::uint32_t>::max()))
    throw bad("min_rays must be in [1, 2^32-1], got " + std::to_string(o.min_rays));
}

// Scratch space of one worker, reused across the rows of a chunk.
struct RowScratch {
  std::vector<Ray> rays = std::vector<Ray>(kBatch);
  std::vector<Hit> hits = std::vector<Hit>(kBatch);
  std::vector<std::int32_t> targets, sort_buffer;  // front-hit patches of the row's rays not yet counted
  std::vector<std::int32_t> run_cols, merged_cols;  // the row's (column, count) runs so far, columns increasing
  std::vector<std::uint32_t> run_counts, merged_counts;
  std::vector<std::uint32_t> permutation;         // origin stratum (row << 16 | column) per direction stratum
};

struct RowResult {
  std::uint32_t nnz = 0, escaped = 0, back_hits = 0;
};

// sample_cosine_hemisphere (Malley's method) with the angle in single precision: the ray is traced in single
// precision anyway, and sincosf costs about half of sincos, which was the largest sampling cost.
Vec3 cosine_direction(double u1, double u2) {
  const double r = std::sqrt(u1);
  const float phi = float(2.0 * kPi * u2);
  const double c = std::cos(phi), s = std::sin(phi);
  return {r * c, r * s, std::sqrt(std::max(0.0, 1.0 - u1))};
}

// Sorts values in [0, 2^(8 * passes)) by LSD radix sort on bytes (std::sort for short arrays).
void sort_indices(std::vector<std::int32_t>& v, std::vector<std::int32_t>& tmp, int passes) {
  if (v.size() < 64) {
    std::sort(v.begin(), v.end());
    return;
  }
  tmp.resize(v.size());
  for (int p = 0; p < passes; ++p) {
    std::uint32_t count[257] = {};
    const int shift = 8 * p;
    for (auto x : v) ++count[((std::uint32_t(x) >> shift) & 255u) + 1];
    for (int k = 0; k < 256; ++k) count[k + 1] += count[k];
    for (auto x : v) tmp[count[(std::uint32_t(x) >> shift) & 255u]++] = x;
    v.swap(tmp);
  }
}

// Front hits are counted in chunks of at most kTargetChunk: a row's memory is bounded by the patch count, not by
// its ray count (O4: 16 bytes per ray of one patch made --rays 2e9 need 32 GB).
constexpr std::size_t kTargetChunk = std::size_t{1} << 20;

// Sorts s.targets, run-length encodes them and merges the runs into s.run_cols/s.run_counts (columns
// increasing); empties s.targets.
void count_targets(RowScratch& s, int sort_passes) {
  sort_indices(s.targets, s.sort_buffer, sort_passes);
  s.merged_cols.clear();
  s.merged_counts.clear();
  std::size_t a = 0, k = 0;
  while (a < s.run_cols.size() || k < s.targets.size()) {
    if (k == s.targets.size() || (a < s.run_cols.size() && s.run_cols[a] < s.targets[k])) {
      s.merged_cols.push_back(s.run_cols[a]);
      s.merged_counts.push_back(s.run_counts[a++]);
      continue;
    }
    std::size_t e = k + 1;
    while (e < s.targets.size() && s.targets[e] == s.targets[k]) ++e;
    std::uint32_t count = std::uint32_t(e - k);
    if (a < s.run_cols.size() && s.run_cols[a] == s.targets[k]) count += s.run_counts[a++];
    s.merged_cols.push_back(s.targets[k]);
    s.merged_counts.push_back(count);
    k = e;
  }
  s.run_cols.swap(s.merged_cols);
  s.run_counts.swap(s.merged_counts);
  s.targets.clear();
}

// Traces the n rays of patch i and writes its sorted (j, count) runs to cols/counts (room for min(n, N) entries:
// one per distinct patch hit).
RowResult trace_row(const PatchSet& ps, const Visibility& vis, const FormFactorOptions& opt, double eps,
                    int sort_passes, std::size_t i, std::uint32_t n, RowScratch& s, std::int32_t* cols,
                    std::uint32_t* counts) {
  Rng rng = stream(opt.seed, StreamDomain::form_factor_row, i);
  // 32-bit uniforms in [0, 1): ample resolution for single-precision rays, half the cost of Rng::uniform.
  const auto uniform = [&rng] { return rng.next_u32() * 0x1p-32; };
  const Frame frame(ps.normal[i]);
  const PatchPointSampler sampler(ps, i);
  const PatchRayOffset offset = patch_ray_offset(ps, i, eps);
  RowResult r;
  SobolShift shift;  // options.sobol: the row's digital shift
  if (opt.sobol)
    for (auto& w : shift.word) w = rng.next_u32();

  // Step 1: strata. m^2 jittered strata per square (m <= kMaxStrataSide), origin strata paired with direction
  // strata by a random permutation.
  const std::uint32_t m =
      opt.stratified && !opt.sobol ? std::min<std::uint32_t>(std::uint32_t(std::sqrt(double(n))), kMaxStrataSide) : 0;
  const std::uint32_t strata = m * m;
  const double inv_m = m ? 1.0 / m : 0.0;
  s.permutation.resize(strata);
  for (std::uint32_t row = 0, k = 0; row < m; ++row)
    for (std::uint32_t col = 0; col < m; ++col) s.permutation[k++] = row << 16 | col;
  for (std::uint32_t k = strata; k > 1; --k) std::swap(s.permutation[k - 1], s.permutation[rng.uniform_index(k)]);

  // Step 2: rays in batches; first hits sorted into front hits, back hits and escapes. A back hit is the absorbing
  // back of a one-sided face; a two-sided face's back is a patch of its own, reached from its front
  // (patch/patch_set.h, "Sides"), so rays from a back patch leave by its reversed normal like any other.
  s.targets.clear();
  s.run_cols.clear();
  s.run_counts.clear();
  std::uint32_t dir_row = 0, dir_col = 0;  // direction stratum of the current ray
  for (std::uint32_t base = 0; base < n; base += kBatch) {
    const std::size_t b = std::min<std::size_t>(kBatch, n - base);
    for (std::size_t k = 0; k < b; ++k) {
      const std::uint32_t ray = base + std::uint32_t(k);
      double u1, u2, u3, u4;
      if (opt.sobol) {
        const auto u = sobol_point(ray, shift);
        u1 = u[0], u2 = u[1], u3 = u[2], u4 = u[3];
      } else {
        u1 = uniform(), u2 = uniform(), u3 = uniform(), u4 = uniform();
      }
      if (ray < strata) {
        const std::uint32_t o = s.permutation[ray];
        u1 = std::min(((o >> 16) + u1) * inv_m, kBelowOne);
        u2 = std::min(((o & 0xffffu) + u2) * inv_m, kBelowOne);
        u3 = std::min((dir_row + u3) * inv_m, kBelowOne);
        u4 = std::min((dir_col + u4) * inv_m, kBelowOne);
        if (++dir_col == m) {
          dir_col = 0;
          ++dir_row;
        }
      }
      const Vec3 w = frame.to_world(cosine_direction(u3, u4));
      s.rays[k] = spawn_ray(offset, sampler.point(u1, u2), w);
    }
    vis.intersect(s.rays.data(), s.hits.data(), b);
    for (std::size_t k = 0; k < b; ++k) {
      const Hit& h = s.hits[k];
      if (h.missed())
        ++r.escaped;
      else if (!h.front)
        ++r.back_hits;
      else
        s.targets.push_back(h.patch);
    }
    if (s.targets.size() >= kTargetChunk) count_targets(s, sort_passes);
  }

  // Step 3: the counts per target patch (sorted, run-length encoded, merged chunk by chunk).
  count_targets(s, sort_passes);
  for (std::size_t k = 0; k < s.run_cols.size(); ++k) {
    cols[r.nnz] = s.run_cols[k];
    counts[r.nnz] = s.run_counts[k];
    ++r.nnz;
  }
  return r;
}

// Over MPI: every rank traced the rows of its block (row_blocks[rank]); afterwards every rank has every row's ray
// outcomes (escaped, back hits: O(N), for the diagnostics and warnings), each from the rank that traced it. F
// keeps its rows (form_factor_rows.h).
void share_ray_outcomes(const std::vector<distributed::Range>& row_blocks, FormFactors& out) {
  distributed::share_blocks(out.escaped, row_blocks);
  distributed::share_blocks(out.back_hits, row_blocks);
}

}  // namespace

std::uint32_t ray_count(const FormFactorOptions& options, double area) {
  check_options(options);
  if (options.rays_per_area <= 0) return std::uint32_t(options.rays_per_patch);
  const double n = std::max(double(options.min_rays), std::round(options.rays_per_area * area));
  if (!(n <= double(std::numeric_limits<std::uint32_t>::max())))
    throw InputError(locate("form factor options", 0, -1,
                            "rays_per_area x area = " + std::to_string(n) + " rays exceeds 2^32-1 for one patch"));
  return std::uint32_t(n);
}

FormFactorRow trace_form_factor_row(const PatchSet& ps, const Visibility& vis, const FormFactorOptions& options,
                                    std::size_t i) {
  check_options(options);
  RADWALK_CHECK(i < ps.size());
  int sort_passes = 0;
  for (std::size_t v = ps.size(); v > 0; v >>= 8) ++sort_passes;
  FormFactorRow row;
  row.rays = ray_count(options, ps.area[i]);
  const std::size_t room = std::min<std::size_t>(row.rays, ps.size());
  row.cols.resize(room);
  row.counts.resize(room);
  RowScratch scratch;
  const RowResult r = trace_row(ps, vis, options, ray_epsilon(ps), sort_passes, i, row.rays, scratch, row.cols.data(),
                                row.counts.data());
  row.cols.resize(r.nnz);
  row.counts.resize(r.nnz);
  row.escaped = r.escaped;
  row.back_hits = r.back_hits;
  return row;
}

FormFactors estimate_form_factors(const PatchSet& ps, const Visibility& vis, const FormFactorOptions& options) {
  FormFactors out = estimate_form_factor_rows(ps, vis, options);
  gather_whole_rows(out.F, out.row_blocks);  // over MPI: every rank gets every row
  return out;
}

FormFactors estimate_form_factor_rows(const PatchSet& ps, const Visibility& vis, const FormFactorOptions& options) {
  check_options(options);
  const std::size_t N = ps.size();
  if (N > std::size_t(std::numeric_limits<std::int32_t>::max()))
    throw InputError(locate(ps.source, 0, -1, "more than 2^31-1 patches"));
  FormFactors out;
  out.options = options;
  out.rays.resize(N);
  out.escaped.resize(N);
  out.back_hits.resize(N);
  for (std::size_t i = 0; i < N; ++i) out.rays[i] = ray_count(options, ps.area[i]);
  const double eps = ray_epsilon(ps);
  int sort_passes = 0;
  for (std::size_t v = N; v > 0; v >>= 8) ++sort_passes;

  // F's arrays are reserved once for the most non-zeros the rays can give, sum_i min(n_i, N) (capped at the
  // 32-bit index range): memory the rows never reach is never touched, so it costs address space only, and F
  // is never copied (a copy would double the peak). Blocks of consecutive rows with at most kBlockRays rays (or
  // one row) are traced into a working buffer with room for min(n_i, N) entries per row, and each row's runs
  // are then appended to F's arrays.
  // Over MPI each rank traces a block of rows with about equal rays (core/distributed.h); with one process, all.
  const std::vector<distributed::Range> row_blocks = distributed::weighted_blocks(
      distributed::size() == 1 ? std::vector<double>() : std::vector<double>(out.rays.begin(), out.rays.end()));
  const distributed::Range mine =
      distributed::size() == 1 ? distributed::Range{0, N} : row_blocks[static_cast<std::size_t>(distributed::rank())];
  std::size_t bound = 0;
  for (std::size_t i = mine.begin; i < mine.end; ++i) bound += std::min<std::size_t>(out.rays[i], N);
  const auto kMaxNonZeros = std::size_t(std::numeric_limits<std::int32_t>::max());
  out.F.resize(Eigen::Index(N), Eigen::Index(N));
  out.F.data().reserve(Eigen::Index(std::min(bound, kMaxNonZeros)));
  std::vector<std::uint32_t> nnz(N);
  std::vector<std::size_t> offset(N + 1);
  std::vector<std::int32_t> buf_cols;
  std::vector<std::uint32_t> buf_counts;
  std::size_t at = 0;  // non-zeros in F so far (of this rank's rows, over MPI)
  Progress progress("form factors", mine.size());
  for (std::size_t first = mine.begin; first < mine.end;) {
    std::size_t last = first, total = 0;
    while (last < mine.end && (last == first || total + std::min<std::size_t>(out.rays[last], N) <= kBlockRays)) {
      offset[last] = total;
      total += std::min<std::size_t>(out.rays[last++], N);  // a row has at most N non-zeros
    }
    buf_cols.resize(total);
    buf_counts.resize(total);
    // The rows of the block in the order they are traced (options.morton_order); each writes its own slot.
    std::vector<std::uint32_t> order;
    if (options.morton_order) {
      order = morton_order(ps.centroid, first, last);
    } else {
      order.resize(last - first);
      std::iota(order.begin(), order.end(), std::uint32_t(first));
    }
    parallel_chunks(last - first, 16, [&](std::size_t b, std::size_t e) {
      RowScratch scratch;
      for (std::size_t q = b; q < e; ++q) {
        const std::size_t i = order[q];
        const RowResult r = trace_row(ps, vis, options, eps, sort_passes, i, out.rays[i], scratch, buf_cols.data() + offset[i],
                                      buf_counts.data() + offset[i]);
        nnz[i] = r.nnz;
        out.escaped[i] = r.escaped;
        out.back_hits[i] = r.back_hits;
      }
      progress.advance(e - b);
    });
    std::size_t block_nnz = 0;
    for (std::size_t i = first; i < last; ++i) block_nnz += nnz[i];
    if (at + block_nnz > kMaxNonZeros)
      throw InputError(locate(ps.source, 0, -1, "form-factor matrix has more than 2^31-1 non-zeros"));
    out.F.resizeNonZeros(Eigen::Index(at + block_nnz));  // within the reservation: no reallocation
    std::int32_t* cols = out.F.innerIndexPtr();
    float* values = out.F.valuePtr();
    for (std::size_t i = first; i < last; ++i) {
      const double inv_n = 1.0 / out.rays[i];
      for (std::uint32_t q = 0; q < nnz[i]; ++q, ++at) {
        cols[at] = buf_cols[offset[i] + q];
        values[at] = float(buf_counts[offset[i] + q] * inv_n);
      }
    }
    first = last;
  }
  progress.finish();
  buf_cols = {};
  buf_counts = {};
  if (distributed::size() > 1) {
    share_ray_outcomes(row_blocks, out);
    out.row_blocks = row_blocks;
  }

  // CSR outer index by prefix sums of the row lengths (the other ranks' rows empty: nnz[i] = 0 there).
  std::int32_t* outer = out.F.outerIndexPtr();
  outer[0] = 0;
  for (std::size_t i = 0; i < N; ++i) outer[i + 1] = outer[i] + std::int32_t(nnz[i]);
  return out;
}

}  // namespace radwalk
