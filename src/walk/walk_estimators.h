#pragma once
// with_estimator: the one dispatch from a random-walk method (walk_method.h) to its estimator class.
//
//   with_estimator(method, f) calls f(MethodTag<M>{}) for the method M == method and returns what f returns
//   (the same type for every method). MethodTag<M> carries M, its direction and its estimator class:
//     gathering estimators (gather_estimators.h): Tables, Walk<K>, moment_source;
//     shooting estimators (shoot_estimators.h):   Tables, Particle<K>, moment_source;
//   so f branches on the direction with `if constexpr` and otherwise treats every estimator alike. Every row of
//   kWalkMethods must have its EstimatorOf specialisation (a compile error otherwise).
//   with_estimator_tables(method, kernel, f) also builds the estimator's Tables from kernel.tables() and calls
//   f(MethodTag<M>{}, tables).
#include <cstddef>
#include <utility>

#include "core/check.h"
#include "walk/gather_estimators.h"
#include "walk/shoot_estimators.h"
#include "walk/walk_method.h"

namespace radwalk {

template <WalkMethod M>
struct MethodTag {
  static constexpr WalkMethod kMethod = M;
  static constexpr WalkDirection kDirection = direction_of(M);
  using Estimator = typename EstimatorOf<M>::type;
};

template <std::size_t I = 0, class F>
decltype(auto) with_estimator(WalkMethod method, F&& f) {
  constexpr auto M = static_cast<WalkMethod>(I);
  if constexpr (I + 1 < kWalkMethods.size()) {
    if (method != M) return with_estimator<I + 1>(method, std::forward<F>(f));
  } else {
    RADWALK_CHECK_EQ(static_cast<std::size_t>(method), I);
  }
  return std::forward<F>(f)(MethodTag<M>{});
}

// with_estimator with the estimator's tables built once from the kernel's data: f(MethodTag<M>{}, tables).
template <TransitionKernel K, class F>
decltype(auto) with_estimator_tables(WalkMethod method, const K& kernel, F&& f) {
  return with_estimator(method, [&](auto m) -> decltype(auto) {
    const typename decltype(m)::Estimator::Tables tables(kernel.tables());
    return f(m, tables);
  });
}

}  // namespace radwalk
