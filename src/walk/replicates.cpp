#include "walk/replicates.h"

#include "core/check.h"

namespace radwalk {

long replicate_particles(const WalkOptions& options, int r) {
  const long R = options.replicates;
  return options.particles / R + (r < options.particles % R ? 1 : 0);
}

ReplicateStart replicate_start(const PatchRgb& E, int r, const ReplicateDirectLight& direct, WalkCounters& counters) {
  ReplicateStart start{E, E};
  if (direct) {
    start.source = direct(static_cast<std::uint64_t>(r), counters);
    start.base += start.source;
  }
  return start;
}

ReplicateEstimate replicate_estimate(const std::vector<PatchRgb>& B_r, long particles) {
  const auto R = static_cast<double>(B_r.size());
  RADWALK_CHECK(B_r.size() >= 2);  // a spread needs two replicates (check_walk_options)
  ReplicateEstimate e;
  e.B = PatchRgb::Zero(B_r[0].rows(), 3);
  for (const PatchRgb& B : B_r) e.B += B;
  e.B /= R;
  PatchRgb spread = PatchRgb::Zero(e.B.rows(), 3);
  for (const PatchRgb& B : B_r) spread += (B - e.B).square();
  e.se = (spread / (R * (R - 1))).sqrt();
  e.var = e.se.square() * static_cast<double>(particles);
  return e;
}

}  // namespace radwalk
