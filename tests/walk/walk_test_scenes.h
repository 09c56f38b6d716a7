#pragma once
// The random-walk tests' problems on the unit cube of reference_problems.h (exact F) and per-walk score helpers.
#include <cmath>
#include <vector>

#include "core/rng.h"
#include "patch/patch_builder.h"
#include "solve/problem.h"
#include "core/check.h"
#include "support/reference_problems.h"
#include "walk/walk_estimators.h"
#include "walk/walk_options.h"

namespace radwalk::test {

// A reflecting, emitting cube with different values per face and channel (every channel non-trivial; channel
// spreads moderate, so weights rho/p stay near 1 and fourth moments are finite for the variance tests).
inline RadiosityProblem mixed_cube(const std::vector<int>& faces = kCubeFaces) {
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
inline PatchSet cube_patches(const RadiosityProblem& problem, const std::vector<int>& faces = kCubeFaces) {
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

// Per-walk scores of patch i, channel by channel: x[c][w], from the streams stream(seed, StreamDomain::gather_walk, i, w), for a gathering
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
        Rng rng = stream(seed, StreamDomain::gather_walk, i, static_cast<std::uint64_t>(w));
        typename decltype(m)::Estimator::template Walk<K> walk(kernel, tables, i, rng);
        run_walk(kernel, walk, counters);
        for (int c = 0; c < 3; ++c) x[c][static_cast<std::size_t>(w)] = walk.score()(c);
      }
    }
  });
  return x;
}

// Per-particle scores Y_j (radiosity units, emission excluded): y[j * 3 + c][w], streams stream(seed, StreamDomain::shoot_particle, 0, w),
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
        Rng rng = stream(seed, StreamDomain::shoot_particle, 0, static_cast<std::uint64_t>(w));
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
