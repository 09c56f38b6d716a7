#pragma once
// Small problems with exact form factors for the random-walk tests, and sample-moment helpers.
//
// Unit cube, faces in the order x=0, x=1, y=0, y=1, z=0, z=1 (face i is opposite face i ^ 1), normals inward;
// exact form factors: opposite 0.199824896 (Howell C-11), adjacent 0.200043776 (C-14).
#include <cmath>
#include <vector>

#include "core/rng.h"
#include "patch/patch_builder.h"
#include "solve/problem.h"
#include "core/check.h"
#include "walk/walk_estimators.h"
#include "walk/walk_options.h"

namespace radwalk::test {

inline constexpr double kOpposite = 0.199824896;
inline constexpr double kAdjacent = 0.200043776;

// F of the closed cube restricted to the faces in `faces` (a face left out is a hole: rows then sum below 1).
inline SparseF cube_F(const std::vector<int>& faces = {0, 1, 2, 3, 4, 5}) {
  const auto n = static_cast<int>(faces.size());
  std::vector<Eigen::Triplet<float, std::int32_t>> t;
  for (int a = 0; a < n; ++a)
    for (int b = 0; b < n; ++b)
      if (faces[a] != faces[b])
        t.emplace_back(a, b, static_cast<float>((faces[a] ^ 1) == faces[b] ? kOpposite : kAdjacent));
  SparseF F(n, n);
  F.setFromTriplets(t.begin(), t.end());
  return F;
}

// A problem over cube_F(faces) with the given reflectances and emissions (one row per face kept), unit areas.
inline RadiosityProblem cube_problem(const PatchRgb& rho, const PatchRgb& E,
                                     const std::vector<int>& faces = {0, 1, 2, 3, 4, 5}) {
  RadiosityProblem p;
  p.F = cube_F(faces);
  p.rho = rho;
  p.E = E;
  p.area = Eigen::VectorXd::Ones(static_cast<Eigen::Index>(faces.size()));
  return p;
}

// A reflecting, emitting cube with different values per face and channel (every channel non-trivial; channel
// spreads moderate, so weights rho/p stay near 1 and fourth moments are finite for the variance tests).
inline RadiosityProblem mixed_cube(const std::vector<int>& faces = {0, 1, 2, 3, 4, 5}) {
  PatchRgb rho(6, 3), E(6, 3);
  rho << 0.6, 0.5, 0.4,  0.3, 0.4, 0.35,  0.5, 0.5, 0.5,  0.7, 0.6, 0.65,  0.4, 0.5, 0.3,  0.6, 0.55, 0.7;
  E << 5.0, 3.0, 1.0,  0.0, 0.0, 0.0,  0.0, 1.0, 0.0,  0.0, 0.0, 0.0,  2.0, 0.0, 0.5,  0.0, 0.0, 0.0;
  PatchRgb r(faces.size(), 3), e(faces.size(), 3);
  for (std::size_t k = 0; k < faces.size(); ++k) {
    r.row(static_cast<Eigen::Index>(k)) = rho.row(faces[k]);
    e.row(static_cast<Eigen::Index>(k)) = E.row(faces[k]);
  }
  return cube_problem(r, e, faces);
}

// The cube's faces as a PatchSet (inward normals), with the problem's rho and E.
inline PatchSet cube_patches(const RadiosityProblem& problem, const std::vector<int>& faces = {0, 1, 2, 3, 4, 5}) {
  PatchBuilder b;
  const Vec3 center(0.5, 0.5, 0.5);
  for (std::size_t k = 0; k < faces.size(); ++k) {
    const auto r = static_cast<Eigen::Index>(k);
    const int m = b.add_material("face" + std::to_string(k), problem.rho.row(r).transpose(),
                                 problem.E.row(r).transpose() / kPi);
    const int axis = faces[k] / 2;
    const double at = faces[k] % 2;
    const int u = (axis + 1) % 3, v = (axis + 2) % 3;
    std::vector<Vec3> q(4, Vec3::Zero());
    const double uv[4][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
    for (int c = 0; c < 4; ++c) {
      q[c](axis) = at;
      q[c](u) = uv[c][0];
      q[c](v) = uv[c][1];
    }
    // Counter-clockwise seen from inside: flip when the corner order's normal points out.
    const Vec3 n = (q[1] - q[0]).cross(q[2] - q[0]);
    if (n.dot(center - q[0]) < 0) std::swap(q[1], q[3]);
    b.add_quad(q[0], q[1], q[2], q[3], m);
  }
  return b.build();
}

// Sample mean, unbiased variance and fourth central moment.
struct SampleMoments {
  double mean = 0, var = 0, mu4 = 0;
  std::size_t n = 0;
};
inline SampleMoments sample_moments(const std::vector<double>& x) {
  SampleMoments m;
  m.n = x.size();
  for (double v : x) m.mean += v;
  m.mean /= static_cast<double>(m.n);
  double s2 = 0, s4 = 0;
  for (double v : x) {
    const double d = v - m.mean;
    s2 += d * d;
    s4 += d * d * d * d;
  }
  m.var = s2 / static_cast<double>(m.n - 1);
  m.mu4 = s4 / static_cast<double>(m.n);
  return m;
}

// Per-walk scores of patch i, channel by channel: x[c][w], from the streams Rng(seed, i, w), for a gathering
// method.
template <class K>
std::vector<std::vector<double>> gather_scores(WalkMethod method, const K& kernel, std::size_t i, long walks,
                                               std::uint64_t seed) {
  RADWALK_CHECK(is_gathering(method));
  std::vector<std::vector<double>> x(3, std::vector<double>(static_cast<std::size_t>(walks)));
  with_estimator_tables(method, kernel, [&](auto m, const auto& tables) {
    if constexpr (decltype(m)::kDirection == WalkDirection::gather) {
      WalkCounters counters;
      for (long w = 0; w < walks; ++w) {
        Rng rng(seed, i, static_cast<std::uint64_t>(w));
        typename decltype(m)::Estimator::template Walk<K> walk(kernel, tables, i, rng);
        run_walk(kernel, walk, counters);
        for (int c = 0; c < 3; ++c) x[c][static_cast<std::size_t>(w)] = walk.score()(c);
      }
    }
  });
  return x;
}

// Per-particle scores Y_j (radiosity units, emission excluded): y[j * 3 + c][w], streams Rng(seed, kShootStream, w),
// for a shooting method.
template <class K>
std::vector<std::vector<double>> shoot_scores(WalkMethod method, const K& kernel, const RadiosityProblem& problem,
                                              long particles, std::uint64_t seed) {
  RADWALK_CHECK(!is_gathering(method));
  const std::size_t N = problem.size();
  const ShootSource source = make_shoot_source(problem.E, problem.area);
  std::vector<std::vector<double>> y(3 * N, std::vector<double>(static_cast<std::size_t>(particles), 0.0));
  with_estimator_tables(method, kernel, [&](auto m, const auto& tables) {
    if constexpr (decltype(m)::kDirection == WalkDirection::shoot) {
      WalkCounters counters;
      for (long w = 0; w < particles; ++w) {
        Rng rng(seed, kShootStream, static_cast<std::uint64_t>(w));
        typename decltype(m)::Estimator::template Particle<K> particle(kernel, tables, source, rng);
        run_particle(kernel, particle, counters, [&](std::size_t j, const Rgb& power) {
          for (int c = 0; c < 3; ++c)
            y[j * 3 + static_cast<std::size_t>(c)][static_cast<std::size_t>(w)] +=
                power(c) / problem.area(static_cast<Eigen::Index>(j));
        });
      }
    }
  });
  return y;
}

}  // namespace radwalk::test
